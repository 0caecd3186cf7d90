// The shared tabled coated force laws of the AFM fits (afm_internal.hpp; THEORY.md section 15,
// "Tabled coated force laws").
#include <map>
#include <mutex>
#include <tuple>

#include "afm_internal.hpp"

namespace coatcontact::fit::internal {

namespace {

using Key = std::tuple<double, bool, double, double, double>;
std::mutex tables_mutex;
std::map<Key, std::shared_ptr<const CoatedTable>>& tables() {
  static std::map<Key, std::shared_ptr<const CoatedTable>> all;
  return all;
}

}  // namespace

std::shared_ptr<const CoatedTable> afm_coated_table(const AfmCoating& coating) {
  const Substrate& s = coating.substrate;
  const Key key{coating.film.poisson_ratio, s.rigid, s.rigid ? 0.0 : s.material.youngs_modulus,
                s.rigid ? 0.0 : s.material.poisson_ratio, coating.solver_tolerance};
  const std::lock_guard<std::mutex> lock(tables_mutex);
  auto& all = tables();
  auto it = all.find(key);
  if (it != all.end()) return it->second;
  if (all.size() >= 16) all.clear();  // the fits holding one keep it
  CoatedTableOptions options;
  options.a_over_t_min = kCoatingAOverT[0];
  options.a_over_t_max = kCoatingAOverT[1];
  options.solver_tolerance = coating.solver_tolerance;
  auto table = std::make_shared<const CoatedTable>(Stack::film_on(coating.film, coating.substrate), 0, options);
  all.emplace(key, table);
  return table;
}

void afm_clear_coated_tables() {
  const std::lock_guard<std::mutex> lock(tables_mutex);
  tables().clear();
}

}  // namespace coatcontact::fit::internal
