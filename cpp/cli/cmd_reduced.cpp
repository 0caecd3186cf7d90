// `coatcontact reduced`: the six reduced variables Π_s, Δ_s, Π_c, Δ_c, E_eq, Γ(1) of the
// coated-substrate contact versus a/t (THEORY.md section 5; solver: docs/solver.md).
#include <iostream>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/reduced_table.hpp"
#include "commands.hpp"

namespace coatcontact::cli {

namespace {

const std::vector<OptionSpec> kSpec = {
    film_option(),
    layer_option(false),
    substrate_option(),
    indenter_option(),
    {"--a-over-t", "LIST", "contact radius over film thickness: v1,v2,... or MIN:MAX:N (log-spaced)", true},
    tol_option("1e-8"),
    {"--direct", "", "solve every radius on its own instead of reading many from the verified interpolant", false},
    {"--output", "FILE", "write the table to FILE (atomically) instead of stdout", false},
    strict_option(),
};

const std::vector<std::string> kColumns = {"a_over_t", "Pi_s",   "Delta_s", "Pi_c",
                                           "Delta_c",  "E_eq",   "Gamma1",  "error_estimate"};

}  // namespace

int run_reduced(const Args& args) {
  return run_guarded("reduced", [&]() -> int {
    const Arguments arguments(args, kSpec);
    if (arguments.help()) {
      std::cout << usage("reduced", "--film E1,nu1 --substrate E0,nu0|rigid "
                                    "--a-over-t LIST [--tol T] [--direct] [--strict] [--output FILE]",
                         "Reduced variables of the coated-substrate contact (Barthel & Perriot 2007):\n"
                         "sphere Pi_s = 2 R F_H / (a^3 E1*), Delta_s = R delta_H / a^2; cone\n"
                         "Pi_c = 4 tan(beta) F_H / (pi a^2 E1*), Delta_c = 2 tan(beta) delta_H / (pi a);\n"
                         "flat punch E_eq = S / (2 a E1*) and edge value Gamma1 = Gamma(1).\n"
                         "error_estimate bounds the largest relative error of the six values\n"
                         "(<= tol). Many radii are read from one Chebyshev interpolant in ln(a/t) whose\n"
                         "segments are checked against direct solves at their ends (the row's estimate\n"
                         "is the segment's; a row above tol is solved directly); --direct solves each\n"
                         "radius on its own. A radius where the tolerance cannot be met is a '# not delivered'\n"
                         "row with its reason (header and stderr count them; exit 0 while one radius\n"
                         "is delivered, 3 when none is); with --strict, exit 3 at the first one.",
                         kSpec);
      return kExitSuccess;
    }
    const Stack stack = parse_stack(arguments);
    const std::vector<double> radii = parse_list(arguments.require("--a-over-t"), "--a-over-t");
    double tolerance = kDefaultTolerance;
    if (const auto text = arguments.get("--tol")) {
      tolerance = parse_number(*text, "--tol");
      if (!(tolerance >= kMinimumTolerance && tolerance <= kMaximumTolerance)) {
        throw InputError("--tol: " + *text + " is outside the allowed range [1e-13, 1e-1]");
      }
    }
    for (const double a : radii) {
      if (!(a > 0.0) || !(a <= kMaximumAOverT)) {
        throw InputError("--a-over-t: " + format_value(a, "a_over_t") +
                         " is not allowed; every a/t must be > 0 and <= 1e8");
      }
    }
    const ReducedSolver solver(stack);
    const bool strict = arguments.has("--strict");
    std::vector<PointStatus> status(radii.size());
    InterpolatedSweep sweep;
    if (arguments.has("--direct")) {
      sweep.rows = strict ? solver.sweep(radii, tolerance) : solver.sweep(radii, tolerance, status);
      sweep.direct_reason = "--direct";
    } else {
      sweep = interpolated_sweep(solver, radii, tolerance, strict ? nullptr : &status);
    }
    const std::vector<ReducedVariables>& rows = sweep.rows;
    require_some_delivered(status, "radius");
    const auto where = [&](std::size_t i) { return "a_over_t = " + format_value(radii[i], "a_over_t"); };

    Output output(arguments.get("--output").value_or(""));
    std::ostream& out = output.stream();
    std::vector<std::pair<std::string, std::string>> header = {
        {"coatcontact reduced", "reduced variables of the coated-substrate contact (THEORY.md section 5)"},
    };
    add_material_header(header, stack);
    header.emplace_back("tolerance", format_parameter(tolerance, "tolerance"));
    header.emplace_back("method", sweep.direct_reason.empty()
                                      ? std::to_string(sweep.interpolated) + " of " + std::to_string(rows.size()) +
                                            " rows from the verified interpolant in ln(a/t) (" +
                                            std::to_string(sweep.segments) + " segments, " +
                                            std::to_string(sweep.source_solves) +
                                            " direct solves of nodes and segment ends), the others solved directly"
                                      : "every row solved directly (" + sweep.direct_reason + ")");
    report_not_delivered(header, "reduced", status, where);
    write_header(out, header, kColumns);
    for (std::size_t i = 0; i < rows.size(); ++i) {
      const ReducedVariables& v = rows[i];
      if (!status[i].delivered) {
        write_not_delivered(out, where(i), status[i].reason);
        continue;
      }
      write_row(out, {v.a_over_t, v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1, v.error_estimate},
                kColumns);
    }
    output.commit();
    return kExitSuccess;
  });
}

}  // namespace coatcontact::cli
