// Maugis-Dugdale options and output of `adhesive`, `pulloff` and `sphere` (THEORY.md
// section 13; lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3).
#include "lambda_options.hpp"

#include <algorithm>

#include <cmath>
#include <iostream>
#include <limits>
#include <optional>
#include <ostream>
#include <sstream>
#include <string>
#include <utility>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/maugis_dugdale.hpp"
#include "coatcontact/reduced.hpp"
#include "checks.hpp"

namespace coatcontact::cli {

namespace {

using Header = std::vector<std::pair<std::string, std::string>>;
constexpr double kInf = std::numeric_limits<double>::infinity();

const char* const kNormalization =
    "P = F/(pi w R), D = delta/(pi^2 w^2 R/E1*^2)^(1/3), a_bar = a/(pi w R^2/E1*)^(1/3), "
    "eta = t/(pi w R^2/E1*)^(1/3) (THEORY.md section 5)";
const char* const kMaugis =
    "lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3; m = c/a (c: outer radius of the Dugdale zone); "
    "Maugis's a_bar_M = (4/3)^(1/3) a_bar, Delta_M = (4/3)^(2/3) D; lambda = inf is JKR (THEORY.md section 13)";

std::string num(double v) { return std::isinf(v) ? "inf" : format_parameter(v, "header value"); }

// One TSV row; inf (lambda = JKR, m at the end of the curve a -> 0) is written as "inf".
void write_cells(std::ostream& os, const std::vector<double>& values, const std::vector<std::string>& columns) {
  std::string line;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i != 0) line += '\t';
    line += std::isinf(values[i]) && values[i] > 0.0 ? "inf" : format_value(values[i], columns[i]);
  }
  os << line << '\n';
}

std::string join(const std::vector<double>& values) {
  std::string s;
  for (std::size_t i = 0; i < values.size(); ++i) s += (i ? "," : "") + num(values[i]);
  return s;
}

// The library's lambda check with the option and the text it came from.
void check_lambda(double lambda, const std::string& option, const std::string& text) {
  try {
    coatcontact::check_lambda(lambda, text.empty() ? "" : "from " + quoted(text) + "");
  } catch (const InputError& e) {
    throw InputError(option + ": " + e.what());
  }
}

MaugisDugdaleOptions md_options(bool direct) {
  MaugisDugdaleOptions o;
  o.use_table = !direct;
  return o;
}

std::string md_solver_text(const MaugisDugdaleModel& md) {
  const std::string direct = "per contact radius: factored system (p = " + std::to_string(md.options().nodes_per_panel) +
                             "), Brent root of h(c) = h0 in ln(c/a - 1)";
  if (!md.options().use_table) return direct + " (--md-direct)";
  if (md.table_in_closed_form()) {
    return "a homogeneous half-space: Maugis's closed forms stand for the reduced table of the cohesive zone (THEORY.md "
           "section 13), no direct solve; error estimates ~1e-11 relative (--md-direct: the direct solve throughout)";
  }
  return "reduced table of the cohesive zone (THEORY.md section 13, 'The cohesive zone as a table'), a/t in [" +
         num(md.options().table_a_over_t_min) + ", " + num(md.options().table_a_over_t_max) +
         "], c/t <= 1e4, tiles built on demand (resting on " + std::to_string(md.table_nodes()) +
         " direct solves, read from the solve cache where it holds them); outside it " + direct + "; each value with its error estimate (--md-direct: the direct "
         "solve throughout)";
}

}  // namespace

OptionSpec md_direct_option() {
  return {"--md-direct", "",
          "Maugis-Dugdale values by the direct per-radius solve (the reference; slower) instead of the reduced "
          "table of the cohesive zone",
          false};
}

bool parse_md_direct(const Arguments& args, bool used, const std::string& needs) {
  if (!args.has("--md-direct")) return false;
  if (!used) throw InputError("--md-direct: only with " + needs + " (it selects the Maugis-Dugdale solve)");
  return true;
}

OptionSpec lambda_option() {
  return {"--lambda", "LIST",
          "Maugis-Dugdale transition parameter 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3, each in " +
              lambda_range_text() + " (inf or omitted: JKR)",
          false};
}

