// Any axisymmetric indenter (THEORY.md section 11): the adhesion floor's ShapeContact, solved
// directly at every model radius (no interpolant; w enters only through delta_fp ~ sqrt(w), so
// dF/d ln w stays analytic, the other derivatives are central differences in ln p). The shape's
// own parameters (cone angle, tip radius, ...) are fixed.
#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/shape_contact.hpp"
#include "coatcontact/shape_solver.hpp"
#include "force_model.hpp"
#include "stack_cache.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

constexpr double kMinAOverT = kAOverTRange[0];
constexpr double kMaxAOverT = kAOverTRange[1];

// One stack: the shape floor's solver on it (no table, no interpolant).
using ShapeEntry = SolverEntry<ShapeSolver>;

class ShapeModel : public ForceModel {
 public:
  explicit ShapeModel(const Problem& problem) : problem_(problem), cache_(problem, cache_capacity(problem)) {}
  ModelAtData evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) override;
  std::vector<double> shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) override;
  std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double k) override {
    coatcontact::detail::GslHandlerOff handler_off;
    const ShapeJump s = contact_at(p.branch(true)).pulloff(k).spring;
    if (!s.interior) return std::nullopt;
    return std::array<double, 3>{s.radius, s.penetration, s.force};
  }
  long solver_calls() const override { return shape_calls_; }
  // delta0(a) = |delta|: the adhesionless radius of the largest penetration (bisection in ln a).
  double adhesionless_radius(double d) const override {
    const IndenterShape& shape = *problem_.shape;
    double lo = 1e-15, hi = std::min(1.0, shape.max_contact_radius());
    if (shape.flat() || shape.delta0(hi) <= d) return hi;
    for (int i = 0; i < 200 && hi / lo > 1.0 + 1e-9; ++i) {
      const double mid = std::sqrt(lo * hi);
      (shape.delta0(mid) < d ? lo : hi) = mid;
    }
    return hi;
  }
  // No sphere radius for the JKR estimate: the default w axis.
  double work_estimate(const Measurements&) const override { return 0.0; }

 private:
  ShapeContact contact_at(const Parameters& branch) {
    return ShapeContact(cache_.get(branch).solver(), problem_.shape, branch.total_thickness(), branch.work(),
                        problem_.solver_tolerance);
  }
  const Problem& problem_;
  StackCache<ShapeEntry> cache_;
  long shape_calls_ = 0;  // ShapeContact::at calls
};

}  // namespace

