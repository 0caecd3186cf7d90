// The AFM readers on the real files of data/afm/: every channel sample equals, bit for bit, a
// decoding written here from the file's own bytes (JPK: the raw big-endian channel read from the
// zip through libzip, scaled by the header's encoder and calibration slots; Igor: the wave's
// floats; text formats: the numbers of the text), with point counts and metadata as the headers
// say. Usage: test_afm_readers DATA_DIR
#include <zip.h>

#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace afm = coatcontact::afm;
using Props = std::map<std::string, std::string>;

namespace {

std::string data_dir;

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// One zip entry through libzip, opened by path (independent of the reader's in-memory use).
std::string zip_entry(const std::string& path, const std::string& name) {
  int error = 0;
  zip_t* archive = zip_open(path.c_str(), ZIP_RDONLY, &error);
  if (archive == nullptr) return {};
  zip_stat_t st;
  std::string data;
  if (zip_stat(archive, name.c_str(), 0, &st) == 0) {
    zip_file_t* f = zip_fopen(archive, name.c_str(), 0);
    data.resize(st.size);
    if (f != nullptr) {
      const zip_int64_t got = zip_fread(f, data.data(), st.size);
      if (got != static_cast<zip_int64_t>(st.size)) data.clear();
      zip_fclose(f);
    }
  }
  zip_close(archive);
  return data;
}

// key=value lines (the JPK numbers and names need no unescaping).
Props properties(const std::string& text) {
  Props p;
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty() || line[0] == '#') continue;
    const auto eq = line.find('=');
    if (eq != std::string::npos) p[line.substr(0, eq)] = line.substr(eq + 1);
  }
  return p;
}

double num(const Props& p, const std::string& key) {
  const auto it = p.find(key);
  if (it == p.end()) {
    check::that(false, ("property present: " + key).c_str());
    return 0.0;
  }
  return std::strtod(it->second.c_str(), nullptr);
}

// The settings of channel `ch` under one spelling: "channel.ch.data.X"/"channel.ch.X" inline,
// or "lcd-info.N.X" of the shared header when the segment says channel.ch.lcd-info.*=N.
struct ChannelSettings {
  Props segment, shared;
  std::string ch;
  std::string key(const std::string& inline_key, const std::string& shared_key) const {
    const auto ref = segment.find("channel." + ch + ".lcd-info.*");
    if (ref != segment.end()) return "lcd-info." + ref->second + "." + shared_key;
    return "channel." + ch + "." + inline_key;
  }
  const Props& props() const { return segment.count("channel." + ch + ".lcd-info.*") ? shared : segment; }
  double number(const std::string& inline_key, const std::string& shared_key) const { return num(props(), key(inline_key, shared_key)); }
  std::string text(const std::string& inline_key, const std::string& shared_key) const {
    const auto it = props().find(key(inline_key, shared_key));
    return it == props().end() ? std::string() : it->second;
  }
};

// Decodes channel `ch` of one segment in calibration slot `slot` by hand.
std::vector<double> jpk_channel(const std::string& path, const std::string& folder, const std::string& ch,
                                const std::string& slot) {
  ChannelSettings s;
  s.segment = properties(zip_entry(path, folder + "segment-header.properties"));
  s.shared = properties(zip_entry(path, "shared-data/header.properties"));
  s.ch = ch;
  const std::string encoder = s.text("data.encoder.type", "encoder.type");
  const double offset = s.number("data.encoder.scaling.offset", "encoder.scaling.offset");
  const double multiplier = s.number("data.encoder.scaling.multiplier", "encoder.scaling.multiplier");
  // The chain of slots down to the base, applied from the base up.
  std::vector<std::pair<double, double>> chain;
  const std::string base = s.text("conversion-set.conversions.base", "conversion-set.conversions.base");
  for (std::string c = slot; c != base;) {
    const std::string k = "conversion-set.conversion." + c + ".";
    chain.emplace_back(s.number(k + "scaling.offset", k + "scaling.offset"), s.number(k + "scaling.multiplier", k + "scaling.multiplier"));
    c = s.text(k + "base-calibration-slot", k + "base-calibration-slot");
    if (chain.size() > 5) break;
  }
  const std::string raw = zip_entry(path, folder + "channels/" + ch + ".dat");
  const auto* b = reinterpret_cast<const unsigned char*>(raw.data());
  const std::size_t width = encoder == "signedshort" ? 2 : 4;
  std::vector<double> out;
  for (std::size_t i = 0; i + width <= raw.size(); i += width) {
    double v = 0.0;
    if (width == 2) v = static_cast<std::int16_t>((b[i] << 8) | b[i + 1]);
    else v = static_cast<std::int32_t>((std::uint32_t{b[i]} << 24) | (std::uint32_t{b[i + 1]} << 16) | (std::uint32_t{b[i + 2]} << 8) | b[i + 3]);
    v = offset + multiplier * v;
    for (auto it = chain.rbegin(); it != chain.rend(); ++it) v = it->first + it->second * v;
    out.push_back(v);
  }
  return out;
}

