// The nanoindentation readers on the real files of data/indentation/: every channel equals a
// decoding written here from the file itself (text: the numbers of each line parsed with
// strtod and scaled by the unit the header names; zip: each entry read through libzip; .xls:
// the cells read through FreeXL), the calibration fields as the file states them, and bad
// files (made here from the good ones) rejected with the file, sheet or entry and line named.
// Usage: test_indent_readers DATA_DIR WORK_DIR
#include <freexl.h>
#include <zip.h>

#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/indentation.hpp"

namespace indent = coatcontact::indent;
using coatcontact::InputError;

namespace {

std::string data_dir, work_dir;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

void write(const std::string& path, const std::string& bytes) {
  std::ofstream out(path, std::ios::binary);
  out << bytes;
}

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(line);
  }
  return lines;
}

// The tab-separated numbers of a line; commas as decimal marks when `comma`.
std::vector<double> numbers(std::string line, bool comma = false) {
  if (comma) for (char& c : line) if (c == ',') c = '.';
  std::vector<double> out;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, '\t')) out.push_back(std::strtod(field.c_str(), nullptr));
  return out;
}

// Channel sample i against the decoded value (the reader's unit scaling: one division or
// multiplication by a power of ten, correctly rounded either way).
void same(double got, double want, const std::string& what) {
  check::close(got, want, check::tier::kRounding, what, 1e-300);
}

void hysitron_txt() {
  const std::string path = data_dir + "/RobinSteel0000LC.txt";
  const auto tests = indent::read_indentation(path);
  check::that(tests.size() == 1, "Hysitron text: one test");
  const auto& t = tests.at(0);
  const auto lines = lines_of(slurp(path));
  check::that(lines.at(2) == "Number of Points = 5304", "Hysitron text: the count line");
  check::that(t.depth.size() == 5304 && t.load.size() == 5304 && t.time.size() == 5304, "Hysitron text: 5304 points");
  bool all = t.segment.size() == 5304;
  std::size_t i = 0;
  int segment = 0;
  for (std::size_t k = 4; all && k < lines.size(); ++k) {
    if (lines[k].empty()) {  // blank lines separate the segments
      ++segment;
      continue;
    }
    const auto v = numbers(lines[k]);  // Depth (nm), Load (µN), Time (s), Depth (V), Load (V)
    all = i < t.depth.size() && v.size() == 5 && t.depth[i] == v[0] / 1e9 && t.load[i] == v[1] / 1e6 && t.time[i] == v[2] &&
          t.extra.at("Depth [V]")[i] == v[3] && t.extra.at("Load [V]")[i] == v[4] && t.segment[i] == segment;
    ++i;
  }
  check::that(all && i == 5304, "Hysitron text: every channel of every line as decoded (nm, µN, s, V), segments between blank lines");
  check::that(t.segment.back() == 4, "Hysitron text: five segments (four blank lines)");
  same(t.depth[0], 0.814723e-9, "Hysitron text: first depth");
  same(t.load[0], 1.836146e-6, "Hysitron text: first load");
  check::that(t.metadata.at("date") == "Mon Apr 29 10:41:06 2019", "Hysitron text: the date");
  check::that(t.name == "RobinSteel0000LC", "Hysitron text: the name is the file's stem");
  check::that(t.stiffness.empty() && t.hardness.empty() && std::isnan(t.calibration.poisson), "Hysitron text: no CSM, no calibration invented");
}