// F and delta from ShapeContact at each radius (THEORY.md sections 5, 11). At
// fixed a, F = F_H + S delta_fp and delta = delta_H + delta_fp with delta_fp ~ sqrt(w), so
// dF/d ln w = (F - F_H)/2 and d delta/d ln w = (delta - delta_H)/2 exactly; d/da along the
// curve is a central difference in ln a. delta,F data: a* >= a_c on the stable branch as for
// the sphere, a_c the displacement-controlled pull-off of ShapeContact::pulloff.
ModelAtData ShapeModel::evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) {
  const ShapeContact contact = contact_at(p);
  const double total_thickness = p.total_thickness();
  const std::size_t n = data.size();
  ModelAtData out = ModelAtData::zeros(n);  // force_lnt stays 0: t is differenced
  const auto check_radius = [&](double a) {
    const double x = a / total_thickness;
    if (!(x >= kMinAOverT && x <= kMaxAOverT)) {
      throw NumericalError("the model needs a/t = " + short_text(x) + ", outside [" + short_text(kMinAOverT) + ", " +
                           short_text(kMaxAOverT) + "]");
    }
    if (a > problem_.shape->max_contact_radius()) {
      throw NumericalError("the model needs a contact radius " + short_text(a) + " m beyond the shape's largest, " +
                           short_text(problem_.shape->max_contact_radius()) + " m");
    }
  };
  const auto at = [&](double a) {
    ++shape_calls_;
    return contact.at(a);
  };
  // dF/da and d delta/da along the curve (relative step kStep in a).
  const auto along = [&](double a) {
    const ShapePoint up = at(a * std::exp(kStep)), down = at(a * std::exp(-kStep));
    const double da = a * (std::exp(kStep) - std::exp(-kStep));
    return std::array<double, 2>{(up.force - down.force) / da, (up.penetration - down.penetration) / da};
  };
  const bool radius_data = data.kind == DataKind::kRadiusForce;
  const bool need_slope = !data.sigma_abscissa.empty();
  if (!radius_data || with_pulloff) {
    ShapePulloff pulloff;
    bool found = false;
    try {
      pulloff = contact.pulloff(0.0);
      found = true;
    } catch (const NumericalError&) {
      if (!radius_data) throw;
    }
    if (found) {
      if (pulloff.load.interior) {
        out.has_load_pulloff = true;
        out.load_pulloff_radius = pulloff.load.radius;
        out.load_pulloff_penetration = pulloff.load.penetration;
        out.load_pulloff_force = pulloff.load.force;
      }
      if (pulloff.displacement.interior) {
        out.has_pulloff = true;
        out.pulloff_radius = pulloff.displacement.radius;
        out.pulloff_penetration = pulloff.displacement.penetration;
        out.pulloff_force = pulloff.displacement.force;
      } else if (!radius_data) {
        throw NumericalError("delta(a) of the shape has no minimum for a in [" + short_text(pulloff.scan_min) + ", " +
                             short_text(pulloff.scan_max) + "] m (no displacement-controlled pull-off)");
      }
    }
  }
  if (radius_data) {
    for (std::size_t i = 0; i < n; ++i) check_radius(data.abscissa[i]);
    const std::vector<ShapePoint> points = contact.curve(data.abscissa);
    shape_calls_ += static_cast<long>(n);
    for (std::size_t i = 0; i < n; ++i) {
      out.radius[i] = points[i].radius;
      out.penetration[i] = points[i].penetration;
      out.force[i] = points[i].force;
      out.force_lnw[i] = (points[i].force - points[i].force_h) / 2.0;
      if (need_slope) out.force_x[i] = along(points[i].radius)[0];
    }
    return out;
  }
  const double a_c = out.pulloff_radius;
  const double delta_max = *std::max_element(data.abscissa.begin(), data.abscissa.end());
  std::vector<double> grid{a_c};
  std::vector<double> grid_delta{out.pulloff_penetration};
  while (grid_delta.back() < delta_max) {
    if (grid.size() > kMaxBracketSteps) {
      throw NumericalError("the model's delta(a) stays below the largest measured delta up to a = " +
                           short_text(grid.back()) + " m");
    }
    const double a = std::min(grid.back() * kBracketRatio, problem_.shape->max_contact_radius());
    if (!(a > grid.back())) throw NumericalError("the largest measured delta is beyond the shape's largest radius");
    check_radius(a);
    grid.push_back(a);
    grid_delta.push_back(at(a).penetration);
  }
  for (std::size_t i = 0; i < n; ++i) {
    const double delta = data.abscissa[i];
    double a = a_c;
    if (delta <= out.pulloff_penetration) {
      out.clamped[i] = true;
    } else {
      std::size_t k = 1;
      while (grid_delta[k] < delta) ++k;
      a = find_root([&](double r) { return at(r).penetration - delta; }, grid[k - 1], grid[k]);
    }
    const ShapePoint s = at(a);
    out.radius[i] = a;
    out.penetration[i] = s.penetration;
    out.force[i] = s.force;
    const double force_lnw = (s.force - s.force_h) / 2.0;
    const double penetration_lnw = (s.penetration - s.penetration_h) / 2.0;
    if (out.clamped[i]) {
      out.force_lnw[i] = force_lnw;
    } else {
      const auto d = along(a);
      out.slope[i] = d[0] / d[1];
      out.force_x[i] = out.slope[i];
      out.force_lnw[i] = force_lnw - out.slope[i] * penetration_lnw;
    }
  }
  return out;
}

// Direct solves at the model radii for q; at fixed measured delta the residual moves by
// dF - slope d delta.
std::vector<double> ShapeModel::shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) {
  const std::size_t n = m.radius.size();
  const ShapeContact load = contact_at(q.branch(false));
  const ShapeContact unload = contact_at(q.branch(true));
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    const bool unloading = q.hysteresis && data.unloading[i];
    const ShapePoint s = (unloading ? unload : load).at(m.radius[i]);
    ++shape_calls_;
    out[i] = s.force - m.slope[i] * s.penetration;
  }
  return out;
}

std::unique_ptr<ForceModel> make_shape_model(const Problem& problem) { return std::make_unique<ShapeModel>(problem); }

}  // namespace coatcontact::fit::internal
