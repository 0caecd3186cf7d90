// Regression (issue 40, item 2; label unit): the solve cache's store (CacheRecords,
// docs/solver.md "Solve cache") kept every copy of a record and had no size cap.
//  - records written by writers that did not see each other are read once each, bit for bit;
//  - a folder's files are merged into one once they are many, each record once;
//  - above the size cap the folders used longest ago are removed (a folder read recently is
//    kept), the total stays below the cap plus one folder, and a user's file is never removed.
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/solve_cache.hpp"
#include "solve_cache.hpp"

using namespace coatcontact;
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kRecordBytes = 32, kIdBytes = 16;

// Record `id` of key `key`: its id twice, then two values that depend on both.
std::string record(std::uint64_t key, std::uint64_t id) {
  std::string r(kRecordBytes, '\0');
  const double values[2] = {1.0 / static_cast<double>(id + 3), static_cast<double>(key) + 0.1};
  std::memcpy(r.data(), &id, 8);
  std::memcpy(r.data() + 8, &key, 8);
  std::memcpy(r.data() + 16, values, 16);
  return r;
}

std::string key_text(std::uint64_t key) { return "test key " + std::to_string(key); }

std::unique_ptr<detail::CacheRecords> open(const fs::path& root, std::uint64_t key) {
  return std::make_unique<detail::CacheRecords>(root.string(), "test", key_text(key), kRecordBytes, kIdBytes);
}

// The key's folder (the FNV-1a hash of its text under the build id's 16 digits).
fs::path folder_of(const fs::path& root, std::uint64_t key) {
  const std::string text = key_text(key);
  std::uint64_t h = 1469598103934665603ull;
  for (const char c : text) {
    h ^= static_cast<unsigned char>(c);
    h *= 1099511628211ull;
  }
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(h));
  return root / std::string(solve_cache_build_id()).substr(0, 16) / ("test-" + std::string(hash));
}

std::size_t entries(const fs::path& folder) {
  std::size_t n = 0;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    n += it->path().extension() == ".bin" ? 1 : 0;
  }
  return n;
}

std::uintmax_t entry_bytes(const fs::path& root) {
  std::uintmax_t total = 0;
  for (const auto& e : fs::recursive_directory_iterator(root)) {
    if (e.is_regular_file() && e.path().extension() == ".bin") total += e.file_size();
  }
  return total;
}

// Every record loaded is one of `ids` of `key`, bit for bit, each exactly once.
bool loads_exactly(const fs::path& root, std::uint64_t key, std::uint64_t first, std::uint64_t count) {
  const auto reader = open(root, key);
  std::vector<int> seen(count, 0);
  for (const std::string& r : reader->loaded()) {
    std::uint64_t id = 0;
    std::memcpy(&id, r.data(), 8);
    if (id < first || id >= first + count || r != record(key, id) || seen[id - first]++ != 0) return false;
  }
  return reader->loaded().size() == count;
}

}  // namespace

int main() {
  const fs::path root = fs::temp_directory_path() / ("cc_cache_size_cap_" + std::to_string(::getpid()));
  fs::remove_all(root);

  // Three writers open the key before any of them writes: 100 records common to all, 10 each of their own.
  {
    std::vector<std::unique_ptr<detail::CacheRecords>> writers;
    for (int w = 0; w < 3; ++w) writers.push_back(open(root, 0));
    for (int w = 0; w < 3; ++w) {
      for (std::uint64_t id = 0; id < 100; ++id) writers[w]->add(record(0, id));
      for (std::uint64_t id = 0; id < 10; ++id) writers[w]->add(record(0, 100 + 10 * w + id));
      writers[w]->add(record(0, 0));  // added twice: written once
      writers[w]->flush();
    }
  }
  check::that(entries(folder_of(root, 0)) == 3, "three writers wrote three files");
  check::that(loads_exactly(root, 0, 0, 130), "records written three times are read once each, bit for bit");

  // One writer after another, 5 new records each: merged once the folder has 8 files.
  for (std::uint64_t w = 0; w < 12; ++w) {
    const auto writer = open(root, 0);
    for (std::uint64_t id = 0; id < 5; ++id) writer->add(record(0, 130 + 5 * w + id));
    writer->add(record(0, 7));  // known: not written again
  }
  check::that(entries(folder_of(root, 0)) <= 8, "the folder's files merged (" +
                                                    std::to_string(entries(folder_of(root, 0))) + " files)");
  check::that(loads_exactly(root, 0, 0, 190), "after merging every record is read once, bit for bit");
  const std::uintmax_t key0_bytes = entry_bytes(root);
  check::that(key0_bytes < 3 * 190 * kRecordBytes,
              "merged size " + std::to_string(key0_bytes) + " bytes for 190 records");

  // The size cap: keys of 100 records (~3.3 kB a folder) under a cap of 64 KiB.
  const std::uintmax_t cap = 64 * 1024;
  detail::set_cache_size_cap(cap);
  std::ofstream(root / "notes.txt") << "a user's file\n";
  bool evicted_in_order = false, any_evicted = false;
  for (std::uint64_t key = 1; key <= 40; ++key) {
    {
      const auto writer = open(root, key);
      for (std::uint64_t id = 0; id < 100; ++id) writer->add(record(key, id));
    }
    if (key == 2) std::ofstream(folder_of(root, 2) / "mine.txt") << "a user's file\n";
    if (key == 12) check::that(loads_exactly(root, 1, 0, 100), "key 1 read back before the cap is reached");
    const std::uintmax_t total = entry_bytes(root);
    check::that(total <= cap + 4096, "after key " + std::to_string(key) + ": " + std::to_string(total) +
                                          " bytes of entries, cap " + std::to_string(cap));
    if (!any_evicted && entries(folder_of(root, 0)) == 0) {
      any_evicted = true;
      // Key 1 was read after keys 2..11 were written: it is used more recently than they are.
      evicted_in_order = entries(folder_of(root, 1)) > 0 && entries(folder_of(root, 2)) == 0;
    }
  }
  check::that(any_evicted, "folders were evicted above the cap");
  check::that(evicted_in_order, "the folder used longest ago went first; one read recently stayed");
  check::that(loads_exactly(root, 40, 0, 100), "the newest key is kept whole");
  check::that(fs::exists(root / "notes.txt"), "a user's file in the cache folder is kept");
  check::that(fs::exists(folder_of(root, 2) / "mine.txt"), "a user's file in an evicted folder is kept");
  detail::set_cache_size_cap(detail::kDefaultCacheSizeCap);
  fs::remove_all(root);
  return check::exit_code();
}
