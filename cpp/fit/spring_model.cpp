// Base-displacement data through a spring (THEORY.md section 10): the abscissa of z,F data is
// z = delta + F/k of a sphere on a spring of stiffness k; the model's delta + F/k is matched to
// z on the branch stable under spring control (a >= the spring pull-off radius), and k is the
// last parameter ("k"), fitted or fixed. F and z together carry k: dz/dF = d delta/dF + 1/k.
#include <algorithm>
#include <cmath>
#include <memory>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"
#include "sphere_model.hpp"

namespace coatcontact::fit::internal {
namespace {

using coatcontact::detail::short_text;

class SpringModel : public SphereModel {
 public:
  using SphereModel::SphereModel;

  // k: at fixed a, z moves by d(F/k)/d ln k = -F/k; at fixed measured z the residual moves by
  // -slope times that (0 at clamped points, where a = a_c).
  std::optional<std::vector<double>> analytic_column(const Parameters& p, const ModelAtData& m, const Measurements& data,
                                                     std::size_t parameter) const override {
    if (parameter + 1 != p.values.size()) return SphereModel::analytic_column(p, m, data, parameter);
    std::vector<double> column(m.radius.size(), 0.0);
    for (std::size_t i = 0; i < column.size(); ++i) {
      column[i] = m.clamped[i] ? 0.0 : m.slope[i] * m.force[i] / p.stiffness();
    }
    return column;
  }

  // The pull-off through the spring the data were taken through: the fitted (or fixed) k.
  double reported_spring(const Parameters& p, double) const override { return p.values.back(); }

  // Within kSearchSpringFactor of its hint.
  void add_search_axes(const Parameters& hint, const std::vector<int>& free_index,
                       std::vector<SearchAxis>& axes) const override {
    const int last = static_cast<int>(hint.values.size() - 1);
    if (std::find(free_index.begin(), free_index.end(), last) == free_index.end()) return;
    const double k = hint.stiffness();
    axes.push_back({hint.values.size() - 1, log_axis(k / kSearchSpringFactor, k * kSearchSpringFactor, kCoarsePointsPerDecade)});
  }

 protected:
  double compliance(const Parameters& p) const override { return 1.0 / p.stiffness(); }
  double shifted_abscissa(const SiPoint& s, const Parameters& q) const override {
    return s.penetration + s.force / q.stiffness();
  }
  // z = delta + F/k: the branch stable under spring control starts at the spring's pull-off.
  std::array<double, 2> branch_start(const ContactModel& cm, const Parameters& p, const Pulloff&,
                                     const ModelAtData&) const override {
    const double k_bar = p.stiffness() * cm.contact().penetration_scale() / cm.contact().force_scale();
    const SpringPulloff s = cm.contact().model().pulloff_spring(cm.contact().eta(), k_bar);
    if (!s.point.interior) {
      throw NumericalError("delta + F/k has no minimum in the scanned range at k = " + short_text(p.stiffness()) +
                           " N/m (no spring-controlled pull-off)");
    }
    const double radius = s.point.a_bar * cm.contact().length_scale();
    const double force = s.point.load * cm.contact().force_scale();
    return {radius, s.point.penetration * cm.contact().penetration_scale() + force / p.stiffness()};
  }
};

}  // namespace

std::unique_ptr<ForceModel> make_spring_model(const Problem& problem) { return std::make_unique<SpringModel>(problem); }

}  // namespace coatcontact::fit::internal
