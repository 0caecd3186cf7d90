// ZipArchive over libzip: the archive is opened from memory or from its file, each entry read whole with its
// CRC checked by libzip. (No ZIP_CHECKCONS: instruments write archives whose local and central
// headers disagree in harmless fields; a damaged entry still fails its CRC.)
#include "zip_archive.hpp"

#include <zip.h>

#include <algorithm>

#include "read_support.hpp"

namespace coatcontact::afm::detail {

ZipArchive::ZipArchive(const std::string& bytes, const std::string& file) : file_(file) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  if (source == nullptr) {
    const std::string text = zip_error_strerror(&error);
    zip_error_fini(&error);
    fail(file, "", "cannot read the zip archive (" + text + ")");
  }
  archive_ = zip_open_from_source(source, ZIP_RDONLY, &error);
  if (archive_ == nullptr) {
    const std::string text = zip_error_strerror(&error);
    zip_source_free(source);
    zip_error_fini(&error);
    fail(file, "", "not a readable zip archive, truncated or corrupt (" + text + ")");
  }
  zip_error_fini(&error);
}

ZipArchive::ZipArchive(FromPath, const std::string& path) : file_(path) {
  int code = 0;
  archive_ = zip_open(path.c_str(), ZIP_RDONLY, &code);
  if (archive_ == nullptr) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    const std::string text = zip_error_strerror(&error);
    zip_error_fini(&error);
    fail(path, "", "not a readable zip archive, truncated or corrupt (" + text + ")");
  }
}

void ZipArchive::for_each_name(const std::function<void(const std::string& name)>& visit) const {
  const zip_int64_t count = zip_get_num_entries(archive_, 0);
  std::string text;
  for (zip_int64_t i = 0; i < count; ++i) {
    const char* name = zip_get_name(archive_, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_RAW);
    if (name == nullptr) continue;
    text = name;
    visit(text);
  }
}

const std::vector<std::string>& ZipArchive::names() const {
  if (!listed_) {
    for_each_name([this](const std::string& name) { names_.push_back(name); });
    listed_ = true;
  }
  return names_;
}

ZipArchive::~ZipArchive() {
  if (archive_ != nullptr) zip_discard(archive_);
}

// libzip's own name index: a map's archive holds ~10 entries per curve, so a scan per lookup
// would make reading a map quadratic in its curves.
bool ZipArchive::has(const std::string& name) const {
  return zip_name_locate(archive_, name.c_str(), ZIP_FL_ENC_RAW) >= 0;
}

std::uint64_t ZipArchive::size_of(const std::string& name) const {
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat(archive_, name.c_str(), ZIP_FL_ENC_RAW, &stat) != 0) fail(file_, name, "entry missing from the archive");
  if ((stat.valid & ZIP_STAT_SIZE) == 0) fail(file_, name, "entry has no valid size");
  return stat.size;
}

std::string ZipArchive::read(const std::string& name, std::uint64_t max_bytes, const char* what) const {
  zip_stat_t stat;
  zip_stat_init(&stat);
  if (zip_stat(archive_, name.c_str(), ZIP_FL_ENC_RAW, &stat) != 0) {
    fail(file_, name, "entry missing from the archive");
  }
  if ((stat.valid & ZIP_STAT_SIZE) == 0) fail(file_, name, "entry has no valid size");
  if (stat.size > max_bytes) {
    fail(file_, name, "entry of " + std::to_string(stat.size) + " bytes (uncompressed) exceeds the limit of " +
                          std::to_string(max_bytes) + " bytes for " + what + "; corrupt or not an instrument's file");
  }
  zip_file_t* entry = zip_fopen_index(archive_, stat.index, 0);
  if (entry == nullptr) {
    fail(file_, name, std::string("cannot open the entry (") + zip_strerror(archive_) + ")");
  }
  std::string data(static_cast<std::size_t>(stat.size), '\0');
  zip_uint64_t done = 0;
  while (done < stat.size) {
    const zip_int64_t got = zip_fread(entry, data.data() + done, stat.size - done);
    if (got <= 0) {
      const std::string text = got < 0 ? zip_error_strerror(zip_file_get_error(entry)) : "unexpected end of data";
      zip_fclose(entry);
      fail(file_, name, "truncated or corrupt entry (" + text + ")");
    }
    done += static_cast<zip_uint64_t>(got);
  }
  // A read past the announced size must return 0; otherwise the CRC check fails here.
  char extra = 0;
  const zip_int64_t tail = zip_fread(entry, &extra, 1);
  const std::string tail_error = tail < 0 ? zip_error_strerror(zip_file_get_error(entry)) : "";
  zip_fclose(entry);
  if (tail != 0) fail(file_, name, "truncated or corrupt entry (" + (tail < 0 ? tail_error : std::string("longer than its size")) + ")");
  return data;
}

}  // namespace coatcontact::afm::detail
