// The reduced table of the Maugis-Dugdale cohesive zone (THEORY.md section 13, "The cohesive
// zone as a table"); see md_table.hpp.
#include "md_table.hpp"

#include <gsl/gsl_interp2d.h>
#include <gsl/gsl_spline.h>
#include <gsl/gsl_spline2d.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <atomic>
#include <exception>
#include <functional>
#include <limits>
#include <string>
#include <thread>
#include <vector>

#include "coatcontact/detail/constants.hpp"
#include "coatcontact/detail/brent.hpp"
#include "coatcontact/detail/format.hpp"
#include "coatcontact/detail/gsl_handler_off.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"
#include "coatcontact/solve_cache.hpp"
#include "solve_cache.hpp"

namespace coatcontact::detail {

namespace {

using detail::kPi;
constexpr int kTwoD = 4;  // d, f, g_r, g_s
constexpr int kOneD = 2;  // delta_h, force_h
// The radius functions cost one factorization per node (~100 µs, more than a 2-D node) and
// vary with a/t as fast as the 2-D ones (on a rigid base with nu = 0.5 F_H/a³ spans decades).
// Tabled as ln(ratio) (nearly straight where the ratio is a power of a/t), on a grid x1 twice
// finer than x that refines it (x1[2 i] = x[i]): a radius node on an x node reads its column's
// factorization, so a tile's radius nodes cost half a factorization per column more. The
// error matched the ratios on a 4 times finer grid, and AFM fits moved by <= 2e-3 of their
// standard errors (THEORY.md section 13, "The radius functions on the columns"). Even, so that
// x1's coarse grid (every other node) holds every x node too.
constexpr std::size_t kOneDRefinement = 2;
static_assert(kOneDRefinement % 2 == 0, "x1's coarse nodes must hold x's nodes");
// Points per coarse interval (2-D: per direction) at which fine and coarse are compared.
constexpr int kSamples = 5;

// T - atan T without cancellation (series below T = 0.1: T^17/17 is 1e-14 of T^3/3); angle =
// atan T, computed once by the caller.
double tan_minus_angle(double t, double angle) {
  if (t >= 0.1) return t - angle;
  double sum = 0.0, power = t * t * t, t2 = t * t;
  for (int k = 1; k <= 7; ++k, power *= t2) sum += (k % 2 == 1 ? 1.0 : -1.0) * power / (2 * k + 1);
  return sum;
}

// tan φa = sqrt(c² - a²)/a and φa = arccos(a/c) at c/a - 1 = excess: what the homogeneous
// forms below spend their square root and arctangent on (a root's last read and its state share them).
struct ZoneAngle {
  double tan = 0.0, angle = 0.0;
};
ZoneAngle zone_angle(double excess) {
  const double t = std::sqrt(excess * (2.0 + excess));
  return {t, std::atan(t)};
}
std::pair<double, double> homogeneous_gap_at(double a, double e, ZoneAngle z) {
  const double t = z.tan, phi = z.angle;
  return {a * a / kPi * (phi * t * t + tan_minus_angle(t, phi)), 2.0 * a / kPi * (t * phi - e)};
}
CohesiveFunctions homogeneous_functions_at(double a, double e, ZoneAngle z) {
  const double t = z.tan, phi = z.angle;
  CohesiveFunctions h;
  h.delta_h = a * a;
  h.force_h = 4.0 * a * a * a / 3.0;
  h.d = -a * t;
  h.f = -a * a * (t + (1.0 + e) * (1.0 + e) * phi);
  h.g_r = a * a / kPi * (phi * t * t + tan_minus_angle(t, phi));
  h.g_s = 2.0 * a / kPi * (t * phi - e);
  return h;
}

// The ratio stored for each function: value / homogeneous value (THEORY.md section 13).
void to_array_2d(const CohesiveFunctions& v, double* out) {
  out[0] = v.d;
  out[1] = v.f;
  out[2] = v.g_r;
  out[3] = v.g_s;
}
void from_array_2d(const double* in, CohesiveFunctions& v) {
  v.d = in[0];
  v.f = in[1];
  v.g_r = in[2];
  v.g_s = in[3];
}

struct Spline2d {
  gsl_spline2d* spline = nullptr;
  ~Spline2d() { gsl_spline2d_free(spline); }
};
struct Spline1d {
  gsl_spline* spline = nullptr;
  ~Spline1d() { gsl_spline_free(spline); }
};

// Index of the interval of the sorted grid g holding v (clamped to the first and last).
std::size_t cell_of(const std::vector<double>& g, double v) {
  const auto it = std::upper_bound(g.begin(), g.end(), v);
  const auto k = static_cast<std::size_t>(std::max<std::ptrdiff_t>(it - g.begin() - 1, 0));
  return std::min(k, g.size() - 2);
}

// Cubic splines of y against x on all nodes and on every other node (x_coarse), and the
// largest |fine - coarse| in each coarse interval: the error estimate of the fine one.
void fit_pair(const std::vector<double>& x, const std::vector<double>& x_coarse, const std::vector<double>& y,
              std::vector<double>& y_coarse, Spline1d& fine, Spline1d& coarse, std::vector<double>& error) {
  y_coarse.clear();
  for (std::size_t i = 0; i < x.size(); i += 2) y_coarse.push_back(y[i]);
  fine.spline = gsl_spline_alloc(gsl_interp_cspline, x.size());
  coarse.spline = gsl_spline_alloc(gsl_interp_cspline, x_coarse.size());
  if (!fine.spline || !coarse.spline || gsl_spline_init(fine.spline, x.data(), y.data(), x.size()) != 0 ||
      gsl_spline_init(coarse.spline, x_coarse.data(), y_coarse.data(), x_coarse.size()) != 0) {
    throw NumericalError("Maugis-Dugdale table: GSL refused a 1-D spline");
  }
  error.assign(x_coarse.size() - 1, 0.0);
  for (std::size_t i = 0; i + 1 < x_coarse.size(); ++i) {
    for (int p = 1; p < 2 * kSamples; ++p) {
      const double v = x_coarse[i] + (x_coarse[i + 1] - x_coarse[i]) * p / (2 * kSamples);
      error[i] = std::max(error[i], std::abs(gsl_spline_eval(fine.spline, v, nullptr) -
                                             gsl_spline_eval(coarse.spline, v, nullptr)));
    }
  }
}

std::vector<double> grid(double lo, double hi, double step) {
  const int half = std::max(3, static_cast<int>(std::ceil((hi - lo) / (2.0 * step))));
  const int n = 2 * half + 1;
  std::vector<double> g(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) g[static_cast<std::size_t>(k)] = lo + (hi - lo) * k / (n - 1);
  return g;
}

// grid with `factor` - 1 equally spaced nodes inserted in each interval; its node factor i is
// grid[i] itself (bit for bit: a radius node there is the column's).
std::vector<double> refined_grid(const std::vector<double>& grid, std::size_t factor) {
  std::vector<double> fine((grid.size() - 1) * factor + 1);
  for (std::size_t i = 0; i + 1 < grid.size(); ++i) {
    for (std::size_t k = 0; k < factor; ++k) {
      fine[i * factor + k] = k == 0 ? grid[i] : grid[i] + (grid[i + 1] - grid[i]) * static_cast<double>(k) / factor;
    }
  }
  fine.back() = grid.back();
  return fine;
}

// ln(h/h0) from h - h0 = difference (its sign exact: the bracket's decisions are those on h - h0),
// continued linearly below h/h0 = 1e-3 (h may reach zero or below on a layered stack).
double log_gap_ratio(double difference, double h0) {
  if (!(h0 > 0.0)) return difference;  // (no ratio: the difference itself keeps the signs)
  constexpr double kFloor = 1e-3;
  const double x = difference / h0;
  return x > kFloor - 1.0 ? std::log1p(x) : std::log(kFloor) + (x - (kFloor - 1.0)) / kFloor;
}

// f remembering its last two values: GSL's Brent starts by evaluating the bracket's two ends,
// which bracket_outward (or the caller) has just evaluated; f must be a pure function. (The
// object itself: a std::function holding it would be allocated on the heap once per root.)
template <class F>
auto remembering_last_two(F f) {
  constexpr double kNone = std::numeric_limits<double>::quiet_NaN();
  return [f, u = std::array<double, 2>{kNone, kNone}, v = std::array<double, 2>{}, next = 0](double x) mutable {
    if (x == u[0]) return v[0];
    if (x == u[1]) return v[1];
    const double y = f(x);
    u[next] = x;
    v[next] = y;
    next ^= 1;
    return y;
  };
}

}  // namespace

CohesiveFunctions cohesive_functions(const CohesiveZone& zone, double excess) { return zone.functions(excess); }

CohesiveFunctions homogeneous_functions(double a, double excess) {
  return homogeneous_functions_at(a, excess, zone_angle(excess));
}

std::pair<double, double> homogeneous_gap_functions(double a, double excess) {
  return homogeneous_gap_at(a, excess, zone_angle(excess));
}

CohesiveFunctions homogeneous_end_functions(double c) {
  CohesiveFunctions h;
  h.d = -c;
  h.f = -0.5 * kPi * c * c;
  h.g_r = 0.5 * c * c;
  h.g_s = c * (1.0 - 2.0 / kPi);
  return h;
}

std::optional<std::pair<double, double>> bracket_outward(const std::function<double(double)>& f, double start,
                                                         double lo, double hi, double step) {
  double u0 = std::clamp(start, lo, hi), f0 = f(u0);
  if (f0 == 0.0) return std::pair{u0, u0};
  for (int k = 0; k < 200; ++k) {
    const double u1 = f0 > 0.0 ? std::max(lo, u0 - step) : std::min(hi, u0 + step);
    if (u1 == u0) return std::nullopt;
    const double f1 = f(u1);
    if ((f1 > 0.0) != (f0 > 0.0) || f1 == 0.0) return f0 > 0.0 ? std::pair{u1, u0} : std::pair{u0, u1};
    u0 = u1;
    f0 = f1;
    step *= 1.5;
  }
  return std::nullopt;
}

double homogeneous_root(double sigma_hat, double h0, double a, double lo, double hi) {
  // Safeguarded Newton on L(s) = ln(g_R + σ̂ g_σ) - ln h0, e = e^s (THEORY.md section 13, "The
  // homogeneous root by Newton"): L grows with slope between 1 and 2 and is nearly straight.
  if (!(h0 > 0.0)) return lo;  // h >= 0 >= h0 on the whole range: its low end, as before
  const double log_h0 = std::log(h0);
  // The first iterate is s = 0 (unless the range excludes it): its e, tan and angle are the
  // same numbers for every root, computed once (by the same calls: the same bits).
  static const std::array<double, 3> at_zero = [] {
    volatile double zero = 0.0;
    const double e = std::exp(zero), t = std::sqrt(e * (2.0 + e));
    return std::array<double, 3>{e, t, std::atan(t)};
  }();
  auto log_gap = [&](double s) {
    const bool zero = s == 0.0;
    const double e = zero ? at_zero[0] : std::exp(s), t = zero ? at_zero[1] : std::sqrt(e * (2.0 + e)),
                 phi = zero ? at_zero[2] : std::atan(t);
    const double g_r = a * a / kPi * (phi * t * t + tan_minus_angle(t, phi)), g_s = 2.0 * a / kPi * (t * phi - e);
    const double dg_r = 2.0 * a * a / kPi * (t / (1.0 + e) + (1.0 + e) * phi);  // d/de
    const double dg_s = 2.0 * a / kPi * ((1.0 + e) * phi / t - e / (1.0 + e));
    const double gap = g_r + sigma_hat * g_s;
    return std::pair{std::log(gap) - log_h0, e * (dg_r + sigma_hat * dg_s) / gap};
  };
  constexpr double kTolerance = 1e-9;  // in s; Newton's last step leaves ~its square
  double l = lo, h = hi;               // L(l) < 0 < L(h) where known
  bool l_known = false, h_known = false;
  double s = std::clamp(0.0, lo, hi);
  for (int k = 0; k < 200; ++k) {
    const auto [value, slope] = log_gap(s);
    if (value == 0.0) return s;
    if (value > 0.0) {
      if (s == lo) return lo;
      h = s;
      h_known = true;
    } else {
      if (s == hi) return hi;
      l = s;
      l_known = true;
    }
    double next = s - value / slope;
    if (next >= l && next <= h && std::abs(next - s) <= kTolerance) return next;
    if (!(next > l && next < h)) {  // NaN included
      if (next <= l && !l_known) {
        next = l;  // the root may lie below the range: its end decides
      } else if (next >= h && !h_known) {
        next = h;
      } else {
        next = 0.5 * (l + h);
      }
    }
    if (h - l <= kTolerance) return next;
    s = next;
  }
  return s;
}

double homogeneous_end_root(double sigma_hat, double h0) {
  const double b = sigma_hat * (1.0 - 2.0 / kPi);
  return 2.0 * h0 / (b + std::sqrt(b * b + 2.0 * h0));
}

// A node in the solve cache: its kind, its index in that kind's grid, its values (ratios).
enum NodeKind : std::int64_t { kNode2d = 0, kNodeEnd = 1, kNodeRadius = 2 };
// Lagrange interpolation of degree up to kCheckDegree on the nodes of `grid` nearest v within
// [first, last]: the check of the cubic splines (their difference is the splines' error to
// O(h^2) relative, THEORY.md section 13, "Error estimates of the state"). Writes the first node
// and the weights, returns the number of nodes.
constexpr std::size_t kCheckDegree = 7;
std::size_t check_weights(const std::vector<double>& grid, std::size_t first, std::size_t last, double v, int degree,
                          std::size_t& start, double* w) {
  const std::size_t n = std::min({kCheckDegree, static_cast<std::size_t>(degree), last - first}) + 1;
  const std::size_t cell = cell_of(grid, v);
  const std::size_t back = (n - 1) / 2;
  start = std::clamp(cell >= back ? cell - back : 0, first, last + 1 - n);
  for (std::size_t i = 0; i < n; ++i) {
    w[i] = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      if (j != i) w[i] *= (v - grid[start + j]) / (grid[start + i] - grid[start + j]);
    }
  }
  return n;
}

