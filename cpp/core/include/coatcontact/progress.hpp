// Progress and interruption of long library calls (sweeps of contact radii, curves, pull-offs).
//
// A hook installed for a thread is called by every parallel sweep that thread starts, on that
// thread, between units of work (one contact radius, one pull-off): hook(done, total) with
// the units finished so far and the sweep's total. Returning false stops the sweep: the units
// not yet started are skipped and the call throws Interrupted (coatcontact/errors.hpp).
// Bindings use it to check for signals (Python's Ctrl-C) and to report progress.
#pragma once
#include <cstddef>
#include <functional>

namespace coatcontact {

using ProgressHook = std::function<bool(std::size_t done, std::size_t total)>;

// Installs `hook` for the calling thread (an empty one removes it); returns the previous one.
ProgressHook exchange_progress_hook(ProgressHook hook);

// Installs `hook` for the calling thread for the lifetime of the object (the previous hook
// is restored after it); an empty hook removes any.
class ScopedProgressHook {
 public:
  explicit ScopedProgressHook(ProgressHook hook);
  ~ScopedProgressHook();
  ScopedProgressHook(const ScopedProgressHook&) = delete;
  ScopedProgressHook& operator=(const ScopedProgressHook&) = delete;

 private:
  ProgressHook previous_;
};

// False in a process forked from the one that loaded the library: an OpenMP runtime whose
// worker threads the parent had started does not survive fork() (libgomp then waits forever
// for threads the child does not have), so sweeps in a forked child run serially.
bool parallel_sweeps_allowed();

}  // namespace coatcontact
