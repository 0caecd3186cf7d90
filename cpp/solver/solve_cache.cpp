// The solve cache (coatcontact/solve_cache.hpp, solve_cache.hpp; docs/solver.md).
//
// One folder per kind and key, <directory>/<build id, 16 digits>/<kind>-<FNV-1a of the key>; in
// it, files written by the processes that solved something new, each complete or absent
// (written under a temporary name starting with '.', then renamed): several processes (make -j)
// add entries at once without locks, and a reader takes the union. File: the line
// "coatcontact <kind> cache 1", the key line, a count, the fixed-size records, then an FNV-1a
// checksum of all that precedes. A "solve" record: the tolerance, a/t, the six values and the
// error estimate (binary doubles) and the unknowns (int64).
#include "solve_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

#include "coatcontact/detail/build_id.hpp"
#include "coatcontact/solve_cache.hpp"

namespace coatcontact {

namespace {

std::mutex g_directory_mutex;
bool g_directory_set = false;
std::string g_directory;

}  // namespace

void set_solve_cache_directory(const std::string& directory) {
  const std::lock_guard<std::mutex> lock(g_directory_mutex);
  g_directory = directory;
  g_directory_set = true;
}

std::string solve_cache_directory() {
  const std::lock_guard<std::mutex> lock(g_directory_mutex);
  if (!g_directory_set) {
    const char* value = std::getenv("COATCONTACT_CACHE");
    g_directory = value != nullptr ? value : "";
    g_directory_set = true;
  }
  return g_directory;
}

const char* solve_cache_build_id() { return detail::kBuildId; }

namespace detail {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kDoublesPerEntry = 9;
constexpr std::size_t kEntryBytes = kDoublesPerEntry * sizeof(double) + sizeof(std::int64_t);
// A folder with more files than this is merged into one by the next process that writes.
constexpr std::size_t kMergeAbove = 8;

std::uint64_t fnv1a(const char* data, std::size_t n) {
  std::uint64_t h = 1469598103934665603ull;
  for (std::size_t i = 0; i < n; ++i) {
    h ^= static_cast<unsigned char>(data[i]);
    h *= 1099511628211ull;
  }
  return h;
}

std::uint64_t bits(double x) {
  std::uint64_t b = 0;
  std::memcpy(&b, &x, sizeof b);
  return b;
}

template <class T>
void put(std::string& out, T value) {
  out.append(reinterpret_cast<const char*>(&value), sizeof value);
}

template <class T>
T get(const std::string& in, std::size_t& at) {
  T value;
  std::memcpy(&value, in.data() + at, sizeof value);
  at += sizeof value;
  return value;
}

std::string unique_name() {
  static std::atomic<unsigned> sequence{0};
  const auto now = std::chrono::system_clock::now().time_since_epoch();
  std::ostringstream name;
  name << std::hex << std::chrono::duration_cast<std::chrono::nanoseconds>(now).count() << "-"
       << std::dec << ::getpid() << "-" << sequence++ << ".bin";
  return name.str();
}

// Parses one file into its records; false if it is not a complete file of this format and key.
bool parse(const std::string& text, const std::string& magic, const std::string& key, std::size_t record_bytes,
           bool& foreign, std::vector<std::string>& out) {
  foreign = false;
  if (text.size() < magic.size() || text.compare(0, magic.size(), magic) != 0) return false;
  const std::size_t key_end = text.find('\n', magic.size());
  if (key_end == std::string::npos) return false;
  if (text.compare(magic.size(), key_end - magic.size(), key) != 0) {
    foreign = true;  // another key with the same hash: leave it alone
    return false;
  }
  std::size_t at = key_end + 1;
  if (text.size() < at + 2 * sizeof(std::uint64_t)) return false;
  const auto count = get<std::uint64_t>(text, at);
  if (count > (text.size() - at) / record_bytes || text.size() != at + count * record_bytes + sizeof(std::uint64_t)) {
    return false;
  }
  std::size_t sum_at = text.size() - sizeof(std::uint64_t);
  if (get<std::uint64_t>(text, sum_at) != fnv1a(text.data(), text.size() - sizeof(std::uint64_t))) return false;
  for (std::uint64_t i = 0; i < count; ++i, at += record_bytes) out.push_back(text.substr(at, record_bytes));
  return true;
}

}  // namespace

std::string exact_text(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
}

CacheRecords::CacheRecords(const std::string& directory, const std::string& kind, const std::string& key,
                           std::size_t record_bytes)
    : magic_("coatcontact " + kind + " cache 1\n"), key_(key), record_bytes_(record_bytes) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key_.data(), key_.size())));
  build_folder_ = (fs::path(directory) / std::string(kBuildId).substr(0, 16)).string();
  folder_ = (fs::path(build_folder_) / (kind + "-" + hash)).string();
  std::error_code ec;
  for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;  // being written
    std::ifstream in(it->path(), std::ios::binary);
    if (!in) continue;
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bool foreign = false;
    std::vector<std::string> read;
    if (!parse(text, magic_, key_, record_bytes_, foreign, read)) {
      std::error_code ignored;
      if (!foreign) fs::remove(it->path(), ignored);  // corrupt or truncated: solved again
      continue;
    }
    loaded_.insert(loaded_.end(), std::make_move_iterator(read.begin()), std::make_move_iterator(read.end()));
    loaded_files_.push_back(it->path().string());
  }
}