void hysitron_hld() {
  const std::string path = data_dir + "/Exp-50mN_0000.hld";
  const auto tests = indent::read_indentation(path);
  check::that(tests.size() == 1, "hld: one test");
  const auto& t = tests.at(0);
  const auto lines = lines_of(slurp(path));
  std::size_t at = 0;
  while (at < lines.size() && lines[at] != "Test Data Points: 1068") ++at;
  check::that(at + 2 < lines.size(), "hld: the test block in the file");
  check::that(t.depth.size() == 1068, "hld: 1068 points");
  bool all = t.depth.size() == 1068;
  for (std::size_t i = 0; all && i < t.depth.size(); ++i) {
    // Time_s Disp_nm Force_µN LoadCell_nm PiezoDisp_nm Disp_V Force_V Piezo_LowV
    const auto v = numbers(lines.at(at + 2 + i));
    all = v.size() == 8 && t.time[i] == v[0] && t.depth[i] == v[1] / 1e9 && t.load[i] == v[2] / 1e6 &&
          t.extra.at("LoadCell [m]")[i] == v[3] / 1e9 && t.extra.at("PiezoDisp [m]")[i] == v[4] / 1e9 &&
          t.extra.at("Disp [V]")[i] == v[5] && t.extra.at("Force [V]")[i] == v[6] && t.extra.at("Piezo_LowV")[i] == v[7];
  }
  check::that(all, "hld: every channel of every test line as decoded (s, nm, µN, V; Piezo_LowV as named)");
  check::that(t.metadata.at("Number of Segments") == "4", "hld: header key 'Number of Segments'");
  check::that(t.metadata.at("Segment Begin Time (3)") == "4.67914 s", "hld: repeated keys numbered");
  check::that(t.metadata.at("Force C1L") == "165800 \xc2\xb5N/V", "hld: Latin-1 micro sign as UTF-8");
  check::that(t.metadata.at("Sample Approach Data Points") == "312", "hld: the approach block counted");
  // Segments begin at 0, 2.00192, 4.67914, 5.67914 s (the header's "Segment Begin Time").
  bool segments = t.segment.size() == t.time.size();
  for (std::size_t i = 0; segments && i < t.time.size(); ++i) {
    const double s = t.time[i];
    const int want = s >= 5.67914 ? 3 : s >= 4.67914 ? 2 : s >= 2.00192 ? 1 : 0;
    segments = t.segment[i] == want;
  }
  check::that(segments, "hld: each point's segment from the header's begin times");
}

std::string zip_entry(const std::string& path, const std::string& name) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (archive == nullptr) return {};
  zip_stat_t st;
  std::string data;
  if (zip_stat(archive, name.c_str(), 0, &st) == 0) {
    zip_file_t* f = zip_fopen(archive, name.c_str(), 0);
    data.resize(st.size);
    if (f == nullptr || zip_fread(f, data.data(), st.size) != static_cast<zip_int64_t>(st.size)) data.clear();
    if (f != nullptr) zip_fclose(f);
  }
  zip_close(archive);
  return data;
}

void micromaterials() {
  const std::string path = data_dir + "/multipleIndentations.zip";
  const auto tests = indent::read_indentation(path);
  check::that(tests.size() == 39, "Micromaterials: 39 indents");
  bool all = !tests.empty();
  for (const auto& t : tests) {
    const auto lines = lines_of(zip_entry(path, t.name + ".txt"));
    all = all && lines.size() == t.depth.size();
    for (std::size_t i = 0; all && i < lines.size(); ++i) {
      const auto v = numbers(lines[i]);  // time [s], depth [nm], load [mN]
      all = v.size() == 3 && t.time[i] == v[0] && t.depth[i] == v[1] / 1e9 && t.load[i] == v[2] / 1e3;
    }
  }
  check::that(all, "Micromaterials: every channel of every entry as decoded (s, nm, mN)");
  const auto& first = tests.at(0);
  check::that(first.name == "1000nmXX 1 6958 -4555" && first.metadata.at("target") == "1000nmXX" &&
                  first.metadata.at("stage y") == "-4555", "Micromaterials: name and its fields");
  // The columns' meaning (see micromaterials_reader.cpp): the deepest point is near the
  // 1000 nm target, and the load holds its peak while the depth creeps.
  double hmax = 0.0, pmax = 0.0;
  for (std::size_t i = 0; i < first.depth.size(); ++i) hmax = std::fmax(hmax, first.depth[i]), pmax = std::fmax(pmax, first.load[i]);
  check::that(hmax > 0.95e-6 && hmax < 1.1e-6, "Micromaterials: peak depth near the 1000 nm target");
  check::that(pmax > 0.05 && pmax < 0.5, "Micromaterials: peak load of order 0.1 N");
}

