// `coatcontact kernel`: surface compliance C(q) (THEORY.md section 3) and the kernel
// H(u) = int_0^inf [C(q)-1] cos(qu) dq (section 4) of a film on a substrate.
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/kernel.hpp"
#include "commands.hpp"

namespace coatcontact::cli {

namespace {

const std::vector<OptionSpec> kSpec = {
    film_option(),
    layer_option(false),
    substrate_option(),
    indenter_option(),
    {"--q", "LIST", "q = k t values for C(q): v1,v2,... or MIN:MAX:N (log-spaced)", false},
    {"--u", "LIST", "u = r/t values for H(u): v1,v2,... or MIN:MAX:N (log-spaced)", false},
    {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
};

// Default q list when neither --q nor --u is given.
constexpr const char* kDefaultQ = "0.001:100:26";

std::string text_of(double value) { return format_parameter(value, "parameter"); }

}  // namespace

int run_kernel(const Args& args) {
  return run_guarded("kernel", [&]() -> int {
    const Arguments arguments(args, kSpec);
    if (arguments.help()) {
      std::cout << usage("kernel",
                         "(--film E1,nu1 | --layer h,E,nu[,slip] ...) --substrate E0,nu0|rigid [--q LIST] "
                         "[--u LIST] [--output FILE]",
                         "Surface compliance C(q) of a film (thickness t) bonded to a substrate,\n"
                         "u_z(k) = 2 C(kt) p(k) / (E1* k), with q = k t; and the kernel\n"
                         "H(u) = int_0^inf [C(q) - 1] cos(q u) dq of the integral equation, u = r/t.\n"
                         "Prints 'q C' rows (--q) and/or 'u H' rows (--u); with both, two blocks\n"
                         "separated by two blank lines. Without either, C(q) at q = 0.001:100:26.\n"
                         "With --layer (repeated, top first): a stack, q = k T and u = r/T with T the\n"
                         "total thickness, C normalized by the top layer's E* (THEORY.md section 12).",
                         kSpec);
      return kExitSuccess;
    }
    const Stack stack = parse_stack(arguments);
    std::vector<double> qs, us;
    const auto q_text = arguments.get("--q");
    const auto u_text = arguments.get("--u");
    if (q_text) qs = parse_list(*q_text, "--q");
    if (u_text) us = parse_list(*u_text, "--u");
    if (!q_text && !u_text) qs = parse_list(kDefaultQ, "--q");
    for (const double q : qs) {
      if (!(q >= 0.0)) {
        throw InputError("--q: " + text_of(q) + " is not allowed; every q must be >= 0");
      }
    }

    // Compute everything before opening the output, so a failure leaves no file.
    const std::vector<double> cs = qs.empty() ? std::vector<double>{} : compliance(stack, qs);
    std::vector<double> hs;
    if (!us.empty()) {
      const KernelTable table(stack);
      table.eval(us, hs);
    }

    std::vector<std::pair<std::string, std::string>> header = {
        {"coatcontact kernel", "THEORY.md sections 3-4"},
    };
    add_material_header(header, stack);

    Output output(arguments.get("--output").value_or(""));
    std::ostream& out = output.stream();
    if (!qs.empty()) {
      auto items = header;
      items.push_back({"quantity", stack.is_multilayer() ? "surface compliance C(q), q = k T"
                                                         : "surface compliance C(q), q = k t"});
      const std::vector<std::string> columns = {"q", "C"};
      write_header(out, items, columns);
      for (std::size_t i = 0; i < qs.size(); ++i) write_row(out, {qs[i], cs[i]}, columns);
    }
    if (!us.empty()) {
      if (!qs.empty()) out << "\n\n";
      auto items = header;
      items.push_back({"quantity", stack.is_multilayer()
                                       ? "kernel H(u) = int_0^inf [C(q)-1] cos(qu) dq, u = r/T"
                                       : "kernel H(u) = int_0^inf [C(q)-1] cos(qu) dq, u = r/t"});
      const std::vector<std::string> columns = {"u", "H"};
      write_header(out, items, columns);
      for (std::size_t i = 0; i < us.size(); ++i) write_row(out, {us[i], hs[i]}, columns);
    }
    output.commit();
    return kExitSuccess;
  });
}

}  // namespace coatcontact::cli
