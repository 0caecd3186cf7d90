// The solve cache (coatcontact/solve_cache.hpp, solve_cache.hpp; docs/solver.md, "Solve cache").
//
// DIR holds CACHEDIR.TAG (written when the cache creates DIR or adopts one that is empty or
// holds only what the cache writes; any other DIR is refused) and the folders
// <build id, 16 hex>/<kind>-<FNV-1a of the key>/; in each, files written by the processes that
// solved something new, each complete or absent (written under a temporary name starting with
// '.', then renamed). File: the line "coatcontact <kind> cache 1", the key line, a count, the
// fixed-size records (kind "table": the length of its one record, then the record), then an
// FNV-1a checksum of all that precedes. A record's first id_bytes
// identify it (a "solve" record: the tolerance and a/t, then the six values, the error estimate
// and the unknowns): a record read twice is kept once. Only a file whose name and first line
// are the cache's own is ever removed, and only inside a tagged DIR, never behind a symbolic
// link; then the folders that leaves empty and the cache's lock files.
#include "solve_cache.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>
#include <thread>

#include "coatcontact/detail/build_id.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/solve_cache.hpp"

namespace coatcontact {
namespace detail {

namespace {

namespace fs = std::filesystem;

constexpr std::size_t kDoublesPerEntry = 9;
constexpr std::size_t kEntryBytes = kDoublesPerEntry * sizeof(double) + sizeof(std::int64_t);
// The bytes that identify a "solve" record: the bits of the tolerance and of a/t.
constexpr std::size_t kEntryIdBytes = 2 * sizeof(double);
// A folder with this many files is merged into one by the next process that writes.
constexpr std::size_t kMergeAbove = 8;

constexpr char kTagName[] = "CACHEDIR.TAG";
// The Cache Directory Tagging Specification's signature (backup tools skip the folder), then
// the line that makes the folder this cache's own: both must be there before it removes anything.
constexpr char kTagOwnLines[] =
    "Signature: 8a477f597d28d172789f06886806bc55\n"
    "# This file is a cache directory tag created by coatcontact (its solve cache).\n";
constexpr char kTagRest[] =
    "# coatcontact removes only its own entries here; the folder may be deleted at any time.\n"
    "# For information about cache directory tags see https://bford.info/cachedir/\n";
constexpr char kTagTemporaryPrefix[] = ".coatcontact-tag-";
constexpr char kLockName[] = ".lock";
constexpr char kHex[] = "0123456789abcdef";
constexpr char kDecimal[] = "0123456789";

std::atomic<std::uintmax_t> g_size_cap{kDefaultCacheSizeCap};
// Bytes written by this process since its last look at the cache's size (the first write looks).
std::atomic<std::uintmax_t> g_written_unchecked{std::numeric_limits<std::uintmax_t>::max() / 2};

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

// Advances `at` over characters of `set`; true if it moved.
bool skip(const std::string& s, std::size_t& at, const char* set) {
  const std::size_t from = at;
  while (at < s.size() && s[at] != '\0' && std::strchr(set, s[at]) != nullptr) ++at;
  return at > from;
}

// A name unique_name() makes ("<hex>-<pid>-<n>.bin"; `temporary`: with the leading '.' of a
// file being written).
bool own_entry_name(const std::string& name, bool& temporary) {
  temporary = !name.empty() && name[0] == '.';
  std::size_t at = temporary ? 1 : 0;
  if (!skip(name, at, kHex) || at >= name.size() || name[at++] != '-') return false;
  if (!skip(name, at, kDecimal) || at >= name.size() || name[at++] != '-') return false;
  if (!skip(name, at, kDecimal)) return false;
  return name.compare(at, std::string::npos, ".bin") == 0;
}

bool build_folder_name(const std::string& name) {
  std::size_t at = 0;
  return name.size() == 16 && skip(name, at, kHex) && at == name.size();
}

bool key_folder_name(const std::string& name) {
  const std::size_t dash = name.find('-');
  std::size_t at = 0;
  return dash != std::string::npos && skip(name, at, "abcdefghijklmnopqrstuvwxyz") && at == dash &&
         build_folder_name(name.substr(dash + 1));
}

// Not following a symbolic link: the cache never works behind one inside DIR.
bool real_directory(const fs::path& p) {
  std::error_code ec;
  return fs::is_directory(fs::symlink_status(p, ec));
}

bool real_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(fs::symlink_status(p, ec));
}

std::vector<fs::path> entries_of(const fs::path& folder) {
  std::vector<fs::path> out;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) out.push_back(it->path());
  return out;
}

// The first line of a cache file: "coatcontact <kind> cache 1".
bool own_header(const fs::path& file) {
  std::ifstream in(file, std::ios::binary);
  char buffer[64];
  in.read(buffer, sizeof buffer);
  const std::string head(buffer, static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  const std::string prefix = "coatcontact ";
  if (head.compare(0, prefix.size(), prefix) != 0) return false;
  std::size_t at = prefix.size();
  return skip(head, at, "abcdefghijklmnopqrstuvwxyz") && head.compare(at, 9, " cache 1\n") == 0;
}

// Removes `file` if it is provably the cache's: its name, a regular file, its first line.
void remove_own_entry(const fs::path& file) {
  bool temporary = false;
  if (!own_entry_name(file.filename().string(), temporary) || !real_file(file) || !own_header(file)) return;
  std::error_code ec;
  fs::remove(file, ec);
}

// The cache's entries and lock in one <kind>-<hash> folder, then the folder if that empties it.
void remove_own_folder(const fs::path& folder) {
  std::error_code ec;
  for (const fs::path& p : entries_of(folder)) {
    if (p.filename() == kLockName) {
      if (real_file(p)) fs::remove(p, ec);
    } else {
      remove_own_entry(p);
    }
  }
  fs::remove(folder, ec);  // only if empty
}

// Entries of other builds can never be read again by this one: the first process of a new
// build removes them (a cache shared by two builds then only loses time, never numbers).
void remove_other_builds(const fs::path& root, const fs::path& own) {
  std::error_code ec;
  for (const fs::path& build : entries_of(root)) {
    if (build == own || !build_folder_name(build.filename().string()) || !real_directory(build)) continue;
    for (const fs::path& folder : entries_of(build)) {
      if (key_folder_name(folder.filename().string()) && real_directory(folder)) remove_own_folder(folder);
    }
    fs::remove(build, ec);  // only if empty
  }
}

bool own_tag(const fs::path& root) {
  const fs::path tag = root / kTagName;
  if (!real_file(tag)) return false;
  std::ifstream in(tag, std::ios::binary);
  std::string head(sizeof kTagOwnLines - 1, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  return in.gcount() == static_cast<std::streamsize>(head.size()) && head == kTagOwnLines;
}

// A folder holding nothing but what the cache writes (nothing at all, or the untagged cache of
// an earlier version: build folders of key folders of its entries and locks) may be adopted.
bool only_cache_content(const fs::path& root) {
  for (const fs::path& build : entries_of(root)) {
    const std::string name = build.filename().string();
    if (name.rfind(kTagTemporaryPrefix, 0) == 0) continue;  // an adoption under way
    if (name == kLockName && real_file(build)) continue;
    if (!build_folder_name(name) || !real_directory(build)) return false;
    for (const fs::path& folder : entries_of(build)) {
      if (!key_folder_name(folder.filename().string()) || !real_directory(folder)) return false;
      for (const fs::path& p : entries_of(folder)) {
        bool temporary = false;
        const bool entry = own_entry_name(p.filename().string(), temporary) && own_header(p);
        if (!real_file(p) || !(entry || p.filename() == kLockName)) return false;
      }
    }
  }
  return true;
}

enum class Root { absent, adoptable, own, refused };

// What DIR is (following a link given as DIR itself); `why` says why it is refused.
Root root_state(const fs::path& root, std::string& why) {
  std::error_code ec;
  const fs::file_status link = fs::symlink_status(root, ec);
  const fs::file_status target = fs::status(root, ec);
  if (target.type() == fs::file_type::not_found) {
    if (link.type() == fs::file_type::symlink) {
      why = "is a symbolic link to nothing";
      return Root::refused;
    }
    return Root::absent;
  }
  if (ec) {
    why = "cannot be examined (" + ec.message() + ")";
    return Root::refused;
  }
  if (target.type() != fs::file_type::directory) {
    why = target.type() == fs::file_type::regular ? "is a file, not a folder"
                                                  : "is not a folder (a device or other special file)";
    return Root::refused;
  }
  if (own_tag(root)) return Root::own;
  fs::directory_iterator it(root, ec);
  if (ec) {
    why = "cannot be read (" + ec.message() + ")";
    return Root::refused;
  }
  if (only_cache_content(root)) return Root::adoptable;
  // Processes started at once on an empty DIR: another may have written the tag (and entries)
  // after own_tag() above looked, and only_cache_content() then saw them.
  if (own_tag(root)) return Root::own;
  why = real_file(root / kTagName) ? "is another program's cache folder (its CACHEDIR.TAG is not coatcontact's)"
                                   : "is a folder with other files in it and no coatcontact CACHEDIR.TAG";
  return Root::refused;
}

// DIR is the cache's own, creating it or adopting it (writing the tag) if needed.
bool ensure_own_root(const fs::path& root) {
  std::string why;
  std::error_code ec;
  Root state = root_state(root, why);
  if (state == Root::absent) {
    fs::create_directories(root, ec);
    if (ec) return false;
    state = root_state(root, why);
  }
  if (state != Root::adoptable) return state == Root::own;
  // Whole or absent for a reader: written under a temporary name, then renamed.
  const fs::path temporary = root / (kTagTemporaryPrefix + unique_name());
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out << kTagOwnLines << kTagRest;
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      return false;
    }
  }
  fs::rename(temporary, root / kTagName, ec);
  if (ec) fs::remove(temporary, ec);
  return own_tag(root);
}

// An exclusive flock(2) on `path` (created if needed), or none if another process holds it.
class FileLock {
 public:
  explicit FileLock(const fs::path& path)
      : fd_(::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW | O_NONBLOCK, 0644)) {
    if (fd_ >= 0 && ::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
      ::close(fd_);
      fd_ = -1;
    }
  }
  ~FileLock() {
    if (fd_ >= 0) ::close(fd_);
  }
  FileLock(const FileLock&) = delete;
  FileLock& operator=(const FileLock&) = delete;
  bool held() const { return fd_ >= 0; }

