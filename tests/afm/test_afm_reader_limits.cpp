// Regression tests of issue 40 (items 3, 6, 7) and issue 36 (grid indices, truncated text) for
// the AFM readers. The bad files are made here from the real ones of data/afm/ (entries copied
// through libzip with one change) or written whole; each test is named after the bug it pins.
// Grid indices are checked against a decoding of the JPK headers written here and against the
// order of the curves' positions. Usage: test_afm_reader_limits DATA_DIR MAKE_AFM_MAP WORK_DIR
#include <sys/stat.h>
#include <unistd.h>
#include <zip.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "zip_entries.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace afm = coatcontact::afm;
using coatcontact::InputError;

namespace {

std::string data_dir, make_map, work;

using Entry = coatcontact_test::ZipEntry;
using coatcontact_test::write_zip;
const auto& entries_of = coatcontact_test::zip_entries;

// A copy of data/afm/`name` with `change` applied to its entries (return false to drop one).
std::string variant(const std::string& name, const std::string& tag, const std::function<bool(Entry&)>& change) {
  std::vector<Entry> kept;
  for (Entry& e : entries_of(data_dir + "/" + name)) {
    if (change(e)) kept.push_back(std::move(e));
  }
  const std::string ext = name.substr(name.rfind('.'));
  const std::string path = work + "/" + tag + ext;
  write_zip(path, kept);
  return path;
}

void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

const char* const kSpot = "fmt-jpk-fd_spot3-0192.jpk-force";
const char* const kMap = "fmt-jpk-fd_map2x2_extracted.jpk-force-map";

afm::Calibration user_calibration() {
  afm::Calibration c;
  c.spring_constant = 0.05;
  c.sensitivity = 5e-8;
  return c;
}

// ---- item 6: silent wrong results ----

void regression_jpk_missing_segment_header_drops_later_segments() {
  const std::string dropped = variant(kSpot, "no_header_0", [](Entry& e) { return e.name != "segments/0/segment-header.properties"; });
  check::throws<InputError>([&] { afm::read_force_curves(dropped); }, {"segments/0/segment-header.properties", "segment header missing"});
  // Segment 1 renumbered 2: folder 1 is missing, the old reader stopped at segment 0.
  const std::string renumbered = variant(kSpot, "renumbered", [](Entry& e) {
    if (e.name.rfind("segments/1/", 0) == 0) e.name = "segments/2/" + e.name.substr(11);
    return true;
  });
  check::throws<InputError>([&] { afm::read_force_curves(renumbered); }, {"segments/1/segment-header.properties", "missing"});
  // The good file: both segments.
  const auto curves = afm::read_force_curves(data_dir + "/" + kSpot);
  check::that(curves.size() == 1 && curves[0].segments.size() == 2, "spot3: two segments");
}

// num-points of segment 0 halved: the channel holds twice the points.
void regression_jpk_num_points_smaller_than_channel_read_as_prefix() {
  std::string points;
  for (const Entry& e : entries_of(data_dir + "/" + kSpot)) {
    if (e.name != "segments/0/segment-header.properties") continue;
    std::istringstream in(e.data);
    std::string line;
    while (std::getline(in, line)) {
      if (line.rfind("force-segment-header.num-points=", 0) == 0) points = line.substr(32);
    }
  }
  check::that(!points.empty(), "spot3 segment 0 states num-points");
  if (points.empty()) return;
  const std::string half = std::to_string(std::stol(points) / 2);
  const std::string path = variant(kSpot, "half_points", [&](Entry& e) {
    if (e.name == "segments/0/segment-header.properties") {
      e.data = replace(e.data, "force-segment-header.num-points=" + points, "force-segment-header.num-points=" + half);
      e.data = replace(e.data, "num-points=" + points, "num-points=" + half);
      while (e.data.find("num-points=" + points) != std::string::npos) e.data = replace(e.data, "num-points=" + points, "num-points=" + half);
    }
    return true;
  });
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"segments/0/", "longer than its header says", half});
}

