// Reduced variables over (a/t, one layer's modulus): THEORY.md section 15, "Tabled coated force
// laws". Across the nodes ln X is interpolated by the polynomial through the `stencil` nearest
// nodes; the one through the next nearest as well differs from it by about its error (the next
// term of Newton's form), which is the cross-node estimate.
#include "coatcontact/coated_table.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string>

#include "coatcontact/detail/format.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact {

namespace {

constexpr int kVariables = 6;

std::array<double, kVariables> logs_of(const ReducedPoint& p) {
  return {std::log(p.pi_s), std::log(p.delta_s), std::log(p.pi_c), std::log(p.delta_c), std::log(p.e_eq), std::log(p.gamma1)};
}
std::array<double, kVariables> dlogs_of(const ReducedPoint& p) {
  return {p.dlog_pi_s, p.dlog_delta_s, p.dlog_pi_c, p.dlog_delta_c, p.dlog_e_eq, p.dlog_gamma1};
}

// Lagrange weights at x of the integer nodes `nodes`.
std::vector<double> lagrange(double x, const std::vector<long>& nodes) {
  std::vector<double> w(nodes.size(), 1.0);
  for (std::size_t a = 0; a < nodes.size(); ++a) {
    for (std::size_t b = 0; b < nodes.size(); ++b) {
      if (a != b) w[a] *= (x - static_cast<double>(nodes[b])) / static_cast<double>(nodes[a] - nodes[b]);
    }
  }
  return w;
}

}  // namespace

// A node is built a decade of a/t at a time, when a lookup first needs that decade: a curve
// rarely reaches the top decades, whose solves cost most (at a/t ~ 30 ~50x one at a/t ~ 1).
// Each decade is a verified ReducedTable of its own over fixed ends, so a value does not depend
// on which decades exist.
struct CoatedTable::Node {
  explicit Node(const Stack& stack, const CoatedTableOptions& o) : options(o), solver(stack), source(solver, o.solver_tolerance) {
    first = static_cast<int>(std::floor(std::log10(o.a_over_t_min) + 1e-9));
    last = std::max(first, static_cast<int>(std::ceil(std::log10(o.a_over_t_max) - 1e-9)) - 1);
  }
  int decade_of(double a_over_t) const {
    // (a decade's upper end belongs to it: a sweep that stops at 10^k needs no decade above)
    int d = static_cast<int>(std::ceil(std::log10(a_over_t))) - 1;
    if (a_over_t <= std::pow(10.0, d)) --d;  // log10's rounding at a decade's end
    if (a_over_t > std::pow(10.0, d + 1)) ++d;
    return std::clamp(d, first, last);
  }
  // The decade's table, built if needed (the caller holds the CoatedTable's mutex).
  const ReducedTable& decade(int d) {
    auto it = decades.find(d);
    if (it != decades.end()) return *it->second;
    auto table = std::make_unique<ReducedTable>(source, sweep_table_options(options.a_over_t_tolerance));
    table->prepare_range(std::max(options.a_over_t_min, std::pow(10.0, d)), std::min(options.a_over_t_max, std::pow(10.0, d + 1)));
    return *decades.emplace(d, std::move(table)).first->second;
  }
  std::size_t solves() const {
    std::size_t n = 0;
    for (const auto& [d, table] : decades) n += table->source_evaluations();
    return n;
  }
  CoatedTableOptions options;
  ReducedSolver solver;
  SolverSource source;
  int first = 0, last = 0;
  std::map<int, std::unique_ptr<ReducedTable>> decades;
};

CoatedTable::CoatedTable(const Stack& stack, std::size_t free_layer, CoatedTableOptions options)
    : stack_(stack), free_layer_(free_layer), options_(options) {
  if (free_layer >= stack.layers().size()) {
    throw InputError("coated table: free layer " + std::to_string(free_layer) + " of a stack of " +
                     std::to_string(stack.layers().size()) + " layers");
  }
  if (!(options_.nodes_per_decade > 0.0 && options_.nodes_per_decade <= 64.0)) {
    throw InputError("coated table: nodes per decade must be in (0, 64]");
  }
  if (options_.stencil < 2 || options_.stencil > 12 || options_.stencil % 2 != 0) {
    throw InputError("coated table: the stencil must be even, 2..12 nodes");
  }
  scale_free_ = stack.layers().size() == 1 && stack.substrate().rigid && stack.indenter().rigid;
  reference_ = stack.substrate().rigid ? 1.0 : stack.substrate().material.youngs_modulus;
}

CoatedTable::~CoatedTable() = default;

Stack CoatedTable::stack_with(double modulus) const {
  std::vector<Layer> layers = stack_.layers();
  layers[free_layer_].material.youngs_modulus = modulus;
  return Stack(layers, stack_.substrate(), stack_.indenter());
}

CoatedTable::Node& CoatedTable::node(long j) const {
  auto it = nodes_.find(j);
  if (it != nodes_.end()) return *it->second;
  const double modulus = scale_free_ ? stack_.layers()[free_layer_].material.youngs_modulus
                                     : reference_ * std::pow(10.0, static_cast<double>(j) / options_.nodes_per_decade);
  auto built = std::make_unique<Node>(stack_with(modulus), options_);
  return *nodes_.emplace(j, std::move(built)).first->second;
}

std::size_t CoatedTable::nodes() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  return nodes_.size();
}

std::size_t CoatedTable::source_solves() const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::size_t n = 0;
  for (const auto& [j, node] : nodes_) n += node->solves();
  return n;
}

std::vector<CoatedValues> CoatedTable::at(double modulus, const std::vector<double>& a_over_t) const {
  CoatedSweepCache cache;
  return at(modulus, a_over_t, cache);
}