 private:
  int fd_;
};

struct OwnFolder {
  fs::path path;
  fs::file_time_type used;  // the folder's time: set when a process reads or writes an entry
  std::uintmax_t bytes = 0;
};

std::vector<OwnFolder> own_folders(const fs::path& root) {
  std::vector<OwnFolder> out;
  std::error_code ec;
  for (const fs::path& build : entries_of(root)) {
    if (!build_folder_name(build.filename().string()) || !real_directory(build)) continue;
    for (const fs::path& folder : entries_of(build)) {
      if (!key_folder_name(folder.filename().string()) || !real_directory(folder)) continue;
      OwnFolder f{folder, fs::last_write_time(folder, ec), 0};
      for (const fs::path& p : entries_of(folder)) {
        bool temporary = false;
        if (own_entry_name(p.filename().string(), temporary) && real_file(p)) {
          const std::uintmax_t size = fs::file_size(p, ec);
          if (!ec) f.bytes += size;
        }
      }
      out.push_back(f);
    }
  }
  return out;
}

// Above the size cap, the folders used longest ago are removed until a quarter of the cap is
// free (one process at a time; a folder being merged is skipped).
void evict(const fs::path& root, std::uintmax_t cap) {
  const FileLock evicting(root / kLockName);
  if (!evicting.held()) return;
  std::vector<OwnFolder> folders = own_folders(root);
  std::uintmax_t total = 0;
  for (const OwnFolder& f : folders) total += f.bytes;
  if (total <= cap) return;
  std::sort(folders.begin(), folders.end(), [](const OwnFolder& a, const OwnFolder& b) { return a.used < b.used; });
  for (const OwnFolder& f : folders) {
    if (total <= cap - cap / 4) break;
    const FileLock merging(f.path / kLockName);
    if (!merging.held()) continue;
    remove_own_folder(f.path);
    total -= f.bytes;
  }
  std::error_code ec;
  for (const fs::path& build : entries_of(root)) {
    if (build_folder_name(build.filename().string()) && real_directory(build)) fs::remove(build, ec);  // if empty
  }
}

