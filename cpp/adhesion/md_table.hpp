// The reduced table of the Maugis-Dugdale cohesive zone (THEORY.md section 13, "The cohesive
// zone as a table"): at fixed (a, c) the zone is linear in its loads 1/R, δ and σ̂, so
//   δ = δ_H(a)/R + σ̂ d(a, c),   F = F_H(a)/R + σ̂ f(a, c),   h(c) = g_R(a, c)/R + σ̂ g_σ(a, c).
// The four 2-D functions are tabulated once per stack as ratios to their homogeneous closed
// forms against x = ln(a/t) and τ = (s - s_min)/(s_max(x) - s_min), s = ln(c/a - 1), where
// s_max(x) keeps c below c_over_t_max (GSL bicubic gsl_spline2d), with an error
// estimate from a second interpolant on every other node. The grid is cut into tiles, each
// interpolated on its own nodes plus a margin and built on first use: a query solves only the
// nodes of the tiles it touches. Units as cohesive_zone.hpp (t = 1, E1* = 1, R = 1).
// Library-private (not installed).
//
// Thread safety: every const member function may run concurrently; a tile is built once
// (std::call_once), the nodes it needs under one lock.
//
// With a cache key and the solve cache on (coatcontact/solve_cache.hpp), the nodes solved by
// earlier processes are read instead of solved, and the new ones are written when the table
// is destroyed: a node is a pure function of the stack, the options and its grid index, so
// every value the table returns is the same with and without the cache.
#pragma once
#include <functional>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <utility>

#include "cohesive_zone.hpp"
#include "factored_system.hpp"
#include "kernel_source.hpp"