// The vDeflection distance (sensitivity) or force (spring constant) slot multiplier of the file
// set to `value` in every header that defines it.
std::string with_file_calibration(const std::string& slot, const std::string& value, const std::string& tag) {
  const std::string key = "vDeflection.conversion-set.conversion." + slot + ".scaling.multiplier=";
  return variant(kSpot, tag, [&](Entry& e) {
    if (e.name.find(".properties") == std::string::npos) return true;
    std::string out, line;
    std::istringstream in(e.data);
    while (std::getline(in, line)) {
      const std::size_t at = line.find(key);
      if (at != std::string::npos) line = line.substr(0, at + key.size()) + value;
      out += line + "\n";
    }
    e.data = out;
    return true;
  });
}

void regression_jpk_file_calibration_not_validated() {
  for (const char* value : {"0.0", "-5.0E-8"}) {
    const std::string path = with_file_calibration("distance", value, std::string("sensitivity_") + (value[0] == '-' ? "negative" : "zero"));
    check::throws<InputError>([&] { afm::read_force_curves(path); }, {"the file's sensitivity", "--sensitivity"});
    afm::Calibration user;
    user.sensitivity = 5e-8;  // the user's value replaces the file's
    check::that(afm::read_force_curves(path, user).size() == 1, std::string("sensitivity ") + value + " replaced by --sensitivity");
  }
  const std::string k0 = with_file_calibration("force", "0.0", "spring_zero");
  check::throws<InputError>([&] { afm::read_force_curves(k0); }, {"the file's spring constant", "--spring-constant"});
}

const char* const kWorkshopHead =
    "Force-Distance Curve\nFile Format:\t3\n\nDate:\t22 October 2020\nTime:\t14:16:20\nMode:\tSingle\nPoint:\t1\n"
    "X, um:\t0.5\nY, um:\t0.5\n\nExtend Z-Sense(nm),Extend Force(nN),Retract Z-Sense(nm),Retract Force(nN)\n";

std::string workshop_rows(int rows) {
  std::string text;
  for (int i = 0; i < rows; ++i) {
    text += std::to_string(4000 + i) + ".5,0.05" + std::to_string(i % 10) + "," + std::to_string(5000 - i) + ".5,0.07\n";
  }
  return text;
}

void regression_workshop_csv_more_fields_than_columns_accepted() {
  const std::string good = work + "/good.csv";
  write_text(good, kWorkshopHead + workshop_rows(30));
  check::that(afm::read_force_curves(good).at(0).point_count() == 60, "a well-formed Workshop CSV: 2 x 30 points");
  // A decimal-comma export: 8 fields a row under 4 column names.
  const std::string comma = work + "/decimal_comma.csv";
  write_text(comma, kWorkshopHead + std::string("4000,5,0,05,5000,5,0,07\n") + workshop_rows(3));
  check::throws<InputError>([&] { afm::read_force_curves(comma); }, {"line 12", "8 fields", "the column line has 4"});
}

void regression_workshop_csv_truncated_mid_row_reads_force_0() {
  const std::string whole = kWorkshopHead + workshop_rows(30);
  // Cut inside the last row's last value ("0.07" -> "0"): the old reader read a force of 0.
  const std::string path = work + "/truncated.csv";
  write_text(path, whole.substr(0, whole.size() - 4));
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"line 41", "ends inside this row", "truncated"});
  const std::string cut_field = work + "/truncated_field.csv";
  write_text(cut_field, whole.substr(0, whole.size() - 12));
  check::throws<InputError>([&] { afm::read_force_curves(cut_field); }, {"line 41", "truncated"});
  // NT-MDT text the same way.
  const std::string ntmdt = work + "/truncated.txt";
  write_text(ntmdt, "1,0\t2,0\t3,0\n1,5\t2,5\t3,5\n2,0\t3,0\t4");
  check::throws<InputError>([&] { afm::read_force_curves(ntmdt); }, {"line 3", "truncated"});
}

// ---- item 3: unbounded reads ----

