// The solve cache's kernel tables (cpp/solver/table_cache.cpp; docs/solver.md "Solve cache";
// label unit): a table loaded from the cache is the table built, bit for bit, and so are the
// solves on it; a corrupt or truncated entry is detected, removed and the table built again;
// different stacks and grids never share an entry; an image that is not one is refused.
#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/cc_kernel_image.h"
#include "coatcontact/kernel.hpp"
#include "kernel_values.hpp"
#include "coatcontact/reduced.hpp"
#include "coatcontact/solve_cache.hpp"
#include "materials.hpp"
#include "solve_cache.hpp"
#include "table_kernel.hpp"

using namespace coatcontact;
using coatcontact::test::elastic;
using coatcontact::test::material;
namespace fs = std::filesystem;

namespace {

// The three-layer stack of `make figures` (data/figures.conf STACK_LAYERS): its table is the
// one worth caching (~0.17 s of CPU, the multilayer compliance on a 4x refined grid).
Stack figure_stack(double top_modulus = 10.0) {
  std::vector<Layer> layers(3);
  const double h[3] = {1, 1, 2}, e[3] = {top_modulus, 1, 3}, nu[3] = {0.3, 0.45, 0.35};
  for (int i = 0; i < 3; ++i) {
    layers[static_cast<std::size_t>(i)].thickness = h[i];
    layers[static_cast<std::size_t>(i)].material = material(e[i], nu[i]);
  }
  return Stack(layers, elastic(100.0, 0.25));
}

Stack film(double ratio) {
  Layer layer;
  layer.thickness = 1.0;
  layer.material = material(ratio, 0.25);
  return Stack({layer}, elastic(1.0, 0.25));
}

// u over the tabulated range, beyond it (the asymptotic series) and at the nodes.
std::vector<double> probes(const KernelTableInfo& info) {
  std::vector<double> u;
  for (int k = 0; k <= 3000; ++k) u.push_back(1.3 * info.u_max * k / 3000.0);
  for (int k = 0; k < 50; ++k) u.push_back(info.du * (7 * k + 1));
  return u;
}

bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

bool same_info(const KernelTableInfo& a, const KernelTableInfo& b) {
  return a.u_max == b.u_max && a.du == b.du && a.c_zero == b.c_zero && a.half_integral == b.half_integral &&
         a.abs_accuracy == b.abs_accuracy && a.max_abs_h == b.max_abs_h;
}

// H (and H1 when the table has it) at the probes.
std::vector<double> values_of(const KernelTable& table, bool with_h1) {
  return check::kernel_values(table, probes(table.info()), with_h1);
}

std::vector<double> values_of(const detail::TableKernel& table, const KernelTableInfo& info) {
  const std::vector<double> u = probes(info);
  std::vector<double> h(u.size());
  table.evaluate(u.size(), u.data(), h.data());
  return h;
}

// The entry files of kind "table" under the cache.
std::vector<fs::path> table_entries(const fs::path& root) {
  std::vector<fs::path> out;
  if (!fs::exists(root)) return out;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    const std::string folder = e.path().parent_path().filename().string();
    if (e.is_regular_file() && e.path().extension() == ".bin" && folder.rfind("table-", 0) == 0) out.push_back(e.path());
  }
  return out;
}

// The reduced variables at radii on both solver tables (compact and full grid), as doubles.
std::vector<double> solves(const Stack& stack) {
  const ReducedSolver solver(stack);
  std::vector<double> out;
  for (double a : {0.05, 0.7, 6.0, 60.0}) {
    const ReducedVariables v = solver.solve(a, 1e-8);
    for (double x : {v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1, v.error_estimate}) out.push_back(x);
    out.push_back(v.unknowns);
  }
  return out;
}