std::optional<std::vector<double>> parse_lambdas(const Arguments& args) {
  const auto text = args.get("--lambda");
  if (!text) return std::nullopt;
  std::vector<double> values;
  bool finite = false;
  if (text->find(':') != std::string::npos) {
    values = parse_list(*text, "--lambda");
  } else {
    std::string item;
    std::istringstream in(*text + ",");
    std::size_t count = 0;
    while (std::getline(in, item, ',')) {
      ++count;
      const auto first = item.find_first_not_of(" \t");
      const auto last = item.find_last_not_of(" \t");
      const std::string trimmed = first == std::string::npos ? "" : item.substr(first, last - first + 1);
      values.push_back(trimmed == "inf" ? kInf : parse_number(trimmed, "--lambda"));
    }
    if (count == 0 || text->back() == ',') throw InputError("--lambda: empty item in " + quoted(*text) + "");
  }
  for (double v : values) {
    if (!std::isinf(v)) {
      check_lambda(v, "--lambda", *text);
      finite = true;
    }
  }
  if (!finite) return std::nullopt;
  return values;
}

void write_md_adhesive(std::ostream& os, const Stack& stack, const std::vector<double>& etas,
                       const std::vector<double>& lambdas, const std::vector<double>& a_bar_given, double tol,
                       bool direct) {
  const MaugisDugdaleModel md(stack, md_options(direct));
  const ReducedSolver solver(stack);
  const AdhesiveModel jkr(solver, tol);
  const std::vector<double> a_bar =
      a_bar_given.empty() ? [&] {
        const auto [lo, hi] = jkr.default_curve_range();
        return log_spaced(lo, hi, 400);
      }() : a_bar_given;
  {
    double finite = 0.0, lambda0 = 0.0;
    for (double lambda : lambdas) {
      if (!std::isinf(lambda)) {
        finite += 1.0;
        lambda0 = lambda;
      }
    }
    plan_md_work(md, etas.front(), lambda0, *std::max_element(a_bar.begin(), a_bar.end()),
                 finite * static_cast<double>(etas.size() * a_bar.size()), false, "--eta, --lambda and --a-bar");
  }
  struct Block {
    double eta, lambda;
    std::vector<std::vector<double>> rows;
    MaugisDugdalePoint end;
  };
  std::vector<Block> blocks;
  for (double eta : etas) {
    for (double lambda : lambdas) {
      Block b{eta, lambda, {}, {}};
      if (std::isinf(lambda)) {
        for (const CurvePoint& p : jkr.curve(eta, a_bar)) {
          b.rows.push_back({eta, lambda, p.a_bar, p.a_over_t, p.load, p.penetration, 1.0, tol * std::abs(p.load),
                            tol * std::abs(p.penetration)});
        }
      } else {
        for (const MaugisDugdalePoint& p : md.curve(eta, lambda, a_bar)) {
          b.rows.push_back({eta, lambda, p.a_bar, p.a_over_t, p.load, p.penetration, p.m, p.load_error,
                            p.penetration_error});
        }
        b.end = md.point(eta, lambda, 0.0);
      }
      blocks.push_back(std::move(b));
    }
  }
  Header h{{"command", "adhesive"}};
  add_material_header(h, stack);
  h.emplace_back("normalization", kNormalization);
  h.emplace_back("Maugis-Dugdale", kMaugis);
  h.emplace_back("eta", join(etas));
  h.emplace_back("lambda", join(lambdas));
  h.emplace_back("a_bar points", std::to_string(a_bar.size()));
  h.emplace_back("solver", md_solver_text(md) + "; JKR blocks (lambda = inf) from the reduced-variable table at "
                           "tolerance " + num(tol));
  h.emplace_back("P_err, D_err", "error estimates of P and D: the table's (or the direct solve's, ~1e-11 relative); "
                                 "JKR blocks: the tolerance times |P|, |D|");
  for (const Block& b : blocks) {
    if (std::isinf(b.lambda)) continue;
    h.emplace_back("end of the curve a -> 0, eta=" + num(b.eta) + " lambda=" + num(b.lambda),
                   "P = " + num(b.end.load) + " +- " + num(b.end.load_error) + ", D = " + num(b.end.penetration) +
                       " +- " + num(b.end.penetration_error) + ", c_bar = " + num(b.end.c_bar) +
                       " (contact shrunk to a point at finite force)");
  }
  h.emplace_back("blocks", "one per (eta, lambda), eta outer, in the order given, separated by two blank lines "
                           "(gnuplot index)");
  const std::vector<std::string> columns = {"eta", "lambda", "a_bar", "a_over_t", "P", "D", "m", "P_err", "D_err"};
  write_header(os, h, columns);
  for (std::size_t k = 0; k < blocks.size(); ++k) {
    if (k > 0) os << "\n\n";
    for (const auto& row : blocks[k].rows) write_cells(os, row, columns);
  }
}

