// The one entry point of the AFM readers: detect the format, read the file, dispatch.
#include "coatcontact/afm_readers.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <sys/stat.h>

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

namespace {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

std::string read_file(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) throw InputError(path + ": cannot open the file (no such file)");
  if (!S_ISREG(info.st_mode)) throw InputError(path + ": not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path + ": cannot open the file");
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw InputError(path + ": read error");
  if (bytes.empty()) throw InputError(path + ": empty file");
  return bytes;
}

}  // namespace

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
  return detail::detect_format_of(detail::read_file(path), path);
}

std::vector<ForceCurve> read_force_curves(const std::string& path, const Calibration& calibration) {
  check_calibration(calibration);
  return detail::read_bytes(detail::read_file(path), path, calibration);
}

std::vector<ForceCurve> read_force_curves_from_bytes(const std::string& bytes, const std::string& name,
                                                     const Calibration& calibration) {
  check_calibration(calibration);
  if (bytes.empty()) throw InputError(name + ": empty file");
  return detail::read_bytes(bytes, name, calibration);
}

}  // namespace coatcontact::afm
