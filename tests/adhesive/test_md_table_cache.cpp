// The cohesive-zone table's nodes in the solve cache (docs/solver.md, "Solve cache"): a table
// that reads the nodes an earlier table wrote returns the same values, bit for bit, as one
// solved without the cache, and solves nothing for queries the first one answered; a new query
// region is solved and added; another table option is another key (nothing read); a corrupt
// file is removed and its nodes solved again.
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/solve_cache.hpp"
#include "coatcontact/stack.hpp"
#include "md_table.hpp"
#include "solve_cache.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;
namespace fs = std::filesystem;

namespace {

struct Query {
  double sigma_hat, h0, a;
};

// Every value of the table's states at the queries (-1 where there is none), and a curve end.
std::vector<double> states(const detail::MaugisDugdaleTable& table, const std::vector<Query>& queries) {
  std::vector<double> out;
  for (const Query& q : queries) {
    const auto st = table.solve(q.sigma_hat, q.h0, q.a);
    if (!st) {
      out.push_back(-1.0);
      continue;
    }
    for (double v : {st->excess, st->delta, st->force, st->excess_error, st->delta_error, st->force_error}) {
      out.push_back(v);
    }
  }
  const auto end = table.solve_end(0.8, 0.5);
  out.push_back(end ? end->excess : -1.0);
  return out;
}

bool identical(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

std::vector<fs::path> files(const fs::path& root) {
  std::vector<fs::path> out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file() && e.path().extension() == ".bin") out.push_back(e.path());  // not its tag
  }
  return out;
}

}  // namespace

int main() {
  Substrate base;
  base.material = {1.0, 0.25};
  const Stack soft = Stack::film_on({0.1, 0.25}, base);
  const detail::TableKernel kernel(soft);
  const detail::Discretization disc;
  const detail::CohesiveQuadrature quadrature;
  detail::MdTableOptions options;
  options.a_over_t_min = 1e-2;
  options.a_over_t_max = 1e1;
  options.c_over_t_max = 1e3;
  const std::string key = detail::SolveCache::key_of(soft);
  const std::vector<Query> first = {{0.5, 2.0, 0.03}, {2.0, 0.2, 0.02}, {0.1, 5.0, 0.05}};
  const std::vector<Query> second = {{1.0, 1.0, 8.0}};  // tiles of its own (2.4 in ln a_over_t)

  const fs::path root = fs::temp_directory_path() / ("cc_md_cache_" + std::to_string(::getpid()));
  fs::remove_all(root);

  set_solve_cache_directory("");
  std::vector<double> reference, reference2;
  {
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, options, key);
    reference = states(table, first);
    reference2 = states(table, second);
  }

  set_solve_cache_directory(root.string());
  long cold_nodes = 0;
  {
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, options, key);
    check::that(identical(states(table, first), reference), "cold cache: the values of no cache, bit for bit");
    cold_nodes = table.nodes_used();
    check::that(table.nodes_solved() >= cold_nodes, "cold cache: every node used was solved");
  }
  check::that(files(root).size() == 1, "the cold table wrote one file");
  {
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, options, key);
    check::that(identical(states(table, first), reference), "warm cache: the values of no cache, bit for bit");
    check::that(table.nodes_solved() == 0, "warm cache: nothing solved (solved " +
                                               std::to_string(table.nodes_solved()) + ")");
    check::that(table.nodes_used() == cold_nodes, "warm cache: the same nodes used as the cold table");
    check::that(identical(states(table, second), reference2), "warm cache, new region: the values of no cache");
    check::that(table.nodes_solved() > 0, "warm cache, new region: its nodes solved");
  }
  check::that(files(root).size() == 2, "the new region's nodes written to a second file");
  std::vector<fs::path> written = files(root);
  {
    detail::MdTableOptions other = options;
    other.step = 0.25;
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, other, key);
    states(table, first);
    check::that(table.nodes_used() > 0 && table.nodes_solved() >= table.nodes_used(),
                "another table option: every node it uses solved, none read from the cache");
  }
  {
    // Corrupt the two files of the first key: removed, their nodes solved again, the same values.
    for (const fs::path& f : written) {
      std::fstream io(f, std::ios::in | std::ios::out | std::ios::binary);
      io.seekp(static_cast<std::streamoff>(fs::file_size(f) / 2));
      io.put('\x5a');
    }
    const detail::MaugisDugdaleTable table(kernel, disc, quadrature, options, key);
    check::that(identical(states(table, first), reference), "corrupt files: the values of no cache");
    check::that(table.nodes_solved() > 0, "corrupt files: the nodes solved again");
    for (const fs::path& f : written) check::that(!fs::exists(f), "corrupt file removed: " + f.string());
  }
  set_solve_cache_directory("");
  fs::remove_all(root);
  {
    // A radius node on an x node reads its column's factorization, built by whichever of the
    // radius tile (margin 2) and the 2-D tile (margin 1 here) comes first: the same values in
    // either order (radii forward and backward, tiles built on demand).
    detail::MdTableOptions narrow = options;
    narrow.margin_cells = 1;
    std::vector<double> radii;
    for (int k = 0; k <= 12; ++k) radii.push_back(0.012 * std::pow(700.0, k / 12.0));
    auto values = [&](bool backward) {
      const detail::MaugisDugdaleTable table(kernel, disc, quadrature, narrow);
      std::vector<double> out(2 * 4 * radii.size());
      for (std::size_t n = 0; n < radii.size(); ++n) {
        const std::size_t k = backward ? radii.size() - 1 - n : n;
        const detail::MdTableValue v = table.at(radii[k], 0.5);
        const double row[8] = {v.value.delta_h, v.value.force_h, v.value.d,     v.value.f,
                               v.error.delta_h, v.error.force_h, v.error.d, v.error.f};
        std::memcpy(&out[8 * k], row, sizeof row);
      }
      return out;
    };
    check::that(identical(values(false), values(true)),
                "radius nodes on the columns: the same values whichever tile factors the column");
  }
  return check::exit_code();
}