void fischerscope() {
  const std::string path = data_dir + "/FS1.txt";
  const auto tests = indent::read_indentation(path);
  check::that(tests.size() == 10, "FischerScope: 10 tests");
  const auto lines = lines_of(slurp(path));
  std::size_t test = 0;
  bool all = tests.size() == 10;
  for (std::size_t k = 0; all && k < lines.size(); ++k) {
    if (lines[k] != "F\th\tt") continue;
    const auto& t = tests.at(test++);
    for (std::size_t i = 0; all && i < t.depth.size(); ++i) {
      const auto v = numbers(lines.at(k + 1 + i), true);  // F [mN], h [µm], t [s]
      all = v.size() == 3 && t.load[i] == v[0] / 1e3 && t.depth[i] == v[1] / 1e6 && t.time[i] == v[2];
    }
    const std::size_t next = k + 1 + t.depth.size();
    all = all && (next == lines.size() || lines[next].find(".hap") != std::string::npos);
  }
  check::that(all && test == 10, "FischerScope: every line of every test as decoded (decimal commas; mN, µm, s)");
  const auto& second = tests.at(1);
  check::that(second.name == "Block 1 Value 2", "FischerScope: the block and value name the test");
  check::that(second.calibration.eps == 0.75, "FischerScope: Epsilon = 0.750");
  same(second.vendor_results.at("HM"), 3842.0e6, "FischerScope: HM 3842.0 N/mm^2 in Pa");
  check::that(second.metadata.at("x") == "44.54" && second.metadata.at("date") == "26.05.2020  15:20:59", "FischerScope: position and date");
  check::that(second.metadata.at("parameter F") == "ESP n 300.000mN/120s/37s", "FischerScope: the test parameters");
}

// One cell of a sheet through FreeXL, as a number (NaN if empty or text).
double cell(const void* book, unsigned row, unsigned short column) {
  FreeXL_CellValue v{};
  if (freexl_get_cell_value(book, row, column, &v) != FREEXL_OK) return NAN;
  if (v.type == FREEXL_CELL_DOUBLE) return v.value.double_value;
  if (v.type == FREEXL_CELL_INT) return v.value.int_value;
  return NAN;
}

void nanosuite() {
  const std::string path = data_dir + "/FS_Calibration.xls";
  const auto tests = indent::read_indentation(path);
  check::that(tests.size() == 16, "NanoSuite: 16 tests");
  check::that(tests.at(0).name == "Test 001" && tests.at(15).name == "Test 016", "NanoSuite: in the order of their numbers");
  const void* book = nullptr;
  check::that(freexl_open(path.c_str(), &book) == FREEXL_OK, "NanoSuite: FreeXL opens the file");
  unsigned sheets = 0;
  freexl_get_info(book, FREEXL_BIFF_SHEET_COUNT, &sheets);
  bool all = true;
  int compared = 0;
  for (unsigned s = 0; s < sheets; ++s) {
    const char* name = nullptr;
    freexl_get_worksheet_name(book, static_cast<unsigned short>(s), &name);
    if (std::string(name).rfind("Test ", 0) != 0) continue;
    const auto& t = tests.at(static_cast<std::size_t>(std::atoi(name + 5) - 1));
    freexl_select_active_worksheet(book, static_cast<unsigned short>(s));
    unsigned rows = 0;
    unsigned short columns = 0;
    freexl_worksheet_dimensions(book, &rows, &columns);
    // Columns: segment, depth [nm], load [mN], time [s], stiffness [N/m], H [GPa], E [GPa];
    // 1.797e308 (DBL_MAX) is the software's "no value", NaN here. Rows from 3 up to "END".
    const auto decode = [](double v, double divide, double multiply) {
      return v >= DBL_MAX ? NAN : divide != 1.0 ? v / divide : v * multiply;
    };
    std::size_t i = 0;
    for (unsigned r = 2; r < rows && all; ++r, ++i) {
      if (std::isnan(cell(book, r, 1))) break;  // "END"
      const double want[6] = {decode(cell(book, r, 1), 1e9, 1), decode(cell(book, r, 2), 1e3, 1), decode(cell(book, r, 3), 1, 1),
                              decode(cell(book, r, 4), 1, 1),  decode(cell(book, r, 5), 1, 1e9), decode(cell(book, r, 6), 1, 1e9)};
      const double got[6] = {t.depth.at(i), t.load.at(i), t.time.at(i), t.stiffness.at(i), t.hardness.at(i), t.modulus.at(i)};
      for (int c = 0; c < 6; ++c) all = all && (got[c] == want[c] || (std::isnan(got[c]) && std::isnan(want[c])));
      ++compared;
    }
    all = all && i == t.depth.size();
  }
  freexl_close(book);
  check::that(all && compared > 16 * 1000, "NanoSuite: every cell of every test sheet as decoded (nm, mN, s, N/m, GPa)");
  const auto& t1 = tests.at(0);
  check::that(t1.segment.front() == 1 && t1.segment.back() == 4 && t1.metadata.at("segment 3") == "Unload From Peak Segment Type",
              "NanoSuite: segments numbered from the labels of the first column");
  // Results, Required Inputs, Inputs Editable Post Test (the values the sheets show).
  same(t1.vendor_results.at("E_mean"), 76.318e9, "NanoSuite: Test 001 E over the range");
  same(t1.vendor_results.at("H_mean"), 9.784e9, "NanoSuite: Test 001 H over the range");
  same(tests.at(15).vendor_results.at("E_mean"), 76.906e9, "NanoSuite: Test 016 E over the range");
  const auto& c = t1.calibration.area.coefficients;
  check::that(c.size() == 3 && c[0] == 27.3136 && c[1] == 152.6988585 && c[2] == -494.1823171, "NanoSuite: the three area coefficients");
  check::that(t1.calibration.poisson == 0.18, "NanoSuite: Poisson's ratio 0.18");
  check::that(t1.calibration.tip == "Berk40_20210907_MarilaineSP", "NanoSuite: the tip's name");
  same(t1.calibration.range_min, 100e-9, "NanoSuite: averaging range from 100 nm");
  same(t1.calibration.range_max, 200e-9, "NanoSuite: averaging range to 200 nm");
  check::that(std::isnan(t1.calibration.frame_stiffness) && t1.metadata.at("Frame Stiffness Correction [N/m]") == "0",
              "NanoSuite: no frame stiffness invented; its correction (0) in the metadata");
  check::that(t1.metadata.at("Results: Mean: E Average Over Defined Range [GPa]") == "75.25", "NanoSuite: the Results' mean row");
}

