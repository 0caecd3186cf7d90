// Physics-aware checks of the CLI (see checks.hpp).
#include "checks.hpp"

#include <algorithm>
#include <ctime>
#include <cmath>
#include <cstdlib>
#include <regex>
#include <sstream>
#include <thread>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::cli {
namespace {

std::string show(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

// Solver evaluations per decade of a/t in the interpolation table (TableOptions::order + 1).
constexpr double kEvaluationsPerDecade = 25.0;

}  // namespace

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

double plan_table_work(const ReducedSolver& solver, double tolerance, double a_over_t_min,
                       double a_over_t_max, const std::string& options, bool points_may_fail) {
  double total = 0.0, slowest = 0.0;
  int ends_failed = 0;
  std::string first_failure;
  for (double a : {a_over_t_min, a_over_t_max}) {
    const double start = thread_cpu_seconds();
    try {
      solver.solve(a, tolerance);
    } catch (const NumericalError& e) {
      const std::string refusal =
          options + ": the solver cannot reach the tolerance " + show(tolerance) + " at a/t = " + show(a) +
          " (an end of the a/t range this request needs), so the run would fail after building the whole "
          "table; allowed: a larger --tol, or parameters needing a/t closer to 1 (solver: " + e.what() + ")";
      // Points delivered one by one: one end's points fail alone; both ends failing is refused
      // as before (the run would deliver next to nothing after all the work).
      if (!points_may_fail || (++ends_failed == 2 || a_over_t_min == a_over_t_max)) {
        throw InputError(first_failure.empty() ? refusal : first_failure);
      }
      first_failure = refusal;
    } catch (const InputError& e) {
      throw InputError(options + ": " + e.what());
    }
    const double seconds = thread_cpu_seconds() - start;
    total += seconds;
    slowest = std::max(slowest, seconds);
  }
  const double decades = std::max(1.0, std::ceil(std::log10(a_over_t_max / a_over_t_min)) + 1.0);
  // Mean of the two ends per node, nodes solved in parallel (ReducedSolver::sweep).
  const double threads = std::max(1u, std::thread::hardware_concurrency());
  const double estimate = 0.5 * total * kEvaluationsPerDecade * decades / threads;
  if (estimate > kMaxWorkSeconds) {
    throw InputError(options + ": estimated run time " + show(std::round(estimate)) + " s (" + show(decades) +
                     " decades of a/t, up to " + show(slowest) + " s per solve) is over the limit of " +
                     show(kMaxWorkSeconds) + " s; allowed: a larger --tol or a narrower range");
  }
  progress_set_estimate(estimate);
  return estimate;
}

void plan_md_work(const MaugisDugdaleModel& md, double eta, double lambda, double a_bar, double evaluations,
                  bool parallel, const std::string& options) {
  // The first solve also builds the kernel table: time the second.
  double start = thread_cpu_seconds();
  try {
    md.point(eta, lambda, a_bar);
    start = thread_cpu_seconds();
    md.point(eta, lambda, 0.999 * a_bar);
  } catch (const NumericalError&) {
    return;  // the run itself reports the point it cannot solve
  }
  const double seconds = thread_cpu_seconds() - start;
  const double threads = parallel ? std::max(1u, std::thread::hardware_concurrency()) : 1.0;
  const double estimate = seconds * evaluations / threads;
  if (estimate > kMaxWorkSeconds) {
    throw InputError(options + ": estimated run time " + show(std::round(estimate)) + " s (" + show(evaluations) +
                     " Maugis-Dugdale solves at ~" + show(seconds) + " s each) is over the limit of " +
                     show(kMaxWorkSeconds) + " s; allowed: fewer values or points");
  }
  progress_set_estimate(estimate);
}

std::vector<double> sphere_default_a_bar(const AdhesiveModel& model, const Contact& sphere, double lo, double hi,
                                         double reach, std::size_t points) {
  // Scan 32 points per decade for the first a_bar past a limit; the curve then ends below it.
  const ValidityLimits limits = sphere.validity_limits();
  const double l = sphere.length_scale();
  const std::size_t scan = std::max<std::size_t>(8, static_cast<std::size_t>(32 * std::log10(hi / lo)));
  double last_inside = 0.0;
  for (std::size_t k = 0; k < scan; ++k) {
    const double a_bar = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(scan - 1));
    const CurvePoint p = model.point(sphere.eta(), a_bar);
    if (!within_validity(a_bar * l, p.penetration * sphere.penetration_scale(), p.load * sphere.force_scale(),
                         limits)) {
      break;
    }
    last_inside = a_bar;
  }
  if (last_inside > lo) hi = std::min(hi, std::max(last_inside, reach));
  std::vector<double> v(points);
  for (std::size_t k = 0; k < points; ++k) {
    v[k] = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(points - 1));
  }
  v.back() = hi;
  return v;
}

