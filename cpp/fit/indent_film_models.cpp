// The empirical film models, each from its published formula (THEORY.md section 16, table of
// the empirical models, with the sources). Sample moduli are plane-strain, E' = E/(1 - nu^2).
#include <cmath>
#include <string>

#include "coatcontact/errors.hpp"
#include "coatcontact/indent_film.hpp"

namespace coatcontact::indent {
namespace {

constexpr double kPi = 3.14159265358979323846;

struct Named {
  FilmModel model;
  const char* name;
};
constexpr Named kNames[] = {
    {FilmModel::kExact, "exact"},
    {FilmModel::kDoernerNix, "doerner-nix"},
    {FilmModel::kKing, "king"},
    {FilmModel::kSahaNix, "saha-nix"},
    {FilmModel::kMencikLinear, "mencik-linear"},
    {FilmModel::kMencikExponential, "mencik-exponential"},
    {FilmModel::kMencikReciprocal, "mencik-reciprocal"},
    {FilmModel::kGao, "gao"},
    {FilmModel::kHayCrawford, "hay-crawford"},
    {FilmModel::kBec, "bec"},
    {FilmModel::kPerriotBarthel, "perriot-barthel"},
};

// 1/E' = 1/E_f' + (1/E_s' - 1/E_f') w: the compliance mixtures of Doerner–Nix and its variants.
double compliance_mix(double ef, double es, double w) { return 1.0 / (1.0 / ef + (1.0 / es - 1.0 / ef) * w); }

// Hay & Crawford (2011): shear moduli weighted with Gao's I0 (film's nu), F = 0.0626.
double hay_crawford(double ef_reduced, double xi, const EmpiricalConstants& c) {
  const double nf = c.film_poisson, ns = c.substrate_poisson;
  const double mu_f = ef_reduced * (1.0 - nf * nf) / (2.0 * (1.0 + nf));
  const double mu_s = c.substrate_reduced * (1.0 - ns * ns) / (2.0 * (1.0 + ns));
  const double i0 = gao_i0(xi, nf), f = 0.0626;
  const double mu = 1.0 / ((1.0 - i0) / (mu_s + f * i0 * mu_f) + i0 / mu_f);
  return 2.0 * mu * (1.0 + nf) / (1.0 - nf * nf);
}

}  // namespace

const std::vector<FilmModel>& film_models() {
  static const std::vector<FilmModel> all = [] {
    std::vector<FilmModel> v;
    for (const auto& n : kNames) v.push_back(n.model);
    return v;
  }();
  return all;
}

const char* film_model_name(FilmModel model) {
  for (const auto& n : kNames)
    if (n.model == model) return n.name;
  return "?";
}

FilmModel film_model_from_name(const std::string& name) {
  std::string allowed;
  for (const auto& n : kNames) {
    if (name == n.name) return n.model;
    allowed += std::string(allowed.empty() ? "" : ", ") + n.name;
  }
  throw InputError("model = '" + name + "' is not known; allowed: " + allowed);
}

bool film_model_has_alpha(FilmModel model) {
  return model == FilmModel::kDoernerNix || model == FilmModel::kKing || model == FilmModel::kSahaNix ||
         model == FilmModel::kMencikExponential || model == FilmModel::kMencikReciprocal;
}

// xi ln((1 + xi^2)/xi^2) = xi log1p(1/xi^2): finite for every xi > 0.
double gao_i0(double xi, double nu) {
  const double l = xi * std::log1p(1.0 / (xi * xi));
  return 2.0 / kPi * std::atan(xi) + ((1.0 - 2.0 * nu) * l - xi / (1.0 + xi * xi)) / (2.0 * kPi * (1.0 - nu));
}

double gao_i1(double xi) { return 2.0 / kPi * std::atan(xi) + xi / kPi * std::log1p(1.0 / (xi * xi)); }

double empirical_apparent(FilmModel model, const FilmGeometry& g, double ef, const EmpiricalConstants& c) {
  const double t = g.thickness, a = g.contact_radius, hc = g.contact_depth, es = c.substrate_reduced;
  switch (model) {
    case FilmModel::kDoernerNix:  // Doerner & Nix (1986)
      return compliance_mix(ef, es, std::exp(-c.alpha * t / hc));
    case FilmModel::kKing:  // King (1987)
      return compliance_mix(ef, es, std::exp(-c.alpha * t / a));
    case FilmModel::kSahaNix:  // Saha & Nix (2002): the film left under the tip, t - h_c > 0
      if (hc >= t) throw NumericalError("saha-nix holds for h_c < t only (h_c/t = " + std::to_string(hc / t) + ")");
      return compliance_mix(ef, es, std::exp(-c.alpha * (t - hc) / a));
    case FilmModel::kMencikLinear:  // Menčík et al. (1997)
      if (a > t) throw NumericalError("mencik-linear holds for a <= t only (a/t = " + std::to_string(a / t) + ")");
      return ef + (es - ef) * a / t;
    case FilmModel::kMencikExponential:
      return es + (ef - es) * std::exp(-c.alpha * a / t);
    case FilmModel::kMencikReciprocal:
      return 1.0 / (1.0 / es + (1.0 / ef - 1.0 / es) * std::exp(-c.alpha * a / t));
    case FilmModel::kGao: {  // Gao, Chiu & Lee (1992): composite nu from I1 inside I0
      const double xi = t / a;
      const double nu = c.substrate_poisson + (c.film_poisson - c.substrate_poisson) * gao_i1(xi);
      return es + (ef - es) * gao_i0(xi, nu);
    }
    case FilmModel::kHayCrawford:  // Hay & Crawford (2011)
      return hay_crawford(ef, t / a, c);
    case FilmModel::kBec:  // Bec, Tonck & Loubet (2006): film and substrate springs in series
      return 1.0 / (2.0 * a * (t / ((kPi * a * a + 2.0 * t * a) * ef) + 1.0 / (2.0 * (a + 2.0 * t / kPi) * es)));
    case FilmModel::kPerriotBarthel: {  // Perriot & Barthel (2004), written so a/t -> 0 is the film
      const double l = std::log10(es / ef);
      const double x0 = std::pow(10.0, -0.093 + 0.792 * l + 0.05 * l * l);
      return es + (ef - es) / (1.0 + std::pow(a / t / x0, 1.27));
    }
    case FilmModel::kExact:
      break;
  }
  throw InputError("empirical_apparent: the exact model is the stack's E_eq, not a formula");
}

}  // namespace coatcontact::indent
