// The one parallel loop of the library (internal): independent units of work (contact radii,
// pull-offs) in an OpenMP loop, each unit's exception kept and the first one (in index
// order) rethrown, as a serial loop would. Serial in a forked child (parallel_sweeps_allowed)
// and for a single unit; the calling thread's progress hook (coatcontact/progress.hpp) is
// called between units and can stop the loop (Interrupted).
#pragma once
#include <cstddef>
#include <functional>

namespace coatcontact::detail {

void parallel_for(std::size_t count, const std::function<void(std::size_t index)>& body);

}  // namespace coatcontact::detail