constexpr std::size_t kNodeRecordBytes = 2 * sizeof(std::int64_t) + kTwoD * sizeof(double);
constexpr std::size_t kNodeIdBytes = 2 * sizeof(std::int64_t);  // the kind and the index identify a node

std::string node_record(NodeKind kind, std::size_t index, const double* values, int count) {
  std::string r(kNodeRecordBytes, '\0');
  const auto k = static_cast<std::int64_t>(kind), i = static_cast<std::int64_t>(index);
  std::memcpy(r.data(), &k, sizeof k);
  std::memcpy(r.data() + sizeof k, &i, sizeof i);
  std::memcpy(r.data() + 2 * sizeof k, values, static_cast<std::size_t>(count) * sizeof(double));
  return r;
}

// One tile of the 2-D table: own coarse cells [cell_x0, cell_x0 + own_x) x [cell_s0, ...),
// splines on the fine nodes [node_x0, node_x1] x [node_s0, node_s1] (own cells plus margins).
struct MaugisDugdaleTable::Tile2d {
  std::size_t cell_x0 = 0, cell_s0 = 0, own_x = 0, own_s = 0;
  std::size_t node_x0 = 0, node_x1 = 0, node_s0 = 0, node_s1 = 0;  // the fine nodes interpolated
  Spline2d fine[kTwoD], coarse[kTwoD];
  std::vector<double> cell_error[kTwoD];  // own cells, index (j - cell_s0) own_x + (i - cell_x0)
};

// One tile of a 1-D function set (the radius functions δ_H, F_H against x, or the curve's end
// against ln c): own coarse intervals from interval0, error per interval of the tile's range.
struct MaugisDugdaleTable::Tile1d {
  std::size_t interval0 = 0;  // the tile's first coarse interval (margin included)
  std::size_t node0 = 0, node1 = 0;  // the fine nodes interpolated
  std::vector<Spline1d> fine, coarse;
  std::vector<std::vector<double>> interval_error;
};