void bad_files() {
  const std::string txt = slurp(data_dir + "/RobinSteel0000LC.txt");
  write(work_dir + "/truncated.txt", txt.substr(0, txt.rfind('\n', txt.size() / 2) + 1));  // whole lines
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/truncated.txt"); }, {"truncated.txt", "declares 5304 points"});
  std::string bad = txt;
  bad.replace(bad.find("0.558046"), 8, "0.55x046");
  write(work_dir + "/bad_number.txt", bad);
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/bad_number.txt"); }, {"bad_number.txt", "line 6", "field 1"});
  const std::string hld = slurp(data_dir + "/Exp-50mN_0000.hld");
  write(work_dir + "/cut.hld", hld.substr(0, hld.rfind('\n', hld.size() - 20000) + 1));
  write(work_dir + "/cut_line.hld", hld.substr(0, hld.size() - 20000));
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/cut_line.hld"); }, {"cut_line.hld", "line 2264", "2 fields"});
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/cut.hld"); }, {"cut.hld", "truncated"});
  std::string fs = slurp(data_dir + "/FS1.txt");
  const auto at = fs.find("0,438949");
  fs.replace(at, 8, "0.438949");
  write(work_dir + "/point.txt", fs);
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/point.txt"); }, {"point.txt", "Block 1 Value 1", "line 87", "decimal comma"});
  write(work_dir + "/fake.xls", "not an excel file at all");
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/fake.xls"); }, {"fake.xls", "NanoSuite"});
  const std::string xls = slurp(data_dir + "/FS_Calibration.xls");
  write(work_dir + "/half.xls", xls.substr(0, xls.size() / 2));
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/half.xls"); }, {"half.xls"});
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/missing.txt"); }, {"missing.txt", "no such file"});
  write(work_dir + "/other.dat", "hello\n");
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/other.dat"); }, {"other.dat", "unknown indentation file format"});
  // A Micromaterials entry with a text field: the archive's entry and line named.
  const std::string entry = zip_entry(data_dir + "/multipleIndentations.zip", "1000nmXX 1 6958 -4555.txt");
  int error = 0;
  zip_t* out = zip_open((work_dir + "/bad.zip").c_str(), ZIP_CREATE | ZIP_TRUNCATE, &error);
  std::string broken = entry;
  broken.replace(broken.find("-377.529733"), 11, "-377.5x9733");
  zip_source_t* source = zip_source_buffer(out, broken.data(), broken.size(), 0);
  zip_file_add(out, "indent 1.txt", source, ZIP_FL_OVERWRITE);
  zip_close(out);
  check::throws<InputError>([&] { indent::read_indentation(work_dir + "/bad.zip"); }, {"bad.zip", "indent 1.txt", "line 2", "field 2"});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_indent_readers DATA_DIR WORK_DIR\n");
    return 2;
  }
  data_dir = argv[1];
  work_dir = argv[2];
  hysitron_txt();
  hysitron_hld();
  micromaterials();
  fischerscope();
  nanosuite();
  bad_files();
  return check::exit_code();
}
