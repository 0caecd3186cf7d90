// The one entry point of the AFM readers: detect the format, read the file, dispatch.
#include "coatcontact/afm_readers.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <sys/stat.h>

#include <filesystem>

#include "../number_text.hpp"
#include "jpk_reader.hpp"
#include "read_limits.hpp"
#include "read_support.hpp"
#include "zip_archive.hpp"

namespace coatcontact::afm {

const char* file_format_name(FileFormat format) {
  switch (format) {
    case FileFormat::kJpk: return "JPK archive";
    case FileFormat::kIgorBinaryWave: return "Igor binary wave";
    case FileFormat::kAfmWorkshopCsv: return "AFM Workshop CSV";
    case FileFormat::kAfmWorkshopZip: return "AFM Workshop zipped map";
    case FileFormat::kNtmdtText: return "NT-MDT text export";
  }
  return "unknown";
}

namespace detail {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// stat(2) of an input file: InputError naming it and the reason unless it is a regular file.
struct stat stat_input(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) {
    throw InputError(path + ": cannot open the file (" + (errno == ENOENT ? std::string("no such file") : std::strerror(errno)) + ")");
  }
  if (!S_ISREG(info.st_mode)) throw InputError(path + ": not a regular file");
  return info;
}

// The whole file, up to kMaxWholeFileBytes (its size checked before reading).
std::string read_file(const std::string& path) {
  const struct stat info = stat_input(path);
  if (static_cast<std::uint64_t>(info.st_size) > kMaxWholeFileBytes) {
    throw InputError(path + ": " + std::to_string(info.st_size) + " bytes exceed the limit of " + std::to_string(kMaxWholeFileBytes) +
                     " bytes for a file read whole (Igor, AFM Workshop, NT-MDT; an instrument's curve is far smaller)");
  }
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (in == nullptr) throw InputError(path + ": cannot open the file (" + std::strerror(errno) + ")");
  std::string bytes(static_cast<std::size_t>(info.st_size), '\0');
  const std::size_t got = std::fread(bytes.data(), 1, bytes.size(), in);
  const int error = std::ferror(in) ? errno : 0;
  std::fclose(in);
  if (error != 0) throw InputError(path + ": read error (" + std::strerror(error) + ")");
  bytes.resize(got);  // a file that shrank since stat(2)
  if (bytes.empty()) throw InputError(path + ": empty file");
  return bytes;
}

FileFormat detect_format_of(const std::string& bytes, const std::string& file) {
  const bool zip = bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04", 4) == 0;
  if (zip) {
    const ZipArchive archive(bytes, file);
    bool jpk = false, csv = false;
    for (const auto& name : archive.names()) {
      if (name.rfind("segments/", 0) == 0 || name.rfind("index/", 0) == 0 || name == "header.properties") jpk = true;
      if (ends_with(name, ".csv")) csv = true;
    }
    if (jpk) return FileFormat::kJpk;
    if (csv) return FileFormat::kAfmWorkshopZip;
    fail(file, "", "a zip archive that is neither a JPK file nor an AFM Workshop map");
  }
  const bool igor_header = bytes.size() >= 2 && ((bytes[0] == 5 && bytes[1] == 0) || (bytes[0] == 0 && bytes[1] == 5));
  if (igor_header && ends_with(file, ".ibw")) return FileFormat::kIgorBinaryWave;
  if (bytes.compare(0, 20, "Force-Distance Curve") == 0) return FileFormat::kAfmWorkshopCsv;
  // NT-MDT: the first line is three tab-separated numbers.
  const std::size_t eol = bytes.find_first_of("\r\n");
  std::string first = bytes.substr(0, eol);
  if (std::count(first.begin(), first.end(), '\t') == 2) {
    bool numeric = true;
    for (char c : first) {
      if (!((c >= '0' && c <= '9') || c == ',' || c == '.' || c == '-' || c == '+' || c == 'e' || c == 'E' || c == '\t' || c == ' ')) numeric = false;
    }
    if (numeric) return FileFormat::kNtmdtText;
  }
  if (ends_with(file, ".ibw")) fail(file, "", "not an Igor binary wave of version 5");
  if (ends_with(file, ".jpk-force") || ends_with(file, ".jpk-force-map") || ends_with(file, ".jpk-qi-data") ||
      ends_with(file, ".jpk-qi-series")) {
    fail(file, "", "not a zip archive, so not a JPK file (truncated or corrupt?)");
  }
  fail(file, "", "unknown AFM file format (known: JPK .jpk-force/.jpk-force-map/.jpk-qi-data/.jpk-qi-series, "
                 "Asylum .ibw, AFM Workshop .csv/.zip, NT-MDT .txt)");
}

bool starts_as_zip(const std::string& path) {
  stat_input(path);
  std::FILE* in = std::fopen(path.c_str(), "rb");
  if (in == nullptr) throw InputError(path + ": cannot open the file (" + std::strerror(errno) + ")");
  char magic[4] = {0, 0, 0, 0};
  const std::size_t got = std::fread(magic, 1, 4, in);
  const int error = std::ferror(in) ? errno : 0;
  std::fclose(in);
  if (error != 0) throw InputError(path + ": read error (" + std::strerror(error) + ")");
  return got == 4 && std::string(magic, 4) == std::string("PK\x03\x04", 4);
}

bool is_jpk(const ZipArchive& archive) {
  bool jpk = false;
  archive.for_each_name([&](const std::string& name) {
    if (name.rfind("segments/", 0) == 0 || name.rfind("index/", 0) == 0 || name == "header.properties") jpk = true;
  });
  return jpk;
}

std::vector<ForceCurve> read_bytes(const std::string& bytes, const std::string& file, const Calibration& calibration) {
  switch (detect_format_of(bytes, file)) {
    case FileFormat::kJpk: return read_jpk(bytes, file, calibration);
    case FileFormat::kIgorBinaryWave: return read_igor(bytes, file, calibration);
    case FileFormat::kAfmWorkshopCsv: return read_afm_workshop_csv(bytes, file, "", calibration);
    case FileFormat::kAfmWorkshopZip: return read_afm_workshop_zip(bytes, file, calibration);
    case FileFormat::kNtmdtText: return read_ntmdt_text(bytes, file, calibration);
  }
  fail(file, "", "unknown format");
}

}  // namespace detail