// Parses one file into its records; false if it is not a complete file of this format and key.
bool parse(const std::string& text, const std::string& magic, const std::string& key, std::size_t record_bytes,
           bool& foreign, std::vector<std::string>& out) {
  foreign = false;
  if (text.size() < magic.size() || text.compare(0, magic.size(), magic) != 0) return false;
  const std::size_t key_end = text.find('\n', magic.size());
  if (key_end == std::string::npos) return false;
  std::size_t at = key_end + 1;
  if (text.size() < at + 2 * sizeof(std::uint64_t)) return false;
  const auto count = get<std::uint64_t>(text, at);
  // record_bytes 0: one record, `count` its length in bytes.
  const std::uint64_t bytes = record_bytes == 0 ? count : count * record_bytes;
  if ((record_bytes != 0 && count > (text.size() - at) / record_bytes) ||
      text.size() != at + bytes + sizeof(std::uint64_t)) {
    return false;
  }
  std::size_t sum_at = text.size() - sizeof(std::uint64_t);
  if (get<std::uint64_t>(text, sum_at) != fnv1a(text.data(), text.size() - sizeof(std::uint64_t))) return false;
  // Complete and intact (a damaged key line fails the checksum above, and the file is removed).
  if (text.compare(magic.size(), key_end - magic.size(), key) != 0) {
    foreign = true;  // another key with the same hash: leave it alone
    return false;
  }
  if (record_bytes == 0) {
    out.push_back(text.substr(at, count));
    return true;
  }
  for (std::uint64_t i = 0; i < count; ++i, at += record_bytes) out.push_back(text.substr(at, record_bytes));
  return true;
}

}  // namespace