// The pull-off table: base columns, the spring's (with springs), then the error columns of every
// other printed quantity, appended after the others so that existing column positions keep their
// meaning. rows: one per (eta, lambda) without springs, one per k_bar with them.
void write_pulloff_rows(std::ostream& os, const Header& h, bool springs, const std::vector<std::vector<double>>& rows,
                        const std::vector<std::vector<double>>& extra_errors,
                        const std::vector<std::vector<double>>& spring_errors) {
  std::vector<std::string> columns = {"eta",    "lambda",     "P_load", "a_bar_load", "D_load",   "m_load",
                                      "P_disp", "a_bar_disp", "D_disp", "m_disp",     "P_load_err", "D_disp_err"};
  if (springs) {
    for (const char* c : {"k_bar", "P_spring", "a_bar_spring", "D_spring", "Z_spring_err"}) columns.emplace_back(c);
  }
  for (const char* c : {"a_bar_load_err", "D_load_err", "m_load_err", "P_disp_err", "a_bar_disp_err", "m_disp_err"}) {
    columns.emplace_back(c);
  }
  if (springs) {
    for (const char* c : {"P_spring_err", "a_bar_spring_err", "D_spring_err"}) columns.emplace_back(c);
  }
  write_header(os, h, columns);
  const std::size_t per_pair = springs ? rows.size() / extra_errors.size() : 1;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    std::vector<double> row = rows[i];
    const std::vector<double>& extra = extra_errors[i / per_pair];
    row.insert(row.end(), extra.begin(), extra.end());
    if (springs) row.insert(row.end(), spring_errors[i].begin(), spring_errors[i].end());
    write_cells(os, row, columns);
  }
}