void check_calibration(const Calibration& calibration) {
  if (calibration.spring_constant && !(std::isfinite(*calibration.spring_constant) && *calibration.spring_constant > 0.0)) {
    throw InputError("--spring-constant: " + detail::number_text(*calibration.spring_constant) + " is not allowed; the spring constant must be a finite number > 0 [N/m]");
  }
  if (calibration.sensitivity && !(std::isfinite(*calibration.sensitivity) && *calibration.sensitivity > 0.0)) {
    throw InputError("--sensitivity: " + detail::number_text(*calibration.sensitivity) + " is not allowed; the sensitivity must be a finite number > 0 [m/V]");
  }
}

FileFormat detect_format(const std::string& path) {
  if (detail::starts_as_zip(path)) {
    const detail::ZipArchive archive(detail::ZipArchive::FromPath{}, path);
    if (detail::is_jpk(archive)) return FileFormat::kJpk;
  }
  return detail::detect_format_of(detail::read_file(path), path);
}

// Through a CurveSource: a JPK archive is read entry by entry from its file, never whole.
std::vector<ForceCurve> read_force_curves(const std::string& path, const Calibration& calibration) {
  const CurveSource source(path, calibration);
  std::vector<ForceCurve> curves;
  curves.reserve(source.size());
  for (std::size_t i = 0; i < source.size(); ++i) curves.push_back(source.read(i));
  return curves;
}

std::vector<ForceCurve> read_force_curves_from_bytes(const std::string& bytes, const std::string& name,
                                                     const Calibration& calibration) {
  check_calibration(calibration);
  if (bytes.empty()) throw InputError(name + ": empty file");
  return detail::read_bytes(bytes, name, calibration);
}