struct MaugisDugdaleTable::Grids {
  // x = ln(a/t); τ in [0, 1] maps to s = ln(c/a - 1) = s_min + τ (s_max(x) - s_min).
  std::vector<double> x, tau, x_coarse, tau_coarse;
  std::vector<double> xe, xe_coarse;  // the end of the curve a = 0: ln(c/t)
  std::vector<double> x1, x1_coarse;  // the radius functions δ_H, F_H: x refined kOneDRefinement times
  std::size_t tiles_x = 0, tiles_s = 0, tiles_e = 0;
  // Node values (ratios to the homogeneous forms; y: their logarithms) and whether they are
  // solved; 2-D index j nx + i.
  std::vector<double> z[kTwoD], y[kOneD], ye[kTwoD];
  std::vector<char> solved, column_solved, end_solved, radius_solved;
  // Nodes the built tiles rest on (solved here or read from the cache).
  std::vector<char> used, end_used, radius_used;
  std::vector<std::unique_ptr<CohesiveZone>> columns;  // the factored system per radius
  std::unique_ptr<CohesiveZone> end_zone;
  std::mutex node_lock;
  std::vector<std::unique_ptr<Tile2d>> tiles;
  std::vector<std::unique_ptr<Tile1d>> radius_tiles, end_tiles;
  std::unique_ptr<std::once_flag[]> tile_once, radius_once, end_once;
  std::atomic<long> nodes{0}, nodes_used{0};
  std::atomic<long long> nanoseconds{0};
  std::unique_ptr<CacheRecords> cache;  // null without the solve cache; written on destruction
};

namespace {

// Fine node range [first, last] of tile t (tile_cells own coarse cells, margin_cells more on
// each side) on a grid with `cells` coarse cells.
void tile_range(std::size_t t, std::size_t cells, int tile_cells, int margin_cells, std::size_t& own0,
                std::size_t& own, std::size_t& first, std::size_t& last) {
  const std::size_t b = static_cast<std::size_t>(tile_cells), m = static_cast<std::size_t>(margin_cells);
  own0 = t * b;
  own = std::min(b, cells - own0);
  std::size_t c0 = own0 >= m ? own0 - m : 0, c1 = std::min(cells, own0 + own + m);
  // GSL's bicubic spline needs four coarse nodes: widen a short tile at a grid end.
  while (c1 - c0 < 3 && (c0 > 0 || c1 < cells)) {
    if (c1 < cells) ++c1;
    if (c1 - c0 < 3 && c0 > 0) --c0;
  }
  first = 2 * c0;
  last = 2 * c1;
}

std::size_t tile_count(std::size_t cells, int tile_cells) {
  return (cells + static_cast<std::size_t>(tile_cells) - 1) / static_cast<std::size_t>(tile_cells);
}

class Stopwatch {
 public:
  explicit Stopwatch(std::atomic<long long>& total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  ~Stopwatch() {
    total_ += std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start_).count();
  }
  Stopwatch(const Stopwatch&) = delete;
  Stopwatch& operator=(const Stopwatch&) = delete;

 private:
  std::atomic<long long>& total_;
  std::chrono::steady_clock::time_point start_;
};

}  // namespace

MaugisDugdaleTable::MaugisDugdaleTable(const KernelSource& kernel, const Discretization& disc,
                                       const CohesiveQuadrature& quadrature, const MdTableOptions& options,
                                       const std::string& cache_key)
    : kernel_(kernel), disc_(disc), quadrature_(quadrature), options_(options) {
  if (options.node_points_per_piece >= 4) {
    quadrature_.points_per_piece = std::min(quadrature_.points_per_piece, options.node_points_per_piece);
  }
  if (!(options.a_over_t_min > 0.0 && options.a_over_t_min < options.a_over_t_max && options.excess_min > 0.0 &&
        options.excess_min < 1.0 && options.c_over_t_max >= 10.0 * options.a_over_t_max && options.step > 0.0 &&
        std::isfinite(options.c_over_t_max) && options.end_c_over_t_min > 0.0 &&
        options.end_c_over_t_min < options.c_over_t_max && options.tile_cells >= 1 && options.margin_cells >= 0)) {
    throw InputError("Maugis-Dugdale table: need 0 < a_over_t_min < a_over_t_max, c_over_t_max >= 10 a_over_t_max, "
                     "0 < excess_min < 1, step > 0, tile_cells >= 1 and margin_cells >= 0");
  }
  auto g = std::make_unique<Grids>();
  const double s_min = std::log(options_.excess_min);
  g->x = grid(std::log(options_.a_over_t_min), std::log(options_.a_over_t_max), options_.step);
  // τ spacing: `step` in s where the s range is widest (the smallest a).
  const double widest = std::log(excess_max(options_.a_over_t_min)) - s_min;
  g->tau = grid(0.0, 1.0, options_.step / widest);
  g->xe = grid(std::log(options_.end_c_over_t_min), std::log(options_.c_over_t_max), 0.5 * options_.step);
  for (std::size_t i = 0; i < g->x.size(); i += 2) g->x_coarse.push_back(g->x[i]);
  for (std::size_t j = 0; j < g->tau.size(); j += 2) g->tau_coarse.push_back(g->tau[j]);
  for (std::size_t i = 0; i < g->xe.size(); i += 2) g->xe_coarse.push_back(g->xe[i]);
  g->x1 = refined_grid(g->x, kOneDRefinement);
  for (std::size_t i = 0; i < g->x1.size(); i += 2) g->x1_coarse.push_back(g->x1[i]);
  g->radius_solved.assign(g->x1.size(), 0);
  const std::size_t nx = g->x.size(), ns = g->tau.size(), ne = g->xe.size();
  for (int k = 0; k < kTwoD; ++k) {
    g->z[k].assign(nx * ns, 0.0);
    g->ye[k].assign(ne, 0.0);
  }
  for (int k = 0; k < kOneD; ++k) g->y[k].assign(g->x1.size(), 0.0);
  g->solved.assign(nx * ns, 0);
  g->used.assign(nx * ns, 0);
  g->column_solved.assign(nx, 0);
  g->end_solved.assign(ne, 0);
  g->end_used.assign(ne, 0);
  g->radius_used.assign(g->x1.size(), 0);
  g->columns.resize(nx);
  g->tiles_x = tile_count(g->x_coarse.size() - 1, options_.tile_cells);
  g->tiles_s = tile_count(g->tau_coarse.size() - 1, options_.tile_cells);
  g->tiles_e = tile_count(g->xe_coarse.size() - 1, options_.tile_cells);
  g->tiles.resize(g->tiles_x * g->tiles_s);
  g->radius_tiles.resize(g->tiles_x);
  g->end_tiles.resize(g->tiles_e);
  g->tile_once = std::make_unique<std::once_flag[]>(g->tiles.size());
  g->radius_once = std::make_unique<std::once_flag[]>(g->tiles_x);
  g->end_once = std::make_unique<std::once_flag[]>(g->tiles_e);
  const std::string directory = solve_cache_directory();
  if (!cache_key.empty() && !directory.empty()) {
    // Everything a node's value depends on besides its grid index.
    const MdTableOptions& o = options_;
    const std::string key = cache_key + "; zone table " + exact_text(o.a_over_t_min) + " " +
                            std::to_string(kOneDRefinement) + " refines x, ln ratios " +
                            exact_text(o.a_over_t_max) + " " + exact_text(o.excess_min) + " " +
                            exact_text(o.c_over_t_max) + " " + exact_text(o.end_c_over_t_min) + " " +
                            exact_text(o.step) + "; panels " + std::to_string(disc_.nodes_per_panel) + " " +
                            exact_text(disc_.edge_panel) + " " + exact_text(disc_.growth) + " " +
                            exact_text(disc_.single_panel_limit) + " " + exact_text(disc_.quadrature_accuracy) +
                            "; annulus " + std::to_string(quadrature_.points_per_piece) + " " +
                            exact_text(quadrature_.piece_length) + " " + exact_text(quadrature_.piece_angle);
    g->cache = std::make_unique<CacheRecords>(directory, "zone", key, kNodeRecordBytes, kNodeIdBytes);
  }
  grids_ = std::move(g);
  load_cached_nodes();
}