bool same(const std::vector<double>& a, std::size_t begin, const std::vector<double>& b) {
  if (begin + b.size() > a.size() || b.empty()) return false;
  for (std::size_t i = 0; i < b.size(); ++i) {
    if (a[begin + i] != b[i]) return false;
  }
  return true;
}

struct JpkExpect {
  std::string file;
  std::string piezo_slot;             // "calibrated"
  std::string measured;               // measured-height channel
  std::vector<afm::SegmentKind> kinds;
};

void check_jpk_curve(const std::string& path, const afm::ForceCurve& curve, const std::string& folder,
                     const std::string& measured, const std::vector<afm::SegmentKind>& kinds) {
  const std::string name = path + " " + folder;
  check::that(curve.segments.size() == kinds.size(), ("segment count " + name).c_str());
  for (std::size_t s = 0; s < curve.segments.size() && s < kinds.size(); ++s) {
    const std::string seg = folder + "segments/" + std::to_string(s) + "/";
    const Props header = properties(zip_entry(path, seg + "segment-header.properties"));
    const auto& segment = curve.segments[s];
    check::that(segment.kind == kinds[s], ("segment kind " + name + seg).c_str());
    check::that(segment.size() == static_cast<std::size_t>(num(header, "force-segment-header.num-points")),
                ("point count as num-points " + name + seg).c_str());
    check::that(same(curve.force, segment.begin, jpk_channel(path, seg, "vDeflection", "force")), ("force bit for bit " + name + seg).c_str());
    check::that(same(curve.height_piezo, segment.begin, jpk_channel(path, seg, "height", "calibrated")), ("height (piezo) bit for bit " + name + seg).c_str());
    check::that(same(curve.height_measured, segment.begin, jpk_channel(path, seg, measured, "nominal")), ("height (measured) bit for bit " + name + seg).c_str());
    const double duration = num(header, "force-segment-header.duration");
    const std::size_t n = segment.size();
    bool time_ok = true;
    const double start = s == 0 ? 0.0 : curve.time[segment.begin - 1] + 0.0;
    (void)start;
    for (std::size_t i = 0; i < n; ++i) {
      double t0 = 0.0;
      for (std::size_t r = 0; r < s; ++r) t0 += curve.segments[r].duration;
      if (curve.time[segment.begin + i] != t0 + duration * static_cast<double>(i) / static_cast<double>(n)) time_ok = false;
    }
    check::that(time_ok, ("time = segment start + duration i/n " + name + seg).c_str());
    bool index_ok = true;
    for (std::size_t i = segment.begin; i < segment.end; ++i) index_ok = index_ok && curve.segment[i] == static_cast<int>(s);
    check::that(index_ok, ("segment index channel " + name + seg).c_str());
  }
}

