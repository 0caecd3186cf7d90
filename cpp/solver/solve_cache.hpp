// The solve cache's stores (internal to the solver floor and the floors above it; public
// switch: coatcontact/solve_cache.hpp; design: docs/solver.md). Thread-safe.
#pragma once
#include <chrono>
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <unordered_set>
#include <utility>
#include <vector>

#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::detail {

// The cache's size cap (bytes of entries under DIR): above it, the folders used longest ago are
// removed until a quarter of it is free. kDefaultCacheSizeCap unless a test sets another.
constexpr std::uintmax_t kDefaultCacheSizeCap = std::uintmax_t{256} << 20;
void set_cache_size_cap(std::uintmax_t bytes);
std::uintmax_t cache_size_cap();

// Whether `directory` cannot be the cache (a file, a device, a non-empty folder without the
// cache's CACHEDIR.TAG, ...); `why` says what it is.
bool solve_cache_root_refused(const std::string& directory, std::string& why);

// The files of one kind of entry ("solve": reduced variables; "zone": the cohesive zone
// table's nodes; "table": kernel tables) under one key, in
// <directory>/<build id>/<kind>-<hash of the key>/: fixed-size binary records, the first
// id_bytes of which identify one (a record is kept once), or with record_bytes 0 one record of
// any length per file (id_bytes 0: one record per key); each file complete or absent.
// Several processes may add files at once; one at a time merges them.
// Nothing is read or removed unless <directory> holds the cache's CACHEDIR.TAG, and only files
// whose name and first line are the cache's are ever removed.
class CacheRecords {
 public:
  // Reads every complete file of this key (a corrupt one of the cache's is removed, a foreign
  // key's left).
  CacheRecords(const std::string& directory, const std::string& kind, const std::string& key,
               std::size_t record_bytes, std::size_t id_bytes);
  ~CacheRecords();  // flush()
  CacheRecords(const CacheRecords&) = delete;
  CacheRecords& operator=(const CacheRecords&) = delete;

  // The records read at construction, each id once.
  const std::vector<std::string>& loaded() const { return loaded_; }
  // A record of record_bytes bytes, written by the next flush() unless its id is known already.
  void add(std::string record);
  // New records into one file, written atomically (a temporary name, then rename), after
  // making DIR the cache's if it is absent or empty; every failure is silent (the cache only
  // saves time). The folder's files are merged when they are many (under its lock file), and
  // the cache is trimmed when it exceeds the size cap.
  void flush();
  // Waits up to `patience` for the key's lock (its folder's .lock, made the cache's if needed),
  // then reads the folder again: of several processes about to compute the same entry, one
  // does while the others wait and read it. Held until destruction, released after the flush.
  // False (no lock, nothing read) if the folder cannot be made or the wait runs out.
  bool wait_for_key(std::chrono::milliseconds patience);

 private:
  void read_folder();
  bool make_folder();
  bool read_entry(const std::string& path, std::vector<std::string>& out, bool& foreign) const;
  void keep_new(std::vector<std::string>& records, std::vector<std::string>& out);
  std::uintmax_t write_entry(const std::vector<std::string>& records) const;
  std::uintmax_t merge(const std::vector<std::string>& records);
  std::string root_;
  std::string build_folder_;
  std::string folder_;
  std::string magic_;
  std::string key_;
  std::size_t record_bytes_;
  std::size_t id_bytes_;
  std::mutex mutex_;
  std::vector<std::string> loaded_, added_;
  std::unordered_set<std::string> ids_;  // of loaded_ and of every record added
  std::size_t files_ = 0;                // complete files of this key in the folder, as far as known
  int key_lock_ = -1;                    // descriptor holding the key's lock (wait_for_key), or -1
};

// Exact text of a double (hexadecimal floating point), for keys.
std::string exact_text(double x);

class SolveCache {
 public:
  // Reads every entry of the stack's folder under `directory` (created on first write).
  SolveCache(const std::string& directory, const Stack& stack);
  SolveCache(const SolveCache&) = delete;
  SolveCache& operator=(const SolveCache&) = delete;

  std::optional<ReducedVariables> find(double a_over_t, double tolerance) const;
  void add(double tolerance, const ReducedVariables& values);
  void flush() { records_.flush(); }

  // The text the entries are keyed by (stack constants as exact bits, build id).
  static std::string key_of(const Stack& stack);

 private:
  using Key = std::pair<std::uint64_t, std::uint64_t>;  // bits of tolerance, a/t
  CacheRecords records_;
  mutable std::mutex mutex_;
  std::map<Key, ReducedVariables> entries_;
};

}  // namespace coatcontact::detail
