// The shared tabled coated force laws of the AFM fits (afm_internal.hpp; THEORY.md section 15,
// "Tabled coated force laws").
#include <cmath>
#include <map>
#include <mutex>
#include <string>
#include <tuple>

#include "afm_internal.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::fit::internal {

namespace {

// nu1, the substrate, the solver's tolerance; a multi-layer stack adds its free layer and, per
// layer, h_i/T, E_i (0 for the free one), nu_i and its bonding.
using Key = std::tuple<double, bool, double, double, double, std::vector<double>>;
std::mutex tables_mutex;
std::map<Key, std::shared_ptr<const CoatedTable>>& tables() {
  static std::map<Key, std::shared_ptr<const CoatedTable>> all;
  return all;
}

}  // namespace

std::vector<double> afm_stack_shape(const AfmCoating& coating) {
  std::vector<double> shape;
  if (coating.layers.empty()) return shape;
  const Stack stack = coating.stack();
  const double total = stack.total_thickness();
  shape.push_back(static_cast<double>(coating.free_layer));
  for (std::size_t i = 0; i < stack.layers().size(); ++i) {
    const Layer& l = stack.layers()[i];
    shape.insert(shape.end(), {l.thickness / total, i == coating.free_layer ? 0.0 : l.material.youngs_modulus,
                               l.material.poisson_ratio, l.slip_below ? 1.0 : 0.0});
  }
  return shape;
}

std::shared_ptr<const CoatedTable> afm_coated_table(const AfmCoating& coating) {
  const Substrate& s = coating.substrate;
  const Key key{coating.film.poisson_ratio, s.rigid, s.rigid ? 0.0 : s.material.youngs_modulus,
                s.rigid ? 0.0 : s.material.poisson_ratio, coating.solver_tolerance, afm_stack_shape(coating)};
  const std::lock_guard<std::mutex> lock(tables_mutex);
  auto& all = tables();
  auto it = all.find(key);
  if (it != all.end()) return it->second;
  if (all.size() >= 16) all.clear();  // the fits holding one keep it
  CoatedTableOptions options;
  options.a_over_t_min = kCoatingAOverT[0];
  options.a_over_t_max = kCoatingAOverT[1];
  options.solver_tolerance = coating.solver_tolerance;
  auto table = std::make_shared<const CoatedTable>(coating.stack(), coating.layers.empty() ? 0 : coating.free_layer, options);
  all.emplace(key, table);
  return table;
}

void afm_clear_coated_tables() {
  const std::lock_guard<std::mutex> lock(tables_mutex);
  tables().clear();
}

void check_afm_coating(const AfmFitProblem& problem) {
  if (!problem.coating || problem.coating->layers.empty()) return;
  const AfmCoating& c = *problem.coating;
  const std::size_t n = c.layers.size();
  if (c.free_layer >= n) {
    throw InputError("afm fit: the free layer " + std::to_string(c.free_layer + 1) + " is not a layer of the stack; allowed: 1.." +
                     std::to_string(n) + " (E1..E" + std::to_string(n) + ")");
  }
  // JKR and DMT read the stack's reduced variables (THEORY.md section 15, "JKR and DMT on a
  // stack"); Maugis-Dugdale's cohesive-zone tables are built per film.
  const bool stack_model = problem.model == AfmModel::kHertz || problem.model == AfmModel::kJkr || problem.model == AfmModel::kDmt;
  if (!stack_model && (n > 1 || c.layers.front().slip_below)) {
    throw InputError(std::string("afm fit: --model ") + problem.model.name() + " takes one bonded film (--film, or one --layer); " +
                     (n > 1 ? "a stack of " + std::to_string(n) + " layers" : std::string("a sliding film")) +
                     " takes --model hertz, jkr or dmt");
  }
  if (n == 1) return;
  if (problem.free.thickness) {
    throw InputError("afm fit: t is free on one film only; a stack of " + std::to_string(n) +
                     " layers frees one layer's modulus (E1..E" + std::to_string(n) + ")");
  }
  if (c.direct) throw InputError("afm fit: the direct coated path takes one film; a stack reads the tabled force law");
  c.stack();  // validates every layer (InputError naming it)
}

}  // namespace coatcontact::fit::internal

namespace coatcontact::fit {

Stack AfmCoating::stack_with(double modulus, double t) const {
  Material free = film;
  free.youngs_modulus = modulus;
  if (layers.empty()) return Stack::film_on(free, substrate);
  std::vector<Layer> all = layers;
  if (free_layer < all.size()) {
    all[free_layer].material = free;
    all[free_layer].thickness = t;
  }
  return Stack(all, substrate);
}

double AfmCoating::total_thickness(double t) const {
  if (layers.size() <= 1) return t;
  double total = 0.0;
  for (std::size_t i = 0; i < layers.size(); ++i) total += i == free_layer ? t : layers[i].thickness;
  return total;
}

double AfmCoating::reference_modulus(double modulus) const {
  if (layers.size() <= 1 || free_layer == 0) {
    Material free = film;
    free.youngs_modulus = modulus;
    return free.reduced_modulus();
  }
  return layers.front().material.reduced_modulus();
}

AfmCoating afm_coating(const Stack& stack, std::size_t free_layer) {
  const std::size_t n = stack.layers().size();
  if (free_layer >= n) {
    throw InputError("afm fit: the free layer " + std::to_string(free_layer + 1) + " is not a layer of the stack; allowed: 1.." +
                     std::to_string(n) + " (E1..E" + std::to_string(n) + ")");
  }
  AfmCoating c;
  c.film = stack.layers()[free_layer].material;
  c.thickness = stack.layers()[free_layer].thickness;
  c.substrate = stack.substrate();
  if (n > 1 || stack.layers().front().slip_below) {
    c.layers = stack.layers();
    c.free_layer = free_layer;
    // Section 12's kernel tables reach ~2e-8 at a/T ~ 1e2 (measured on two layers), short of 1e-8.
    c.solver_tolerance = kStackSolverTolerance;
  }
  return c;
}

}  // namespace coatcontact::fit