// Spring constant and sensitivity: the slot multipliers of vDeflection.
void check_jpk_calibration(const std::string& path, const afm::ForceCurve& curve, const std::string& folder) {
  ChannelSettings s;
  s.segment = properties(zip_entry(path, folder + "segments/0/segment-header.properties"));
  s.shared = properties(zip_entry(path, "shared-data/header.properties"));
  s.ch = "vDeflection";
  const std::string k = "conversion-set.conversion.force.scaling.multiplier";
  const std::string d = "conversion-set.conversion.distance.scaling.multiplier";
  check::that(curve.metadata.spring_constant == s.number(k, k), ("spring constant as the header " + path).c_str());
  check::that(curve.metadata.sensitivity == s.number(d, d), ("sensitivity as the header " + path).c_str());
  check::that(curve.metadata.spring_constant_source == afm::CalibrationSource::kFile, "spring constant from the file");
}

using K = afm::SegmentKind;

void test_jpk_single(const std::string& file, const std::string& measured, const std::vector<K>& kinds, double nominal_k) {
  const std::string path = data_dir + "/" + file;
  const auto curves = afm::read_force_curves(path);
  check::that(curves.size() == 1, ("one curve in " + file).c_str());
  check_jpk_curve(path, curves[0], "", measured, kinds);
  check_jpk_calibration(path, curves[0], "");
  check::close(curves[0].metadata.spring_constant, nominal_k, 0.01, ("k as the data README says " + file).c_str());
  check::that(curves[0].metadata.vendor == "JPK", "vendor JPK");
  check::that(curves[0].metadata.source_file == path, "source file recorded");
}

void test_jpk_map(const std::string& file, const std::string& measured, std::size_t count) {
  const std::string path = data_dir + "/" + file;
  const auto curves = afm::read_force_curves(path);
  check::that(curves.size() == count, ("curve count of " + file).c_str());
  const Props general = properties(zip_entry(path, "header.properties"));
  double ilength = 0.0;
  bool meander = false;  // back-and-forth: odd rows run backwards (issue 36)
  for (const auto& [key, value] : general) {
    const std::string tail = "position-pattern.grid.ilength", pattern = "position-pattern.back-and-forth";
    if (key.size() > tail.size() && key.compare(key.size() - tail.size(), tail.size(), tail) == 0) ilength = std::strtod(value.c_str(), nullptr);
    if (key.size() > pattern.size() && key.compare(key.size() - pattern.size(), pattern.size(), pattern) == 0) meander = value == "true";
  }
  if (!check::that(ilength > 0, "grid ilength in the map header")) return;
  for (std::size_t c = 0; c < curves.size(); ++c) {
    // The curves' folders in numeric order: index/0/, index/1/, ... as listed in the archive.
    const std::string folder = curves[c].metadata.entry;
    const Props own = properties(zip_entry(path, folder + "header.properties"));
    check_jpk_curve(path, curves[c], folder, measured, {K::kApproach, K::kRetract});
    check_jpk_calibration(path, curves[c], folder);
    double position_index = -1.0, x = 0.0, y = 0.0;
    for (const auto& [key, value] : own) {
      const auto ends = [&](const char* tail) { const std::size_t n = std::strlen(tail); return key.size() >= n && key.compare(key.size() - n, n, tail) == 0; };
      if (ends("header.position-index")) position_index = std::strtod(value.c_str(), nullptr);
      if (ends("header.position.x")) x = std::strtod(value.c_str(), nullptr);
      if (ends("header.position.y")) y = std::strtod(value.c_str(), nullptr);
    }
    const long i = static_cast<long>(position_index), n = static_cast<long>(ilength);
    const long column = meander && (i / n) % 2 == 1 ? n - 1 - i % n : i % n;
    check::that(curves[c].metadata.grid_index_x && *curves[c].metadata.grid_index_x == column, ("grid index x " + folder).c_str());
    check::that(curves[c].metadata.grid_index_y && *curves[c].metadata.grid_index_y == i / n, ("grid index y " + folder).c_str());
    check::that(curves[c].metadata.position_x && *curves[c].metadata.position_x == x, ("position x " + folder).c_str());
    check::that(curves[c].metadata.position_y && *curves[c].metadata.position_y == y, ("position y " + folder).c_str());
    check::that(curves[c].metadata.curve_index == c && curves[c].metadata.curve_count == count, "curve index in the map");
  }
}