void set_cache_size_cap(std::uintmax_t bytes) { g_size_cap = bytes; }
std::uintmax_t cache_size_cap() { return g_size_cap; }

bool solve_cache_root_refused(const std::string& directory, std::string& why) {
  return root_state(fs::path(directory), why) == Root::refused;
}

std::string exact_text(double x) {
  char buffer[40];
  std::snprintf(buffer, sizeof buffer, "%a", x);
  return buffer;
}

CacheRecords::CacheRecords(const std::string& directory, const std::string& kind, const std::string& key,
                           std::size_t record_bytes, std::size_t id_bytes)
    : root_(directory),
      magic_("coatcontact " + kind + " cache 1\n"),
      key_(key),
      record_bytes_(record_bytes),
      id_bytes_(std::min(id_bytes, record_bytes)) {
  char hash[17];
  std::snprintf(hash, sizeof hash, "%016llx", static_cast<unsigned long long>(fnv1a(key_.data(), key_.size())));
  build_folder_ = (fs::path(root_) / std::string(kBuildId).substr(0, 16)).string();
  folder_ = (fs::path(build_folder_) / (kind + "-" + hash)).string();
  std::error_code exists;
  const bool own = own_tag(root_) || (fs::exists(root_, exists) && ensure_own_root(root_));  // adopted if it may be
  if (own) read_folder();
}

