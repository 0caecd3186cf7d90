// The solve cache (docs/solver.md, "Solve cache"): opt-in, persistent store of the reduced
// variables the ReducedSolver has solved, in the spirit of FFTW's wisdom. A process that finds
// a radius there reads the exact doubles a solve would return, so every printed number is the
// same with a cold cache, a warm one and none. Entries are keyed by the stack, the tolerance
// and the build id (a hash of the code that produces them and of its build); a corrupt or
// foreign entry is ignored (corrupt ones removed) and solved again.
#pragma once
#include <string>

namespace coatcontact {

// Directory of the cache, or "" (no cache, the default). Initially the environment variable
// COATCONTACT_CACHE (unset or empty: none). Affects ReducedSolvers constructed afterwards.
// The directory must not exist yet, be empty (it is then made the cache's, with a CACHEDIR.TAG)
// or be one the cache made: otherwise set_solve_cache_directory throws InputError, and so does
// solve_cache_directory for a COATCONTACT_CACHE that names another (a file, a device, a
// non-empty folder of the user's). The cache removes only files it can identify as its own.
void set_solve_cache_directory(const std::string& directory);
std::string solve_cache_directory();

// Throws InputError, naming `name` (the option or variable that gave it), the directory and what
// is allowed, if `directory` cannot be the cache (see above); "" (no cache) is allowed.
void check_solve_cache_directory(const std::string& directory, const std::string& name);

// The build id that keys the entries (hex SHA-256).
const char* solve_cache_build_id();

}  // namespace coatcontact
