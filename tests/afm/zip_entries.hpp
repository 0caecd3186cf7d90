// Zip archives as lists of entries, for the AFM tests that build variants of real files
// (JPK force maps are zip archives). Test-only helpers, header-only.
#pragma once
#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

namespace coatcontact_test {

struct ZipEntry {
  std::string name, data;
};

// Every entry of the archive at `path`, in order (none if it cannot be opened).
inline std::vector<ZipEntry> zip_entries(const std::string& path) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY, &error);
  std::vector<ZipEntry> out;
  if (archive == nullptr) return out;
  for (zip_int64_t i = 0; i < zip_get_num_entries(archive, 0); ++i) {
    zip_stat_t st;
    zip_stat_index(archive, static_cast<zip_uint64_t>(i), 0, &st);
    ZipEntry e{st.name, std::string(st.size, '\0')};
    zip_file_t* f = zip_fopen_index(archive, static_cast<zip_uint64_t>(i), 0);
    if (f != nullptr) {
      zip_fread(f, e.data.data(), st.size);
      zip_fclose(f);
    }
    out.push_back(std::move(e));
  }
  zip_discard(archive);
  return out;
}

// Writes `entries` as a new archive at `path`; `stored`: without compression.
inline void write_zip(const std::string& path, const std::vector<ZipEntry>& entries, bool stored = false) {
  std::remove(path.c_str());
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  for (const ZipEntry& e : entries) {
    // libzip frees a buffer it owns only when it is not empty: an empty entry (a folder) gets
    // no buffer (LeakSanitizer found the 1-byte copies).
    zip_source_t* source = nullptr;
    if (e.data.empty()) {
      source = zip_source_buffer(archive, nullptr, 0, 0);
    } else {
      char* copy = static_cast<char*>(std::malloc(e.data.size()));
      std::copy(e.data.begin(), e.data.end(), copy);
      source = zip_source_buffer(archive, copy, e.data.size(), 1);
    }
    const zip_int64_t i = zip_file_add(archive, e.name.c_str(), source, ZIP_FL_OVERWRITE);
    if (stored) zip_set_file_compression(archive, static_cast<zip_uint64_t>(i), ZIP_CM_STORE, 0);
  }
  zip_close(archive);
}

}  // namespace coatcontact_test
