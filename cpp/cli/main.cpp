// coatcontact: command-line front end. Dispatches to one subcommand per file (cmd_*.cpp).
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <iostream>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/solve_cache.hpp"
#include "commands.hpp"

namespace {

struct Command {
  const char* name;
  int (*run)(const coatcontact::cli::Args&);
  const char* summary;
};

// One line per subcommand, in the order they are listed by --help.
const Command kCommands[] = {
    {"kernel", coatcontact::cli::run_kernel, "surface compliance C(q) and kernel H(u) of the coated substrate"},
    {"reduced", coatcontact::cli::run_reduced, "reduced variables Pi_s, Delta_s, Pi_c, Delta_c, E_eq, Gamma1 versus a/t"},
    {"fit", coatcontact::cli::run_fit, "fit w (and t, E1) to measured a,F or delta,F data"},
    {"adhesive", coatcontact::cli::run_adhesive, "normalized adhesive sphere curves P(a_bar), D(a_bar) per eta"},
    {"pulloff", coatcontact::cli::run_pulloff, "normalized pull-off (load and displacement control) per eta"},
    {"sphere", coatcontact::cli::run_sphere, "adhesive sphere in physical units: a, delta, F and pull-off forces"},
    {"contact", coatcontact::cli::run_contact, "any axisymmetric indenter (cone, power law, blunted cone, profile) in SI units"},
    {"afm", coatcontact::cli::run_afm, "AFM force curves from instrument files: show, export"},
    {"kinetics", coatcontact::cli::run_kinetics, "rate-dependent adhesion: crack kinetics at the edge, driven through a spring"},
    {"indent", coatcontact::cli::run_indent, "nanoindentation files: show (the vendors' files in SI)"},
};

void print_overview(std::ostream& out) {
  out << "usage: coatcontact <command> [options]   (coatcontact <command> --help for details)\n\n"
         "Adhesive (JKR) contact of a rigid sphere, cone or flat punch with an elastic film\n"
         "bonded to an elastic or rigid substrate (Barthel & Perriot, J. Phys. D 40 (2007) 1059).\n\n"
         "commands:\n";
  for (const auto& c : kCommands) {
    out << "  " << c.name << std::string(12 - std::strlen(c.name), ' ') << c.summary << "\n";
  }
  out << "\noptions: --version (print the version and exit), -h/--help\n"
         "  --cache DIR (before the command): keep solved reduced variables in DIR and reuse them\n"
         "  (the same numbers, less time; default: the environment variable COATCONTACT_CACHE)\n"
         "exit codes: 0 success, 2 bad usage or input, 3 numerical failure\n";
}

int dispatch(std::vector<std::string> args) {
  if (!args.empty() && args[0] == "--cache") {
    if (args.size() < 2 || args[1].empty()) {
      std::cerr << "coatcontact: error: --cache needs a directory (--cache DIR before the command)\n";
      return 2;
    }
    coatcontact::set_solve_cache_directory(args[1]);
    args.erase(args.begin(), args.begin() + 2);
  }
  if (args.empty()) {
    print_overview(std::cerr);
    return 2;
  }
  if (args[0] == "--help" || args[0] == "-h" || args[0] == "help") {
    print_overview(std::cout);
    return 0;
  }
  if (args[0] == "--version") {
    std::cout << "coatcontact " << coatcontact::cli::version_string() << "\n";
    return 0;
  }
  for (const auto& c : kCommands) {
    if (args[0] == c.name) {
      return c.run(std::vector<std::string>(args.begin() + 1, args.end()));
    }
  }
  std::string shown = args[0].substr(0, 60);
  if (shown.size() < args[0].size()) shown += "... (" + std::to_string(args[0].size()) + " characters)";
  std::cerr << "coatcontact: error: unknown command '" << shown
            << "' (run 'coatcontact --help' for the list)\n";
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  // The "# command:" line of outputs leaves out --cache DIR: the numbers do not depend on it.
  std::vector<const char*> recorded(argv, argv + argc);
  if (argc >= 3 && std::strcmp(argv[1], "--cache") == 0) recorded.erase(recorded.begin() + 1, recorded.begin() + 3);
  coatcontact::cli::set_command_line(static_cast<int>(recorded.size()), recorded.data());
  const int code = dispatch(std::vector<std::string>(argv + 1, argv + argc));
  // Help, version and summaries go to stdout directly: a failed write (a full disk, a closed
  // pipe with SIGPIPE ignored) must not end in exit 0.
  errno = 0;
  std::cout.flush();
  if (std::fflush(stdout) != 0 || std::ferror(stdout) || !std::cout) {
    const int error_number = errno;
    std::cerr << "coatcontact: error: cannot write to standard output"
              << (error_number != 0 ? std::string(": ") + std::strerror(error_number) : std::string()) << "\n";
    return code == 0 ? 2 : code;
  }
  return code;
}