namespace coatcontact::detail {

// The zone's functions (CohesiveFunctions, cohesive_zone.hpp) at c/a - 1 = excess, R = 1.
CohesiveFunctions cohesive_functions(const CohesiveZone& zone, double excess);
// Which root of h(c) = h0 (THEORY.md section 13, "Which root"): a layered stack's gap need not
// grow monotonically with c. Where no neighbouring root of the same curve guides the search, the
// table and the direct solve both take the root reached by bracketing outward from the
// homogeneous solid's root: f grows with its argument; from `start`, steps of `step` growing by
// half each time toward the side f's sign points to; the first sign change [lo', hi'] is
// returned (nullopt when f keeps its sign to the end of [lo, hi]).
inline constexpr double kRootBracketStep = 0.5;
std::optional<std::pair<double, double>> bracket_outward(const std::function<double(double)>& f, double start,
                                                         double lo, double hi, double step = kRootBracketStep);
// The homogeneous solid's root in s = ln(c/a - 1), clamped to [lo, hi] (a > 0), and at the
// curve's end (a = 0) its c: c²/2 + σ̂ (1 - 2/π) c = h0.
double homogeneous_root(double sigma_hat, double h0, double a, double lo, double hi);
double homogeneous_end_root(double sigma_hat, double h0);

// The homogeneous closed forms (Maugis), free of cancellation as excess -> 0.
CohesiveFunctions homogeneous_functions(double a, double excess);
// Their g_r and g_s alone (the same values, bit for bit): what a root of the gap needs.
std::pair<double, double> homogeneous_gap_functions(double a, double excess);
// The same at the end of the curve, a = 0, zone radius c (d, f, g_r, g_s only).
CohesiveFunctions homogeneous_end_functions(double c);

struct MdTableOptions {
  double a_over_t_min = 1e-3, a_over_t_max = 1e3;
  // c/a - 1 from excess_min; c/t up to c_over_t_max (at least 10 a_over_t_max). The zone of the
  // curve's end is c/t ~ 1.5 lambda^-1/2 / eta: 1e4 covers lambda >= 1e-3 with eta >= 0.01.
  double excess_min = 1e-9, c_over_t_max = 1e4;
  // Below excess_min (the JKR end, lambda ~ 1e4 at large a_bar) the ratios are flat to
  // O(c/a - 1) (THEORY.md section 13): their values at excess_min serve down to excess_floor,
  // the error estimate widened by their linear change in c/a - 1 over that step.
  double excess_floor = 1e-16;
  // The end of the curve (a = 0) is tabulated in ln(c/t) from end_c_over_t_min to c_over_t_max.
  double end_c_over_t_min = 1e-5;
  // Below it (the end's zone at lambda ~ 1e4 is c/t ~ 1e-6) the zone sees the top layer as a
  // half-space: the ratios change by O(c/t); their values at end_c_over_t_min serve down to
  // end_c_over_t_floor, the error widened by their linear change in c.
  double end_c_over_t_floor = 1e-12;
  double step = 0.3;  // node spacing in x = ln(a/t) and (at most) in s = ln(c/a - 1), fine grid
  // The error estimate of a value of at() is error_factor times the largest |fine - coarse| in
  // its coarse cell (coarse: every other node), plus the nodes' own relative noise (solve()'s
  // states use the check interpolants instead, MdTableState).
  // Cubic interpolation makes the fine error ~1/16 of that difference; the pointwise
  // difference alone can vanish by chance (measured: errors up to 2.7 times it), the cell's
  // largest cannot.
  double error_factor = 1.0;
  // The nodes' noise relative to the homogeneous forms (the ratios' scale): their 8-point
  // annulus rule's bound ~4^-16 ~ 2e-10 (below).
  double source_noise = 2e-10;
  // Tiles: tile_cells coarse cells per direction, interpolated with margin_cells more on each
  // side (the splines' end conditions decay over a few nodes; the error estimate sees what is
  // left, since the coarse spline's end error is the larger). The 1-D functions, cheap, keep
  // a margin of at least 2 (with 1, the curve's end on a rigid base missed its estimate by
  // 1e-10 relative where the function is flat). The 2-D tiles keep 2 as well: with 1, the
  // splines of neighbouring tiles disagree at their edges (within the estimate) by enough to
  // move a real AFM fit by 0.19 SE from one spline through the same nodes; with 2, <= 0.018 SE
  // (docs/speed.md, "2-D tile margins of 2 cells? (mdmargin37)").
  int tile_cells = 4;
  int margin_cells = 2;
  // Gauss points per annulus piece at the table's nodes (at most the model's): 8 bounds the
  // quadrature's error by ~4^-16 ~ 2e-10 (THEORY.md section 13), far below the interpolation's;
  // measured, pull-offs move by <= 2.4e-13 from the 10-point nodes, at 0.7 of their cost (6
  // points put one value on a rigid base outside its estimate).
  int node_points_per_piece = 8;
  // The stack is one homogeneous half-space (its kernel H is zero): every function is its
  // closed form (THEORY.md section 13, "Homogeneous closed forms"), returned with the source
  // noise as its error and no node solved.
  bool closed_form = false;
};

// The table's answer at (a, excess): values and absolute error estimates.
struct MdTableValue {
  CohesiveFunctions value;
  CohesiveFunctions error;
};

// The Maugis-Dugdale state at contact radius a from the table: root s of
// g_R + σ̂ g_σ = h0 (R = 1) by Brent, δ and F reconstructed, each with its error estimate.
// The estimate is the whole state's change when a more accurate interpolant of the same nodes
// (Lagrange of degree 7 or 5, error O(h^8), O(h^6) against the cubic splines' O(h^4)) stands for
// the splines, root included (shift, check - splines, signed: errors of the four functions that
// cancel through the root cancel here too), times kStateErrorFactor (THEORY.md section 13,
// "Error estimates of the state").
struct MdTableState {
  double excess = 0.0, delta = 0.0, force = 0.0;
  double excess_error = 0.0, delta_error = 0.0, force_error = 0.0;
  // shift[c]: (excess, delta, force) of check c minus the splines'.
  double shift[3][3] = {};
};
// Three checks: Lagrange of degrees 7 and 5, and the coarse splines (every other node, cubic:
// their error ~16 times the fine ones', weight 1/15); the estimate takes the largest weighted
// shift, so that a check agreeing with the splines by chance does not hide their error.
inline constexpr int kStateChecks = 3;
inline constexpr int kCheckDegrees[kStateChecks] = {7, 5, -1};
inline constexpr double kCheckWeights[kStateChecks] = {1.0, 1.0, 1.0 / 40.0};
// The shift is the splines' error up to the check's own (O(h^2) of it); the factor is a margin
// for that, calibrated against the direct solve (tests/adhesive/test_md_error_estimate.cpp).
inline constexpr double kStateErrorFactor = 3.0;

class MaugisDugdaleTable {
 public:
  // kernel must outlive the table. Nothing is solved until the first query. cache_key: the
  // text that identifies the kernel's stack and build (SolveCache::key_of), or "" for no cache.
  MaugisDugdaleTable(const KernelSource& kernel, const Discretization& disc, const CohesiveQuadrature& quadrature,
                     const MdTableOptions& options = {}, const std::string& cache_key = "");
  ~MaugisDugdaleTable();
  MaugisDugdaleTable(const MaugisDugdaleTable&) = delete;
  MaugisDugdaleTable& operator=(const MaugisDugdaleTable&) = delete;