std::vector<CoatedValues> CoatedTable::at(double modulus, const std::vector<double>& a_over_t, CoatedSweepCache& cache) const {
  if (!(modulus > 0.0 && std::isfinite(modulus))) {
    throw InputError("coated table: the free modulus must be > 0 and finite (got " + detail::short_text(modulus) + ")");
  }
  // The nodes of the quintic (`stencil` nearest) and of the next polynomial (one more node).
  std::vector<long> cubic, quartic;
  if (scale_free_) {
    cubic = {0};
  } else {
    const double x = std::log10(modulus / reference_) * options_.nodes_per_decade;
    const double nearest = std::round(x);
    if (std::abs(x - nearest) < 1e-9) {
      cubic = {static_cast<long>(nearest)};
    } else {
      const long j0 = static_cast<long>(std::floor(x)), half = options_.stencil / 2;
      for (long j = j0 - half + 1; j <= j0 + half; ++j) cubic.push_back(j);
      quartic = cubic;
      quartic.push_back(x - static_cast<double>(j0) < 0.5 ? j0 - half : j0 + half + 1);
    }
  }
  const double x = scale_free_ ? 0.0 : std::log10(modulus / reference_) * options_.nodes_per_decade;
  const std::vector<double> w3 = lagrange(x, cubic), w4 = quartic.empty() ? std::vector<double>{} : lagrange(x, quartic);
  const std::vector<long>& nodes_used = quartic.empty() ? cubic : quartic;
  if (cache.a_over_t_ != a_over_t) {
    for (double v : a_over_t) {
      if (!(v >= options_.a_over_t_min * (1 - 1e-12) && v <= options_.a_over_t_max * (1 + 1e-12))) {
        throw InputError("coated table: a/t = " + detail::short_text(v) + " outside its range [" +
                         detail::short_text(options_.a_over_t_min) + ", " + detail::short_text(options_.a_over_t_max) + "]");
      }
    }
    cache.nodes_.clear();
    cache.a_over_t_ = a_over_t;
  }
  std::vector<const CoatedSweepCache::NodeValues*> values(nodes_used.size());
  for (std::size_t k = 0; k < nodes_used.size(); ++k) {
    auto it = cache.nodes_.find(nodes_used[k]);
    if (it == cache.nodes_.end()) it = cache.nodes_.emplace(nodes_used[k], node_values(nodes_used[k], a_over_t)).first;
    values[k] = &it->second;
  }
  std::vector<CoatedValues> out(a_over_t.size());
  for (std::size_t i = 0; i < a_over_t.size(); ++i) {
    std::array<double, kVariables> v3{}, d3{}, v4{};
    double inner = 0.0, node_error = 0.0;
    for (std::size_t k = 0; k < nodes_used.size(); ++k) {
      const auto& lv = values[k]->logs[i];
      const auto& dv = values[k]->dlogs[i];
      if (k < cubic.size()) {
        const double total = values[k]->total[i], interpolation = values[k]->interpolation[i];
        inner += std::abs(w3[k]) * (total + (options_.a_over_t_safety - 1.0) * interpolation);
        node_error += std::abs(w3[k]) * (total - interpolation);
        for (int j = 0; j < kVariables; ++j) v3[j] += w3[k] * lv[j], d3[j] += w3[k] * dv[j];
      }
      if (!w4.empty()) {
        for (int j = 0; j < kVariables; ++j) v4[j] += w4[k] * lv[j];
      }
    }
    CoatedValues& c = out[i];
    for (int j = 0; j < kVariables && !w4.empty(); ++j) c.cross_error = std::max(c.cross_error, options_.cross_safety * std::abs(v4[j] - v3[j]));
    c.error_estimate = c.cross_error + inner;
    c.node_error = node_error;
    ReducedPoint& p = c.point;
    p.a_over_t = a_over_t[i];
    p.pi_s = std::exp(v3[0]), p.delta_s = std::exp(v3[1]), p.pi_c = std::exp(v3[2]);
    p.delta_c = std::exp(v3[3]), p.e_eq = std::exp(v3[4]), p.gamma1 = std::exp(v3[5]);
    p.dlog_pi_s = d3[0], p.dlog_delta_s = d3[1], p.dlog_pi_c = d3[2];
    p.dlog_delta_c = d3[3], p.dlog_e_eq = d3[4], p.dlog_gamma1 = d3[5];
  }
  return out;
}

// Node j's logs, log-derivatives and estimates at each a/t; its decades built under the lock.
CoatedSweepCache::NodeValues CoatedTable::node_values(long j, const std::vector<double>& a_over_t) const {
  std::vector<const ReducedTable*> tables(a_over_t.size());
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    Node& n = node(j);
    for (std::size_t i = 0; i < a_over_t.size(); ++i) tables[i] = &n.decade(n.decade_of(a_over_t[i]));
  }
  CoatedSweepCache::NodeValues v;
  v.logs.resize(a_over_t.size()), v.dlogs.resize(a_over_t.size());
  v.total.resize(a_over_t.size()), v.interpolation.resize(a_over_t.size());
  for (std::size_t i = 0; i < a_over_t.size(); ++i) {
    const ReducedPoint p = tables[i]->at(a_over_t[i]);
    v.logs[i] = logs_of(p), v.dlogs[i] = dlogs_of(p);
    v.total[i] = tables[i]->error_estimate_at(a_over_t[i]);
    v.interpolation[i] = tables[i]->interpolation_error_at(a_over_t[i]);
  }
  return v;
}

CoatedValues CoatedTable::at(double modulus, double a_over_t) const { return at(modulus, std::vector<double>{a_over_t}).front(); }

}  // namespace coatcontact
