// Support for the `coatcontact` command-line program: option parsing, value parsers,
// atomic output files and TSV formatting. Every parser throws InputError with a message
// that names the option, the offending value and what is allowed.
#pragma once
#include <cstdio>
#include <functional>
#include <iosfwd>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/data_file.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/point_status.hpp"
#include "coatcontact/stack.hpp"
#include "coatcontact/units.hpp"

namespace coatcontact::cli {

// ---- value parsers ---------------------------------------------------------------

// Conventions shared by every parser below:
//  - Locale-independent (std::from_chars). Decimal notation only: "1", "-2.5", "1e-3", "+3".
//    Hex floats, "nan", "inf", an empty string and any trailing text are rejected, and so is a
//    value that overflows a double. Leading and trailing blanks (space, tab) around the whole
//    text and around each comma-separated item are ignored ("1, 2" == "1,2").
//  - A unit suffix is case-sensitive and follows the number directly or after exactly one
//    space: "2MPa", "2 MPa". No suffix means SI.

// `text` in single quotes for a message, control bytes escaped; a text over 60 bytes is cut
// there and followed by "..." and its length, so a huge argument is never echoed whole.
std::string quoted(const std::string& text);

// A finite floating-point number, the whole string (no trailing text). `option` names the
// option in messages, e.g. "--tol".
double parse_number(const std::string& text, const std::string& option);

// "v1,v2,..." (comma-separated numbers) or "MIN:MAX:N" (N log-spaced points, 0 < MIN <= MAX,
// N >= 1 integer; N = 1 requires MIN == MAX). Empty lists and empty items are rejected.
std::vector<double> parse_list(const std::string& text, const std::string& option);

// Largest number of rows (product of the lists a command combines) one run may compute:
// each list alone may hold 1e6 values, and 1e7 rows of a TSV table are ~1 GB of output.
inline constexpr double kMaxRows = 1e7;
// InputError naming the options, their sizes and the limit when the product of the list sizes
// (e.g. {{"--eta", 1000}, {"--a-bar", 1000000}}) exceeds kMaxRows; checked before any work.
void check_rows(const std::vector<std::pair<std::string, std::size_t>>& lists);

// Physical quantity with an optional unit suffix; returns SI.
//   kPressure: Pa kPa MPa GPa     kLength: m mm um µm nm     kEnergy: J/m2 mJ/m2 (m^2, m²)
//   kForce:    N mN uN µN nN
// A bare number is SI. The value (after conversion to SI) must be finite and > 0.
using coatcontact::Quantity;
double parse_quantity(const std::string& text, Quantity kind, const std::string& option);

// The unit table behind parse_quantity (coatcontact/units.hpp, the library's).
using coatcontact::find_unit;
using coatcontact::quantity_name;
using coatcontact::to_si;
using coatcontact::unit_list;
using coatcontact::UnitInfo;

// A list of quantities: "v1,v2,..." (a unit allowed on each item) or "MIN:MAX:N" (a unit
// allowed on MIN and on MAX; N log-spaced points as parse_list). Returns SI.
std::vector<double> parse_quantity_list(const std::string& text, Quantity kind, const std::string& option);

// A quantity per quantity, with an optional unit "TOP/BOTTOM" (no unit: SI). The value must
// be finite and > 0.
//   kStiffness: N/m, a force unit over a length unit (500N/m, 0.5mN/um)
//   kSpeed:     m/s, a length unit over s, ms, min, h (10um/s)
//   kForceRate: N/s, a force unit over s, ms, min, h (1mN/s)
enum class Rate { kStiffness, kSpeed, kForceRate };
double parse_rate(const std::string& text, Rate kind, const std::string& option);
// "v1,v2,..." or "MIN:MAX:N" of rates, a unit allowed on every item and on MIN and MAX.
std::vector<double> parse_rate_list(const std::string& text, Rate kind, const std::string& option);

// "E,nu" with E > 0 (unit suffix allowed, as a pressure) and -1 < nu <= 0.5.
Material parse_material(const std::string& text, const std::string& option);
// "E,nu" or "rigid".
Substrate parse_substrate(const std::string& text, const std::string& option);
// "E2,nu2" or "rigid" (THEORY.md section 9).
Indenter parse_indenter(const std::string& text, const std::string& option);

// ---- arguments -------------------------------------------------------------------

struct OptionSpec {
  std::string name;         // "--film"
  std::string value_name;   // "E1,nu1" (empty: a flag without a value)
  std::string help;         // one line
  bool required = false;
  bool repeatable = false;  // may be given several times (--layer); get_all() lists them
};

// Parses `--name value`, `--name=value`, flags and positionals against a spec.
// Unknown options, missing values, repeated options and missing required options throw
// InputError. `--help`/`-h` is always accepted (then required options are not enforced).
// A value may start with '-' only when a digit (or ".digit") follows, i.e. a negative number;
// any other argument starting with '-' after an option that takes a value is reported as a
// missing value. `--` ends the options: everything after it is positional.
class Arguments {
 public:
  Arguments(const std::vector<std::string>& args, const std::vector<OptionSpec>& spec,
            std::size_t max_positionals = 0);
  bool help() const { return help_; }
  bool has(const std::string& name) const;
  std::optional<std::string> get(const std::string& name) const;
  std::string require(const std::string& name) const;  // InputError if absent
  // Every value of a repeatable option, in command-line order (empty if absent).
  std::vector<std::string> get_all(const std::string& name) const;
  const std::vector<std::string>& positionals() const { return positionals_; }