// The nodes earlier processes solved: set as if solved here (out-of-range or non-finite
// records, which a complete file of this key cannot hold, are ignored).
void MaugisDugdaleTable::load_cached_nodes() const {
  Grids& g = *grids_;
  if (!g.cache) return;
  for (const std::string& r : g.cache->loaded()) {
    std::int64_t kind = 0, index = 0;
    double v[kTwoD];
    std::memcpy(&kind, r.data(), sizeof kind);
    std::memcpy(&index, r.data() + sizeof kind, sizeof index);
    std::memcpy(v, r.data() + 2 * sizeof kind, sizeof v);
    if (index < 0 || !std::all_of(v, v + kTwoD, [](double x) { return std::isfinite(x); })) continue;
    const auto i = static_cast<std::size_t>(index);
    if (kind == kNode2d && i < g.solved.size()) {
      for (int k = 0; k < kTwoD; ++k) g.z[k][i] = v[k];
      g.solved[i] = 1;
    } else if (kind == kNodeEnd && i < g.end_solved.size()) {
      for (int k = 0; k < kTwoD; ++k) g.ye[k][i] = v[k];
      g.end_solved[i] = 1;
    } else if (kind == kNodeRadius && i < g.radius_solved.size()) {
      for (int k = 0; k < kOneD; ++k) g.y[k][i] = v[k];
      g.radius_solved[i] = 1;
    }
  }
}

MaugisDugdaleTable::~MaugisDugdaleTable() = default;

double MaugisDugdaleTable::excess_max(double a) const { return options_.c_over_t_max / a - 1.0; }

namespace {

// body(k) for k < count on every core (independent direct solves); the first exception in
// index order is rethrown after the loop, as a serial loop would. Threads of its own rather
// than an OpenMP loop: the tiles are mostly built from inside the parallel pull-offs
// (MaugisDugdaleModel::pulloffs), where a nested OpenMP loop would run on one thread while the
// other pull-offs wait for the node lock. Serial in a forked child (progress.hpp).
void for_each_node(std::size_t count, const std::function<void(std::size_t)>& body) {
  std::vector<std::exception_ptr> errors(count);
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t k = next++; k < count; k = next++) {
      try {
        body(k);
      } catch (...) {
        errors[k] = std::current_exception();
      }
    }
  };
  const std::size_t cores = std::max(1u, std::thread::hardware_concurrency());
  const std::size_t helpers = parallel_sweeps_allowed() ? std::min(cores, count) - std::min<std::size_t>(count, 1) : 0;
  std::vector<std::thread> threads;
  threads.reserve(helpers);
  for (std::size_t t = 0; t < helpers; ++t) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
  for (const auto& e : errors) {
    if (e) std::rethrow_exception(e);
  }
}

}  // namespace

void MaugisDugdaleTable::solve_nodes(const std::vector<std::pair<std::size_t, std::size_t>>& nodes) const {
  Grids& g = *grids_;
  const std::lock_guard<std::mutex> lock(g.node_lock);
  const std::size_t nx = g.x.size();
  std::vector<std::size_t> columns;
  std::vector<std::pair<std::size_t, std::size_t>> missing;
  std::vector<char> column_listed(nx, 0), node_listed(g.solved.size(), 0);
  for (const auto& [i, j] : nodes) {
    const std::size_t n = j * nx + i;
    if (!g.used[n]) {
      g.used[n] = 1;
      ++g.nodes_used;
    }
    if (g.solved[n] || node_listed[n]) continue;
    missing.emplace_back(i, j);
    node_listed[n] = 1;
    if (!g.column_solved[i] && !column_listed[i]) {
      columns.push_back(i);
      column_listed[i] = 1;
    }
  }
  if (missing.empty()) return;
  const Stopwatch watch(g.nanoseconds);
  // One factorization per contact radius, shared by the column's nodes.
  for_each_node(columns.size(), [&](std::size_t c) {
    const std::size_t i = columns[c];
    g.columns[i] = std::make_unique<CohesiveZone>(kernel_, std::exp(g.x[i]), 1.0, disc_, quadrature_);
  });
  for (std::size_t i : columns) g.column_solved[i] = 1;
  g.nodes += static_cast<long>(columns.size());
  const double s_min = std::log(options_.excess_min);
  for_each_node(missing.size(), [&](std::size_t n) {
    const auto [i, j] = missing[n];
    const double a = std::exp(g.x[i]);
    const double s_max = std::log(excess_max(a));
    const double e = std::exp(s_min + g.tau[j] * (s_max - s_min));
    double value[kTwoD], hom[kTwoD];
    to_array_2d(g.columns[i]->functions(e), value);
    to_array_2d(homogeneous_functions(a, e), hom);
    for (int k = 0; k < kTwoD; ++k) g.z[k][j * nx + i] = value[k] / hom[k];
  });
  for (const auto& [i, j] : missing) {
    const std::size_t n = j * nx + i;
    g.solved[n] = 1;
    if (g.cache) {
      const double v[kTwoD] = {g.z[0][n], g.z[1][n], g.z[2][n], g.z[3][n]};
      g.cache->add(node_record(kNode2d, n, v, kTwoD));
    }
  }
  g.nodes += static_cast<long>(missing.size());
}

// Marks [first, last] as used; the indices among them not solved yet.
std::vector<std::size_t> MaugisDugdaleTable::use_nodes(std::vector<char>& used, const std::vector<char>& solved,
                                                      std::size_t first, std::size_t last) const {
  std::vector<std::size_t> missing;
  for (std::size_t i = first; i <= last; ++i) {
    if (!used[i]) {
      used[i] = 1;
      ++grids_->nodes_used;
    }
    if (!solved[i]) missing.push_back(i);
  }
  return missing;
}

void MaugisDugdaleTable::solve_end_nodes(std::size_t first, std::size_t last) const {
  Grids& g = *grids_;
  const std::lock_guard<std::mutex> lock(g.node_lock);
  const std::vector<std::size_t> missing = use_nodes(g.end_used, g.end_solved, first, last);
  if (missing.empty()) return;
  const Stopwatch watch(g.nanoseconds);
  if (!g.end_zone) g.end_zone = std::make_unique<CohesiveZone>(kernel_, 0.0, 1.0, disc_, quadrature_);
  for_each_node(missing.size(), [&](std::size_t n) {
    const std::size_t i = missing[n];
    const double c = std::exp(g.xe[i]);
    double value[kTwoD], hom[kTwoD];
    to_array_2d(g.end_zone->functions(c), value);
    to_array_2d(homogeneous_end_functions(c), hom);
    for (int k = 0; k < kTwoD; ++k) g.ye[k][i] = value[k] / hom[k];
  });
  for (std::size_t i : missing) {
    g.end_solved[i] = 1;
    if (g.cache) {
      const double v[kTwoD] = {g.ye[0][i], g.ye[1][i], g.ye[2][i], g.ye[3][i]};
      g.cache->add(node_record(kNodeEnd, i, v, kTwoD));
    }
  }
  g.nodes += static_cast<long>(missing.size());
}

void MaugisDugdaleTable::solve_radius_nodes(std::size_t first, std::size_t last) const {
  Grids& g = *grids_;
  const std::lock_guard<std::mutex> lock(g.node_lock);
  const std::vector<std::size_t> missing = use_nodes(g.radius_used, g.radius_solved, first, last);
  if (missing.empty()) return;
  const Stopwatch watch(g.nanoseconds);
  // One factorization per radius; the adhesionless solution gives δ_H, F_H. A node on an x
  // node reads its column's factorization, built here if missing and kept for the column's
  // 2-D nodes: the same zone either way, so the same values whichever is solved first.
  std::vector<char> column_built(missing.size(), 0);
  for_each_node(missing.size(), [&](std::size_t n) {
    const std::size_t i = missing[n], column = i / kOneDRefinement;
    const double a = std::exp(g.x1[i]);
    CohesiveFunctions v;
    if (i % kOneDRefinement != 0) {
      v = CohesiveZone(kernel_, a, 1.0, disc_, quadrature_).adhesionless();
    } else {
      if (!g.column_solved[column]) {
        g.columns[column] = std::make_unique<CohesiveZone>(kernel_, a, 1.0, disc_, quadrature_);
        column_built[n] = 1;
      }
      v = g.columns[column]->adhesionless();
    }
    const CohesiveFunctions h = homogeneous_functions(a, 1.0);
    const double ratio[kOneD] = {v.delta_h / h.delta_h, v.force_h / h.force_h};
    for (int k = 0; k < kOneD; ++k) {
      if (!(ratio[k] > 0.0) || !std::isfinite(ratio[k])) {
        throw NumericalError("Maugis-Dugdale table: adhesionless " + std::string(k == 0 ? "penetration" : "load") +
                             " not positive at a/t = " + short_text(a));
      }
      g.y[k][i] = std::log(ratio[k]);
    }
  });
  for (std::size_t n = 0; n < missing.size(); ++n) {
    if (column_built[n]) {
      g.column_solved[missing[n] / kOneDRefinement] = 1;
      ++g.nodes;
    }
  }
  for (std::size_t i : missing) {
    g.radius_solved[i] = 1;
    if (g.cache) {
      const double v[kTwoD] = {g.y[0][i], g.y[1][i], 0.0, 0.0};
      g.cache->add(node_record(kNodeRadius, i, v, kTwoD));
    }
  }
  g.nodes += static_cast<long>(missing.size());
}

