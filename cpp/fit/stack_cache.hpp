// The few stacks a fit needs at once (private to the fit floor): the stack at the parameters
// and its neighbours e^(+-h) in each table-changing free parameter (for the Jacobian), most
// recent first. Every distinct set of h_i/T and E_i enters C(q) and needs its own solver; an
// Entry is built from (Problem, StackKey) and reports the reduced-variable solves it made.
#pragma once
#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

#include "force_model.hpp"

namespace coatcontact::fit::internal {

// The entry of a model solved at every point: its solver (ShapeSolver, MaugisDugdaleModel) on
// the stack, no table.
template <class Solver>
class SolverEntry {
 public:
  SolverEntry(const Problem& problem, const StackKey& key)
      : key_(key), solver_(std::make_unique<Solver>(stack_of(problem, key))) {}
  const Solver& solver() const { return *solver_; }
  const StackKey& key() const { return key_; }
  long source_evaluations() const { return 0; }

 private:
  StackKey key_;
  std::unique_ptr<Solver> solver_;
};

template <class Entry>
class StackCache {
 public:
  StackCache(const Problem& problem, std::size_t capacity) : problem_(problem), capacity_(capacity) {}

  Entry& get(const Parameters& p) {
    const StackKey key = StackKey::of(p);
    for (auto it = entries_.begin(); it != entries_.end(); ++it) {
      if ((*it)->key() == key) {
        std::rotate(entries_.begin(), it, it + 1);
        return *entries_.front();
      }
    }
    if (entries_.size() >= capacity_) {
      retired_calls_ += entries_.back()->source_evaluations();
      entries_.pop_back();
    }
    entries_.insert(entries_.begin(), std::make_unique<Entry>(problem_, key));
    return *entries_.front();
  }

  // Reduced-variable solves of every table built so far.
  long solver_calls() const {
    long calls = retired_calls_;
    for (const auto& e : entries_) calls += e->source_evaluations();
    return calls;
  }

 private:
  const Problem& problem_;
  std::size_t capacity_;
  std::vector<std::unique_ptr<Entry>> entries_;
  long retired_calls_ = 0;
};

}  // namespace coatcontact::fit::internal