// A header entry of 64 MB of blanks compresses to ~64 KB: refused from its declared size.
void regression_jpk_zip_bomb_allocates_gigabytes() {
  const std::string path = variant(kSpot, "zip_bomb", [](Entry& e) {
    if (e.name == "header.properties") e.data += std::string(64u << 20, ' ');
    return true;
  });
  struct stat info {};
  stat(path.c_str(), &info);
  check::below(static_cast<double>(info.st_size), 2e6, "the bomb file is small");
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"header.properties", "exceeds the limit", "bytes for a .properties header"});
}

// Shared settings referenced by many keys of a header: 400 references x 1000 settings.
void regression_jpk_properties_bomb_takes_minutes() {
  const std::string path = variant("fmt-jpk-fd_single-modified_2023.jpk-force", "properties_bomb", [](Entry& e) {
    if (e.name == "shared-data/header.properties") {
      for (int k = 0; k < 1000; ++k) e.data += "lcd-info.77.bomb" + std::to_string(k) + "=1\n";
    }
    if (e.name == "segments/0/segment-header.properties") {
      for (int r = 0; r < 400; ++r) e.data += "bomb" + std::to_string(r) + ".lcd-info.*=77\n";
    }
    return true;
  });
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"segments/0/segment-header.properties", "more than 200000 settings"});
}

// The central directory's uncompressed size of an entry set to ~2 GB.
void regression_jpk_lying_entry_size_allocates_2gb() {
  const std::string good = variant(kSpot, "lying_source", [](Entry&) { return true; });
  std::ifstream in(good, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  bool patched = false;
  for (std::size_t at = bytes.find("PK\x01\x02"); at != std::string::npos; at = bytes.find("PK\x01\x02", at + 4)) {
    const std::size_t name_length = static_cast<unsigned char>(bytes[at + 28]) | (static_cast<unsigned char>(bytes[at + 29]) << 8);
    if (bytes.compare(at + 46, name_length, "header.properties") == 0 && name_length == 17) {
      bytes[at + 24] = '\x00', bytes[at + 25] = '\x00', bytes[at + 26] = '\x00', bytes[at + 27] = '\x7f';
      patched = true;
    }
  }
  check::that(patched, "the central directory entry of header.properties was found");
  const std::string path = work + "/lying_size.jpk-force";
  write_text(path, bytes);
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"header.properties"});
  check::throws<InputError>([&] { afm::read_force_curves_from_bytes(bytes, "lying.jpk-force"); }, {"header.properties"});
}

// A sparse 300 MB file: refused from its size, never read.
void regression_afm_file_without_size_cap_read_whole() {
  const std::string path = work + "/huge.csv";
  write_text(path, kWorkshopHead);
  check::that(truncate(path.c_str(), 300ll << 20) == 0, "a sparse 300 MB file");
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"huge.csv", "exceed the limit of 268435456 bytes"});
  check::throws<InputError>([&] { afm::detect_format(path); }, {"exceed the limit"});
}

void regression_workshop_csv_rows_times_columns() {
  std::string names = "Extend Z-Sense(nm),Extend Force(nN),Retract Z-Sense(nm),Retract Force(nN)";
  for (int c = 0; c < 100; ++c) names += ",x";
  const std::string path = work + "/wide.csv";
  write_text(path, replace(kWorkshopHead, "Extend Z-Sense(nm),Extend Force(nN),Retract Z-Sense(nm),Retract Force(nN)", names) + workshop_rows(5));
  check::throws<InputError>([&] { afm::read_force_curves(path); }, {"line 11", "104 columns", "limit of 64"});
}

// ---- issue 36: grid indices from the scan pattern ----

