// The outcome of one point of an array computed point by point (radii of `reduced`, of a
// curve, of a shape's contact): delivered, or not delivered with the reason. The tolerant
// overloads of ReducedSolver::sweep, AdhesiveModel::curve and ShapeContact::curve return
// every point they can and one PointStatus per point; bad input still fails the whole call
// (InputError), and a point never carries a NaN (its values are 0 and must not be read).
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace coatcontact {

struct PointStatus {
  bool delivered = true;
  std::string reason;  // the NumericalError's message when not delivered, else empty
};

// Points not delivered.
inline std::size_t failed_points(const std::vector<PointStatus>& status) {
  std::size_t failed = 0;
  for (const PointStatus& s : status) failed += s.delivered ? 0 : 1;
  return failed;
}

}  // namespace coatcontact
