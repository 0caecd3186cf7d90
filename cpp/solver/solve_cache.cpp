// The solve cache (coatcontact/solve_cache.hpp, solve_cache.hpp; docs/solver.md).
//
// One folder per stack, <directory>/<build id, 16 digits>/solve-<FNV-1a of the key>; in it, files written by the
// processes that solved something new, each complete or absent (written under a temporary
// name starting with '.', then renamed): several processes (make -j) add entries at once
// without locks, and a reader takes the union. File: the line "coatcontact solve cache 1",
// the key line, a count, per entry the tolerance, a/t, the six values and the error estimate
// (binary doubles) and the unknowns (int64), then an FNV-1a checksum of all that precedes.
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

const char kMagic[] = "coatcontact solve cache 1\n";
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

std::string exact(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
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

// Parses one file; false if it is not a complete file of this format.
bool parse(const std::string& text, const std::string& key, bool& foreign,
           std::vector<std::pair<double, ReducedVariables>>& out) {
  foreign = false;
  const std::size_t magic = std::strlen(kMagic);
  if (text.size() < magic || text.compare(0, magic, kMagic) != 0) return false;
  const std::size_t key_end = text.find('\n', magic);
  if (key_end == std::string::npos) return false;
  if (text.compare(magic, key_end - magic, key) != 0) {
    foreign = true;  // another key with the same hash: leave it alone
    return false;
  }
  std::size_t at = key_end + 1;
  if (text.size() < at + 2 * sizeof(std::uint64_t)) return false;
  const auto count = get<std::uint64_t>(text, at);
  if (count > (text.size() - at) / kEntryBytes || text.size() != at + count * kEntryBytes + sizeof(std::uint64_t)) {
    return false;
  }
  std::size_t sum_at = text.size() - sizeof(std::uint64_t);
  if (get<std::uint64_t>(text, sum_at) != fnv1a(text.data(), text.size() - sizeof(std::uint64_t))) return false;
  for (std::uint64_t i = 0; i < count; ++i) {
    double d[kDoublesPerEntry];
    for (double& x : d) x = get<double>(text, at);
    ReducedVariables v;
    v.a_over_t = d[1];
    v.pi_s = d[2];
    v.delta_s = d[3];
    v.pi_c = d[4];
    v.delta_c = d[5];
    v.e_eq = d[6];
    v.gamma1 = d[7];
    v.error_estimate = d[8];
    v.unknowns = static_cast<int>(get<std::int64_t>(text, at));
    out.emplace_back(d[0], v);
  }
  return true;
}

}  // namespace

// Entries of other builds can never be read again by this one: the first process of a new
// build removes them (a cache shared by two builds then only loses time, never numbers).
void SolveCache::remove_other_builds() const {
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

std::string SolveCache::key_of(const Stack& stack) {
  std::ostringstream key;
  key << "build " << kBuildId << "; layers";
  for (const Layer& layer : stack.layers()) {
    key << " " << exact(layer.thickness) << "," << exact(layer.material.youngs_modulus) << ","
        << exact(layer.material.poisson_ratio) << (layer.slip_below ? ",slip" : "");
  }
  const Substrate& s = stack.substrate();
  key << "; substrate "
      << (s.rigid ? std::string("rigid") : exact(s.material.youngs_modulus) + "," + exact(s.material.poisson_ratio));
  const Indenter& i = stack.indenter();
  key << "; indenter "
      << (i.rigid ? std::string("rigid") : exact(i.material.youngs_modulus) + "," + exact(i.material.poisson_ratio));
  return key.str();
}

SolveCache::SolveCache(const std::string& directory, const Stack& stack) : key_(key_of(stack)) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key_.data(), key_.size())));
  build_folder_ = (fs::path(directory) / std::string(kBuildId).substr(0, 16)).string();
  folder_ = (fs::path(build_folder_) / (std::string("solve-") + hash)).string();
  std::error_code ec;
  for (fs::directory_iterator it(folder_, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.empty() || name[0] == '.') continue;  // being written
    std::ifstream in(it->path(), std::ios::binary);
    if (!in) continue;
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    std::vector<std::pair<double, ReducedVariables>> read;
    bool foreign = false;
    if (!parse(text, key_, foreign, read)) {
      std::error_code ignored;
      if (!foreign) fs::remove(it->path(), ignored);  // corrupt or truncated: solved again
      continue;
    }
    for (const auto& [tolerance, v] : read) entries_[{bits(tolerance), bits(v.a_over_t)}] = v;
    loaded_files_.push_back(it->path().string());
  }
}

SolveCache::~SolveCache() { flush(); }

std::optional<ReducedVariables> SolveCache::find(double a_over_t, double tolerance) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const auto it = entries_.find({bits(tolerance), bits(a_over_t)});
  if (it == entries_.end()) return std::nullopt;
  return it->second;
}

void SolveCache::add(double tolerance, const ReducedVariables& values) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (entries_.emplace(Key{bits(tolerance), bits(values.a_over_t)}, values).second) {
    added_.emplace_back(tolerance, values);
  }
}

void SolveCache::flush() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (added_.empty()) return;
  const bool merge = loaded_files_.size() >= kMergeAbove;
  std::vector<std::pair<double, ReducedVariables>> write;
  if (merge) {
    for (const auto& [key, v] : entries_) {
      double tolerance = 0.0;
      std::memcpy(&tolerance, &key.first, sizeof tolerance);
      write.emplace_back(tolerance, v);
    }
  } else {
    write = added_;
  }
  std::string text = kMagic + key_ + "\n";
  put<std::uint64_t>(text, write.size());
  for (const auto& [tolerance, v] : write) {
    for (double x : {tolerance, v.a_over_t, v.pi_s, v.delta_s, v.pi_c, v.delta_c, v.e_eq, v.gamma1,
                     v.error_estimate}) {
      put<double>(text, x);
    }
    put<std::int64_t>(text, v.unknowns);
  }
  put<std::uint64_t>(text, fnv1a(text.data(), text.size()));
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
    loaded_files_.clear();
  }
}

}  // namespace detail
}  // namespace coatcontact
