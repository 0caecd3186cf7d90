// Loading and unloading with their own adhesion energy (JKR hysteresis): the loading rows
// (Measurements::unloading false) take w_load (the parameter vector's w), the unloading rows
// w_unload (after the moduli). Any force model that takes one w evaluates each branch; the
// pull-offs are the unloading branch's.
#include <algorithm>
#include <memory>
#include <utility>

#include "force_model.hpp"

namespace coatcontact::fit::internal {
namespace {

class BranchModel : public ForceModel {
 public:
  explicit BranchModel(std::unique_ptr<ForceModel> inner) : inner_(std::move(inner)) {}

  // Each branch's points with their own w, merged back into the data's order.
  ModelAtData evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) override {
    const std::size_t n = data.size();
    ModelAtData out = ModelAtData::zeros(n);
    for (const bool unloading : {false, true}) {
      Measurements part;
      part.kind = data.kind;
      std::vector<std::size_t> index;
      for (std::size_t i = 0; i < n; ++i) {
        if (data.unloading[i] != unloading) continue;
        index.push_back(i);
        part.abscissa.push_back(data.abscissa[i]);
        part.force.push_back(data.force[i]);
      }
      if (index.empty()) continue;
      const ModelAtData m = inner_->evaluate(p.branch(unloading), part, unloading && with_pulloff);
      for (std::size_t k = 0; k < index.size(); ++k) {
        const std::size_t i = index[k];
        out.radius[i] = m.radius[k];
        out.penetration[i] = m.penetration[k];
        out.force[i] = m.force[k];
        out.force_lnw[i] = m.force_lnw[k];
        out.force_lnt[i] = m.force_lnt[k];
        out.slope[i] = m.slope[k];
        out.force_x[i] = m.force_x[k];
        out.clamped[i] = m.clamped[k];
      }
      if (unloading) copy_pulloffs(m, out);
    }
    return out;
  }

  // Each adhesion energy moves only the points of its own branch.
  std::optional<std::vector<double>> analytic_column(const Parameters& p, const ModelAtData& m, const Measurements& data,
                                                     std::size_t parameter) const override {
    const bool is_unload_work = parameter == unload_work_index(p.layers);
    if (parameter != static_cast<std::size_t>(kWork) && !is_unload_work) {
      return inner_->analytic_column(p, m, data, parameter);
    }
    std::vector<double> column = m.force_lnw;
    for (std::size_t i = 0; i < column.size(); ++i) {
      if (data.unloading[i] != is_unload_work) column[i] = 0.0;
    }
    return column;
  }

  std::vector<double> shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) override {
    return inner_->shifted_force(q, m, data);
  }
  std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double k) override {
    return inner_->spring_pulloff(p, k);
  }
  double reported_spring(const Parameters& p, double given) const override { return inner_->reported_spring(p, given); }
  double interpolation_error(const Parameters& p, const ModelAtData& m, const Measurements& data) override {
    return inner_->interpolation_error(p, m, data);
  }
  long solver_calls() const override { return inner_->solver_calls(); }
  double adhesionless_radius(double penetration) const override { return inner_->adhesionless_radius(penetration); }
  bool work_separates() const override { return inner_->work_separates(); }
  double work_estimate(const Measurements& data) const override { return inner_->work_estimate(data); }
  std::vector<std::size_t> work_parameters(const Parameters& hint) const override {
    return {static_cast<std::size_t>(kWork), unload_work_index(hint.layers)};
  }
  std::vector<std::size_t> work_parameter_of_points(const Parameters& hint, const Measurements& data) const override {
    std::vector<std::size_t> out(data.size(), static_cast<std::size_t>(kWork));
    for (std::size_t i = 0; i < data.size(); ++i) {
      if (data.unloading[i]) out[i] = unload_work_index(hint.layers);
    }
    return out;
  }
  void add_search_axes(const Parameters& hint, const std::vector<int>& free_index,
                       std::vector<SearchAxis>& axes) const override {
    inner_->add_search_axes(hint, free_index, axes);
  }

 private:
  static void copy_pulloffs(const ModelAtData& m, ModelAtData& out) {
    out.has_pulloff = m.has_pulloff;
    out.pulloff_radius = m.pulloff_radius;
    out.pulloff_penetration = m.pulloff_penetration;
    out.pulloff_force = m.pulloff_force;
    out.has_load_pulloff = m.has_load_pulloff;
    out.load_pulloff_radius = m.load_pulloff_radius;
    out.load_pulloff_penetration = m.load_pulloff_penetration;
    out.load_pulloff_force = m.load_pulloff_force;
  }

  std::unique_ptr<ForceModel> inner_;
};

}  // namespace

std::unique_ptr<ForceModel> make_branch_model(std::unique_ptr<ForceModel> inner) {
  return std::make_unique<BranchModel>(std::move(inner));
}

}  // namespace coatcontact::fit::internal
