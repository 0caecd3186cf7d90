// The one entry point of the nanoindentation readers: detect the format, read, dispatch.
// A new reader: its file, its IndentFormat value and name, its detection and dispatch lines here.
#include <algorithm>
#include <cctype>

#include "indent_support.hpp"

namespace coatcontact::indent {

const char* indent_format_name(IndentFormat format) {
  switch (format) {
    case IndentFormat::kNanoSuiteXls: return "NanoSuite .xls";
    case IndentFormat::kHysitronTxt: return "Hysitron text";
    case IndentFormat::kHysitronHld: return "Hysitron .hld";
    case IndentFormat::kMicromaterialsZip: return "Micromaterials .zip";
    case IndentFormat::kFischerScopeTxt: return "FischerScope text";
  }
  return "unknown";
}

namespace detail {

namespace {

bool has_extension(const std::string& file, const char* extension) {
  std::string lower = file.substr(file.size() >= 5 ? file.size() - 5 : 0);
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ends_with(lower, extension);
}

}  // namespace

IndentFormat detect_format_of(const std::string& bytes, const std::string& file) {
  if (bytes.compare(0, 8, "\xD0\xCF\x11\xE0\xA1\xB1\x1A\xE1", 8) == 0) return IndentFormat::kNanoSuiteXls;  // OLE2 compound file
  if (bytes.compare(0, 4, "PK\x03\x04", 4) == 0) return IndentFormat::kMicromaterialsZip;
  const std::string head = bytes.substr(0, 4096);
  if (head.rfind("File Version: Hysitron", 0) == 0) return IndentFormat::kHysitronHld;
  if (head.substr(0, head.find('\n')).find("\tName of the application") != std::string::npos) return IndentFormat::kFischerScopeTxt;
  // Hysitron text: "Number of Points = N" among the first lines (after the date).
  std::size_t line_end = 0;
  for (int line = 0; line < 4 && line_end != std::string::npos; ++line) line_end = head.find('\n', line_end + 1);
  if (head.substr(0, line_end).find("Number of Points =") != std::string::npos) return IndentFormat::kHysitronTxt;
  if (has_extension(file, ".xls")) fail(file, "", 0, "not an Excel 97-2003 workbook (no OLE2 signature), so not a NanoSuite export");
  if (has_extension(file, ".zip")) fail(file, "", 0, "not a zip archive (truncated or corrupt?)");
  if (has_extension(file, ".hld")) fail(file, "", 1, "a Hysitron .hld file starts with 'File Version: Hysitron'");
  fail(file, "", 0,
       "unknown indentation file format (known: NanoSuite .xls, Hysitron .txt and .hld, Micromaterials .zip, "
       "FischerScope .txt)");
}

}  // namespace detail

IndentFormat detect_indent_format(const std::string& path) {
  return detail::detect_format_of(detail::read_file(path), path);
}

std::vector<IndentTest> read_indentation(const std::string& path) {
  const std::string bytes = detail::read_file(path);
  if (detail::detect_format_of(bytes, path) == IndentFormat::kNanoSuiteXls) return detail::read_nanosuite_xls(path);
  return read_indentation_from_bytes(bytes, path);
}

std::vector<IndentTest> read_indentation_from_bytes(const std::string& bytes, const std::string& name) {
  if (bytes.empty()) detail::fail(name, "", 0, "empty file");
  switch (detail::detect_format_of(bytes, name)) {
    case IndentFormat::kNanoSuiteXls: detail::fail(name, "", 0, "the .xls reader reads files, not bytes in memory");
    case IndentFormat::kHysitronTxt: return detail::read_hysitron_txt(bytes, name);
    case IndentFormat::kHysitronHld: return detail::read_hysitron_hld(bytes, name);
    case IndentFormat::kMicromaterialsZip: return detail::read_micromaterials_zip(bytes, name);
    case IndentFormat::kFischerScopeTxt: return detail::read_fischerscope_txt(bytes, name);
  }
  detail::fail(name, "", 0, "unknown format");
}

}  // namespace coatcontact::indent
