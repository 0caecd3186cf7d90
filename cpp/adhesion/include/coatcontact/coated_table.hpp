// The reduced variables of a coating as functions of a/t AND of one layer's modulus
// (THEORY.md section 15, "Tabled coated force laws"): verified ReducedTables in ln(a/t) at nodes
// of log10(E_L/E_ref) (E_ref the base's modulus, 1 Pa on a rigid base), Lagrange in ln X
// across the nearest nodes. A fit with the layer's modulus free reads every trial from it.
//
// Thread safety: a node's decades of a/t are built (prepare_range) under the table's mutex
// before any reader sees them; a built decade is only read, so one CoatedTable serves every
// thread. A decade is built when a lookup first needs it.
#pragma once
#include <array>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <vector>

#include "coatcontact/reduced.hpp"
#include "coatcontact/reduced_table.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact {

struct CoatedTableOptions {
  double a_over_t_min = 1e-2, a_over_t_max = 1e2;  // the range served (InputError outside)
  double solver_tolerance = 1e-8;                  // of the direct solves at the nodes
  // Tolerance of each node's verified interpolant in ln(a/t) (sweep_table_options).
  double a_over_t_tolerance = 1e-6;
  // Nodes per decade of the free layer's modulus and of the Lagrange interpolant across them
  // (even, 2..12: the nearest ones). Largest error measured (tests/afm/test_afm_coated_table.cpp,
  // 240 points, a/t 1e-3..1e3): cubic at 4 per decade 2.3e-4, at 8 2.0e-5; quintic at 4 3.3e-5,
  // at 6 4.1e-6, at 8 6.5e-7.
  double nodes_per_decade = 8.0;
  int stencil = 6;
  // Cross-node estimate: this factor x |P(stencil) - P(stencil + 1)| (the next node's term
  // estimates the interpolant's error; for the quintic at 8 per decade measured to fall short of
  // it by up to 2.4x).
  double cross_safety = 3.0;
  // The nodes' interpolation estimate in ln(a/t) (ReducedTable::interpolation_error_at) times
  // this factor (measured to fall short of the actual error by up to 1.2x at 1e-6).
  double a_over_t_safety = 1.5;
};

// Values at one (a/t, E_L) with the estimate of their largest relative error.
struct CoatedValues {
  ReducedPoint point;
  double error_estimate = 0.0;  // cross_error + the nodes' in-a/t estimates (a_over_t_safety x interpolation + node_error)
  double cross_error = 0.0;     // cross-node estimate, largest over the variables
  double node_error = 0.0;      // the nodes' own (solver) error estimates, interpolated
};

// The nodes' values at one grid of a/t, kept by one caller (not shared between threads) that
// asks for many moduli at that grid, as a fit's trials do: each node's tables are read once per
// grid, and a new modulus costs only the sums across the nodes. Another grid clears it.
class CoatedSweepCache {
 public:
  std::size_t nodes() const { return nodes_.size(); }

 private:
  friend class CoatedTable;
  struct NodeValues {
    std::vector<std::array<double, 6>> logs, dlogs;  // ln X and d ln X / d ln(a/t) per a/t
    std::vector<double> total, interpolation;        // the node table's estimates per a/t
  };
  std::vector<double> a_over_t_;
  std::map<long, NodeValues> nodes_;
};

class CoatedTable {
 public:
  // `stack` fixes everything but layer `free_layer`'s Young's modulus (its Poisson ratio stays).
  // A single layer on a rigid base under a rigid indenter is scale-free (E1 only scales F): one
  // node serves every E1.
  CoatedTable(const Stack& stack, std::size_t free_layer, CoatedTableOptions options = {});
  ~CoatedTable();
  CoatedTable(const CoatedTable&) = delete;
  CoatedTable& operator=(const CoatedTable&) = delete;

  // Reduced variables at each a/t for the free modulus `modulus` [Pa] (the stack's unit),
  // each row's error_estimate the table's; builds the nodes it needs (thread-safe).
  std::vector<CoatedValues> at(double modulus, const std::vector<double>& a_over_t) const;
  CoatedValues at(double modulus, double a_over_t) const;
  // The same values, the nodes' values at `a_over_t` kept in `cache` (bit-identical to the above).
  std::vector<CoatedValues> at(double modulus, const std::vector<double>& a_over_t, CoatedSweepCache& cache) const;

  bool scale_free() const { return scale_free_; }
  std::size_t nodes() const;
  std::size_t source_solves() const;  // direct solves of all nodes built so far
  const CoatedTableOptions& options() const { return options_; }

 private:
  struct Node;
  Node& node(long j) const;  // caller holds mutex_
  CoatedSweepCache::NodeValues node_values(long j, const std::vector<double>& a_over_t) const;
  Stack stack_with(double modulus) const;

  Stack stack_;
  std::size_t free_layer_;
  CoatedTableOptions options_;
  bool scale_free_ = false;
  double reference_ = 1.0;  // E_ref
  mutable std::mutex mutex_;
  mutable std::map<long, std::unique_ptr<Node>> nodes_;
};

}  // namespace coatcontact