struct CurveSource::Impl {
  std::string path;
  FileFormat format = FileFormat::kJpk;
  std::unique_ptr<detail::ZipArchive> archive;  // a JPK archive, read on demand
  detail::JpkLayout layout;
  Calibration calibration;
  std::vector<ForceCurve> curves;  // the other formats, read whole
  std::vector<std::string> errors;  // a zipped Workshop map: why curve i cannot be read ("" if it can)
};

CurveSource::CurveSource(const std::string& path, const Calibration& calibration) : impl_(std::make_unique<Impl>()) {
  check_calibration(calibration);
  impl_->path = path;
  impl_->calibration = calibration;
  if (detail::starts_as_zip(path)) {
    auto archive = std::make_unique<detail::ZipArchive>(detail::ZipArchive::FromPath{}, path);
    if (detail::is_jpk(*archive)) {
      impl_->layout = detail::jpk_layout(*archive, path);
      impl_->archive = std::move(archive);
      impl_->format = FileFormat::kJpk;
      return;
    }
  }
  const std::string bytes = detail::read_file(path);
  impl_->format = detail::detect_format_of(bytes, path);
  // One corrupt curve of a zipped map is that curve's error, not the map's.
  if (impl_->format == FileFormat::kAfmWorkshopZip) impl_->curves = detail::read_afm_workshop_entries(bytes, path, calibration, impl_->errors);
  else impl_->curves = detail::read_bytes(bytes, path, calibration);
}

CurveSource::~CurveSource() = default;
const std::string& CurveSource::path() const { return impl_->path; }
FileFormat CurveSource::format() const { return impl_->format; }
std::size_t CurveSource::size() const {
  return impl_->archive ? impl_->layout.size() : impl_->curves.size();
}

ForceCurve CurveSource::read(std::size_t index) const {
  if (index >= size()) throw InputError(impl_->path + ": no curve " + std::to_string(index));
  if (impl_->archive) return detail::read_jpk_curve(*impl_->archive, impl_->layout, index, impl_->path, impl_->calibration);
  if (index < impl_->errors.size() && !impl_->errors[index].empty()) throw InputError(impl_->errors[index]);
  return impl_->curves[index];
}

CurveMetadata CurveSource::place(std::size_t index) const {
  try {
    if (impl_->archive && index < size()) return detail::jpk_curve_place(*impl_->archive, impl_->layout, index, impl_->path);
  } catch (const std::exception&) {
  }
  if (!impl_->archive && index < impl_->curves.size()) return impl_->curves[index].metadata;
  CurveMetadata m;
  m.source_file = impl_->path;
  m.curve_index = index;
  m.curve_count = size();
  return m;
}

std::vector<std::string> afm_files_in_folder(const std::string& folder) {
  static const char* const extensions[] = {".jpk-force", ".jpk-force-map", ".jpk-qi-data", ".jpk-qi-series",
                                           ".ibw", ".csv", ".zip", ".txt"};
  std::vector<std::string> files;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(folder, error)) {
    const std::string name = entry.path().filename().string();
    const auto extension = std::find_if(std::begin(extensions), std::end(extensions),
                                        [&](const char* e) { return detail::ends_with(name, e); });
    if (extension == std::end(extensions)) continue;
    // The error_code form: a symlink loop or a dangling link is an error to report, not an
    // exception out of is_regular_file().
    std::error_code kind_error;
    const bool regular = entry.is_regular_file(kind_error);
    if (kind_error && kind_error != std::errc::no_such_file_or_directory) {
      throw InputError(entry.path().string() + ": cannot read the file in the folder (" + kind_error.message() + ")");
    }
    if (!regular) continue;
    // A batch table has one line per row and names its file in it.
    if (name.find_first_of("\n\r") != std::string::npos) {
      throw InputError(folder + ": the file name " + coatcontact::detail::quote(name) +
                       " holds a line break, which a batch table cannot name; rename the file");
    }
    files.push_back(entry.path().string());
  }
  if (error) throw InputError(folder + ": cannot list the folder (" + error.message() + ")");
  std::sort(files.begin(), files.end());
  if (files.empty()) throw InputError(folder + ": no AFM files in the folder (by extension: .jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series, .ibw, .csv, .zip, .txt)");
  return files;
}

}  // namespace coatcontact::afm