void CacheRecords::read_folder() {
  if (!real_directory(build_folder_) || !real_directory(folder_)) return;
  // A merger renames its file into place before it removes the files it merged: a file that
  // vanished while this one read the folder means a merged file to find by looking again.
  std::unordered_set<std::string> seen;
  for (int pass = 0, vanished = 1; vanished != 0 && pass < 4; ++pass) {
    vanished = 0;
    for (const fs::path& path : entries_of(folder_)) {
      bool temporary = false;
      const std::string name = path.filename().string();
      if (!own_entry_name(name, temporary) || !seen.insert(name).second) continue;  // not the cache's: never touched
      std::error_code ec;
      if (temporary) {  // being written, or left by a killed process an hour ago
        const auto age = fs::file_time_type::clock::now() - fs::last_write_time(path, ec);
        if (!ec && age > std::chrono::hours(1)) remove_own_entry(path);
        continue;
      }
      std::vector<std::string> read;
      bool foreign = false;
      if (read_entry(path, read, foreign)) {
        keep_new(read, loaded_);
        ++files_;
      } else if (!foreign) {
        remove_own_entry(path);  // corrupt or truncated: solved again
      } else if (!fs::exists(fs::symlink_status(path, ec))) {
        vanished = 1;
      }
    }
  }
  std::error_code ec;
  if (!loaded_.empty()) fs::last_write_time(folder_, fs::file_time_type::clock::now(), ec);  // used: evicted last
}

// The folder as flush() makes it: DIR the cache's, the key's folder there, other builds gone.
bool CacheRecords::make_folder() {
  if (!ensure_own_root(root_)) return false;  // not the cache's folder (any more): nothing written
  std::error_code ec;
  const bool new_build = !fs::exists(fs::symlink_status(build_folder_, ec));
  fs::create_directories(folder_, ec);
  if (ec || !real_directory(build_folder_) || !real_directory(folder_)) return false;  // a link or a file in the way
  if (new_build) remove_other_builds(root_, build_folder_);
  return true;
}