namespace {

// Splines on all nodes and on every other node of grid[first..last] for each component, and
// the largest |fine - coarse| per coarse interval of that range.
void fit_1d(const std::vector<double>& grid_all, const std::vector<double>* values, int components,
            std::size_t first, std::size_t last, std::vector<Spline1d>& fine, std::vector<Spline1d>& coarse,
            std::vector<std::vector<double>>& error) {
  const std::vector<double> x(grid_all.begin() + static_cast<long>(first),
                              grid_all.begin() + static_cast<long>(last) + 1);
  std::vector<double> x_coarse;
  for (std::size_t i = 0; i < x.size(); i += 2) x_coarse.push_back(x[i]);
  fine.resize(static_cast<std::size_t>(components));
  coarse.resize(static_cast<std::size_t>(components));
  error.resize(static_cast<std::size_t>(components));
  for (int k = 0; k < components; ++k) {
    const std::vector<double> y(values[k].begin() + static_cast<long>(first),
                                values[k].begin() + static_cast<long>(last) + 1);
    std::vector<double> y_coarse;
    const auto kk = static_cast<std::size_t>(k);
    fit_pair(x, x_coarse, y, y_coarse, fine[kk], coarse[kk], error[kk]);
  }
}

}  // namespace

const MaugisDugdaleTable::Tile1d& MaugisDugdaleTable::tile_radius(std::size_t ti) const {
  Grids& g = *grids_;
  std::call_once(g.radius_once[ti], [&] {
    std::size_t own0, own, first, last;
    tile_range(ti, g.x_coarse.size() - 1, options_.tile_cells, std::max(2, options_.margin_cells), own0, own, first,
               last);
    // The x1 nodes of [x_first, x_last] (x1 refines x).
    const std::size_t first1 = kOneDRefinement * first, last1 = kOneDRefinement * last;
    solve_radius_nodes(first1, last1);
    auto tile = std::make_unique<Tile1d>();
    tile->interval0 = first1 / 2;
    tile->node0 = first1;
    tile->node1 = last1;
    GslHandlerOff guard;
    fit_1d(g.x1, g.y, kOneD, first1, last1, tile->fine, tile->coarse, tile->interval_error);
    g.radius_tiles[ti] = std::move(tile);
  });
  return *g.radius_tiles[ti];
}

const MaugisDugdaleTable::Tile1d& MaugisDugdaleTable::tile_end(std::size_t ti) const {
  Grids& g = *grids_;
  std::call_once(g.end_once[ti], [&] {
    std::size_t own0, own, first, last;
    tile_range(ti, g.xe_coarse.size() - 1, options_.tile_cells, std::max(2, options_.margin_cells), own0, own, first,
               last);
    solve_end_nodes(first, last);
    auto tile = std::make_unique<Tile1d>();
    tile->interval0 = first / 2;
    tile->node0 = first;
    tile->node1 = last;
    GslHandlerOff guard;
    fit_1d(g.xe, g.ye, kTwoD, first, last, tile->fine, tile->coarse, tile->interval_error);
    g.end_tiles[ti] = std::move(tile);
  });
  return *g.end_tiles[ti];
}

const MaugisDugdaleTable::Tile2d& MaugisDugdaleTable::tile_2d(std::size_t ti, std::size_t tj) const {
  Grids& g = *grids_;
  const std::size_t index = tj * g.tiles_x + ti;
  std::call_once(g.tile_once[index], [&] {
    std::size_t ox0, ox, fx0, fx1, os0, os, fs0, fs1;
    tile_range(ti, g.x_coarse.size() - 1, options_.tile_cells, options_.margin_cells, ox0, ox, fx0, fx1);
    tile_range(tj, g.tau_coarse.size() - 1, options_.tile_cells, options_.margin_cells, os0, os, fs0, fs1);
    std::vector<std::pair<std::size_t, std::size_t>> nodes;
    for (std::size_t j = fs0; j <= fs1; ++j) {
      for (std::size_t i = fx0; i <= fx1; ++i) nodes.emplace_back(i, j);
    }
    solve_nodes(nodes);
    const std::size_t nx = g.x.size();
    const std::size_t tx = fx1 - fx0 + 1, ts = fs1 - fs0 + 1, cx = tx / 2 + 1, cs = ts / 2 + 1;
    const std::vector<double> x(g.x.begin() + static_cast<long>(fx0), g.x.begin() + static_cast<long>(fx1) + 1);
    const std::vector<double> tau(g.tau.begin() + static_cast<long>(fs0), g.tau.begin() + static_cast<long>(fs1) + 1);
    std::vector<double> x_coarse, tau_coarse;
    for (std::size_t i = 0; i < tx; i += 2) x_coarse.push_back(x[i]);
    for (std::size_t j = 0; j < ts; j += 2) tau_coarse.push_back(tau[j]);
    auto tile = std::make_unique<Tile2d>();
    tile->cell_x0 = ox0;
    tile->cell_s0 = os0;
    tile->own_x = ox;
    tile->own_s = os;
    tile->node_x0 = fx0;
    tile->node_x1 = fx1;
    tile->node_s0 = fs0;
    tile->node_s1 = fs1;
    GslHandlerOff guard;
    for (int k = 0; k < kTwoD; ++k) {
      std::vector<double> z(tx * ts), zc(cx * cs);
      for (std::size_t j = 0; j < ts; ++j) {
        for (std::size_t i = 0; i < tx; ++i) z[j * tx + i] = g.z[k][(fs0 + j) * nx + fx0 + i];
      }
      for (std::size_t j = 0; j < cs; ++j) {
        for (std::size_t i = 0; i < cx; ++i) zc[j * cx + i] = z[2 * j * tx + 2 * i];
      }
      tile->fine[k].spline = gsl_spline2d_alloc(gsl_interp2d_bicubic, tx, ts);
      tile->coarse[k].spline = gsl_spline2d_alloc(gsl_interp2d_bicubic, cx, cs);
      if (!tile->fine[k].spline || !tile->coarse[k].spline ||
          gsl_spline2d_init(tile->fine[k].spline, x.data(), tau.data(), z.data(), tx, ts) != 0 ||
          gsl_spline2d_init(tile->coarse[k].spline, x_coarse.data(), tau_coarse.data(), zc.data(), cx, cs) != 0) {
        throw NumericalError("Maugis-Dugdale table: GSL refused the 2-D spline");
      }
      // Error map of the own cells: |fine - coarse| on a 5 x 5 grid inside each coarse cell and
      // at the fine nodes on its edges; the largest value is the cell's.
      const gsl_spline2d* fine = tile->fine[k].spline;
      const gsl_spline2d* coarse = tile->coarse[k].spline;
      tile->cell_error[k].assign(ox * os, 0.0);
      for (std::size_t jj = 0; jj < os; ++jj) {
        for (std::size_t ii = 0; ii < ox; ++ii) {
          const std::size_t i = ox0 + ii - fx0 / 2, j = os0 + jj - fs0 / 2;  // coarse index in the tile
          double worst = 0.0;
          for (int p = 1; p < kSamples; ++p) {
            for (int q = 1; q < kSamples; ++q) {
              const double xv = x_coarse[i] + (x_coarse[i + 1] - x_coarse[i]) * p / kSamples;
              const double tv = tau_coarse[j] + (tau_coarse[j + 1] - tau_coarse[j]) * q / kSamples;
              worst = std::max(worst, std::abs(gsl_spline2d_eval(fine, xv, tv, nullptr, nullptr) -
                                               gsl_spline2d_eval(coarse, xv, tv, nullptr, nullptr)));
            }
          }
          for (std::size_t p = 2 * i; p <= 2 * i + 2; ++p) {
            for (std::size_t q = 2 * j; q <= 2 * j + 2; ++q) {
              worst = std::max(worst, std::abs(z[q * tx + p] - gsl_spline2d_eval(coarse, x[p], tau[q], nullptr, nullptr)));
            }
          }
          tile->cell_error[k][jj * ox + ii] = worst;
        }
      }
    }
    g.tiles[index] = std::move(tile);
  });
  return *g.tiles[index];
}