std::map<std::string, std::string> properties_of(const std::string& text) {
  std::map<std::string, std::string> p;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    const std::size_t eq = line.find('=');
    if (eq != std::string::npos && line[0] != '#') p[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return p;
}

std::string suffix_value(const std::map<std::string, std::string>& p, const std::string& suffix) {
  for (const auto& [k, v] : p) {
    if (k.size() >= suffix.size() && k.compare(k.size() - suffix.size(), suffix.size(), suffix) == 0) return v;
  }
  return "";
}

// Grid x follows position x within a row, grid y position y within a column (strictly).
void check_position_order(const std::vector<afm::CurveMetadata>& m, const std::string& what) {
  int compared = 0;
  bool ok = true;
  for (std::size_t a = 0; a < m.size(); ++a) {
    for (std::size_t b = a + 1; b < m.size(); ++b) {
      if (!m[a].grid_index_x || !m[b].grid_index_x || !m[a].position_x || !m[b].position_x) continue;
      if (*m[a].grid_index_y == *m[b].grid_index_y && *m[a].grid_index_x != *m[b].grid_index_x) {
        ok = ok && ((*m[a].grid_index_x < *m[b].grid_index_x) == (*m[a].position_x < *m[b].position_x));
        ++compared;
      }
      if (*m[a].grid_index_x == *m[b].grid_index_x && *m[a].grid_index_y != *m[b].grid_index_y) {
        ok = ok && ((*m[a].grid_index_y < *m[b].grid_index_y) == (*m[a].position_y < *m[b].position_y));
        ++compared;
      }
    }
  }
  check::that(ok && compared > 0, what + ": grid indices in the order of the positions (" + std::to_string(compared) + " pairs)");
}

void regression_grid_mirrored_on_odd_rows_of_back_and_forth_maps() {
  int maps = 0;
  for (const auto& entry : std::filesystem::directory_iterator(data_dir)) {
    const std::string path = entry.path().string();
    const bool jpk_map = path.size() > 9 && (path.find(".jpk-force-map") != std::string::npos || path.find(".jpk-qi-data") != std::string::npos);
    const bool workshop_map = path.find(".zip") != std::string::npos;
    if (!jpk_map && !workshop_map) continue;
    ++maps;
    afm::Calibration calibration = user_calibration();
    const afm::CurveSource source(path, calibration);
    std::vector<afm::CurveMetadata> places;
    for (std::size_t i = 0; i < source.size(); ++i) places.push_back(source.place(i));
    if (workshop_map) places.clear();
    if (workshop_map) for (const auto& c : afm::read_force_curves(path, calibration)) places.push_back(c.metadata);
    const std::string name = entry.path().filename().string();
    check::that(places.size() > 1 && places.front().grid_index_x.has_value(), name + ": grid indices known");
    if (places.size() > 1) check_position_order(places, name);
    if (!jpk_map) continue;
    // Decoding written here: index/N/header.properties' position-index k on the grid of
    // header.properties: row k / ilength, column k % ilength, backwards on odd rows of a
    // back-and-forth pattern.
    std::map<std::string, std::string> general;
    std::map<long, std::map<std::string, std::string>> curve_headers;
    for (const Entry& e : entries_of(path)) {
      if (e.name == "header.properties") general = properties_of(e.data);
      const std::size_t slash = e.name.find('/', 6);
      if (e.name.rfind("index/", 0) == 0 && slash != std::string::npos && slash > 6 && e.name.compare(slash, std::string::npos, "/header.properties") == 0) {
        curve_headers[std::stol(e.name.substr(6))] = properties_of(e.data);
      }
    }
    const long ilength = std::stol(suffix_value(general, "position-pattern.grid.ilength"));
    const bool meander = suffix_value(general, "position-pattern.back-and-forth") == "true";
    bool all = !curve_headers.empty() && curve_headers.size() == places.size();
    std::size_t i = 0;
    for (const auto& [number, header] : curve_headers) {
      const long k = std::stol(suffix_value(header, "header.position-index"));
      const long row = k / ilength, column = meander && row % 2 == 1 ? ilength - 1 - k % ilength : k % ilength;
      if (i < places.size()) all = all && places[i].grid_index_x == column && places[i].grid_index_y == row;
      ++i;
    }
    check::that(all, name + ": grid indices equal the decoding of position-index (back-and-forth " + std::string(meander ? "true" : "false") + ")");
  }
  check::that(maps >= 3, "the real maps of data/afm were found");
}

// The synthetic writer's two patterns read back as its truth file says.
void synthetic_back_and_forth_map_round_trips() {
  for (const bool meander : {false, true}) {
    const std::string tag = meander ? "meander" : "lines";
    const std::string map = work + "/synthetic_" + tag + ".jpk-force-map", truth = work + "/synthetic_" + tag + ".tsv";
    const std::string command = make_map + " " + map + " 3 4 --points 40 --clean --truth " + truth + (meander ? " --back-and-forth" : "");
    check::that(std::system(command.c_str()) == 0, "make_afm_map " + tag);
    const afm::CurveSource source(map, {});
    std::ifstream in(truth);
    std::string line;
    std::size_t n = 0;
    bool all = true;
    std::vector<afm::CurveMetadata> places;
    while (std::getline(in, line)) {
      if (line.empty() || line[0] == '#') continue;
      std::istringstream row(line);
      long curve = 0, gx = 0, gy = 0;
      row >> curve >> gx >> gy;
      const afm::CurveMetadata m = source.read(static_cast<std::size_t>(curve)).metadata;
      all = all && m.grid_index_x == gx && m.grid_index_y == gy;
      places.push_back(m);
      ++n;
    }
    check::that(all && n == 12, "synthetic " + tag + " map: 12 grid indices as written");
    if (meander) check::that(places[3].grid_index_x == 2 && places[5].grid_index_x == 0, "row 1 runs backwards");
    check_position_order(places, "synthetic " + tag);
  }
}

// ---- item 8: a NaN or inf in a curve ----

// Item 8: a NaN or inf in a curve's channel was flagged no_contact or no_convergence; the curve
// is readable and its data are bad: bad_data (9), with the reader's reason, the other curves
// fitted. The synthetic map's vDeflection channels (big-endian float) get a NaN (curve 0) and
// an inf (curve 1) written here.
void regression_nan_inf_curve_not_flagged_bad_data() {
  const std::string map = work + "/finite.jpk-force-map";
  const std::string command = make_map + " " + map + " 2 2 --points 100 --clean";
  check::that(std::system(command.c_str()) == 0, "make_afm_map 2 x 2");
  std::vector<Entry> entries = entries_of(map);
  for (Entry& e : entries) {
    for (int curve = 0; curve < 2; ++curve) {
      if (e.name != "index/" + std::to_string(curve) + "/segments/0/channels/vDeflection.dat") continue;
      const unsigned char bytes[2][4] = {{0x7f, 0xc0, 0, 0}, {0x7f, 0x80, 0, 0}};  // NaN, +inf
      for (int k = 0; k < 4; ++k) e.data[40 + k] = static_cast<char>(bytes[curve][k]);
    }
  }
  const std::string bad = work + "/nonfinite.jpk-force-map";
  write_zip(bad, entries);
  coatcontact::fit::AfmBatchSettings settings;
  settings.problem.tip = coatcontact::fit::afm_paraboloid(10e-6);
  coatcontact::fit::AfmBatchOptions options;
  std::vector<coatcontact::fit::AfmCurveRow> rows;
  options.sink = [&](const std::vector<coatcontact::fit::AfmCurveRow>& chunk) { rows.insert(rows.end(), chunk.begin(), chunk.end()); };
  coatcontact::fit::afm_fit_batch({bad}, {}, settings, options);
  check::that(rows.size() == 4, "four rows");
  if (rows.size() != 4) return;
  for (int curve = 0; curve < 2; ++curve) {
    check::that(rows[curve].flag == coatcontact::fit::AfmFlag::kBadData,
                "curve " + std::to_string(curve) + " (" + (curve == 0 ? "NaN" : "inf") + ") flagged bad_data: " + rows[curve].message);
    check::that(rows[curve].message.find("not finite") != std::string::npos, "its reason says the value is not finite");
  }
  check::that(rows[2].flag == coatcontact::fit::AfmFlag::kFitted && rows[3].flag == coatcontact::fit::AfmFlag::kFitted,
              "the other curves fitted");
}

// ---- items 4 (library) and 7 ----

void regression_jobs_65536_segfaults() {
  coatcontact::fit::AfmBatchOptions options;
  options.jobs = 65536;
  coatcontact::fit::AfmBatchSettings settings;
  check::throws<InputError>([&] { coatcontact::fit::afm_fit_batch({data_dir + "/" + kSpot}, user_calibration(), settings, options); },
                            {"jobs: 65536 is not allowed", "1 to 1024"});
}

void regression_symlink_loop_in_folder_is_internal_error() {
  const std::string folder = work + "/loop_folder";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(data_dir + "/" + kSpot, folder + "/a.jpk-force");
  std::filesystem::create_symlink("b.jpk-force", folder + "/b.jpk-force");
  check::throws<InputError>([&] { afm::afm_files_in_folder(folder); }, {"b.jpk-force", "cannot read the file in the folder"});
}

void regression_newline_in_file_name_aborts_batch() {
  const std::string folder = work + "/newline_folder";
  std::filesystem::remove_all(folder);
  std::filesystem::create_directories(folder);
  std::filesystem::copy_file(data_dir + "/" + kSpot, folder + "/a\nb.jpk-force");
  check::throws<InputError>([&] { afm::afm_files_in_folder(folder); }, {"holds a line break", "rename the file"});
}

// A zipped AFM Workshop map with one CSV cut mid-row: that curve alone cannot be read.
void regression_one_corrupt_curve_fails_whole_map() {
  const char* const name = "fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip";
  std::string bad_entry;
  const std::string path = variant(name, "one_bad_csv", [&](Entry& e) {
    if (bad_entry.empty() && e.name.find(".csv") != std::string::npos) {
      bad_entry = e.name;
      e.data = e.data.substr(0, e.data.size() / 2);
      while (!e.data.empty() && e.data.back() == '\n') e.data.pop_back();
    }
    return true;
  });
  afm::Calibration calibration = user_calibration();
  const afm::CurveSource source(path, calibration);
  check::that(source.size() == 16, "the map keeps its 16 curves");
  check::throws<InputError>([&] { source.read(0); }, {bad_entry, "truncated"});
  check::that(source.place(0).entry == bad_entry, "the unreadable curve keeps its entry");
  bool others = true;
  for (std::size_t i = 1; i < source.size(); ++i) others = others && source.read(i).point_count() > 0 && source.read(i).metadata.grid_index_x.has_value();
  check::that(others, "the 15 other curves are read, with grid indices");
  check::throws<InputError>([&] { afm::read_force_curves(path, calibration); }, {bad_entry});
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(stderr, "usage: test_afm_reader_limits DATA_DIR MAKE_AFM_MAP WORK_DIR\n");
    return 2;
  }
  data_dir = argv[1];
  make_map = argv[2];
  work = argv[3];
  std::filesystem::create_directories(work);
  regression_jpk_missing_segment_header_drops_later_segments();
  regression_jpk_num_points_smaller_than_channel_read_as_prefix();
  regression_jpk_file_calibration_not_validated();
  regression_workshop_csv_more_fields_than_columns_accepted();
  regression_workshop_csv_truncated_mid_row_reads_force_0();
  regression_jpk_zip_bomb_allocates_gigabytes();
  regression_jpk_properties_bomb_takes_minutes();
  regression_jpk_lying_entry_size_allocates_2gb();
  regression_afm_file_without_size_cap_read_whole();
  regression_workshop_csv_rows_times_columns();
  regression_grid_mirrored_on_odd_rows_of_back_and_forth_maps();
  synthetic_back_and_forth_map_round_trips();
  regression_nan_inf_curve_not_flagged_bad_data();
  regression_jobs_65536_segfaults();
  regression_symlink_loop_in_folder_is_internal_error();
  regression_newline_in_file_name_aborts_batch();
  regression_one_corrupt_curve_fails_whole_map();
  return check::exit_code();
}
