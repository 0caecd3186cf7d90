// Micromaterials NanoTest export: a zip archive with one text file per indent, named
// "<target depth> <index> <stage x> <stage y>.txt", each line "time [s] <tab> depth [nm] <tab>
// load [mN]" without a header. The columns' meaning is read off the curve's shape: the second
// creeps up while the third holds constant at peak (depth under a load hold), and ends at a
// residual value with the third at zero (plastic depth after unloading).
#include <algorithm>

#include "../afm/zip_archive.hpp"
#include "indent_support.hpp"

namespace coatcontact::indent::detail {

IndentTest read_micromaterials_text(const std::string& text, const std::string& file, const std::string& entry) {
  IndentTest test;
  const std::size_t room = std::min(kMaxPoints, text.size() / 6 + 1);
  test.time.reserve(room);
  test.depth.reserve(room);
  test.load.reserve(room);
  Lines lines(text);
  std::string_view line;
  while (lines.next(line)) {
    if (trim(line).empty()) continue;
    const auto fields = split(trim(line), '\t');
    if (fields.size() != 3) fail(file, entry, lines.number(), std::to_string(fields.size()) + " fields; three expected (time [s], depth [nm], load [mN])");
    double v[3];
    for (int k = 0; k < 3; ++k) {
      if (!parse_number(fields[k], v[k])) fail(file, entry, lines.number(), "field " + std::to_string(k + 1) + " is not a number");
    }
    if (test.depth.size() >= kMaxPoints) fail(file, entry, lines.number(), "more than " + std::to_string(kMaxPoints) + " points");
    test.time.push_back(v[0]);
    test.depth.push_back(scale(v[1], 1e-9));
    test.load.push_back(scale(v[2], 1e-3));
  }
  std::string stem = entry.substr(entry.find_last_of('/') + 1);
  if (ends_with(stem, ".txt")) stem.resize(stem.size() - 4);
  test.name = stem;
  test.metadata["format"] = indent_format_name(IndentFormat::kMicromaterialsZip);
  test.metadata["entry"] = entry;
  // The name's fields as the vendor writes them (target depth, index, stage x and y).
  const auto parts = split(stem, ' ');
  if (parts.size() == 4) {
    test.metadata["target"] = std::string(parts[0]);
    test.metadata["index"] = std::string(parts[1]);
    test.metadata["stage x"] = std::string(parts[2]);
    test.metadata["stage y"] = std::string(parts[3]);
  }
  finish_test(test, file, entry);
  return test;
}

std::vector<IndentTest> read_micromaterials_zip(const std::string& bytes, const std::string& file) {
  const afm::detail::ZipArchive archive(bytes, file);
  std::vector<IndentTest> tests;
  for (const auto& name : archive.names()) {
    if (name.empty() || name.back() == '/') continue;  // folders
    if (!ends_with(name, ".txt")) continue;
    if (tests.size() >= kMaxTests) fail(file, "", 0, "more than " + std::to_string(kMaxTests) + " tests");
    tests.push_back(read_micromaterials_text(archive.read(name, kMaxFileBytes, "a Micromaterials test"), file, name));
  }
  if (tests.empty()) fail(file, "", 0, "a zip archive without .txt entries: not a Micromaterials export");
  return tests;
}

}  // namespace coatcontact::indent::detail