void MaugisDugdaleTable::build() const {
  if (options_.closed_form) return;
  const Grids& g = *grids_;
  // Every node first (one parallel pass), then the tiles' splines.
  std::vector<std::pair<std::size_t, std::size_t>> nodes;
  for (std::size_t j = 0; j < g.tau.size(); ++j) {
    for (std::size_t i = 0; i < g.x.size(); ++i) nodes.emplace_back(i, j);
  }
  solve_nodes(nodes);
  solve_end_nodes(0, g.xe.size() - 1);
  for (std::size_t tj = 0; tj < g.tiles_s; ++tj) {
    for (std::size_t ti = 0; ti < g.tiles_x; ++ti) tile_2d(ti, tj);
  }
  for (std::size_t ti = 0; ti < g.tiles_x; ++ti) tile_radius(ti);
  for (std::size_t ti = 0; ti < g.tiles_e; ++ti) tile_end(ti);
}

double MaugisDugdaleTable::build_seconds() const { return 1e-9 * static_cast<double>(grids_->nanoseconds.load()); }
long MaugisDugdaleTable::nodes_solved() const { return grids_->nodes.load(); }
long MaugisDugdaleTable::nodes_used() const { return grids_->nodes_used.load(); }
int MaugisDugdaleTable::nodes_x() const { return static_cast<int>(grids_->x.size()); }
int MaugisDugdaleTable::nodes_s() const { return static_cast<int>(grids_->tau.size()); }

// The table's radii, with a margin of rounding at the ends: a_bar/eta at a_bar = eta a_over_t_max
// may round just beyond it (at() clamps ln a to the grid).
bool MaugisDugdaleTable::covers_radius(double a) const {
  if (options_.closed_form) return a > 0.0 && std::isfinite(a);
  constexpr double kRounding = 1e-12;
  return a >= options_.a_over_t_min * (1.0 - kRounding) && a <= options_.a_over_t_max * (1.0 + kRounding);
}

bool MaugisDugdaleTable::covers(double a, double excess) const {
  const MdTableOptions& o = options_;
  // The ends with a margin of rounding: ln and exp of an end need not return it exactly.
  constexpr double kRounding = 1e-12;
  return covers_radius(a) && excess >= std::min(o.excess_floor, o.excess_min) * (1.0 - kRounding) &&
         excess <= excess_max(a) * (1.0 + kRounding);
}

MdTableValue MaugisDugdaleTable::closed_form_value(double a, double excess) const {
  MdTableValue out;
  out.value = homogeneous_functions(a, excess);
  const CohesiveFunctions& v = out.value;
  const double noise = options_.source_noise;
  out.error.d = noise * std::abs(v.d);
  out.error.f = noise * std::abs(v.f);
  out.error.g_r = noise * std::abs(v.g_r);
  out.error.g_s = noise * std::abs(v.g_s);
  out.error.delta_h = noise * std::abs(v.delta_h);
  out.error.force_h = noise * std::abs(v.force_h);
  return out;
}

MdTableValue MaugisDugdaleTable::at(double a, double excess, int check) const {
  if (!covers(a, excess)) {
    throw InputError("Maugis-Dugdale table: (a/t, c/a - 1) = (" + short_text(a) + ", " + short_text(excess) +
                     ") outside the table");
  }
  if (options_.closed_form) return closed_form_value(a, excess);
  const Grids& g = *grids_;
  const double s_min = std::log(options_.excess_min), s_max = std::log(excess_max(a));
  // Clamped: the logarithms of end values may round just outside the grid.
  const double x = std::clamp(std::log(a), g.x.front(), g.x.back());
  const double tau = std::clamp((std::log(excess) - s_min) / (s_max - s_min), 0.0, 1.0);
  const std::size_t cell_x = cell_of(g.x_coarse, x), cell_s = cell_of(g.tau_coarse, tau);
  const auto b = static_cast<std::size_t>(options_.tile_cells);
  const Tile2d& tile = tile_2d(cell_x / b, cell_s / b);
  const Tile1d& radius = tile_radius(cell_x / b);
  const CohesiveFunctions hom = homogeneous_functions(a, excess);
  double hom2[kTwoD], value[kTwoD], error[kTwoD];
  to_array_2d(hom, hom2);
  const std::size_t cell = (cell_s - tile.cell_s0) * tile.own_x + (cell_x - tile.cell_x0);
  // Below excess_min: r(e) = r(e_min) + O(e), the slope in e from the first fine node e_1.
  double flat_weight = 0.0, tau_1 = 0.0;
  if (excess < options_.excess_min) {
    tau_1 = g.tau[1];
    const double e_1 = std::exp(s_min + tau_1 * (s_max - s_min));
    flat_weight = (options_.excess_min - excess) / (e_1 - options_.excess_min);
  }
  double wx[kCheckDegree + 1], wt[kCheckDegree + 1];
  std::size_t ix = 0, it = 0, nx = 0, nt = 0;
  if (check > 0) {
    nx = check_weights(g.x, tile.node_x0, tile.node_x1, x, check, ix, wx);
    nt = check_weights(g.tau, tile.node_s0, tile.node_s1, tau, check, it, wt);
  }
  for (int k = 0; k < kTwoD; ++k) {
    double r = 0.0;
    if (check > 0) {
      for (std::size_t q = 0; q < nt; ++q) {
        for (std::size_t p = 0; p < nx; ++p) r += wt[q] * wx[p] * g.z[k][(it + q) * g.x.size() + ix + p];
      }
    } else {
      r = gsl_spline2d_eval((check < 0 ? tile.coarse : tile.fine)[k].spline, x, tau, nullptr, nullptr);
    }
    double flat = 0.0;
    if (flat_weight > 0.0) {
      flat = flat_weight * std::abs(gsl_spline2d_eval(tile.fine[k].spline, x, tau_1, nullptr, nullptr) - r);
    }
    value[k] = r * hom2[k];
    error[k] = (options_.error_factor * tile.cell_error[k][cell] + flat + options_.source_noise * std::abs(r)) *
               std::abs(hom2[k]);
  }
  MdTableValue out;
  from_array_2d(value, out.value);
  from_array_2d(error, out.error);
  const double hom1[kOneD] = {hom.delta_h, hom.force_h};
  double v1[kOneD], e1[kOneD];
  const std::size_t interval = cell_of(g.x1_coarse, x) - radius.interval0;
  double w1[kCheckDegree + 1];
  std::size_t i1 = 0, n1 = 0;
  if (check > 0) n1 = check_weights(g.x1, radius.node0, radius.node1, x, check, i1, w1);
  for (int k = 0; k < kOneD; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    double r = 0.0;
    if (check > 0) {
      for (std::size_t p = 0; p < n1; ++p) r += w1[p] * g.y[k][i1 + p];
    } else {
      r = gsl_spline_eval((check < 0 ? radius.coarse : radius.fine)[kk].spline, x, nullptr);
    }
    // r is ln(ratio): its error Δ is the ratio's relative error e^Δ - 1.
    const double ratio = std::exp(r);
    v1[k] = ratio * hom1[k];
    e1[k] = (std::expm1(options_.error_factor * radius.interval_error[kk][interval]) + options_.source_noise) * ratio *
            std::abs(hom1[k]);
  }
  out.value.delta_h = v1[0];
  out.value.force_h = v1[1];
  out.error.delta_h = e1[0];
  out.error.force_h = e1[1];
  return out;
}

namespace {

constexpr double kBracketStep = kRootBracketStep;

// The largest of the checks' weighted shifts of quantity i (excess, delta, force).
double largest_shift(const MdTableState& st, int i) {
  double out = 0.0;
  for (int c = 0; c < kStateChecks; ++c) out = std::max(out, kCheckWeights[c] * std::abs(st.shift[c][i]));
  return out;
}  // first step in s (or ln c) from the homogeneous root

}  // namespace