CacheRecords::~CacheRecords() { flush(); }

void CacheRecords::add(std::string record) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (record.size() == record_bytes_) added_.push_back(std::move(record));
}

// Entries of other builds can never be read again by this one: the first process of a new
// build removes them (a cache shared by two builds then only loses time, never numbers).
void CacheRecords::remove_other_builds() const {
  const fs::path own = fs::path(build_folder_);
  std::error_code ec;
  for (fs::directory_iterator it(own.parent_path(), ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const bool build_folder = name.size() == 16 && name.find_first_not_of("0123456789abcdef") == std::string::npos;
    if (build_folder && it->path() != own) {
      std::error_code ignored;
      fs::remove_all(it->path(), ignored);
    }
  }
}

void CacheRecords::flush() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (added_.empty()) return;
  const bool merge = loaded_files_.size() >= kMergeAbove;
  const std::size_t count = added_.size() + (merge ? loaded_.size() : 0);
  std::string text = magic_ + key_ + "\n";
  text.reserve(text.size() + (count + 2) * record_bytes_);
  put<std::uint64_t>(text, count);
  if (merge) {
    for (const std::string& r : loaded_) text += r;
  }
  for (const std::string& r : added_) text += r;
  put<std::uint64_t>(text, fnv1a(text.data(), text.size()));
  if (merge) loaded_.insert(loaded_.end(), added_.begin(), added_.end());
  added_.clear();

  std::error_code ec;
  const bool new_build = !fs::exists(build_folder_, ec);
  fs::create_directories(folder_, ec);
  if (ec) return;
  if (new_build) remove_other_builds();
  const std::string name = unique_name();
  const fs::path temporary = fs::path(folder_) / ("." + name);
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      return;
    }
  }
  fs::rename(temporary, fs::path(folder_) / name, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return;
  }
  if (merge) {
    for (const std::string& file : loaded_files_) fs::remove(file, ec);
    loaded_files_.assign(1, (fs::path(folder_) / name).string());
  }
}

std::string SolveCache::key_of(const Stack& stack) {
  std::ostringstream key;
  key << "build " << kBuildId << "; layers";
  for (const Layer& layer : stack.layers()) {
    key << " " << exact_text(layer.thickness) << "," << exact_text(layer.material.youngs_modulus) << ","
        << exact_text(layer.material.poisson_ratio) << (layer.slip_below ? ",slip" : "");
  }
  const Substrate& s = stack.substrate();
  key << "; substrate "
      << (s.rigid ? std::string("rigid")
                  : exact_text(s.material.youngs_modulus) + "," + exact_text(s.material.poisson_ratio));
  const Indenter& i = stack.indenter();
  key << "; indenter "
      << (i.rigid ? std::string("rigid")
                  : exact_text(i.material.youngs_modulus) + "," + exact_text(i.material.poisson_ratio));
  return key.str();
}

SolveCache::SolveCache(const std::string& directory, const Stack& stack)
    : records_(directory, "solve", key_of(stack), kEntryBytes) {
  for (const std::string& r : records_.loaded()) {
    std::size_t at = 0;
    double d[kDoublesPerEntry];
    for (double& x : d) x = get<double>(r, at);
    ReducedVariables v;
    v.a_over_t = d[1];
    v.pi_s = d[2];
    v.delta_s = d[3];
    v.pi_c = d[4];
    v.delta_c = d[5];
    v.e_eq = d[6];
    v.gamma1 = d[7];
    v.error_estimate = d[8];
    v.unknowns = static_cast<int>(get<std::int64_t>(r, at));
    entries_[{bits(d[0]), bits(v.a_over_t)}] = v;
  }
}

std::optional<ReducedVariables> SolveCache::find(double a_over_t, double tolerance) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = entries_.find({bits(tolerance), bits(a_over_t)});
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

void SolveCache::add(double tolerance, const ReducedVariables& values) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (!entries_.emplace(Key{bits(tolerance), bits(values.a_over_t)}, values).second) return;
  std::string record;
  for (double x : {tolerance, values.a_over_t, values.pi_s, values.delta_s, values.pi_c, values.delta_c,
                   values.e_eq, values.gamma1, values.error_estimate}) {
    put<double>(record, x);
  }
  put<std::int64_t>(record, values.unknowns);
  records_.add(std::move(record));
}

}  // namespace detail
}  // namespace coatcontact
