// Kernel tables through the solve cache (docs/solver.md, "Solve cache"): a table is built once
// per stack, grid and build, then every later process, map or Dask worker that uses the same
// cache folder loads its image (cc_kernel_image.h) instead of building it again. The entry
// kind "table": one record per file, the table's creation status (int64) then, when that is
// CC_OK, its image; a table whose grid misses its accuracy target (CC_ERR_ACCURACY, a compact
// grid too short for the stack) is remembered as such, so the next process goes straight to
// the next grid. Keyed by the exact arrays the kernel library builds from, the grid and the
// build id: the same H bit for bit, whichever process built it.
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <sstream>
#include <string>
#include <vector>

#include "coatcontact/cc_kernel_image.h"
#include "coatcontact/errors.hpp"
#include "coatcontact/kernel.hpp"
#include "coatcontact/detail/build_id.hpp"
#include "coatcontact/solve_cache.hpp"
#include "solve_cache.hpp"

namespace coatcontact::detail {

namespace {

// Longer than any table's build (the figures' three-layer stack: ~0.2 s; the finest stack grid,
// 32 times refined: a few seconds): a waiter gives up only on a builder that hangs.
constexpr std::chrono::milliseconds kBuildPatience{60000};

int build(const kernel_detail::StackArrays& a, const TableGrid& grid, cc_kernel_table** table) {
  if (grid.compact) {
    return cc_kernel_table_create_stack_range(a.n(), a.thickness.data(), a.youngs.data(), a.poisson.data(),
                                              a.slip.data(), a.rigid, a.e_base, a.nu_base, grid.u_range, table);
  }
  return (grid.h_only ? cc_kernel_table_create_stack_h : cc_kernel_table_create_stack)(
      a.n(), a.thickness.data(), a.youngs.data(), a.poisson.data(), a.slip.data(), a.rigid, a.e_base, a.nu_base,
      grid.variant, table);
}

// The cache folder, or "" for none (a folder the cache refuses only costs the build here; the
// solvers report it, coatcontact/solve_cache.hpp).
std::string cache_folder() {
  try {
    return solve_cache_directory();
  } catch (const InputError&) {
    return "";
  }
}

// Status, then the image of a built table.
std::string record_of(int status, const cc_kernel_table* table) {
  std::string record(sizeof(std::int64_t), '\0');
  const std::int64_t s = status;
  std::memcpy(record.data(), &s, sizeof s);
  int n = 0;
  if (status != CC_OK) return record;
  if (cc_kernel_table_image_size(table, &n) != CC_OK) return "";
  std::vector<double> image(static_cast<std::size_t>(n));
  if (cc_kernel_table_image(table, n, image.data()) != CC_OK) return "";
  record.append(reinterpret_cast<const char*>(image.data()), image.size() * sizeof(double));
  return record;
}

// The table (CC_OK) or the remembered failure held by `record`; -1 if it holds neither.
int from_record(const std::string& record, cc_kernel_table** table) {
  if (record.size() < sizeof(std::int64_t)) return -1;
  std::int64_t status = 0;
  std::memcpy(&status, record.data(), sizeof status);
  const std::size_t bytes = record.size() - sizeof status;
  if (status == CC_ERR_ACCURACY && bytes == 0) return CC_ERR_ACCURACY;
  if (status != CC_OK || bytes % sizeof(double) != 0 || bytes / sizeof(double) > std::size_t{1} << 30) return -1;
  std::vector<double> image(bytes / sizeof(double));
  std::memcpy(image.data(), record.data() + sizeof status, bytes);
  return cc_kernel_table_from_image(static_cast<int>(image.size()), image.data(), table) == CC_OK ? CC_OK : -1;
}

}  // namespace

std::string kernel_table_key(const kernel_detail::StackArrays& a, const TableGrid& grid) {
  std::ostringstream key;
  key << "build " << kBuildId << "; layers";
  for (int i = 0; i < a.n(); ++i) {
    const auto k = static_cast<std::size_t>(i);
    key << " " << exact_text(a.thickness[k]) << "," << exact_text(a.youngs[k]) << "," << exact_text(a.poisson[k])
        << (a.slip[k] != 0 ? ",slip" : "");
  }
  key << "; base " << (a.rigid != 0 ? std::string("rigid") : exact_text(a.e_base) + "," + exact_text(a.nu_base));
  key << "; grid " << grid.variant;
  if (grid.compact) {
    key << "; compact " << exact_text(grid.u_range) << "; H";
  } else {
    key << "; full" << (grid.h_only ? "; H" : "; H and H1");
  }
  return key.str();
}

int create_stack_table(const kernel_detail::StackArrays& a, const TableGrid& grid, cc_kernel_table** table) {
  const std::string folder = cache_folder();
  // Arguments the kernel library refuses are reported by it, never looked up.
  const bool valid_range = !grid.compact || (grid.u_range > 0.0 && std::isfinite(grid.u_range));
  if (folder.empty() || !valid_range || table == nullptr) return build(a, grid, table);
  CacheRecords records(folder, "table", kernel_table_key(a, grid), 0, 0);
  const auto loaded = [&records, table] {
    for (const std::string& record : records.loaded()) {
      const int status = from_record(record, table);
      if (status >= 0) return status;
    }
    return -1;
  };
  int status = loaded();
  if (status >= 0) return status;
  // A process building this table now (make -j, a map's threads, Dask workers started at once)
  // is waited for; after the wait, the table is read, or built here if it is still missing.
  if (records.wait_for_key(kBuildPatience)) {
    status = loaded();
    if (status >= 0) return status;
  }
  status = build(a, grid, table);
  if (status == CC_OK || status == CC_ERR_ACCURACY) {
    std::string record = record_of(status, status == CC_OK ? *table : nullptr);
    if (!record.empty()) records.add(std::move(record));
  }
  return status;  // `records` writes the new entry (atomically), then releases the key's lock
}

}  // namespace coatcontact::detail
