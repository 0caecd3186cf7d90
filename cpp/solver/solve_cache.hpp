// The solve cache's stores (internal to the solver floor and the floors above it; public
// switch: coatcontact/solve_cache.hpp; design: docs/solver.md). Thread-safe.
#pragma once
#include <cstdint>
#include <map>
#include <mutex>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/reduced.hpp"
#include "coatcontact/stack.hpp"

namespace coatcontact::detail {

// The files of one kind of entry ("solve": reduced variables; "zone": the cohesive zone
// table's nodes) under one key, in <directory>/<build id>/<kind>-<hash of the key>/: fixed-size
// binary records, each file complete or absent. Several processes may add files at once.
class CacheRecords {
 public:
  // Reads every complete file of this key (a corrupt one is removed, a foreign key's left).
  CacheRecords(const std::string& directory, const std::string& kind, const std::string& key,
               std::size_t record_bytes);
  ~CacheRecords();  // flush()
  CacheRecords(const CacheRecords&) = delete;
  CacheRecords& operator=(const CacheRecords&) = delete;

  // The records read at construction, in file order (later files may repeat earlier records).
  const std::vector<std::string>& loaded() const { return loaded_; }
  // A record of record_bytes bytes, written by the next flush().
  void add(std::string record);
  // New records into one file, written atomically (a temporary name, then rename); every
  // failure is silent (the cache only saves time). Merges the folder's files when they are many.
  void flush();

 private:
  void remove_other_builds() const;
  std::string build_folder_;
  std::string folder_;
  std::string magic_;
  std::string key_;
  std::size_t record_bytes_;
  std::mutex mutex_;
  std::vector<std::string> loaded_, added_;
  std::vector<std::string> loaded_files_;
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