void write_md_pulloff(std::ostream& os, const Stack& stack, const std::vector<double>& etas,
                      const std::vector<double>& lambdas, double tol, bool direct, const std::vector<double>& k_bars) {
  const MaugisDugdaleModel md(stack, md_options(direct));
  // The JKR solver only for lambda = inf rows: its kernel table would be a second build of the
  // MD model's.
  const bool any_jkr = std::any_of(lambdas.begin(), lambdas.end(), [](double l) { return std::isinf(l); });
  std::optional<ReducedSolver> solver;
  std::optional<AdhesiveModel> jkr;
  if (any_jkr) {
    solver.emplace(stack);
    jkr.emplace(*solver, tol);
  }
  Header notes;
  std::vector<std::vector<double>> rows;
  // The Maugis-Dugdale pull-offs first, in parallel; rows and notes below in the given order.
  std::vector<std::pair<double, double>> finite;
  for (double eta : etas) {
    for (double lambda : lambdas) {
      if (!std::isinf(lambda)) finite.emplace_back(eta, lambda);
    }
  }
  if (!finite.empty()) {
    plan_md_work(md, finite.front().first, finite.front().second, 1.0,
                 kMdPulloffEvaluations * static_cast<double>(finite.size()), true, "--eta and --lambda");
  }
  const std::vector<MaugisDugdalePulloff> md_results = md.pulloffs(finite);
  // The spring pull-offs (the tiles exist now: each costs ~1 ms from the table).
  std::vector<std::vector<MaugisDugdalePulloffPoint>> md_springs(finite.size());
  for (std::size_t k = 0; k < finite.size(); ++k) {
    for (double k_bar : k_bars) {
      const MaugisDugdalePulloff p = md.pulloff_spring(finite[k].first, finite[k].second, k_bar);
      md_springs[k].push_back(k_bar == 0.0 ? p.load_control : p.spring_control);
      for (const auto& w : p.warnings) {
        if (w.find("spring control") != std::string::npos) notes.emplace_back("warning", w);
      }
    }
  }
  // Rows: the base columns, then per k_bar its own row with k_bar, P, a_bar, D at the jump and
  // the error estimate of Z = D + P/k_bar.
  // The error columns of the other printed quantities (write_pulloff_rows).
  std::vector<std::vector<double>> extra_errors, spring_errors;
  auto add_rows = [&](std::vector<double> base, const std::vector<PulloffPoint>& jkr_springs,
                      const std::vector<MaugisDugdalePulloffPoint>* md_spring) {
    if (k_bars.empty()) {
      rows.push_back(std::move(base));
      return;
    }
    for (std::size_t k = 0; k < k_bars.size(); ++k) {
      std::vector<double> row = base;
      const double k_bar = k_bars[k];
      if (md_spring != nullptr) {
        const MaugisDugdalePoint& q = (*md_spring)[k].point;
        const double z_error = k_bar == 0.0 ? q.load_error : q.penetration_error + q.load_error / k_bar;
        row.insert(row.end(), {k_bar, q.load, q.a_bar, q.penetration, z_error});
        spring_errors.push_back({q.load_error, q.a_bar_error, q.penetration_error});
      } else {
        const PulloffPoint& q = jkr_springs[k];
        const double z_error = k_bar == 0.0 ? tol * std::abs(q.load)
                                            : tol * (std::abs(q.penetration) + std::abs(q.load) / k_bar);
        row.insert(row.end(), {k_bar, q.load, q.a_bar, q.penetration, z_error});
        spring_errors.push_back({tol * std::abs(q.load), tol * q.a_bar, tol * std::abs(q.penetration)});
      }
      rows.push_back(std::move(row));
    }
  };
  std::size_t next = 0;
  for (double eta : etas) {
    for (double lambda : lambdas) {
      const std::string at = "eta=" + num(eta) + " lambda=" + num(lambda);
      if (std::isinf(lambda)) {
        const Pulloff p = jkr->pulloff(eta);
        std::vector<PulloffPoint> springs;
        for (double k_bar : k_bars) {
          const SpringPulloff sp = jkr->pulloff_spring(eta, k_bar);
          springs.push_back(sp.point);
          if (!std::isinf(k_bar) && k_bar != 0.0) {
            for (const auto& w : sp.warnings) notes.emplace_back("warning", w);
          }
        }
        add_rows({eta, lambda, p.load_control.load, p.load_control.a_bar, p.load_control.penetration, 1.0,
                  p.displacement_control.load, p.displacement_control.a_bar, p.displacement_control.penetration, 1.0,
                  tol * std::abs(p.load_control.load), tol * std::abs(p.displacement_control.penetration)},
                 springs, nullptr);
        extra_errors.push_back({tol * p.load_control.a_bar, tol * std::abs(p.load_control.penetration), 0.0,
                                tol * std::abs(p.displacement_control.load), tol * p.displacement_control.a_bar, 0.0});
        for (const auto& w : p.warnings) notes.emplace_back("warning", w);
        continue;
      }
      const std::size_t index = next++;
      const MaugisDugdalePulloff& p = md_results[index];
      const MaugisDugdalePoint& l = p.load_control.point;
      const MaugisDugdalePoint& d = p.displacement_control.point;
      add_rows({eta, lambda, l.load, l.a_bar, l.penetration, l.m, d.load, d.a_bar, d.penetration, d.m, l.load_error,
                d.penetration_error},
               {}, &md_springs[index]);
      extra_errors.push_back({l.a_bar_error, l.penetration_error, l.m_error, d.load_error, d.a_bar_error, d.m_error});
      for (const auto* c : {&p.load_control, &p.displacement_control}) {
        const bool load = c == &p.load_control;
        notes.emplace_back(std::string(load ? "load" : "displacement") + " control, " + at,
                           c->interior ? "stationary minimum of " + std::string(load ? "P" : "D") + " (contact radius > 0)"
                                       : "end of the curve a -> 0: the contact shrinks to a point at finite force "
                                         "(no vertical tangent); m = inf, c_bar = " + num(c->point.c_bar));
      }
      for (const auto& w : p.warnings) notes.emplace_back("warning", w);
    }
  }
  Header h{{"command", "pulloff"}};
  add_material_header(h, stack);
  h.emplace_back("normalization", kNormalization);
  h.emplace_back("Maugis-Dugdale", kMaugis);
  h.emplace_back("eta", join(etas));
  h.emplace_back("lambda", join(lambdas));
  h.emplace_back("solver", md_solver_text(md));
  h.emplace_back("location", "log grid of " + std::to_string(md.options().scan_points_per_decade) +
                                 " points per decade of a_bar and the end a -> 0; each grid minimum refined by "
                                 "Brent's minimiser in ln a_bar" +
                                 (direct ? ", then as the root of dP/da_bar (dD/da_bar) differentiated implicitly "
                                           "through c(a) (a_bar to ~1e-9, less where P is flat near DMT's end: "
                                           "*_err, the location's error included)"
                                 : md.table_in_closed_form()
                                     ? ", then as the root of the closed form's dP/da_bar (dD/da_bar) "
                                       "differentiated through m(a) (*_err: the error estimates of the pull-off's "
                                       "quantities, the location's rounding included; JKR rows: the tolerance "
                                       "times the value; m = inf at the curve's end: m_*_err 0)"
                                     : " to 1e-7 (*_err: the error estimates of the pull-off's quantities, "
                                       "the minimum's location included; JKR rows: the tolerance times the "
                                       "value; m = inf at the curve's end: m_*_err 0)"));
  if (!k_bars.empty()) {
    h.emplace_back("k_bar", join(k_bars));
    h.emplace_back("spring control",
                   "one row per (eta, lambda, k_bar): the jump where dP/dD = -k_bar, the minimum of Z = D + P/k_bar "
                   "along the curve or its end a -> 0 (THEORY.md sections 10 and 13); k_bar = 0 and inf are the load "
                   "and displacement values; Z_spring_err: the error estimate of Z");
  }
  for (auto& n : notes) h.push_back(std::move(n));
  write_pulloff_rows(os, h, !k_bars.empty(), rows, extra_errors, spring_errors);
}

