// A zip archive held in memory, read through libzip (internal to the AFM readers).
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

struct zip;

namespace coatcontact::afm::detail {

class ZipArchive {
 public:
  // `bytes` must outlive the archive. InputError naming `file` if it is not a readable zip.
  ZipArchive(const std::string& bytes, const std::string& file);
  // The archive of the file at `path`, its entries read from the file on demand (a map's
  // memory is one entry, not the archive).
  struct FromPath {};
  ZipArchive(FromPath, const std::string& path);
  ~ZipArchive();
  ZipArchive(const ZipArchive&) = delete;
  ZipArchive& operator=(const ZipArchive&) = delete;

  // Every entry's name, in archive order (listed when first asked for).
  const std::vector<std::string>& names() const;
  // Calls `visit` with each entry's name without keeping the list (a map's archive holds
  // ~10 names per curve).
  void for_each_name(const std::function<void(const std::string& name)>& visit) const;
  bool has(const std::string& name) const;
  // The whole entry; InputError naming the file and entry if it is missing, truncated or
  // corrupt, or if its declared size exceeds `max_bytes` (checked before allocating: a zip
  // bomb or a lying size field is refused, not read). `what` names the limit in the message.
  std::string read(const std::string& name, std::uint64_t max_bytes, const char* what) const;
  // The entry's declared (uncompressed) size; InputError if it is missing.
  std::uint64_t size_of(const std::string& name) const;

 private:
  zip* archive_ = nullptr;
  std::string file_;
  mutable std::vector<std::string> names_;
  mutable bool listed_ = false;
};

}  // namespace coatcontact::afm::detail