 private:
  bool help_ = false;
  std::map<std::string, std::string> values_;  // a repeatable option: its first value
  std::map<std::string, std::vector<std::string>> repeated_;
  std::vector<std::string> positionals_;
};

// Plausibility notes of a command in physical units: bare numbers (SI by convention) far from
// any experiment, with the unit the user likely meant: a modulus below 1 kPa (--film,
// --substrate, --indenter, --layer), a thickness or radius above 0.1 m (--thickness, --radius,
// --shape sphere:R, --layer), a work of adhesion above 1 J/m2 (--work), and a film thicker
// than the sphere's radius. A note never refuses the input: the values are legal, only unlikely.
std::vector<std::string> plausibility_notes(const Arguments& args);
// Writes each note once on stderr ("coatcontact <command>: note: ...") at once (before a long
// run, or its failure) and returns them as "note" header items for the command's output.
std::vector<std::pair<std::string, std::string>> report_plausibility(const std::string& command,
                                                                    const Arguments& args);

// --film and --substrate, the same in every command that takes materials.
OptionSpec film_option();
OptionSpec substrate_option();

// Usage text of a subcommand: synopsis line, description, then one line per option.
// The stack of --film E1,nu1 (one layer) or repeated --layer h,E,nu[,slip] (top first,
// THEORY.md section 12; not both), --substrate E0,nu0|rigid (required) and the optional
// --indenter E2,nu2|rigid (default rigid; THEORY.md section 9). One of --film and --layer is
// required (their specs say required = false; this checks it).
Stack parse_stack(const Arguments& args);
// "h,E,nu[,slip]": thickness (a number or a length with a unit; only ratios enter the
// normalized commands), Young's modulus, Poisson ratio, and an optional "slip" (the
// interface below the layer is frictionless).
Layer parse_layer(const std::string& text, const std::string& option);
// The --layer option line of a command's spec (`si`: thicknesses are lengths).
OptionSpec layer_option(bool si);
// The film thickness of an SI command: --thickness with --film, the total thickness of the
// layers with --layer (then --thickness is refused: the layers carry the lengths).
double coating_thickness(const Arguments& args, const Stack& stack);
// The --indenter option line of a command's spec.
OptionSpec indenter_option();

std::string usage(const std::string& command, const std::string& synopsis,
                  const std::string& description, const std::vector<OptionSpec>& spec);

// ---- output ----------------------------------------------------------------------

// Output to stdout (empty path, "-" or /dev/stdout), to another descriptor open in this
// process (/dev/stderr, /dev/fd/N, /proc/self/fd/N: written to it, so O_APPEND is kept; one
// open for reading only or not open is refused), or to a file written atomically: the data
// go to a temporary file in the same folder, renamed over `path` by commit(). If commit() is
// never called (error, exception) the temporary file is removed; it is also removed if the
// process gets SIGINT or SIGTERM. The temporary file is "<path>.tmp.XXXXXX"; the committed
// file gets mode 0666 & ~umask.
// Safety (exit 2, InputError naming `option`, the path and what is allowed):
//  - only regular files are replaced; an existing device, FIFO, socket or folder is refused,
//    except /dev/null (a character device), which is written in place, never renamed over;
//  - a symbolic link to a regular file replaces that file and keeps the link; a dangling
//    link is refused;
//  - a path that is (same device and inode, or same resolved name) an input registered with
//    register_input(), the regular file standard input is redirected from, or the file of
//    another live Output is refused; so are two Outputs on one stream.
// All or none: while several Outputs are alive, commit() only completes the data; the last
// commit() publishes all of them (streams first, then the renames; with several files each
// existing target first gets a hard link "<path>.old.XXXXXX", which proves it can be replaced
// before any is, and restores it if a later rename fails). An Output destroyed
// without commit() cancels the others. Stdout is held in memory until then, so a failure
// leaves nothing on stdout; a failed write of stdout is an InputError (exit 2).
// Signal cleanup: the first file Output installs SIGINT/SIGTERM handlers (only where the
// action is still the default) that unlink every pending temporary file, then re-raise the
// signal with the default action. At most 64 files are protected at once (more still work,
// without signal cleanup).
class Output {
 public:
  explicit Output(const std::string& path, const std::string& option = "--output");
  ~Output();
  Output(const Output&) = delete;
  Output& operator=(const Output&) = delete;
  std::ostream& stream();
  void commit();  // throws InputError on a write/rename failure

