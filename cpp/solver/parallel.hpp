// The one parallel loop of the library (internal): independent units of work (contact radii,
// pull-offs) on OpenMP's number of threads (plain threads taking units in index order), each
// unit's exception kept and the first one (in index order) rethrown, as a serial loop would.
// Serial in a forked child (parallel_sweeps_allowed), for a single unit and inside a unit of
// another loop; the calling thread's progress hook (coatcontact/progress.hpp) is
// called between units and can stop the loop (Interrupted).
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/errors.hpp"
#include "coatcontact/point_status.hpp"

namespace coatcontact::detail {

// Runs body(0) .. body(count - 1) on at most kMaxThreads threads. InputError naming
// OMP_NUM_THREADS if the environment asks for more (libgomp would try to start them all and
// crash).
void parallel_for(std::size_t count, const std::function<void(std::size_t index)>& body);

// The most threads a parallel loop starts (the CLI's --jobs allows the same).
constexpr long kMaxThreads = 1024;
// InputError "<name>: <value> is not allowed; ..." unless 1 <= value <= kMaxThreads.
void check_thread_count(long value, const std::string& name);

// The points at(0) .. at(count - 1) in the parallel loop, point by point (point_status.hpp): a
// NumericalError leaves blank(i) in its place and its reason in status[i] instead of failing
// the array.
template <class Point, class At, class Blank>
std::vector<Point> parallel_points(std::size_t count, const At& at, const Blank& blank,
                                   std::vector<PointStatus>& status) {
  std::vector<Point> out(count);
  std::vector<PointStatus> outcome(count);
  parallel_for(count, [&](std::size_t i) {
    try {
      out[i] = at(i);
    } catch (const NumericalError& e) {
      out[i] = blank(i);
      outcome[i] = PointStatus{false, e.what()};
    }
  });
  status = std::move(outcome);
  return out;
}

}  // namespace coatcontact::detail
