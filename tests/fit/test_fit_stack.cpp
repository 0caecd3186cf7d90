// Fits through the program on synthetic data of make_synthetic_data.
// `stack`: on a stack of layers, recovery of a buried layer's thickness or modulus (and of w)
// from noisy two-layer data, the one-layer --layer fit against the --film/--thickness fit, and
// the bad input that must stop with exit 2, a message naming the option and no output file.
// `branches`: loading and unloading with their own adhesion energies (w_load, w_unload), the
// branches from a branch column or from the row order, and bad branch values.
// Usage: test_fit_stack COATCONTACT MAKE_SYNTHETIC_DATA stack|branches
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"

namespace {

// An estimate counts as recovered within this many of its standard errors (the noise is
// Gaussian: a correct fit leaves it in 99.7 % of data sets).
constexpr double kStandardErrors = 3.0;

std::string cli;
std::string generator;
std::string folder;

struct Run {
  int status = -1;
  std::string err;
  double seconds = 0.0;
};

// Runs `command` with stderr to a file; returns the exit status and the stderr text.
Run run(const std::string& command) {
  const std::string err_path = folder + "/stderr";
  const auto start = std::chrono::steady_clock::now();
  const int raw = std::system((command + " >/dev/null 2>'" + err_path + "'").c_str());
  Run r;
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  std::ifstream err(err_path);
  std::ostringstream text;
  text << err.rdbuf();
  r.err = text.str();
  return r;
}

// "# key: value" lines of a fit's output table.
std::map<std::string, std::string> header(const std::string& path) {
  std::map<std::string, std::string> out;
  std::ifstream file(path);
  std::string line;
  while (std::getline(file, line)) {
    if (line.rfind("# ", 0) != 0) continue;
    const auto colon = line.find(": ");
    if (colon != std::string::npos) out[line.substr(2, colon - 2)] = line.substr(colon + 2);
  }
  return out;
}

double value(const std::map<std::string, std::string>& h, const std::string& key) {
  const auto it = h.find(key);
  check::that(it != h.end(), "output header has '" + key + "'");
  return it == h.end() ? std::nan("") : std::strtod(it->second.c_str(), nullptr);
}

// The standard error of a free parameter's line "name [unit]: value +- error".
double standard_error(const std::map<std::string, std::string>& h, const std::string& key) {
  const auto it = h.find(key);
  const std::size_t at = it == h.end() ? std::string::npos : it->second.find(" +- ");
  check::that(at != std::string::npos, "output header has '" + key + ": value +- error'");
  return at == std::string::npos ? std::nan("") : std::strtod(it->second.c_str() + at + 4, nullptr);
}

void check_within(const std::map<std::string, std::string>& h, const std::string& name, const std::string& unit,
                  double truth, const std::string& what) {
  const double estimate = value(h, name + " [" + unit + "]");
  const double error = standard_error(h, name + " [" + unit + "]");
  std::printf("%s: %s = %.6g +- %.2g (true %.6g, %.2f standard errors)\n", what.c_str(), name.c_str(), estimate,
              error, truth, (estimate - truth) / error);
  check::that(error > 0.0, what + ": " + name + " has a standard error");
  check::below(std::fabs(estimate - truth) / error, kStandardErrors, what + ": " + name + " within 3 standard errors");
}

const std::string kSubstrate = " --substrate 70GPa,0.22";
const std::string kTwoLayers = " --layer 20um,1MPa,0.49 --layer 30um,5MPa,0.45";

void test_two_layer_recovery() {
  const std::string data = folder + "/two_layers.tsv";
  check::that(run("'" + generator + "' --kind a,F --radius 5mm" + kTwoLayers + kSubstrate +
                  " --work 40mJ/m2 --noise 10uN --seed 3 --output '" + data + "'")
                      .status == 0,
              "generator: two-layer a,F data");
  // h2 starts at half its true value; the global search covers a factor 10 around it.
  const std::string out = folder + "/fit_h2.tsv";
  const Run fit_h2 = run("'" + cli + "' fit '" + data + "' --columns a,F --radius 5mm --layer 20um,1MPa,0.49 "
                         "--layer 15um,5MPa,0.45" + kSubstrate + " --free w,h2 --output '" + out + "'");
  check::that(fit_h2.status == 0, "fit w,h2: exit 0 (" + fit_h2.err + ")");
  std::printf("fit w,h2: %.2f s\n", fit_h2.seconds);
  const auto h = header(out);
  check_within(h, "w", "J/m2", 0.04, "two layers, w,h2 free");
  check_within(h, "h2", "m", 30e-6, "two layers, w,h2 free");
  check::that(h.count("h1 [m]") == 1 && h.at("h1 [m]").find(" (fixed)") != std::string::npos,
              "two layers: h1 reported fixed");

  const std::string out_e = folder + "/fit_e2.tsv";
  const Run fit_e2 = run("'" + cli + "' fit '" + data + "' --columns a,F --radius 5mm --layer 20um,1MPa,0.49 "
                         "--layer 30um,2MPa,0.45" + kSubstrate + " --free w,E2 --output '" + out_e + "'");
  check::that(fit_e2.status == 0, "fit w,E2: exit 0 (" + fit_e2.err + ")");
  std::printf("fit w,E2: %.2f s\n", fit_e2.seconds);
  const auto he = header(out_e);
  check_within(he, "w", "J/m2", 0.04, "two layers, w,E2 free");
  check_within(he, "E2", "Pa", 5e6, "two layers, w,E2 free");
}

void test_one_layer_equals_film() {
  const std::string data = folder + "/one_layer.tsv";
  check::that(run("'" + generator + "' --kind a,F --radius 5mm --film 1MPa,0.49 --thickness 50um" + kSubstrate +
                  " --work 40mJ/m2 --noise 10uN --seed 5 --output '" + data + "'")
                      .status == 0,
              "generator: one-film a,F data");
  const std::string film_out = folder + "/film.tsv", layer_out = folder + "/layer.tsv";
  check::that(run("'" + cli + "' fit '" + data + "' --columns a,F --radius 5mm --film 1MPa,0.49 --thickness 40um" +
                  kSubstrate + " --free w,t --output '" + film_out + "'")
                      .status == 0,
              "fit --film --thickness: exit 0");
  check::that(run("'" + cli + "' fit '" + data + "' --columns a,F --radius 5mm --layer 40um,1MPa,0.49" + kSubstrate +
                  " --free w,h1 --output '" + layer_out + "'")
                      .status == 0,
              "fit --layer (one layer): exit 0");
  const auto film = header(film_out), layer = header(layer_out);
  for (const char* key : {"w [J/m2]", "t [m]", "E1 [Pa]", "residual norm [N]"}) {
    check::close(value(layer, key), value(film, key), check::tier::kRounding,
                 std::string("one layer: --layer against --film/--thickness, ") + key);
  }
  for (const char* key : {"w [J/m2]", "t [m]"}) {
    check::close(standard_error(layer, key), standard_error(film, key), check::tier::kRounding,
                 std::string("one layer: --layer against --film/--thickness, standard error of ") + key);
  }
}

// Exit 2, the option named in the message, and no output file.
void expect_refused(const std::string& arguments, const std::string& fragment, const std::string& what) {
  const std::string out = folder + "/never.tsv";
  const Run r = run("'" + cli + "' fit '" + folder + "/two_layers.tsv' --columns a,F --radius 5mm" + arguments +
                    kSubstrate + " --output '" + out + "'");
  check::that(r.status == 2, what + ": exit 2 (got " + std::to_string(r.status) + ")");
  check::that(r.err.find(fragment) != std::string::npos, what + ": message names '" + fragment + "': " + r.err);
  check::that(!std::filesystem::exists(out), what + ": no output file");
}

void test_bad_input() {
  expect_refused(" --film 1MPa,0.49 --layer 20um,1MPa,0.49 --free w", "--film", "--film with --layer");
  expect_refused(" --film 1MPa,0.49 --layer 20um,1MPa,0.49 --free w", "--layer", "--film with --layer");
  expect_refused(kTwoLayers + " --free w,h3", "--free: 'h3'", "--free h3 with two layers");
  expect_refused(kTwoLayers + " --free w,t", "--free: 't'", "--free t with two layers");
  expect_refused(kTwoLayers + " --free w,t", "h1..h2", "--free t with two layers suggests h1..hN");
  expect_refused(kTwoLayers + " --thickness 50um --free w", "--thickness", "--thickness with --layer");
}

// JKR hysteresis: w = 20 mJ/m2 on loading, 60 mJ/m2 on unloading.
const std::string kFilm = " --radius 5mm --film 1MPa,0.49 --thickness 50um" + kSubstrate;

void test_branch_recovery() {
  const std::string data = folder + "/hysteresis.tsv";
  check::that(run("'" + generator + "' --kind a,F" + kFilm + " --work 20mJ/m2 --work-unload 60mJ/m2 --noise 10uN "
                  "--seed 11 --branch-column yes --output '" + data + "'")
                      .status == 0,
              "generator: a,F data with a branch column");
  const std::string out = folder + "/fit_branches.tsv";
  const Run column = run("'" + cli + "' fit '" + data + "' --columns a=1,F=2,branch=3" + kFilm +
                         " --free w_load,w_unload --output '" + out + "'");
  check::that(column.status == 0, "fit w_load,w_unload (branch column): exit 0 (" + column.err + ")");
  std::printf("fit w_load,w_unload, a,F with a branch column: %.2f s\n", column.seconds);
  const auto h = header(out);
  check_within(h, "w_load", "J/m2", 0.02, "a,F, branch column");
  check_within(h, "w_unload", "J/m2", 0.06, "a,F, branch column");
  check::that(h.count("branches") == 1 && h.at("branches").find("branch column") != std::string::npos,
              "header says where the branches came from");

  // The same rows by their order (no column): the rows after the largest a are unloading.
  const std::string by_order = folder + "/fit_order.tsv";
  check::that(run("'" + cli + "' fit '" + data + "' --columns a=1,F=2" + kFilm + " --free w_load,w_unload --output '" +
                  by_order + "'")
                      .status == 0,
              "fit w_load,w_unload (row order): exit 0");
  const auto ho = header(by_order);
  for (const char* key : {"w_load [J/m2]", "w_unload [J/m2]"}) {
    check::close(value(ho, key), value(h, key), check::tier::kRounding,
                 std::string("branches by row order equal the branch column's, ") + key);
  }

  const std::string penetration = folder + "/hysteresis_delta.tsv";
  check::that(run("'" + generator + "' --kind delta,F" + kFilm + " --work 20mJ/m2 --work-unload 60mJ/m2 --noise 10uN "
                  "--seed 12 --output '" + penetration + "'")
                      .status == 0,
              "generator: delta,F data with two adhesion energies");
  const std::string out_delta = folder + "/fit_branches_delta.tsv";
  const Run delta_run = run("'" + cli + "' fit '" + penetration + "' --columns delta,F" + kFilm +
                            " --free w_load,w_unload --output '" + out_delta + "'");
  check::that(delta_run.status == 0, "fit w_load,w_unload (delta,F): exit 0 (" + delta_run.err + ")");
  std::printf("fit w_load,w_unload, delta,F by row order: %.2f s\n", delta_run.seconds);
  const auto hd = header(out_delta);
  check_within(hd, "w_load", "J/m2", 0.02, "delta,F, row order");
  check_within(hd, "w_unload", "J/m2", 0.06, "delta,F, row order");
}

void test_bad_branches() {
  const std::string bad = folder + "/bad_branch.tsv";
  {
    std::ofstream file(bad);
    file << "# units: um mN 1\n130\t0.1\t1\n150\t0.5\t1\n170\t1.0\t2\n150\t0.3\t0\n";
  }
  const std::string out = folder + "/never.tsv";
  const Run r = run("'" + cli + "' fit '" + bad + "' --columns a=1,F=2,branch=3" + kFilm +
                    " --free w_load,w_unload --output '" + out + "'");
  check::that(r.status == 2, "branch = 2: exit 2 (got " + std::to_string(r.status) + ")");
  check::that(r.err.find("bad_branch.tsv:4:") != std::string::npos, "branch = 2: message names file:line: " + r.err);
  check::that(r.err.find("branch") != std::string::npos, "branch = 2: message names the column: " + r.err);
  check::that(!std::filesystem::exists(out), "branch = 2: no output file");
  const Run w_too = run("'" + cli + "' fit '" + folder + "/hysteresis.tsv' --columns a=1,F=2,branch=3" + kFilm +
                        " --free w,w_unload --output '" + out + "'");
  check::that(w_too.status == 2 && w_too.err.find("--free: 'w'") != std::string::npos,
              "--free w,w_unload: exit 2 naming --free: " + w_too.err);
  const Run one = run("'" + cli + "' fit '" + folder + "/hysteresis.tsv' --columns a=1,F=2,branch=3" + kFilm +
                      " --free w_unload --output '" + out + "'");
  check::that(one.status == 2 && one.err.find("--free") != std::string::npos,
              "--free w_unload alone: exit 2 naming --free: " + one.err);
  check::that(!std::filesystem::exists(out), "bad --free: no output file");
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 4 || (std::string(argv[3]) != "stack" && std::string(argv[3]) != "branches")) {
    std::fprintf(stderr, "usage: test_fit_stack COATCONTACT MAKE_SYNTHETIC_DATA stack|branches\n");
    return 2;
  }
  cli = argv[1];
  generator = argv[2];
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/test_fit_stack.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  if (mkdtemp(buffer.data()) == nullptr) return 2;
  folder = buffer.data();
  if (std::string(argv[3]) == "stack") {
    test_two_layer_recovery();
    test_one_layer_equals_film();
    test_bad_input();
  } else {
    test_branch_recovery();
    test_bad_branches();
  }
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
  return check::exit_code();
}