bool CacheRecords::wait_for_key(std::chrono::milliseconds patience) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (key_lock_ >= 0) return true;
  if (!make_folder()) return false;
  const fs::path path = fs::path(folder_) / kLockName;
  const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd < 0) return false;
  const auto give_up = std::chrono::steady_clock::now() + patience;
  while (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
    if ((errno != EWOULDBLOCK && errno != EINTR) || std::chrono::steady_clock::now() > give_up) {
      ::close(fd);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  key_lock_ = fd;
  read_folder();
  return true;
}

CacheRecords::~CacheRecords() {
  flush();
  if (key_lock_ >= 0) ::close(key_lock_);  // after the entry is in place
}

bool CacheRecords::read_entry(const std::string& path, std::vector<std::string>& out, bool& foreign) const {
  foreign = false;
  std::error_code ec;
  const std::uintmax_t size = real_file(path) ? fs::file_size(path, ec) : 0;
  if (!real_file(path) || size > g_size_cap || ec) {
    foreign = true;  // a folder, a link, a device or a file above the cap under an entry's name: left alone
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    foreign = true;
    return false;
  }
  // One read of the size found: an entry is never changed once in place, and a file shorter
  // than that fails the parse as a truncated one would.
  std::string text(static_cast<std::size_t>(size), '\0');
  in.read(text.data(), static_cast<std::streamsize>(size));
  text.resize(static_cast<std::size_t>(std::max<std::streamsize>(in.gcount(), 0)));
  return parse(text, magic_, key_, record_bytes_, foreign, out);
}

void CacheRecords::keep_new(std::vector<std::string>& records, std::vector<std::string>& out) {
  for (std::string& r : records) {
    if (ids_.insert(r.substr(0, id_bytes_)).second) out.push_back(std::move(r));
  }
}

void CacheRecords::add(std::string record) {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (record_bytes_ != 0 && record.size() != record_bytes_) return;
  std::vector<std::string> one(1, std::move(record));
  keep_new(one, added_);
}

std::uintmax_t CacheRecords::write_entry(const std::vector<std::string>& records) const {
  std::string text = magic_ + key_ + "\n";
  if (record_bytes_ == 0) {  // one record of any length: the count is its length
    if (records.size() != 1) return 0;
    text.reserve(text.size() + records.front().size() + 2 * sizeof(std::uint64_t));
    put<std::uint64_t>(text, records.front().size());
  } else {
    text.reserve(text.size() + (records.size() + 2) * record_bytes_);
    put<std::uint64_t>(text, records.size());
  }
  for (const std::string& r : records) text += r;
  put<std::uint64_t>(text, fnv1a(text.data(), text.size()));
  const std::string name = unique_name();
  const fs::path temporary = fs::path(folder_) / ("." + name);
  std::error_code ec;
  {
    std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
    out.write(text.data(), static_cast<std::streamsize>(text.size()));
    out.close();
    if (!out) {
      fs::remove(temporary, ec);
      return 0;
    }
  }
  fs::rename(temporary, fs::path(folder_) / name, ec);
  if (ec) {
    fs::remove(temporary, ec);
    return 0;
  }
  return text.size();
}

// The caller holds the folder's lock (one merger at a time): every complete file of this key
// now in the folder and `records`, each record once, into one new file; the files read are
// removed once it is in place. Files other processes add meanwhile stay.
std::uintmax_t CacheRecords::merge(const std::vector<std::string>& records) {
  std::unordered_set<std::string> ids;
  std::vector<std::string> all;
  std::vector<fs::path> merged;
  const auto keep = [&](const std::string& r) {
    if (ids.insert(r.substr(0, id_bytes_)).second) all.push_back(r);
  };
  for (const fs::path& path : entries_of(folder_)) {
    bool temporary = false, foreign = false;
    std::vector<std::string> read;
    if (!own_entry_name(path.filename().string(), temporary) || temporary || !read_entry(path, read, foreign)) continue;
    for (const std::string& r : read) keep(r);
    merged.push_back(path);
  }
  for (const std::string& r : records) keep(r);
  const std::uintmax_t bytes = write_entry(all);
  if (bytes == 0) return 0;
  std::error_code ec;
  for (const fs::path& f : merged) fs::remove(f, ec);
  files_ = 1;
  return bytes;
}

void CacheRecords::flush() {
  const std::lock_guard<std::mutex> lock(mutex_);
  if (added_.empty()) return;
  std::vector<std::string> records;
  records.swap(added_);
  if (!make_folder()) return;
  std::uintmax_t written = 0;
  if (files_ >= kMergeAbove) {
    const FileLock merging(fs::path(folder_) / kLockName);
    if (merging.held()) written = merge(records);
  }
  if (written == 0) {
    written = write_entry(records);
    if (written == 0) return;
    ++files_;
  }
  const std::uintmax_t cap = g_size_cap;
  if (g_written_unchecked.fetch_add(written) + written >= cap / 64) {
    g_written_unchecked = 0;
    evict(root_, cap);
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
    : records_(directory, "solve", key_of(stack), kEntryBytes, kEntryIdBytes) {
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

namespace {

std::mutex g_directory_mutex;
bool g_directory_set = false;
std::string g_directory;
std::string g_directory_refused;  // why COATCONTACT_CACHE cannot be the cache ("" if it can)

}  // namespace

void check_solve_cache_directory(const std::string& directory, const std::string& name) {
  std::string why;
  if (directory.empty() || !detail::solve_cache_root_refused(directory, why)) return;
  throw InputError(name + " '" + directory + "' " + why +
                   "; allowed: a folder that does not exist yet or is empty (the cache then makes it its own, "
                   "writing a CACHEDIR.TAG) or one the cache made (holding coatcontact's CACHEDIR.TAG)");
}

void set_solve_cache_directory(const std::string& directory) {
  check_solve_cache_directory(directory, "solve cache folder");
  const std::lock_guard<std::mutex> lock(g_directory_mutex);
  g_directory = directory;
  g_directory_refused.clear();
  g_directory_set = true;
}

std::string solve_cache_directory() {
  const std::lock_guard<std::mutex> lock(g_directory_mutex);
  if (!g_directory_set) {
    const char* value = std::getenv("COATCONTACT_CACHE");
    g_directory = value != nullptr ? value : "";
    try {
      check_solve_cache_directory(g_directory, "COATCONTACT_CACHE");
    } catch (const InputError& e) {
      g_directory_refused = e.what();
    }
    g_directory_set = true;
  }
  if (!g_directory_refused.empty()) throw InputError(g_directory_refused);
  return g_directory;
}

const char* solve_cache_build_id() { return detail::kBuildId; }

}  // namespace coatcontact