// Igor: little-endian float columns after the 384 bytes of headers; note "Key: value" lines.
void test_igor() {
  const std::string path = data_dir + "/fmt-igor-fd_U3_3_p10004.ibw";
  const std::string bytes = slurp(path);
  std::int32_t sizes[4];
  std::memcpy(sizes, bytes.data() + 4, sizeof sizes);  // wfmSize, formulaSize, noteSize, dataEUnitsSize
  std::int32_t n_dim[2];
  std::memcpy(n_dim, bytes.data() + 64 + 68, sizeof n_dim);
  double dt = 0.0;
  std::memcpy(&dt, bytes.data() + 64 + 84, sizeof dt);
  const std::string note = bytes.substr(64 + static_cast<std::size_t>(sizes[0]) + static_cast<std::size_t>(sizes[1]), static_cast<std::size_t>(sizes[2]));
  const auto note_value = [&](const std::string& key) {
    const std::size_t at = note.find("\r" + key + ":");
    return std::strtod(note.c_str() + at + key.size() + 2, nullptr);
  };
  const double k = note_value("SpringConstant");
  const double invols = note_value("InvOLS");
  const auto column = [&](int c, std::size_t i) {
    float f = 0.0f;
    std::memcpy(&f, bytes.data() + 384 + (static_cast<std::size_t>(c) * static_cast<std::size_t>(n_dim[0]) + i) * 4, 4);
    return static_cast<double>(f);
  };
  const auto curves = afm::read_force_curves(path);
  check::that(curves.size() == 1, "one Igor curve");
  const auto& c = curves[0];
  const auto n = static_cast<std::size_t>(n_dim[0]);
  check::that(c.point_count() == n, "Igor point count = nDim[0]");
  bool ok_f = true, ok_p = true, ok_m = true, ok_t = true;
  for (std::size_t i = 0; i < n; ++i) {
    ok_p = ok_p && c.height_piezo[i] == -column(0, i);        // Raw
    ok_f = ok_f && c.force[i] == column(1, i) * 1.0 * k;      // Defl [m] * k
    ok_m = ok_m && c.height_measured[i] == -column(2, i);     // ZSnsr
    ok_t = ok_t && c.time[i] == static_cast<double>(i) * dt;
  }
  check::that(ok_f && ok_p && ok_m && ok_t, "Igor channels bit for bit");
  check::that(c.metadata.spring_constant == k && c.metadata.sensitivity == invols, "Igor k and InvOLS from the note");
  // Note "Indexes: 0,5057,10096" with "Direction: NaN,1,-1": approach to 5057, then retract.
  check::that(c.segments.size() == 2 && c.segments[0].end == 5058 && c.segments[1].end == n &&
                  c.segments[0].kind == K::kApproach && c.segments[1].kind == K::kRetract,
              "Igor segments from the note's Indexes and Direction");
  // A user's sensitivity rescales Defl (made with InvOLS); a user's k replaces the note's.
  afm::Calibration user;
  user.spring_constant = 0.5;
  user.sensitivity = 1e-7;
  const auto scaled = afm::read_force_curves(path, user);
  check::that(scaled[0].force[100] == column(1, 100) * (1e-7 / invols) * 0.5, "Igor force with the user's k and sensitivity");
  check::that(scaled[0].metadata.spring_constant_source == afm::CalibrationSource::kUser, "user k recorded as such");
}

std::vector<std::vector<std::string>> csv_rows(const std::string& text, std::size_t skip) {
  std::vector<std::vector<std::string>> rows;
  std::istringstream in(text);
  std::string line;
  for (std::size_t i = 0; std::getline(in, line); ++i) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (i < skip || line.empty()) continue;
    std::vector<std::string> fields;
    std::stringstream ls(line);
    std::string f;
    while (std::getline(ls, f, ',')) fields.push_back(f);
    rows.push_back(fields);
  }
  return rows;
}