// The radius's part of at()'s coordinates and of covers(), for the root's iterations at one a.
struct MaugisDugdaleTable::GapRadius {
  double a = 0.0, x = 0.0, s_min = 0.0, s_max = 0.0, excess_lo = 0.0, excess_hi = 0.0;
  std::size_t tile_x = 0;
};

MaugisDugdaleTable::GapRadius MaugisDugdaleTable::gap_radius(double a) const {
  constexpr double kRounding = 1e-12;  // as covers()
  GapRadius r;
  r.a = a;
  r.excess_lo = std::min(options_.excess_floor, options_.excess_min) * (1.0 - kRounding);
  r.excess_hi = excess_max(a) * (1.0 + kRounding);
  if (options_.closed_form) return r;
  const Grids& g = *grids_;
  r.s_min = std::log(options_.excess_min);
  r.s_max = std::log(excess_max(a));
  r.x = std::clamp(std::log(a), g.x.front(), g.x.back());
  r.tile_x = cell_of(g.x_coarse, r.x) / static_cast<std::size_t>(options_.tile_cells);
  return r;
}

// Successive reads of one root mostly fall in one cell of one tile: GSL's accelerators find it
// without a binary search (the same cell, so the same value), and the tile is taken again
// without tile_2d()'s std::call_once (the radius fixes the tile's column; tile_tau its row).
struct MaugisDugdaleTable::GapCursor {
  const Tile2d* tile = nullptr;
  double tau_lo = 0.0, tau_hi = -1.0;  // the tile's own τ: [tau_lo, tau_hi), open at the grid's ends
  gsl_interp_accel x{0, 0, 0}, tau{0, 0, 0};
  // The last read's c/a - 1, its angle and τ: Brent's root is its last read, which the state
  // (load_functions) reads again.
  double last_excess = std::numeric_limits<double>::quiet_NaN(), last_tau = 0.0;
  ZoneAngle last_angle;
};

// The tile of cell_of(tau_coarse, tau) / tile_cells: cell k holds tau_coarse[k] <= τ <
// tau_coarse[k + 1], its first and last cells extended to the grid's ends.
const MaugisDugdaleTable::Tile2d& MaugisDugdaleTable::cursor_tile(const GapRadius& radius, double tau,
                                                                  GapCursor& cursor) const {
  if (cursor.tile != nullptr && tau >= cursor.tau_lo && tau < cursor.tau_hi) return *cursor.tile;
  const std::vector<double>& g = grids_->tau_coarse;
  const std::size_t cells = static_cast<std::size_t>(options_.tile_cells), tj = cell_of(g, tau) / cells;
  const std::size_t first = tj * cells, next = first + cells;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  cursor.tile = &tile_2d(radius.tile_x, tj);
  cursor.tau_lo = first == 0 ? -kInf : g[first];
  cursor.tau_hi = next + 1 >= g.size() ? kInf : g[next];
  cursor.x = {0, 0, 0};
  cursor.tau = {0, 0, 0};
  return *cursor.tile;
}

// g_r and g_s alone (the root's iterations need nothing else): as at(), two of its six splines.
std::pair<double, double> MaugisDugdaleTable::gap_functions(const GapRadius& radius, double excess,
                                                            GapCursor& cursor) const {
  const ZoneAngle angle = zone_angle(excess);
  const auto hom = homogeneous_gap_at(radius.a, excess, angle);
  if (options_.closed_form) return hom;
  if (!(excess >= radius.excess_lo && excess <= radius.excess_hi)) {
    throw InputError("Maugis-Dugdale table: (a/t, c/a - 1) = (" + short_text(radius.a) + ", " + short_text(excess) +
                     ") outside the table");
  }
  const double tau = std::clamp((std::log(excess) - radius.s_min) / (radius.s_max - radius.s_min), 0.0, 1.0);
  const Tile2d& tile = cursor_tile(radius, tau, cursor);
  cursor.last_excess = excess;
  cursor.last_angle = angle;
  cursor.last_tau = tau;
  return {gsl_spline2d_eval(tile.fine[2].spline, radius.x, tau, &cursor.x, &cursor.tau) * hom.first,
          gsl_spline2d_eval(tile.fine[3].spline, radius.x, tau, &cursor.x, &cursor.tau) * hom.second};
}

CohesiveFunctions MaugisDugdaleTable::load_functions(const GapRadius& radius, double excess,
                                                     GapCursor& cursor) const {
  if (!(excess >= radius.excess_lo && excess <= radius.excess_hi)) {
    throw InputError("Maugis-Dugdale table: (a/t, c/a - 1) = (" + short_text(radius.a) + ", " + short_text(excess) +
                     ") outside the table");
  }
  const bool again = excess == cursor.last_excess;  // (the same number: the same angle and τ)
  CohesiveFunctions out = homogeneous_functions_at(radius.a, excess, again ? cursor.last_angle : zone_angle(excess));
  if (options_.closed_form) return out;
  const double tau = again ? cursor.last_tau
                           : std::clamp((std::log(excess) - radius.s_min) / (radius.s_max - radius.s_min), 0.0, 1.0);
  const Tile2d& tile = cursor_tile(radius, tau, cursor);
  const Tile1d& radius_tile = tile_radius(radius.tile_x);
  out.d *= gsl_spline2d_eval(tile.fine[0].spline, radius.x, tau, &cursor.x, &cursor.tau);
  out.f *= gsl_spline2d_eval(tile.fine[1].spline, radius.x, tau, &cursor.x, &cursor.tau);
  out.delta_h *= std::exp(gsl_spline_eval(radius_tile.fine[0].spline, radius.x, nullptr));
  out.force_h *= std::exp(gsl_spline_eval(radius_tile.fine[1].spline, radius.x, nullptr));
  out.g_r = out.g_s = 0.0;  // not computed
  return out;
}

std::optional<MdTableState> MaugisDugdaleTable::solve(double sigma_hat, double h0, double a, bool with_errors) const {
  const MdTableOptions& o = options_;
  if (!covers_radius(a)) return std::nullopt;
  // ln(h(c)/h0) (R = 1) in s = ln(c/a - 1); h grows with c (THEORY.md section 13, "The root in
  // ln h"): the sign of h - h0, nearly straight in s.
  const GapRadius radius = gap_radius(a);
  GapCursor cursor;
  auto remembered = remembering_last_two([&](double s) {
    const auto [g_r, g_s] = gap_functions(radius, std::exp(s), cursor);
    return log_gap_ratio(g_r + sigma_hat * g_s - h0, h0);
  });
  const std::function<double(double)> residual = [&remembered](double s) { return remembered(s); };
  const double lo = std::log(std::min(o.excess_floor, o.excess_min)), hi = std::log(excess_max(a));
  const auto bracket = bracket_outward(residual, homogeneous_root(sigma_hat, h0, a, lo, hi), lo, hi, kBracketStep);
  if (!bracket) return std::nullopt;
  double s = bracket->first;
  if (bracket->first != bracket->second) {
    const auto root = brent_root(residual, bracket->first, bracket->second, {1e-13, 0.0, 200});
    if (!root) return std::nullopt;
    s = root->x;
  }
  const double e = std::exp(s);
  if (!with_errors) {
    const CohesiveFunctions v = load_functions(radius, e, cursor);
    MdTableState st;
    st.excess = e;
    st.delta = v.delta_h + sigma_hat * v.d;
    st.force = v.force_h + sigma_hat * v.f;
    return st;
  }
  const MdTableValue v = at(a, e);
  // Slope of the gap in s by central differences of the interpolant: the check interpolant's
  // root is one Newton step from the splines' (their difference is the table's error, ~1e-5:
  // the step's own error is its square).
  const double step = 1e-5;
  const double sp = std::min(s + step, hi), sm = std::max(s - step, lo);
  const MdTableValue vp = at(a, std::exp(sp)), vm = at(a, std::exp(sm));
  const double h_s = (vp.value.g_r - vm.value.g_r + sigma_hat * (vp.value.g_s - vm.value.g_s)) / (sp - sm);
  MdTableState st;
  st.excess = e;
  st.delta = v.value.delta_h + sigma_hat * v.value.d;
  st.force = v.value.force_h + sigma_hat * v.value.f;
  // The nodes' noise on the scale of the homogeneous forms (the ratios are O(1) at most).
  const double noise = o.source_noise;
  const CohesiveFunctions hom = homogeneous_functions(a, e);
  st.excess_error = noise * e;
  st.delta_error = noise * (std::abs(hom.delta_h) + sigma_hat * std::abs(hom.d));
  st.force_error = noise * (std::abs(hom.force_h) + sigma_hat * std::abs(hom.f));
  for (int c = 0; c < kStateChecks; ++c) {
    const MdTableValue c0 = at(a, e, kCheckDegrees[c]);
    const double s_c = std::clamp(s - (c0.value.g_r + sigma_hat * c0.value.g_s - h0) / h_s, lo, hi);
    const MdTableValue c1 = at(a, std::exp(s_c), kCheckDegrees[c]);
    st.shift[c][0] = std::exp(s_c) - e;
    st.shift[c][1] = c1.value.delta_h + sigma_hat * c1.value.d - st.delta;
    st.shift[c][2] = c1.value.force_h + sigma_hat * c1.value.f - st.force;
  }
  st.excess_error += kStateErrorFactor * largest_shift(st, 0);
  st.delta_error += kStateErrorFactor * largest_shift(st, 1);
  st.force_error += kStateErrorFactor * largest_shift(st, 2);
  if (e < o.excess_min) {
    // Below the grid the ratios are held at their edge values, which both splines share: the
    // functions' own estimates (their linear change in c/a - 1) propagated through the root.
    const double d_s = sigma_hat * (vp.value.d - vm.value.d) / (sp - sm);
    const double f_s = sigma_hat * (vp.value.f - vm.value.f) / (sp - sm);
    const double s_error = (v.error.g_r + sigma_hat * v.error.g_s) / std::abs(h_s);
    st.excess_error += e * s_error;
    st.delta_error += v.error.delta_h + sigma_hat * v.error.d + std::abs(d_s) * s_error;
    st.force_error += v.error.force_h + sigma_hat * v.error.f + std::abs(f_s) * s_error;
  }
  return st;
}