void loaded_tables_are_built_tables(const fs::path& root) {
  for (const Stack& stack : {figure_stack(), film(0.1)}) {
    set_solve_cache_directory("");
    const KernelTable built(stack, 0);
    const std::vector<double> reference = values_of(built, true);
    const detail::TableKernel built_h(stack, 2);
    const KernelTableInfo info_h = KernelTable(stack, 2, KernelTable::HOnly{}).info();
    const std::vector<double> reference_h = values_of(built_h, info_h);
    set_solve_cache_directory(root.string());
    const std::size_t before = table_entries(root).size();
    for (int pass = 0; pass < 2; ++pass) {  // pass 0 builds and stores, pass 1 loads
      const KernelTable table(stack, 0);
      check::that(same_info(table.info(), built.info()), "pass " + std::to_string(pass) + ": the same info()");
      check::that(same_bits(values_of(table, true), reference), "pass " + std::to_string(pass) + ": H and H1 bit for bit");
      const detail::TableKernel table_h(stack, 2);
      check::that(same_bits(values_of(table_h, info_h), reference_h), "grid variant 2 (H only) bit for bit");
    }
    check::that(table_entries(root).size() == before + 2, "one entry per table, written once");
  }
  // The solves on loaded tables (the compact grid and the full one) equal those without a cache.
  const Stack stack = figure_stack();
  set_solve_cache_directory("");
  const std::vector<double> reference = solves(stack);
  set_solve_cache_directory(root.string());
  check::that(same_bits(solves(stack), reference), "solves with the tables built into the cache");
  // Only the tables stay: the next solver loads them and solves every radius again.
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_directory() && e.path().filename().string().rfind("solve-", 0) == 0) {
      for (const auto& f : fs::directory_iterator(e.path())) fs::remove(f.path());
    }
  }
  check::that(same_bits(solves(stack), reference), "solves on tables loaded from the cache, bit for bit");
}

// A valid entry whose H differs from the built table's by one value is what the next table
// holds: proof that the table is loaded, not built, once the cache has it.
void a_table_is_loaded_not_built(const fs::path& root) {
  const Stack stack = film(10.0);
  set_solve_cache_directory(root.string());
  const kernel_detail::StackArrays arrays = kernel_detail::stack_arrays(stack);
  const detail::TableGrid grid{1, false, 0.0, true};
  const std::string key = detail::kernel_table_key(arrays, grid);
  cc_kernel_table* raw = nullptr;
  check::that(detail::create_stack_table(arrays, grid, &raw) == CC_OK, "table built");
  int n = 0;
  cc_kernel_table_image_size(raw, &n);
  std::vector<double> image(static_cast<std::size_t>(n));
  check::that(cc_kernel_table_image(raw, n, image.data()) == CC_OK, "image taken");
  cc_kernel_table_destroy(raw);
  const KernelTableInfo info = KernelTable(stack, 1, KernelTable::HOnly{}).info();
  const double h0 = KernelTable(stack, 1, KernelTable::HOnly{}).h(0.0);
  for (const fs::path& p : table_entries(root)) fs::remove(p);
  // Node 0's H follows the header (8 integers, 9 reals) and the Taylor and Lagrange arrays
  // (their sizes: image[1], image[2]; cc_kernel_table_image.f90).
  const auto node0 = static_cast<std::size_t>(17 + image[1] + image[2]);
  check::that(node0 < image.size(), "node 0 inside the image");
  image[node0] += 1.0;
  std::string record(sizeof(std::int64_t), '\0');
  record.append(reinterpret_cast<const char*>(image.data()), image.size() * sizeof(double));
  detail::CacheRecords(root.string(), "table", key, 0, 0).add(record);
  const KernelTable loaded(stack, 1, KernelTable::HOnly{});
  check::close(loaded.h(0.0), h0 + 1.0, check::tier::kMachine, "H(0) is the cache entry's: the table was loaded");
  check::that(same_info(loaded.info(), info), "its other fields are the entry's");
  for (const fs::path& p : table_entries(root)) fs::remove(p);
}

// A truncated entry and one with a flipped byte are removed and the table built again.
void corrupt_entries_are_rebuilt(const fs::path& root) {
  const Stack stack = film(0.1);
  set_solve_cache_directory("");
  const std::vector<double> reference = values_of(KernelTable(stack, 0), true);
  set_solve_cache_directory(root.string());
  for (const fs::path& p : table_entries(root)) fs::remove(p);
  { const KernelTable stored(stack, 0); }
  for (int damage = 0; damage < 3; ++damage) {
    const std::vector<fs::path> entries = table_entries(root);
    check::that(entries.size() == 1, "one entry before damage " + std::to_string(damage));
    if (entries.size() != 1) return;
    const fs::path entry = entries.front();
    const auto size = fs::file_size(entry);
    if (damage == 0) {
      fs::resize_file(entry, size / 2);  // a writer killed mid-file would leave none; a disk might
    } else {
      std::fstream f(entry, std::ios::in | std::ios::out | std::ios::binary);
      f.seekp(static_cast<std::streamoff>(damage == 1 ? size / 3 : 40));  // an H value; the key line
      char c = 0;
      f.read(&c, 1);
      f.seekp(static_cast<std::streamoff>(damage == 1 ? size / 3 : 40));
      c = static_cast<char>(c ^ 0x10);
      f.write(&c, 1);
    }
    const KernelTable table(stack, 0);
    check::that(same_bits(values_of(table, true), reference), "damage " + std::to_string(damage) + ": built again, bit for bit");
    check::that(!fs::exists(entry), "damage " + std::to_string(damage) + ": the damaged entry removed");
    check::that(table_entries(root).size() == 1, "damage " + std::to_string(damage) + ": a new entry written");
  }
}