std::vector<OptionSpec> cohesive_options() {
  return {
      {"--cohesive-stress", "sigma0",
       "Maugis-Dugdale zone: adhesive stress (Pa, or kPa MPa GPa); range h0 = w/sigma0 (not with --range)", false},
      {"--range", "h0",
       "Maugis-Dugdale zone: range of the adhesive stress (m, or mm um nm), at most 1e6 film thicknesses; "
       "sigma0 = w/h0 (not with --cohesive-stress)",
       false},
      md_direct_option(),
  };
}

std::optional<double> parse_cohesive_stress(const Arguments& args, const Stack& stack, double radius,
                                            double thickness, double work) {
  const auto stress = args.get("--cohesive-stress");
  const auto range = args.get("--range");
  if (!stress && !range) return std::nullopt;
  if (stress && range) throw InputError("--cohesive-stress and --range: give one of them, not both");
  const std::string option = stress ? "--cohesive-stress" : "--range";
  const double sigma0 = stress ? parse_quantity(*stress, Quantity::kPressure, option)
                               : work / parse_quantity(*range, Quantity::kLength, option);
  try {
    maugis_scales(radius, thickness, work, stack.reference_modulus(), sigma0);
  } catch (const InputError& e) {
    const std::string message = e.what();
    // eta out of range is reported by the sphere itself, naming the options behind eta.
    if (message.find("(eta = ") == std::string::npos) throw InputError(option + ": " + message);
  }
  return sigma0;
}

