// The sphere through the reduced interpolant (private to the fit floor): THEORY.md section 5 by
// the adhesion floor (ReducedTable, JkrLaw, Contact), the stable branch of delta,F data, and the
// hooks through which base-displacement data (spring_model.cpp) move the abscissa to
// z = delta + F/k.
#pragma once
#include <array>
#include <memory>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"
#include "coatcontact/reduced.hpp"
#include "force_model.hpp"
#include "stack_cache.hpp"

namespace coatcontact::fit::internal {

// One stack: its solver and the adhesive model (SolverSource + ReducedTable) on it.
class SphereEntry {
 public:
  SphereEntry(const Problem& problem, const StackKey& key);
  const AdhesiveModel& model() const { return *model_; }
  const ReducedSolver& solver() const { return *solver_; }
  const StackKey& key() const { return key_; }
  long source_evaluations() const { return static_cast<long>(model_->table().source_evaluations()); }

 private:
  StackKey key_;
  std::unique_ptr<ReducedSolver> solver_;  // declared first: the model keeps a reference
  std::unique_ptr<AdhesiveModel> model_;
};

// F and delta at contact radius a (SI) with their derivatives: along the curve (d/da at
// fixed parameters) and with respect to ln w and ln t at fixed a.
struct SiPoint {
  double radius = 0.0, force = 0.0, penetration = 0.0;
  double force_a = 0.0, penetration_a = 0.0;
  double force_lnw = 0.0, penetration_lnw = 0.0;
  double force_lnt = 0.0, penetration_lnt = 0.0;
};

// The contact for one parameter set: a Contact (which owns the Maugis scales) on the model
// of the parameters' E1.
class ContactModel {
 public:
  ContactModel(const AdhesiveModel& model, double sphere_radius, const Parameters& p);
  SiPoint at(double radius) const;
  // F and delta from reduced variables solved directly (no interpolation).
  SiPoint exact(const ReducedVariables& v, double radius) const;
  const Contact& contact() const { return contact_; }
  void prepare(double radius_min, double radius_max) const;
  void prepare_pulloff() const;  // the decades of AdhesiveModel's pull-off scan, in one batch

 private:
  SiPoint to_si(const coatcontact::CurvePoint& full, const coatcontact::CurvePoint& fixed_x) const;
  const AdhesiveModel& model_;
  double total_thickness_;  // T [m], the unit length
  Contact contact_;
};

class SphereModel : public ForceModel {
 public:
  explicit SphereModel(const Problem& problem);
  ModelAtData evaluate(const Parameters& p, const Measurements& data, bool with_pulloff) override;
  std::optional<std::vector<double>> analytic_column(const Parameters& p, const ModelAtData& m, const Measurements& data,
                                                     std::size_t parameter) const override;
  std::vector<double> shifted_force(const Parameters& q, const ModelAtData& m, const Measurements& data) override;
  std::optional<std::array<double, 3>> spring_pulloff(const Parameters& p, double k) override;
  double interpolation_error(const Parameters& p, const ModelAtData& m, const Measurements& data) override;
  long solver_calls() const override { return cache_.solver_calls() + check_calls_; }
  double adhesionless_radius(double penetration) const override;
  double work_estimate(const Measurements& data) const override;

 protected:
  // The abscissa of delta,F data is delta + compliance F (0 here; 1/k for z,F data).
  virtual double compliance(const Parameters& p) const;
  // x of a point at shifted parameters (shifted_force): delta here, delta + F/k for z,F data.
  virtual double shifted_abscissa(const SiPoint& s, const Parameters& q) const;
  // {a, x} where the branch of delta,F data starts: the displacement-controlled pull-off (the
  // spring's for z,F data). NumericalError when there is none.
  virtual std::array<double, 2> branch_start(const ContactModel& cm, const Parameters& p, const Pulloff& pulloff,
                                             const ModelAtData& out) const;
  const Problem& problem_;

 private:
  // The pull-offs into `out`; the start of the delta,F branch.
  std::array<double, 2> pulloffs(const ContactModel& cm, const Parameters& p, bool radius_data, ModelAtData& out) const;
  // Each measured x at a* >= a_c on the stable branch (fit.hpp).
  void invert(const ContactModel& cm, const Parameters& p, const Measurements& data, std::array<double, 2> start,
              ModelAtData& out) const;
  StackCache<SphereEntry> cache_;
  long check_calls_ = 0;
};

}  // namespace coatcontact::fit::internal
