// Reduced-variable sources for tests only (never in the library): exact homogeneous values
// and smooth synthetic functions with analytic logarithmic derivatives.
#pragma once
#include <cmath>
#include <functional>
#include <vector>

#include "coatcontact/adhesion.hpp"
#include "coatcontact/contact.hpp"

namespace adhesive_test {

// Identical film and substrate: Pi_s = 8/3, Delta_s = 1, Pi_c = 2, Delta_c = E_eq = Gamma = 1
// at every a/t (THEORY.md section 5, homogeneous values).
class HomogeneousSource final : public coatcontact::ReducedSource {
 public:
  HomogeneousSource() {
    film_.youngs_modulus = 1e9;
    film_.poisson_ratio = 0.25;
    substrate_.material = film_;
    stack_ = coatcontact::Stack::film_on(film_, substrate_);
  }
  std::vector<coatcontact::ReducedVariables> evaluate(const std::vector<double>& a_over_t) const override {
    std::vector<coatcontact::ReducedVariables> out;
    for (double x : a_over_t) {
      coatcontact::ReducedVariables v;
      v.a_over_t = x;
      v.pi_s = 8.0 / 3.0;
      v.delta_s = 1.0;
      v.pi_c = 2.0;
      v.delta_c = 1.0;
      v.e_eq = 1.0;
      v.gamma1 = 1.0;
      out.push_back(v);
    }
    ++calls;
    return out;
  }
  const coatcontact::Stack& stack() const override { return stack_; }
  mutable int calls = 0;

 private:
  coatcontact::Material film_;
  coatcontact::Substrate substrate_;
  coatcontact::Stack stack_ = coatcontact::Stack::film_on(film_, substrate_);
};

// A smooth function of x = a/t and its log-derivative d ln f / d ln x.
struct Smooth {
  std::function<double(double)> f;
  std::function<double(double)> dlog;
};

// Sigmoid in ln x from `small` (x -> 0) to `large` (x -> inf): small + (large-small) z/(1+z),
// z = (x/x0)^n, like the Perriot-Barthel fit of E_eq (THEORY.md section 6).
inline Smooth sigmoid(double small, double large, double x0, double n) {
  Smooth s;
  s.f = [=](double x) {
    const double z = std::pow(x / x0, n);
    return small + (large - small) * z / (1.0 + z);
  };
  s.dlog = [=](double x) {
    const double z = std::pow(x / x0, n);
    const double f = small + (large - small) * z / (1.0 + z);
    return (large - small) * n * z / ((1.0 + z) * (1.0 + z)) / f;
  };
  return s;
}

inline Smooth constant(double c) { return {[=](double) { return c; }, [](double) { return 0.0; }}; }

// Synthetic source built from six smooth functions (no physics identity implied).
class SyntheticSource final : public coatcontact::ReducedSource {
 public:
  SyntheticSource(Smooth pi_s, Smooth delta_s, Smooth e_eq, Smooth gamma1, double modulus_ratio)
      : pi_s_(std::move(pi_s)), delta_s_(std::move(delta_s)), e_eq_(std::move(e_eq)), gamma1_(std::move(gamma1)) {
    film_.youngs_modulus = 1e9;
    film_.poisson_ratio = 0.25;
    substrate_.material.youngs_modulus = 1e9 / modulus_ratio;
    substrate_.material.poisson_ratio = 0.25;
    stack_ = coatcontact::Stack::film_on(film_, substrate_);
  }
  std::vector<coatcontact::ReducedVariables> evaluate(const std::vector<double>& a_over_t) const override {
    std::vector<coatcontact::ReducedVariables> out;
    for (double x : a_over_t) {
      coatcontact::ReducedVariables v;
      v.a_over_t = x;
      v.pi_s = pi_s_.f(x);
      v.delta_s = delta_s_.f(x);
      v.pi_c = 2.0 * delta_s_.f(x);
      v.delta_c = delta_s_.f(x);
      v.e_eq = e_eq_.f(x);
      v.gamma1 = gamma1_.f(x);
      out.push_back(v);
    }
    evaluations += a_over_t.size();
    return out;
  }
  const coatcontact::Stack& stack() const override { return stack_; }

  // Exact normalized curve and derivatives from the analytic functions (reference).
  double load(double eta, double a_bar) const {
    const double x = a_bar / eta;
    return a_bar * a_bar * a_bar * pi_s_.f(x) / 2 - 2 * std::sqrt(2.0) * std::pow(a_bar, 1.5) * e_eq_.f(x) / gamma1_.f(x);
  }
  double dload(double eta, double a_bar) const {
    const double x = a_bar / eta;
    const double h = a_bar * a_bar * a_bar * pi_s_.f(x) / 2;
    const double g = 2 * std::sqrt(2.0) * std::pow(a_bar, 1.5) * e_eq_.f(x) / gamma1_.f(x);
    return (h * (3 + pi_s_.dlog(x)) - g * (1.5 + e_eq_.dlog(x) - gamma1_.dlog(x))) / a_bar;
  }
  double penetration(double eta, double a_bar) const {
    const double x = a_bar / eta;
    return a_bar * a_bar * delta_s_.f(x) - std::sqrt(2.0 * a_bar) / gamma1_.f(x);
  }
  double dpenetration(double eta, double a_bar) const {
    const double x = a_bar / eta;
    const double h = a_bar * a_bar * delta_s_.f(x);
    const double g = std::sqrt(2.0 * a_bar) / gamma1_.f(x);
    return (h * (2 + delta_s_.dlog(x)) - g * (0.5 - gamma1_.dlog(x))) / a_bar;
  }
  const Smooth& pi_s() const { return pi_s_; }
  const Smooth& delta_s() const { return delta_s_; }
  const Smooth& e_eq() const { return e_eq_; }
  const Smooth& gamma1() const { return gamma1_; }
  mutable std::size_t evaluations = 0;

 private:
  Smooth pi_s_, delta_s_, e_eq_, gamma1_;
  coatcontact::Material film_;
  coatcontact::Substrate substrate_;
  coatcontact::Stack stack_ = coatcontact::Stack::film_on(film_, substrate_);
};

// Independent reference: zero of g in [lo, hi] by plain bisection (g(lo) < 0 < g(hi)).
inline double bisect(const std::function<double(double)>& g, double lo, double hi) {
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i) {
    const double mid = 0.5 * (lo + hi);
    (g(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

}  // namespace adhesive_test