void write_md_sphere(std::ostream& os, const Stack& stack, double radius, double thickness, double work,
                     double sigma0, std::size_t points, const std::vector<double>& contact_radii, bool direct) {
  const MaugisScales scales = [&] {
    try {
      return maugis_scales(radius, thickness, work, stack.reference_modulus(), sigma0);
    } catch (const InputError& e) {
      throw InputError("--radius, --thickness, --work, --film: " + std::string(e.what()));
    }
  }();
  const double length = scales.length, eta = scales.eta, lambda = scales.lambda;
  const double penetration = scales.penetration, force = scales.force;
  const MaugisDugdaleModel md(stack, md_options(direct));
  const double r = stack.substrate_length_ratio();
  std::vector<double> a_bar;
  try {
    a_bar = scaled_contact_radii(contact_radii, scales);
  } catch (const InputError& e) {
    throw InputError("--contact-radius: " + std::string(e.what()));
  }
  if (a_bar.empty()) a_bar = log_spaced(0.01 * std::min(1.0, r), 10.0 * std::max(1.0, r), points);
  plan_md_work(md, eta, lambda, *std::max_element(a_bar.begin(), a_bar.end()),
               static_cast<double>(a_bar.size()) + kMdPulloffEvaluations, false,
               contact_radii.empty() ? "--points" : "--contact-radius");
  const std::vector<MaugisDugdalePoint> curve = md.curve(eta, lambda, a_bar);
  const MaugisDugdalePulloff p = md.pulloff(eta, lambda);
  const double to_maugis = std::cbrt(4.0 / 3.0);
  Header h{{"command", "sphere"}};
  h.emplace_back("sphere radius R [m]", num(radius));
  h.emplace_back("film thickness t [m]", num(thickness));
  h.emplace_back("work of adhesion w [J/m2]", num(work));
  add_material_header(h, stack);
  h.emplace_back("Maugis-Dugdale adhesive stress sigma0 [Pa]", num(sigma0));
  h.emplace_back("Maugis-Dugdale range h0 = w/sigma0 [m]", num(work / sigma0));
  h.emplace_back("lambda = 2 sigma0 (R/(pi w K^2))^(1/3), K = 4E1*/3", num(lambda));
  h.emplace_back("length scale (pi w R^2/E1*)^(1/3) [m]", num(length));
  h.emplace_back("Maugis length (pi w R^2/K)^(1/3) [m]; a_bar_M = (4/3)^(1/3) a_bar", num(length / to_maugis));
  h.emplace_back("penetration scale (pi^2 w^2 R/E1*^2)^(1/3) [m]", num(penetration));
  h.emplace_back("force scale pi w R [N]", num(force));
  h.emplace_back("eta = t/length scale", num(eta));
  for (const auto* c : {&p.load_control, &p.displacement_control}) {
    const std::string name = c == &p.load_control ? "load control" : "displacement control";
    h.emplace_back("pull-off force, " + name + " [N]", num(c->point.load * force));
    h.emplace_back("pull-off force error estimate, " + name + " [N]", num(c->point.load_error * force));
    h.emplace_back("pull-off contact radius, " + name + " [m]", num(c->point.a_bar * length));
    h.emplace_back("pull-off contact radius error estimate, " + name + " [m]", num(c->point.a_bar_error * length));
    h.emplace_back("pull-off a_bar_M, " + name, num(c->point.a_bar * to_maugis));
    h.emplace_back("pull-off penetration, " + name + " [m]", num(c->point.penetration * penetration));
    h.emplace_back("pull-off penetration error estimate, " + name + " [m]",
                   num(c->point.penetration_error * penetration));
    h.emplace_back("pull-off, " + name, c->interior ? "stationary minimum (contact radius > 0)"
                                                    : "end of the curve a -> 0 (no vertical tangent)");
  }
  h.emplace_back("normalized pull-off P (load, displacement)",
                 num(p.load_control.point.load) + ", " + num(p.displacement_control.point.load));
  h.emplace_back("end of the curve a -> 0", "F = " + num(p.curve_end.load * force) + " N, delta = " +
                                                num(p.curve_end.penetration * penetration) + " m, c = " +
                                                num(p.curve_end.c_bar * length) + " m");
  for (const auto& w : p.warnings) h.emplace_back("warning", si_pulloff_warning(w, length));
  h.emplace_back("solver", md_solver_text(md));
  std::vector<double> a_si, delta_si, force_si;
  for (const MaugisDugdalePoint& q : curve) {
    a_si.push_back(q.a_bar * length);
    delta_si.push_back(q.penetration * penetration);
    force_si.push_back(q.load * force);
  }
  ValidityLimits limits;
  limits.thickness = thickness;
  limits.modulus = scales.modulus;
  limits.sphere_radius = radius;
  progress_pause();
  for (const auto& w : validity_warnings(a_si, delta_si, force_si, limits)) {
    h.emplace_back("warning", w);
    std::cerr << "coatcontact sphere: warning: " << w << "\n";
  }
  h.emplace_back("delta_err_m, F_err_N", "error estimates of delta and F (the table's, or the direct solve's)");
  const std::vector<std::string> columns = {"a_m", "delta_m", "F_N", "c_m", "delta_err_m", "F_err_N"};
  write_header(os, h, columns);
  for (const MaugisDugdalePoint& q : curve) {
    write_row(os, {q.a_bar * length, q.penetration * penetration, q.load * force, q.c_bar * length,
                   q.penetration_error * penetration, q.load_error * force},
              columns);
  }
}

}  // namespace coatcontact::cli
