// Kernel tables built from many threads at once (fortran/cc_kernel_tables.f90 keeps the FFTW plan
// of each transform for the next table of the same grid, shared under the planner lock and run
// concurrently): every table equals the one built alone, bit for bit, whichever thread planned
// its transforms first and whatever ran beside it. Grids mixed: the full grid with and without
// H1, an independent variant, compact grids (R2HC of other lengths), a stack refined twice.
#include <cstdio>
#include <functional>
#include <string>
#include <thread>
#include <vector>

#include "check.hpp"
#include "coatcontact/kernel.hpp"
#include "kernel_values.hpp"

using namespace coatcontact;

namespace {
Stack film_on(double e1, double nu1, double e0, double nu0) {
  Substrate s;
  s.material = {e0, nu0};
  return Stack::film_on({e1, nu1}, s);
}

struct Build {
  std::string name;
  std::function<KernelTable()> make;
};

// H (and H1 where the table has it) on a grid of u through the tabulated range and beyond.
std::vector<double> values_of(const KernelTable& table, bool with_h1) {
  std::vector<double> u;
  for (int i = 0; i <= 4000; ++i) u.push_back(0.173 * i);
  return check::kernel_values(table, u, with_h1);
}
}  // namespace

int main() {
  const Stack soft = film_on(1.0, 0.25, 10.0, 0.25), stiff = film_on(15.0, 0.5, 1.0, 0.25);
  Substrate base;
  base.material = {1.0, 0.3};
  const Stack halved({{0.5, {3.0, 0.3}}, {0.5, {1.0, 0.45}}}, base);
  const std::vector<Build> builds = {
      {"soft full, H and H1", [&] { return KernelTable(soft); }},
      {"soft full, H only", [&] { return KernelTable(soft, 0, KernelTable::HOnly{}); }},
      {"soft variant 1", [&] { return KernelTable(soft, 1, KernelTable::HOnly{}); }},
      {"soft compact 80", [&] { return KernelTable(soft, 80.0); }},
      {"stiff compact 320", [&] { return KernelTable(stiff, 320.0); }},
      {"stiff full, H only", [&] { return KernelTable(stiff, 0, KernelTable::HOnly{}); }},
      {"stack refined twice, compact 160", [&] { return KernelTable(halved, 160.0); }},
  };
  auto has_h1 = [](std::size_t k) { return k == 0; };
  // Alone, one after the other (the first of each grid plans its transforms).
  std::vector<std::vector<double>> alone;
  for (std::size_t k = 0; k < builds.size(); ++k) alone.push_back(values_of(builds[k].make(), has_h1(k)));
  // Every build twice at once from its own thread.
  constexpr int kRounds = 2;
  std::vector<std::vector<double>> together(kRounds * builds.size());
  std::vector<std::thread> threads;
  for (int r = 0; r < kRounds; ++r) {
    for (std::size_t k = 0; k < builds.size(); ++k) {
      threads.emplace_back([&, r, k] { together[r * builds.size() + k] = values_of(builds[k].make(), has_h1(k)); });
    }
  }
  for (std::thread& t : threads) t.join();
  for (int r = 0; r < kRounds; ++r) {
    for (std::size_t k = 0; k < builds.size(); ++k) {
      check::that(together[r * builds.size() + k] == alone[k],
                  builds[k].name + ": built beside the others, the same bits as built alone");
    }
  }
  std::printf("%zu grids, %d concurrent builds each\n", builds.size(), kRounds);
  return check::exit_code();
}