// Values and error estimates of d, f, g_r, g_s at the curve's end, u = ln(c/t).
void MaugisDugdaleTable::end_values(double u, double* value, double* error, int check) const {
  const Grids& g = *grids_;
  u = std::clamp(u, std::log(std::min(options_.end_c_over_t_floor, options_.end_c_over_t_min)), g.xe.back());
  const double below = u < g.xe.front() ? std::exp(u) : 0.0;  // c under the grid
  double hom[kTwoD];
  to_array_2d(homogeneous_end_functions(std::exp(u)), hom);
  if (options_.closed_form) {
    for (int k = 0; k < kTwoD; ++k) {
      value[k] = hom[k];
      error[k] = options_.source_noise * std::abs(value[k]);
    }
    return;
  }
  const double ug = std::max(u, g.xe.front());
  const std::size_t cell = cell_of(g.xe_coarse, ug);
  const Tile1d& tile = tile_end(cell / static_cast<std::size_t>(options_.tile_cells));
  // Under the grid: r(c) = r(c_min) + O(c), the slope from the next node c_1.
  const double c_min = std::exp(g.xe.front()), c_1 = std::exp(g.xe[1]);
  const double flat_weight = below > 0.0 ? (c_min - below) / (c_1 - c_min) : 0.0;
  double w[kCheckDegree + 1];
  std::size_t i0 = 0, n = 0;
  if (check > 0) n = check_weights(g.xe, tile.node0, tile.node1, ug, check, i0, w);
  for (int k = 0; k < kTwoD; ++k) {
    const auto kk = static_cast<std::size_t>(k);
    double r = 0.0;
    if (check > 0) {
      for (std::size_t p = 0; p < n; ++p) r += w[p] * g.ye[k][i0 + p];
    } else {
      r = gsl_spline_eval((check < 0 ? tile.coarse : tile.fine)[kk].spline, ug, nullptr);
    }
    const double flat =
        flat_weight > 0.0 ? flat_weight * std::abs(gsl_spline_eval(tile.fine[kk].spline, g.xe[1], nullptr) - r) : 0.0;
    value[k] = r * hom[k];
    error[k] = (options_.error_factor * tile.interval_error[kk][cell - tile.interval0] + flat +
                options_.source_noise * std::abs(r)) *
               std::abs(hom[k]);
  }
}

std::optional<MdTableState> MaugisDugdaleTable::solve_end(double sigma_hat, double h0) const {
  if (options_.closed_form) {
    // c²/2 + σ̂ (1 - 2/π) c = h0 (THEORY.md section 13, the end's homogeneous forms).
    const double b = sigma_hat * (1.0 - 2.0 / kPi);
    MdTableState st;
    st.excess = 2.0 * h0 / (b + std::sqrt(b * b + 2.0 * h0));
    const CohesiveFunctions h = homogeneous_end_functions(st.excess);
    st.delta = sigma_hat * h.d;
    st.force = sigma_hat * h.f;
    st.excess_error = options_.source_noise * st.excess;
    st.delta_error = options_.source_noise * std::abs(st.delta);
    st.force_error = options_.source_noise * std::abs(st.force);
    return st;
  }
  const Grids& g = *grids_;
  const double lo = std::log(std::min(options_.end_c_over_t_floor, options_.end_c_over_t_min)), hi = g.xe.back();
  std::function<double(double)> residual = [&](double u) {
    double v[kTwoD], e[kTwoD];
    end_values(u, v, e);
    return v[2] + sigma_hat * v[3] - h0;
  };
  const auto bracket = bracket_outward(residual, std::log(homogeneous_end_root(sigma_hat, h0)), lo, hi, kBracketStep);
  if (!bracket) return std::nullopt;
  double u = bracket->first;
  if (bracket->first != bracket->second) {
    const auto root = brent_root(residual, bracket->first, bracket->second, {1e-13, 0.0, 200});
    if (!root) return std::nullopt;
    u = root->x;
  }
  const double step = 1e-5;
  double v[kTwoD], e[kTwoD], vp[kTwoD], vm[kTwoD], vc[kTwoD], scratch[kTwoD];
  end_values(u, v, e);
  const double up = std::min(u + step, hi), um = std::max(u - step, lo);
  end_values(up, vp, scratch);
  end_values(um, vm, scratch);
  const double h_u = (vp[2] - vm[2] + sigma_hat * (vp[3] - vm[3])) / (up - um);
  MdTableState st;
  st.excess = std::exp(u);
  st.delta = sigma_hat * v[0];
  st.force = sigma_hat * v[1];
  // As solve(): the check interpolant's root by one Newton step, the state's change the estimate.
  const double noise = options_.source_noise;
  const CohesiveFunctions hom = homogeneous_end_functions(st.excess);
  st.excess_error = noise * st.excess;
  st.delta_error = noise * sigma_hat * std::abs(hom.d);
  st.force_error = noise * sigma_hat * std::abs(hom.f);
  for (int c = 0; c < kStateChecks; ++c) {
    end_values(u, vc, scratch, kCheckDegrees[c]);
    const double u_c = std::clamp(u - (vc[2] + sigma_hat * vc[3] - h0) / h_u, lo, hi);
    end_values(u_c, vc, scratch, kCheckDegrees[c]);
    st.shift[c][0] = std::exp(u_c) - st.excess;
    st.shift[c][1] = sigma_hat * vc[0] - st.delta;
    st.shift[c][2] = sigma_hat * vc[1] - st.force;
  }
  st.excess_error += kStateErrorFactor * largest_shift(st, 0);
  st.delta_error += kStateErrorFactor * largest_shift(st, 1);
  st.force_error += kStateErrorFactor * largest_shift(st, 2);
  if (u < g.xe.front()) {
    // Under the grid both splines hold the edge values: the functions' own estimates.
    const double u_error = (e[2] + sigma_hat * e[3]) / std::abs(h_u);
    st.excess_error += st.excess * u_error;
    st.delta_error += sigma_hat * (e[0] + std::abs((vp[0] - vm[0]) / (up - um)) * u_error);
    st.force_error += sigma_hat * (e[1] + std::abs((vp[1] - vm[1]) / (up - um)) * u_error);
  }
  return st;
}

}  // namespace coatcontact::detail