  struct Impl;  // (public so that the output set in output.cpp can list them)

 private:
  std::unique_ptr<Impl> impl_;
};

// The table to `output_path` ("" or "-": stdout) and, when `plot_path` is given, the rendered
// picture to it (option "--plot"): all or none, as every Output of a command.
void write_table_and_picture(const std::string& output_path, const std::string& table,
                             const std::optional<std::string>& plot_path, const std::string& picture);

// An input file of this command (e.g. "data file"): no Output may write to it.
void register_input(const std::string& path, const std::string& what);
// A data table of the measure floor (data_file.hpp) read as an input of this command: the file
// is registered (register_input), so no output replaces it. "-" reads standard input.
DataTable read_data_file(const std::string& path, std::size_t expected_columns, const std::vector<bool>& nonnegative = {},
                         const std::vector<std::optional<Quantity>>& kinds = {});
// The text of a command's data file (registered as an input), or of stdin for "-" (bounded
// while it is read: kMaxDataFileBytes).
std::string read_input_text(const std::string& path);
// The checks of the Output constructor without creating anything, so a command can refuse a
// bad target before a long computation. `outputs`: (option, path) pairs, also checked
// against each other (empty path: stdout).
void check_output_path(const std::string& path, const std::string& option);
void check_output_paths(const std::vector<std::pair<std::string, std::string>>& outputs);
// Whether an output path is (or will be) a regular file, replaced atomically: false for
// standard output, descriptors (/dev/stderr, /dev/fd/N) and devices (/dev/null), which take no
// files beside them (no FILE.partial for a resume).
bool output_is_regular_file(const std::string& path);

// ---- run context: command line, version, progress ---------------------------------

// The command line as typed (program name without its folder, arguments shell-quoted); set
// once by main(). write_header() puts it first in every header as "# command: ...".
void set_command_line(int argc, const char* const* argv);
const std::string& command_line();
// "0.1.0" from the CMake project, plus " (git <describe>)" when built from a git checkout.
std::string version_string();

// A progress line on stderr for long work: "\r"-updated, only when stderr is a terminal, shown
// once the command has run for 2 s. run_guarded() runs one per command; the body may set the
// expected total (seconds, from a work estimate) and report steps done, which give the ETA.
void progress_set_estimate(double seconds);
void progress_step(std::size_t done, std::size_t total);
void progress_pause();  // clears the line and stops it (before output or an error message)
// Runs the progress line for its scope (run_guarded makes one per command).
class ProgressScope {
 public:
  explicit ProgressScope(const std::string& command);
  ~ProgressScope();
  ProgressScope(const ProgressScope&) = delete;
  ProgressScope& operator=(const ProgressScope&) = delete;