std::vector<double> contact_default_radii(const ShapeContact& contact, double lo, double hi, double reach,
                                          std::size_t points, double sphere_radius) {
  const ValidityLimits limits = contact.validity_limits(sphere_radius);
  const std::size_t scan = std::max<std::size_t>(8, static_cast<std::size_t>(16 * std::log10(hi / lo)));
  double last_inside = 0.0;
  for (std::size_t k = 0; k < scan; ++k) {
    const double a = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(scan - 1));
    try {
      const ShapePoint p = contact.at(a);
      if (!within_validity(a, p.penetration, p.force, limits)) break;
    } catch (const NumericalError&) {
      break;  // the run itself reports the points it cannot solve
    }
    last_inside = a;
  }
  if (last_inside > lo) hi = std::min(hi, std::max(last_inside, reach));
  std::vector<double> v(points);
  for (std::size_t k = 0; k < points; ++k) {
    v[k] = lo * std::pow(hi / lo, static_cast<double>(k) / static_cast<double>(points - 1));
  }
  v.back() = hi;
  return v;
}

JkrReference jkr_reference(double modulus, double radius, double work, double a_min, double a_max,
                           std::size_t points) {
  JkrReference r;
  const double pi = std::acos(-1.0);
  for (std::size_t k = 0; k < points; ++k) {
    const double a = a_min * std::pow(a_max / a_min, static_cast<double>(k) / static_cast<double>(points - 1));
    r.a.push_back(a);
    r.delta.push_back(a * a / radius - std::sqrt(2.0 * pi * a * work / modulus));
    r.force.push_back(4.0 * modulus * a * a * a / (3.0 * radius) - std::sqrt(8.0 * pi * work * modulus * a * a * a));
  }
  r.pulloff_load = -1.5 * pi * work * radius;
  r.pulloff_disp = -5.0 / 6.0 * pi * work * radius;
  return r;
}

JkrReference jkr_reference(double modulus, double radius, double work, const std::vector<double>& radii,
                           std::size_t points) {
  const auto [lo, hi] = std::minmax_element(radii.begin(), radii.end());
  return jkr_reference(modulus, radius, work, *lo, *hi, points);
}

std::pair<std::string, std::string> jkr_reference_header(const JkrReference& jkr) {
  return {"JKR reference pull-off, load and displacement control [N] (homogeneous film: -3/2 and -5/6 pi w R, "
          "THEORY.md section 5)",
          format_parameter(jkr.pulloff_load, "JKR pull-off") + ", " + format_parameter(jkr.pulloff_disp, "JKR pull-off")};
}

void check_fit_columns(const std::string& columns, const std::vector<std::string>& declared, int declared_line,
                       const std::string& data_path) {
  // --columns against the file's own "# columns:" line (only names this program knows).
  if (declared.size() != 2) return;
  const auto known = [](const std::string& n) { return n == "a" || n == "delta" || n == "F"; };
  if (!known(declared[0]) || !known(declared[1])) return;
  const std::string pair = declared[0] + "," + declared[1];
  if (pair != columns) {
    throw InputError("--columns: '" + columns + "' does not match the data file's column line '# columns: " +
                     declared[0] + " " + declared[1] + "' (" + short_name(data_path) + ":" + std::to_string(declared_line) +
                     "); allowed: --columns " + pair);
  }
}

std::string si_pulloff_warning(const std::string& warning, double length) {
  static const std::regex prefix("^eta=[^:,]*(, k_bar=[^:]*)?: ");
  static const std::regex range("a_bar \\[([^,\\]]+), ([^\\]]+)\\]");
  static const std::regex value("a_bar=([-+0-9.eE]+)");
  const auto si = [&](const std::string& reduced) {
    char* end = nullptr;
    const double v = std::strtod(reduced.c_str(), &end);
    return end != reduced.c_str() && *end == '\0' ? detail::short_text(v * length) : "(" + reduced + ") x " + detail::short_text(length);
  };
  std::string text = std::regex_replace(warning, prefix, "");
  std::string out;
  std::smatch m;
  while (std::regex_search(text, m, range)) {
    out += m.prefix().str() + "contact radii [" + si(m[1]) + ", " + si(m[2]) + "] m (" + m[0].str() + ")";
    text = m.suffix();
  }
  text = out + text;
  out.clear();
  while (std::regex_search(text, m, value)) {
    out += m.prefix().str() + "a = " + si(m[1]) + " m (" + m[0].str() + ")";
    text = m.suffix();
  }
  return out + text;
}

}  // namespace coatcontact::cli
