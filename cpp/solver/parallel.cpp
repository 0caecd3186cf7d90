// parallel_for (parallel.hpp), the thread's progress hook and the fork rule
// (coatcontact/progress.hpp).
#include "parallel.hpp"

#include <pthread.h>
#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <atomic>
#include <cstdlib>
#include <exception>
#include <string>
#include <system_error>
#include <thread>
#include <utility>
#include <vector>

#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"

namespace coatcontact {

namespace {

thread_local ProgressHook current_hook;

std::atomic<bool> forked_child{false};

void mark_forked_child() { forked_child.store(true); }

// Registered when the library is loaded (this file is linked whenever a sweep is).
const int fork_handler_registered = pthread_atfork(nullptr, nullptr, mark_forked_child);

}  // namespace

ProgressHook exchange_progress_hook(ProgressHook hook) {
  ProgressHook previous = std::move(current_hook);
  current_hook = std::move(hook);
  return previous;
}

ScopedProgressHook::ScopedProgressHook(ProgressHook hook) : previous_(exchange_progress_hook(std::move(hook))) {}

ScopedProgressHook::~ScopedProgressHook() { exchange_progress_hook(std::move(previous_)); }

// Without the fork handler (pthread_atfork failed, never seen) nothing can be known.
bool parallel_sweeps_allowed() { return fork_handler_registered != 0 || !forked_child.load(); }

namespace detail {

void check_thread_count(long value, const std::string& name) {
  if (value < 1 || value > kMaxThreads) {
    throw InputError(name + ": " + std::to_string(value) + " is not allowed; expected a whole number of threads from 1 to " +
                     std::to_string(kMaxThreads));
  }
}

namespace {

// True in the threads of a parallel loop while they run its units.
thread_local bool inside_parallel_loop = false;

// The threads of a loop of `count` units: OpenMP's count (OMP_NUM_THREADS, omp_set_num_threads)
// checked against kMaxThreads, and no more than the units.
int loop_threads(std::size_t count) {
#ifdef _OPENMP
  const long wanted = omp_get_max_threads();
  if (wanted > kMaxThreads) {
    const char* environment = std::getenv("OMP_NUM_THREADS");
    const std::string name = environment != nullptr ? "OMP_NUM_THREADS" : "the thread count (omp_set_num_threads, jobs)";
    check_thread_count(wanted, name);
  }
  return static_cast<int>(std::min<long>(wanted, static_cast<long>(std::min<std::size_t>(count, kMaxThreads))));
#else
  (void)count;
  return 1;
#endif
}

}  // namespace

void parallel_for(std::size_t count, const std::function<void(std::size_t index)>& body) {
  std::vector<std::exception_ptr> errors(count);
  const ProgressHook hook = current_hook;  // the calling thread's (a copy: the hook may replace it)
  const std::thread::id caller = std::this_thread::get_id();
  std::atomic<std::size_t> done{0};
  std::atomic<bool> stop{false};
  std::size_t last_reported = 0;  // written by the calling thread only
  auto report = [&](std::size_t finished) {
    bool go_on = false;
    try {
      go_on = hook(finished, count);
    } catch (...) {
      go_on = false;
    }
    last_reported = finished;
    if (!go_on) stop.store(true);
  };
  auto unit = [&](std::size_t i) {
    if (stop.load(std::memory_order_relaxed)) return;
    try {
      body(i);
    } catch (...) {
      errors[i] = std::current_exception();
    }
    const std::size_t finished = done.fetch_add(1) + 1;
    // Only the calling thread runs the hook (a binding's signal check must run there).
    if (hook && std::this_thread::get_id() == caller) report(finished);
  };
  // Units in index order from one counter (dynamic schedule, chunks of one): a caller that
  // puts its costly units first gets them started first.
  std::atomic<std::size_t> next{0};
  auto take_units = [&] {
    for (std::size_t i = next.fetch_add(1); i < count; i = next.fetch_add(1)) unit(i);
  };
  // No threads for a single unit (starting one costs more than the work), nor inside a unit of
  // another loop (nested loops run serially, as OpenMP's default had them).
  if (count > 1 && parallel_sweeps_allowed() && !inside_parallel_loop) {
    const int threads = loop_threads(count);
    // Plain threads joined at the end, not an OpenMP team: a team's idle threads spin-wait at
    // the loop's end and between loops, which cost 15-20 % of a sweep's CPU (docs/speed.md).
    std::vector<std::thread> helpers;
    helpers.reserve(static_cast<std::size_t>(std::max(threads - 1, 0)));
    try {
      for (int t = 1; t < threads; ++t) helpers.emplace_back([&] {
        inside_parallel_loop = true;
        take_units();
      });
    } catch (const std::system_error&) {
      // fewer threads than asked for: the ones started (and the caller) do all units
    }
    inside_parallel_loop = true;
    take_units();
    inside_parallel_loop = false;
    for (std::thread& helper : helpers) helper.join();
  } else {
    take_units();
  }
  // The last unit may have finished on another thread: the hook always sees the end.
  if (hook && !stop.load() && last_reported < count) report(count);
  if (stop.load()) {
    throw Interrupted("interrupted after " + std::to_string(done.load()) + " of " + std::to_string(count) +
                      " units of work");
  }
  for (const auto& error : errors) {
    if (error) std::rethrow_exception(error);  // the first failing unit, as in a serial loop
  }
}

}  // namespace detail

}  // namespace coatcontact
