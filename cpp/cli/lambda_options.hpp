// The Maugis-Dugdale options of `adhesive`, `pulloff` (--lambda) and `sphere`
// (--cohesive-stress, --range), and their output (THEORY.md section 13). Kept apart from
// cmd_adhesive.cpp: that file only asks whether a cohesive zone was requested.
#pragma once
#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/limits.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::cli {

OptionSpec lambda_option();
// --md-direct: the Maugis-Dugdale values by the direct per-radius solve (the reference) instead
// of the reduced table of the cohesive zone.
OptionSpec md_direct_option();
// Whether --md-direct is given; InputError naming it when it is given but unused (`used` false,
// `needs` the options that would use it).
bool parse_md_direct(const Arguments& args, bool used, const std::string& needs);
// The --lambda list; nullopt when absent or every value is inf (then JKR, the default output).
std::optional<std::vector<double>> parse_lambdas(const Arguments& args);
// a_bar empty: the JKR curves' default range, 400 points.
// direct: the per-radius solve for every value (--md-direct), else the reduced table.
void write_md_adhesive(std::ostream& os, const Stack& stack, const std::vector<double>& etas,
                       const std::vector<double>& lambdas, const std::vector<double>& a_bar, double tol, bool direct);
// k_bars (--spring-bar, may be empty): one row per (eta, lambda, k_bar) with the pull-off through
// the spring (THEORY.md sections 10 and 13) as extra columns.
void write_md_pulloff(std::ostream& os, const Stack& stack, const std::vector<double>& etas,
                      const std::vector<double>& lambdas, double tol, bool direct, const std::vector<double>& k_bars);

std::vector<OptionSpec> cohesive_options();
// sigma0 [Pa] from --cohesive-stress or w/--range; nullopt when neither is given. InputError
// naming the option for both given, or the library's (limits.hpp) for a range above
// kMaximumRangeOverThickness film thicknesses or a lambda outside [kMinimumLambda, kMaximumLambda].
std::optional<double> parse_cohesive_stress(const Arguments& args, const Stack& stack, double radius,
                                            double thickness, double work);
// contact_radii [m]: the radii of the curve; empty: `points` log-spaced over the default range.
void write_md_sphere(std::ostream& os, const Stack& stack, double radius, double thickness, double work,
                     double sigma0, std::size_t points, const std::vector<double>& contact_radii, bool direct);

}  // namespace coatcontact::cli
