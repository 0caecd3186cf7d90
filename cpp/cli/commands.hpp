// Subcommands of the `coatcontact` program. Each takes the arguments after its name and
// returns the process exit code (0 success, 2 bad usage or input, 3 numerical failure).
#pragma once
#include <cstddef>
#include <memory>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/indenter_shape.hpp"

namespace coatcontact::cli {

using Args = std::vector<std::string>;

int run_kernel(const Args& args);    // cmd_kernel.cpp: C(q) and H(u) tables
int run_fit(const Args& args);       // cmd_fit.cpp: least-squares fit of measured a,F / delta,F data
int run_adhesive(const Args& args);  // cmd_adhesive.cpp: normalized P(a_bar), D(a_bar) curves
int run_pulloff(const Args& args);   // cmd_adhesive.cpp: normalized pull-off per eta
int run_sphere(const Args& args);    // cmd_adhesive.cpp: adhesive sphere in physical units
int run_reduced(const Args& args);   // cmd_reduced.cpp: reduced variables Pi_s .. Gamma1 versus a/t
int run_contact(const Args& args);   // cmd_contact.cpp: any axisymmetric indenter in physical units
int run_afm(const Args& args);       // cmd_afm.cpp: AFM force curves from instrument files (show, export)
// The indenter of `--shape SPEC` (sphere:R, cone:BETA, punch:A, power:N,R, blunted-cone:R,BETA,
// profile:FILE; cmd_contact.cpp), shared by `contact` and `fit`. InputError naming --shape.
// `profile_end` is set to "FILE:LINE" of a profile's last point.
std::shared_ptr<const IndenterShape> parse_shape(const std::string& text, std::string& profile_end);
// A cone's half included angle: "70deg", "70 deg" or "1.22rad", a bare number in degrees, in
// (0, 90) degrees (cmd_contact.cpp). InputError naming `option`.
double parse_angle(const std::string& text, const std::string& option);
// The number of curve points of `--points N` (an integer, 2 <= N <= 1e6), `fallback` without it
// (cmd_contact.cpp; `contact` and `sphere`). InputError naming --points.
std::size_t parse_point_count(const Arguments& args, std::size_t fallback);
int run_kinetics(const Args& args);  // cmd_kinetics.cpp: rate-dependent adhesion (crack kinetics)
int run_indent(const Args& args);    // cmd_indent.cpp: nanoindentation files (show; the table of indent_commands.hpp)
// (further subcommands are declared here as they land)

}  // namespace coatcontact::cli