 private:
  bool owner_ = false;
};

// A number for a TSV column: "%.17g". Throws NumericalError (naming `column`) if not finite,
// so no NaN/inf is ever printed as a result.
std::string format_value(double value, const std::string& column);

// Shortest decimal text that reads back to the same double ("0.1", not "0.10000000000000001"):
// for parameters echoed in header lines. Throws NumericalError (naming `name`) if not finite.
std::string format_parameter(double value, const std::string& name);

// The header lines describing the film and the substrate, the same in every subcommand:
// "film E1 [Pa]", "film nu1", "film E1* [Pa]", then "substrate: rigid" or "substrate E0 [Pa]",
// "substrate nu0", "substrate E0* [Pa]", and "E1*/E0*" (0 for a rigid substrate); for an
// elastic indenter also "indenter E2 [Pa]", "indenter nu2", "indenter E2* [Pa]" and the
// reference modulus E_r of the normalization (THEORY.md section 9).
void add_material_header(std::vector<std::pair<std::string, std::string>>& items, const Stack& stack);

// Writes "# key: value" header lines and the "# columns: a\tb\t..." line.
void write_header(std::ostream& out, const std::vector<std::pair<std::string, std::string>>& items,
                  const std::vector<std::string>& columns);
// Writes one TSV row (values formatted by format_value).
void write_row(std::ostream& out, const std::vector<double>& values,
               const std::vector<std::string>& columns);

// Arrays point by point (`reduced`, `contact`, `adhesive`): a point whose tolerance cannot be
// met is written in its place as a comment row "# not delivered: <where>: <reason>" (no
// number is printed for it), the header counts such points, stderr says so once, and the exit
// status is 0 as long as one point was delivered (3 when none was). `--strict` instead stops
// at the first such point with exit 3 and no output.
OptionSpec strict_option();
// `--tol T`, worded the same in every command's --help; default_text: the default as printed.
OptionSpec tol_option(const std::string& default_text);
// NumericalError when every point failed (nothing to deliver): the first reason.
void require_some_delivered(const std::vector<PointStatus>& status, const std::string& what);
// The header item counting the points not delivered (nothing when every point was), and the
// one stderr warning of `command` ("coatcontact <command>: warning: ...").
// where(i) names point i ("a_over_t = 1e4").
void report_not_delivered(std::vector<std::pair<std::string, std::string>>& items, const std::string& command,
                          const std::vector<PointStatus>& status,
                          const std::function<std::string(std::size_t)>& where);
// The comment row of a point not delivered.
void write_not_delivered(std::ostream& out, const std::string& where, const std::string& reason);

// Runs a subcommand body, mapping exceptions to exit codes and one-line messages on stderr:
//   InputError -> "coatcontact <command>: error: <message>", exit 2
//   NumericalError -> "coatcontact <command>: numerical failure: <message>", exit 3
//   any other std::exception -> exit 3 as well (reported, never silent).
int run_guarded(const std::string& command, const std::function<int()>& body);

}  // namespace coatcontact::cli
