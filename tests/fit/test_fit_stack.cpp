// Fits on a stack of layers through the program, on synthetic data of make_synthetic_data:
// recovery of a buried layer's thickness (and of w) from noisy two-layer data, the one-layer
// --layer fit against the --film/--thickness fit, and the bad input that must stop with exit
// 2, a message naming the option and no output file.
// Usage: test_fit_stack COATCONTACT MAKE_SYNTHETIC_DATA
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

void check_within(const std::map<std::string, std::string>& h, const std::string& name, const std::string& unit,
                  double truth, const std::string& what) {
  const double estimate = value(h, name + "_" + unit);
  const double error = value(h, name + "_stderr_" + unit);
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
  check_within(h, "w", "J_per_m2", 0.04, "two layers, w,h2 free");
  check_within(h, "h2", "m", 30e-6, "two layers, w,h2 free");
  check::that(h.count("h1_status") == 1 && h.at("h1_status") == "fixed", "two layers: h1 reported fixed");

  const std::string out_e = folder + "/fit_e2.tsv";
  const Run fit_e2 = run("'" + cli + "' fit '" + data + "' --columns a,F --radius 5mm --layer 20um,1MPa,0.49 "
                         "--layer 30um,2MPa,0.45" + kSubstrate + " --free w,E2 --output '" + out_e + "'");
  check::that(fit_e2.status == 0, "fit w,E2: exit 0 (" + fit_e2.err + ")");
  std::printf("fit w,E2: %.2f s\n", fit_e2.seconds);
  const auto he = header(out_e);
  check_within(he, "w", "J_per_m2", 0.04, "two layers, w,E2 free");
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
  for (const char* key : {"w_J_per_m2", "w_stderr_J_per_m2", "t_m", "t_stderr_m", "E1_Pa", "residual_norm_N"}) {
    check::close(value(layer, key), value(film, key), check::tier::kRounding,
                 std::string("one layer: --layer against --film/--thickness, ") + key);
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

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: test_fit_stack COATCONTACT MAKE_SYNTHETIC_DATA\n");
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
  test_two_layer_recovery();
  test_one_layer_equals_film();
  test_bad_input();
  std::error_code ignored;
  std::filesystem::remove_all(folder, ignored);
  return check::exit_code();
}