// Volts to force as the file format defines it: V * sensitivity * k, in that order.
void check_workshop(const afm::ForceCurve& c, const std::string& text, double s, double k, bool volts, const std::string& what) {
  const auto rows = csv_rows(text, 11);  // 10 header lines and the column line
  bool ok = c.point_count() == 2 * rows.size() && c.segments.size() == 2;
  for (std::size_t i = 0; ok && i < rows.size(); ++i) {
    const double z_ext = std::strtod(rows[i][0].c_str(), nullptr), f_ext = std::strtod(rows[i][1].c_str(), nullptr);
    const double z_ret = std::strtod(rows[i][2].c_str(), nullptr), f_ret = std::strtod(rows[i][3].c_str(), nullptr);
    const std::size_t r = rows.size() + i;
    ok = c.height_measured[i] == -(z_ext / 1e9) && c.height_measured[r] == -(z_ret / 1e9) &&
         c.force[i] == (volts ? f_ext * s * k : f_ext / 1e9) && c.force[r] == (volts ? f_ret * s * k : f_ret / 1e9);
  }
  check::that(ok, what);
}

void test_workshop() {
  const std::string single = data_dir + "/fmt-afm-workshop-fd_single_2021-10-22_14.16.csv";
  const auto curves = afm::read_force_curves(single);
  check::that(curves.size() == 1 && curves[0].metadata.date == "2020-10-22" && curves[0].metadata.position_x == 0.5e-6,
              "AFM Workshop CSV metadata (date, X)");
  check_workshop(curves[0], slurp(single), 0.0, 0.0, false, "AFM Workshop CSV channels bit for bit");

  const std::string map = data_dir + "/fmt-afm-workshop-fd_mapping_16_2018-08-01_13.07.zip";
  check::throws<coatcontact::InputError>([&] { afm::read_force_curves(map); }, {map, "--spring-constant", "--sensitivity"});
  afm::Calibration user;
  user.spring_constant = 0.2;
  user.sensitivity = 5e-8;
  const auto maps = afm::read_force_curves(map, user);
  check::that(maps.size() == 16, "16 curves in the AFM Workshop map");
  bool grid = true;
  for (std::size_t i = 0; i < maps.size(); ++i) {
    check_workshop(maps[i], zip_entry(map, maps[i].metadata.entry), 5e-8, 0.2, true, "AFM Workshop map curve bit for bit " + maps[i].metadata.entry);
    grid = grid && maps[i].metadata.grid_shape_x == 4L && maps[i].metadata.grid_shape_y == 4L;
  }
  check::that(grid, "AFM Workshop map is a 4 x 4 grid");
}

void test_ntmdt() {
  const std::string path = data_dir + "/fmt-ntmdt-txt-fd_2015_01_17_gel4-0,1_mQ_adh_6B_Curve_DFL_Height_51.txt";
  check::throws<coatcontact::InputError>([&] { afm::read_force_curves(path); }, {path, "--spring-constant", "--sensitivity"});
  afm::Calibration user;
  user.spring_constant = 0.1;
  user.sensitivity = 2e-7;
  const auto c = afm::read_force_curves(path, user).at(0);
  std::vector<double> h, e, r;
  std::istringstream in(slurp(path));
  std::string line;
  while (std::getline(in, line)) {
    for (char& ch : line) if (ch == ',') ch = '.';
    std::istringstream ls(line);
    double a = 0, b = 0, d = 0;
    if (ls >> a >> b >> d) { h.push_back(a); e.push_back(b); r.push_back(d); }
  }
  std::size_t e0 = 1, r0 = 1;  // one before the first change of each deflection column
  while (e[e0] == e[0]) ++e0;
  while (r[r0] == r[0]) ++r0;
  --e0;
  --r0;
  const std::size_t na = h.size() - e0;
  bool ok = c.point_count() == na + (h.size() - r0);
  for (std::size_t j = 0; ok && j < na; ++j) {
    const std::size_t i = h.size() - 1 - j;  // the approach runs from the last row up
    ok = c.height_piezo[j] == h[i] / 1e9 && c.force[j] == e[i] / 1e9 * (2e-7 * 0.1);
  }
  for (std::size_t i = r0; ok && i < h.size(); ++i) {
    const std::size_t j = na + i - r0;
    ok = c.height_piezo[j] == h[i] / 1e9 && c.force[j] == r[i] / 1e9 * (2e-7 * 0.1);
  }
  check::that(ok, "NT-MDT channels bit for bit (padding cropped, approach reversed)");
}

