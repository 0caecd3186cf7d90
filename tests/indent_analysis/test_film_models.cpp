// The empirical film models (THEORY.md section 16, table of the empirical models): each equals
// its published formula, written out here from the papers, at three points; each gives the film
// for a thick film and the substrate for a thin one; a homogeneous sample is itself under every
// model; and the film analysis inverts a model's own data to its E_f.
#include <cmath>
#include <cstdio>

#include "../common/check.hpp"
#include "coatcontact/indent_film.hpp"
#include "synthetic_film.hpp"

using namespace coatcontact;
using namespace coatcontact::indent;

namespace {

constexpr double kPi = 3.14159265358979323846;
const double kEf = 70e9, kEs = 160e9, kNuF = 0.17, kNuS = 0.22, kAlpha = 0.7;

struct Point {
  double t, a, hc;
};
const Point kPoints[] = {{500e-9, 60e-9, 25e-9}, {500e-9, 250e-9, 100e-9}, {300e-9, 700e-9, 280e-9}};

EmpiricalConstants constants() {
  EmpiricalConstants c;
  c.substrate_reduced = kEs;
  c.film_poisson = kNuF;
  c.substrate_poisson = kNuS;
  c.alpha = kAlpha;
  return c;
}

// Gao, Chiu & Lee (1992), their weights with xi = t/a.
double i0(double xi, double nu) {
  return 2 / kPi * std::atan(xi) +
         ((1 - 2 * nu) * xi * std::log((1 + xi * xi) / (xi * xi)) - xi / (1 + xi * xi)) / (2 * kPi * (1 - nu));
}
double i1(double xi) { return 2 / kPi * std::atan(xi) + xi / kPi * std::log((1 + xi * xi) / (xi * xi)); }

double published(FilmModel m, const Point& p) {
  const double t = p.t, a = p.a, hc = p.hc, ef = kEf, es = kEs;
  switch (m) {
    case FilmModel::kDoernerNix: return 1 / (1 / ef + (1 / es - 1 / ef) * std::exp(-kAlpha * t / hc));
    case FilmModel::kKing: return 1 / (1 / ef + (1 / es - 1 / ef) * std::exp(-kAlpha * t / a));
    case FilmModel::kSahaNix: return 1 / (1 / ef + (1 / es - 1 / ef) * std::exp(-kAlpha * (t - hc) / a));
    case FilmModel::kMencikLinear: return ef + (es - ef) * (a / t);
    case FilmModel::kMencikExponential: return es + (ef - es) * std::exp(-kAlpha * a / t);
    case FilmModel::kMencikReciprocal: return 1 / (1 / es + (1 / ef - 1 / es) * std::exp(-kAlpha * a / t));
    case FilmModel::kGao: {
      const double nu = kNuS + (kNuF - kNuS) * i1(t / a);
      return es + (ef - es) * i0(t / a, nu);
    }
    case FilmModel::kHayCrawford: {
      const double muf = ef * (1 - kNuF * kNuF) / (2 * (1 + kNuF)), mus = es * (1 - kNuS * kNuS) / (2 * (1 + kNuS));
      const double w = i0(t / a, kNuF);
      const double mu = 1 / ((1 - w) / (mus + 0.0626 * w * muf) + w / muf);
      return 2 * mu * (1 + kNuF) / (1 - kNuF * kNuF);
    }
    case FilmModel::kBec:
      return 1 / (2 * a) / (t / ((kPi * a * a + 2 * t * a) * ef) + 1 / (2 * (a + 2 * t / kPi) * es));
    case FilmModel::kPerriotBarthel: {
      const double l = std::log10(es / ef), x0 = std::pow(10, -0.093 + 0.792 * l + 0.05 * l * l);
      return ef + (es - ef) / (1 + std::pow(x0 / (a / t), 1.27));
    }
    case FilmModel::kExact: break;
  }
  return 0;
}

void formulas() {
  for (FilmModel m : film_models()) {
    if (m == FilmModel::kExact) continue;
    for (const Point& p : kPoints) {
      if ((m == FilmModel::kMencikLinear && p.a > p.t) || (m == FilmModel::kSahaNix && p.hc >= p.t)) {
        check::throws<NumericalError>([&] { empirical_apparent(m, {p.t, p.a, p.hc}, kEf, constants()); }, {"holds for"});
        continue;
      }
      // A few operations of exp/log/atan/pow on each side, written differently: kMachine.
      check::close(empirical_apparent(m, {p.t, p.a, p.hc}, kEf, constants()), published(m, p), check::tier::kMachine,
                   std::string(film_model_name(m)) + " at a/t = " + std::to_string(p.a / p.t));
    }
  }
}

void limits() {
  for (FilmModel m : film_models()) {
    if (m == FilmModel::kExact) continue;
    const std::string name = film_model_name(m);
    const double thick = empirical_apparent(m, {1.0, 1e-6, 1e-7}, kEf, constants());
    check::close(thick, kEf, 1e-3, name + ": a thick film is the film (a/t = 1e-6)");
    if (m != FilmModel::kMencikLinear) {
      const double hc = m == FilmModel::kSahaNix ? 0.5 : 1e4;  // Saha–Nix: h_c < t; Doerner–Nix: h_c >> t
      const double thin = empirical_apparent(m, {1.0, 1e5, hc}, kEf, constants());
      // Hay–Crawford carry the substrate's shear modulus back to E' with the film's nu.
      const double want = m == FilmModel::kHayCrawford ? kEs * (1 - kNuS) / (1 - kNuF) : kEs;
      check::close(thin, want, 2e-2, name + ": a thin film is the substrate (a/t = 1e5)");
    } else {
      check::close(empirical_apparent(m, {1.0, 1.0, 0.3}, kEf, constants()), kEs, check::tier::kMachine,
                   name + ": the substrate at a = t");
    }
    EmpiricalConstants same = constants();
    same.substrate_reduced = kEf;
    same.substrate_poisson = kNuF;
    for (const Point& p : kPoints) {
      if (m == FilmModel::kMencikLinear && p.a > p.t) continue;
      const double e = empirical_apparent(m, {p.t, p.a, p.hc}, kEf, same);
      if (m == FilmModel::kHayCrawford)  // its F I0 mu_f term: off by at most F/4 = 1.6 %
        check::below(std::fabs(e / kEf - 1), 0.0626 / 4, name + ": a homogeneous sample within F/4");
      else
        check::close(e, kEf, check::tier::kMachine, name + ": a homogeneous sample is itself");
    }
  }
}

// Data made with a model's own formula, inverted by the film analysis with that model.
void inversion() {
  for (FilmModel m : {FilmModel::kBec, FilmModel::kGao, FilmModel::kHayCrawford, FilmModel::kPerriotBarthel,
                      FilmModel::kKing, FilmModel::kDoernerNix}) {
    IndentTest t;
    t.calibration.area.coefficients = {24.5};
    t.calibration.poisson = kNuF;
    const Indenter diamond_tip{false, diamond()};
    for (int i = 0; i < 12; ++i) {
      const double hc = 10e-9 + 20e-9 * i, area = 24.5 * hc * hc, a = std::sqrt(area / kPi);
      const double ep = empirical_apparent(m, {500e-9, a, hc}, kEf / (1 - kNuF * kNuF), [] {
        EmpiricalConstants c = constants();
        c.substrate_reduced = kEs / (1 - kNuS * kNuS);
        return c;
      }());
      const double er = reduced_of_sample(ep * (1 - kNuF * kNuF), kNuF, diamond_tip);
      const double s = 2 * a * er, p = 8e9 * area;
      t.depth.push_back(hc + 0.75 * p / s);
      t.load.push_back(p);
      t.stiffness.push_back(s);
    }
    FilmOptions o = synthetic::one_film(0, kNuF, 500e-9, kEs, kNuS);
    o.layers.front().material.youngs_modulus = 1.0;
    o.model = m;
    if (film_model_has_alpha(m)) o.alpha = kAlpha;
    const FilmResult r = film(t, OliverPharrOptions{}, o);
    for (double v : r.value) check::close(v, kEf, 1e-9, std::string(film_model_name(m)) + ": inverts its own data");
    check::close(r.mean, kEf, 1e-9, std::string(film_model_name(m)) + ": fit of its own data");
  }
  // alpha fitted when not given: the data's alpha comes back.
}

}  // namespace

int main() {
  formulas();
  limits();
  inversion();
  return check::exit_code();
}