  bool covers(double a, double excess) const;
  bool covers_radius(double a) const;
  // InputError outside the table (see covers()).
  // check > 0: the values of the check interpolant (Lagrange of that degree on the nearest
  // nodes; errors as the splines'), whose difference from the splines' estimates their error;
  // check < 0: the coarse splines'.
  MdTableValue at(double a, double excess, int check = 0) const;
  // The end of the curve a = 0: root c of g_R + σ̂ g_σ = h0 in ln c; `excess` holds c (as
  // CohesiveState). nullopt if the root lies outside [end_c_over_t_min, c_over_t_max].
  std::optional<MdTableState> solve_end(double sigma_hat, double h0) const;
  // Largest c/a - 1 in the table at a.
  double excess_max(double a) const;
  // nullopt if a is outside the table or the root lies outside its excess range. The root is
  // bracketed from the homogeneous solid's root outward, so that only the tiles near it are
  // built.
  // with_errors = false: the values alone, every *_error 0 (saves three of the root's ~15
  // interpolations; for callers that use no estimate, as the AFM fit's trials).
  std::optional<MdTableState> solve(double sigma_hat, double h0, double a, bool with_errors = true) const;

  void build() const;            // builds every tile now (otherwise each on first use)
  double build_seconds() const;  // wall time spent building tiles so far
  // Nodes (2-D, curve-end, radius) the tiles built so far rest on, solved here or read from the
  // cache (the same count either way); and those solved by this table (column factorizations
  // included).
  long nodes_used() const;
  long nodes_solved() const;
  int nodes_x() const;
  int nodes_s() const;
  const MdTableOptions& options() const { return options_; }

 private:
  struct Grids;
  struct Tile2d;
  struct Tile1d;
  const Tile2d& tile_2d(std::size_t ti, std::size_t tj) const;
  const Tile1d& tile_radius(std::size_t ti) const;
  const Tile1d& tile_end(std::size_t ti) const;
  // Solves the missing 2-D nodes (i, j) (and the factorizations of their columns), or the
  // missing curve-end nodes, under the node lock.
  void solve_nodes(const std::vector<std::pair<std::size_t, std::size_t>>& nodes) const;
  void solve_end_nodes(std::size_t first, std::size_t last) const;
  void solve_radius_nodes(std::size_t first, std::size_t last) const;
  void end_values(double u, double* value, double* error, int check = 0) const;
  MdTableValue closed_form_value(double a, double excess) const;
  // g_r and g_s along one radius (the root's iterations): its logarithms and tile column once.
  struct GapRadius;
  struct GapCursor;  // the last tile read and GSL's accelerators into its grid (one root's)
  GapRadius gap_radius(double a) const;
  const Tile2d& cursor_tile(const GapRadius& radius, double tau, GapCursor& cursor) const;
  std::pair<double, double> gap_functions(const GapRadius& radius, double excess, GapCursor& cursor) const;
  // d, f, δ_H and F_H alone (the state without its estimates): at() without g_r and g_s.
  CohesiveFunctions load_functions(const GapRadius& radius, double excess, GapCursor& cursor) const;
  void load_cached_nodes() const;
  std::vector<std::size_t> use_nodes(std::vector<char>& used, const std::vector<char>& solved, std::size_t first,
                                     std::size_t last) const;
  const KernelSource& kernel_;
  Discretization disc_;
  CohesiveQuadrature quadrature_;
  MdTableOptions options_;
  std::unique_ptr<Grids> grids_;
};

}  // namespace coatcontact::detail