// Stacks one ulp apart, grid variants, compact and full grids, H and H with H1: separate entries.
void different_tables_do_not_collide(const fs::path& root) {
  set_solve_cache_directory(root.string());
  for (const fs::path& p : table_entries(root)) fs::remove(p);
  const Stack a = figure_stack(), b = figure_stack(std::nextafter(10.0, 11.0));
  const kernel_detail::StackArrays arrays_a = kernel_detail::stack_arrays(a), arrays_b = kernel_detail::stack_arrays(b);
  const std::vector<detail::TableGrid> grids = {
      {0, false, 0.0, false}, {0, false, 0.0, true}, {1, false, 0.0, true}, {0, true, 80.0, true}, {0, true, 160.0, true}};
  std::vector<std::string> keys;
  for (const auto* arrays : {&arrays_a, &arrays_b}) {
    for (const detail::TableGrid& g : grids) keys.push_back(detail::kernel_table_key(*arrays, g));
  }
  bool distinct = true;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) distinct = distinct && keys[i] != keys[j];
  }
  check::that(distinct, "every stack and grid has its own key");
  // Both stacks through the cache, each twice: each loads its own table.
  for (int pass = 0; pass < 2; ++pass) {
    set_solve_cache_directory("");
    const std::vector<double> ref_a = values_of(KernelTable(a, 0, KernelTable::HOnly{}), false);
    const std::vector<double> ref_b = values_of(KernelTable(b, 0, KernelTable::HOnly{}), false);
    set_solve_cache_directory(root.string());
    check::that(same_bits(values_of(KernelTable(a, 0, KernelTable::HOnly{}), false), ref_a), "stack a: its own table");
    check::that(same_bits(values_of(KernelTable(b, 0, KernelTable::HOnly{}), false), ref_b), "stack b: its own table");
    check::that(!same_bits(ref_a, ref_b), "the two stacks' tables differ");
  }
  check::that(table_entries(root).size() == 2, "two stacks, two entries");
}

void images_that_are_not_refused() {
  set_solve_cache_directory("");
  const KernelTable table(film(0.1), 0);
  cc_kernel_table* raw = nullptr;
  const kernel_detail::StackArrays arrays = kernel_detail::stack_arrays(film(0.1));
  check::that(detail::create_stack_table(arrays, {0, false, 0.0, false}, &raw) == CC_OK, "built");
  int n = 0;
  cc_kernel_table_image_size(raw, &n);
  std::vector<double> image(static_cast<std::size_t>(n));
  cc_kernel_table_image(raw, n, image.data());
  cc_kernel_table_destroy(raw);
  cc_kernel_table* made = nullptr;
  check::that(cc_kernel_table_from_image(n - 1, image.data(), &made) == CC_ERR_ARGUMENT && made == nullptr,
              "one double short: refused");
  std::vector<double> bad = image;
  bad[0] = 2.0;
  check::that(cc_kernel_table_from_image(n, bad.data(), &made) == CC_ERR_ARGUMENT, "another format: refused");
  bad = image;
  bad[3] += 1.0;
  check::that(cc_kernel_table_from_image(n, bad.data(), &made) == CC_ERR_ARGUMENT, "node count off by one: refused");
  bad = image;
  bad[static_cast<std::size_t>(n) / 2] = std::numeric_limits<double>::quiet_NaN();
  check::that(cc_kernel_table_from_image(n, bad.data(), &made) == CC_ERR_ARGUMENT, "a NaN: refused");
  check::that(cc_kernel_table_from_image(n, image.data(), &made) == CC_OK && made != nullptr, "the image: accepted");
  cc_kernel_table_destroy(made);
}

}  // namespace

int main() {
  const fs::path root = fs::temp_directory_path() / ("cc_kernel_table_cache_" + std::to_string(::getpid()));
  fs::remove_all(root);
  loaded_tables_are_built_tables(root);
  a_table_is_loaded_not_built(root);
  corrupt_entries_are_rebuilt(root);
  different_tables_do_not_collide(root);
  images_that_are_not_refused();
  set_solve_cache_directory("");
  fs::remove_all(root);
  return check::exit_code();
}