void test_missing_calibration() {
  const std::string cal = data_dir + "/fmt-jpk-cl_calibration_force-save-2015.02.04-11.25.21.294.jpk-force";
  check::throws<coatcontact::InputError>([&] { afm::read_force_curves(cal); }, {cal, "no spring constant and no sensitivity", "--spring-constant", "--sensitivity"});
  const std::string modified = data_dir + "/fmt-jpk-fd_single-modified_2023.jpk-force";
  check::throws<coatcontact::InputError>([&] { afm::read_force_curves(modified); }, {modified, "no spring constant", "--spring-constant", "spring_constant="});
  // The user's spring constant completes the chain volts -> distance (file) -> force (user).
  afm::Calibration user;
  user.spring_constant = 0.05;
  const auto c = afm::read_force_curves(modified, user).at(0);
  const auto distance = jpk_channel(modified, "segments/0/", "vDeflection", "distance");
  bool ok = true;
  for (std::size_t i = 0; i < distance.size(); ++i) ok = ok && c.force[i] == 0.0 + 0.05 * distance[i];
  check::that(ok && !distance.empty(), "force = k_user x distance slot, bit for bit");
  check::that(c.metadata.spring_constant_source == afm::CalibrationSource::kUser &&
                  c.metadata.sensitivity_source == afm::CalibrationSource::kFile,
              "calibration sources recorded");
  // Both supplied for the calibration run: the sensitivity replaces the undefined distance slot.
  user.sensitivity = 6e-8;
  const auto both = afm::read_force_curves(cal, user).at(0);
  check::that(both.has_force() && both.metadata.sensitivity == 6e-8, "calibration run read with the user's k and sensitivity");
  // Listing without calibration: no force channel, never zeros.
  afm::Calibration listing;
  listing.allow_missing = true;
  const auto listed = afm::read_force_curves(cal, listing).at(0);
  check::that(!listed.has_force() && listed.point_count() == 4096, "listing without calibration has no force channel");
  check::throws<coatcontact::InputError>([&] { listed.tip_position(); }, {"spring constant"});
  // A bad user value.
  afm::Calibration bad;
  bad.spring_constant = -1.0;
  check::throws<coatcontact::InputError>([&] { afm::read_force_curves(cal, bad); }, {"--spring-constant"});
}

void test_tip_position() {
  const auto c = afm::read_force_curves(data_dir + "/fmt-jpk-fd_spot3-0192.jpk-force").at(0);
  const auto tip = c.tip_position();
  bool ok = tip.size() == c.point_count();
  for (std::size_t i = 0; ok && i < tip.size(); ++i) ok = tip[i] == c.height_measured[i] + c.force[i] / c.metadata.spring_constant;
  check::that(ok, "tip position = height (measured) + F/k");
}

}  // namespace

int main(int argc, char** argv) {
  data_dir = argc > 1 ? argv[1] : "data/afm";
  test_jpk_single("fmt-jpk-fd_spot3-0192.jpk-force", "strainGaugeHeight", {K::kApproach, K::kRetract}, 0.0435);
  test_jpk_single("fmt-jpk-cc_pr14-polymergel-2021.06.30.jpk-force", "measuredHeight", {K::kApproach, K::kPause, K::kRetract}, 0.061);
  test_jpk_single("fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force", "capacitiveSensorHeight", {K::kApproach, K::kRetract}, 0.0187);
  test_jpk_map("fmt-jpk-fd_map2x2_extracted.jpk-force-map", "capacitiveSensorHeight", 4);
  test_jpk_map("fmt-jpk-fd_2020.02.07-16.29.05.036.jpk-qi-data", "measuredHeight", 4);
  test_igor();
  test_workshop();
  test_ntmdt();
  test_missing_calibration();
  test_tip_position();
  return check::exit_code();
}
