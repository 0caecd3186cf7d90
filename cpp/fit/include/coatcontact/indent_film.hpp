// The film's modulus (or thickness) from an indentation test (THEORY.md section 16): the
// Oliver–Pharr stiffness and contact radius at each depth against the exact flat-punch
// stiffness of the stack, S = 2 beta a E_ref E_eq(a/t) (the paper's appendix [SecAppendix];
// sections 5, 9, 12), per depth (a root) and fitted over a depth range with its standard
// error; beside it the empirical film models of the literature, each from its published formula.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "coatcontact/oliver_pharr.hpp"
#include "coatcontact/point_status.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::indent {

enum class FilmModel {
  kExact,
  kDoernerNix,
  kKing,
  kSahaNix,
  kMencikLinear,
  kMencikExponential,
  kMencikReciprocal,
  kGao,
  kHayCrawford,
  kBec,
  kPerriotBarthel,
};
// Every model, the exact one first.
const std::vector<FilmModel>& film_models();
// "exact", "doerner-nix", "king", "saha-nix", "mencik-linear", "mencik-exponential",
// "mencik-reciprocal", "gao", "hay-crawford", "bec", "perriot-barthel".
const char* film_model_name(FilmModel model);
// InputError naming the value and the names allowed.
FilmModel film_model_from_name(const std::string& name);
// The models with an empirical constant alpha (Doerner–Nix, King, Saha–Nix, Menčík's exponentials).
bool film_model_has_alpha(FilmModel model);

// ---- the empirical models (plane-strain sample moduli E' = E/(1 - nu^2), in Pa) --------------

struct FilmGeometry {
  double thickness = 0.0;       // t [m]
  double contact_radius = 0.0;  // a [m]
  double contact_depth = 0.0;   // h_c [m]
};

struct EmpiricalConstants {
  double substrate_reduced = 0.0;  // E_s'
  double film_poisson = 0.0;       // nu_f (Gao's composite ratio, Hay–Crawford's shear moduli)
  double substrate_poisson = 0.0;  // nu_s
  double alpha = 1.0;              // the models with an alpha; ignored by the others
};

// The apparent E' of the composite for a film of E_f'. InputError for kExact; NumericalError
// outside a model's range (Menčík's linear law past a = t).
double empirical_apparent(FilmModel model, const FilmGeometry& geometry, double film_reduced,
                          const EmpiricalConstants& constants);
// Gao, Chiu & Lee's weights I0(xi; nu) and I1(xi), xi = t/a.
double gao_i0(double xi, double poisson);
double gao_i1(double xi);

// ---- the film analysis -------------------------------------------------------------------

enum class FilmUnknown { kModulus, kThickness };
enum class ContactDepth { kHalfSpace, kCoated };

struct FilmOptions {
  // The sample, top layer first; the top layer's Poisson ratio is the Oliver–Pharr one. With
  // kModulus the top layer's modulus is the unknown (its value here is not used); with
  // kThickness there is one layer whose thickness is the unknown (its value is not used).
  std::vector<Layer> layers;
  Substrate substrate;
  FilmUnknown unknown = FilmUnknown::kModulus;
  FilmModel model = FilmModel::kExact;
  double alpha = kNotGiven;                       // the empirical alpha; NaN: fitted over the range
  ContactDepth contact_depth = ContactDepth::kHalfSpace;
  double depth_min = kNotGiven, depth_max = kNotGiven;  // fit range [m]; NaN: the test's, else all
  std::size_t max_points = 200;                   // per-depth values at most at this many depths
  double tolerance = 1e-8;                        // of the reduced variables
};

struct FilmResult {
  FilmUnknown unknown = FilmUnknown::kModulus;
  FilmModel model = FilmModel::kExact;
  // Per depth (up to max_points of the Oliver–Pharr points, evenly spread):
  std::vector<double> depth, load, stiffness, contact_depth, contact_radius, a_over_t;
  std::vector<double> apparent_modulus;  // Oliver–Pharr E with the film's nu (the composite)
  std::vector<double> value, value_error;  // E1 [Pa] or t [m], and its error from the fit's scatter
  std::vector<char> in_range;
  std::vector<PointStatus> status;       // a point without a root: not delivered, value 0
  // Over the depth range (every Oliver–Pharr point in it):
  double mean = 0.0, mean_error = 0.0;   // the fitted E1 or t and its standard error
  std::size_t points = 0;
  double rms_relative = 0.0;             // s: RMS of the relative stiffness residual
  double alpha = kNotGiven;              // the empirical alpha used (fitted or given)
  double range_min = 0.0, range_max = 0.0;
};

// Oliver–Pharr (options: area, beta, epsilon, indenter, frame) with the top layer's Poisson
// ratio, then the film. InputError for a bad option (named); NumericalError when the fit over
// the range cannot be made (no delivered point in it).
FilmResult film(const IndentTest& test, const OliverPharrOptions& oliver_pharr, const FilmOptions& options);

// E_ref E_eq(a/t) of the stack with the top layer's modulus set to `top_modulus` [Pa]: the
// Oliver–Pharr E_r a film of that modulus shows at contact radius a (the synthetic data of the
// tests and the notebook).
double stack_contact_modulus(const FilmOptions& options, const Indenter& indenter, double top_modulus,
                             double a_over_t);

}  // namespace coatcontact::indent
