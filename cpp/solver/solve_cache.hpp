// The solve cache's store for one stack (internal to the solver floor; public switch:
// coatcontact/solve_cache.hpp; design: docs/solver.md). Thread-safe.
#pragma once
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::detail {

class SolveCache {
 public:
  // Reads every entry of the stack's folder under `directory` (created on first write).
  SolveCache(const std::string& directory, const Stack& stack);
  // Writes what was solved and not found (flush()).
  ~SolveCache();
  SolveCache(const SolveCache&) = delete;
  SolveCache& operator=(const SolveCache&) = delete;

  std::optional<ReducedVariables> find(double a_over_t, double tolerance) const;
  void add(double tolerance, const ReducedVariables& values);
  // New entries into one file, written atomically (a temporary name, then rename); every
  // failure is silent (the cache only saves time). Merges the folder's files when they are many.
  void flush();

  // The text the entries are keyed by (stack constants as exact bits, build id).
  static std::string key_of(const Stack& stack);

 private:
  using Key = std::pair<std::uint64_t, std::uint64_t>;  // bits of tolerance, a/t
  void remove_other_builds() const;
  std::string build_folder_;
  std::string folder_;
  std::string key_;
  mutable std::mutex mutex_;
  std::map<Key, ReducedVariables> entries_;
  std::vector<std::pair<double, ReducedVariables>> added_;
  std::vector<std::string> loaded_files_;
};

}  // namespace coatcontact::detail
