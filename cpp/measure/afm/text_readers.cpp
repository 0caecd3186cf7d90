// Text exports: AFM Workshop CSV (one curve; a zip of them for a map) and NT-MDT Nova text.
//  AFM Workshop: "Key:<TAB>value" header lines (Date, Time, Mode, Point, "X, um", "Y, um",
//  optionally "Force Constant, nN/nm" and "Light Lever Gain, mV/nm"), then the column line
//  "Extend Z-Sense(nm),Extend Force(nN)|Extend T-B(V),Retract Z-Sense(nm),Retract ..." and
//  comma-separated rows. Z-sense is the measured height, negated so that it decreases towards
//  the sample; T-B is the raw deflection in volts (force = V * sensitivity * k).
//  NT-MDT: three tab-separated columns with decimal commas: height [nm], deflection signal of
//  extend and of retract [nA]; constant padding at the start of a column is an export artefact
//  and is dropped; the approach runs from the last row up. Force = signal [A] * sensitivity
//  [m/A] * k, both supplied by the user.
#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "../number_text.hpp"
#include "read_support.hpp"
#include "zip_archive.hpp"

namespace coatcontact::afm::detail {

namespace {

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t pos = 0;
  while (pos < text.size()) {
    std::size_t end = text.find('\n', pos);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(pos, end - pos);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    lines.push_back(std::move(line));
    pos = end + 1;
  }
  return lines;
}

using coatcontact::detail::split;  // the measure floor's: n separators, n + 1 fields

const char* const kMonths[] = {"January", "February", "March", "April", "May", "June", "July",
                               "August", "September", "October", "November", "December"};

// "22 October 2020" or "Wednesday, August 1, 2018" -> "2020-10-22"; the text itself otherwise.
std::string iso_date(const std::string& text) {
  std::string cleaned;
  for (char c : text) cleaned.push_back(c == ',' ? ' ' : c);
  std::vector<std::string> words;
  for (const auto& w : split(cleaned, ' ')) if (!w.empty()) words.push_back(w);
  int month = 0;
  std::vector<int> numbers;
  for (const auto& w : words) {
    for (int k = 0; k < 12; ++k) if (w == kMonths[k]) month = k + 1;
    double v = 0.0;
    if (parse_double(w, v) && v == std::floor(v) && v > 0 && v < 10000) numbers.push_back(static_cast<int>(v));
  }
  if (month == 0 || numbers.size() != 2) return std::string(trim(text));
  const int day = std::min(numbers[0], numbers[1]), year = std::max(numbers[0], numbers[1]);
  char buffer[48];
  std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02d", year, month, day);
  return buffer;
}

}  // namespace

std::vector<ForceCurve> read_afm_workshop_csv(const std::string& text, const std::string& file,
                                              const std::string& entry, const Calibration& user) {
  const auto lines = lines_of(text);
  std::map<std::string, std::string> header;
  std::size_t column_line = lines.size();
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (std::count(lines[i].begin(), lines[i].end(), ',') >= 3 && lines[i].find("Z-Sense") != std::string::npos) {
      column_line = i;
      break;
    }
    const std::size_t colon = lines[i].find(':');
    if (colon != std::string::npos) header.emplace(std::string(trim(lines[i].substr(0, colon))), std::string(trim(lines[i].substr(colon + 1))));
  }
  if (column_line == lines.size()) fail(file, entry, "no column line (Extend Z-Sense(nm),...) in the AFM Workshop CSV");
  const auto names = split(lines[column_line], ',');
  // Column roles.
  enum Role { kNone, kHeightExtend, kHeightRetract, kForceExtend, kForceRetract, kVoltsExtend, kVoltsRetract };
  std::vector<Role> roles;
  for (const auto& raw_name : names) {
    const std::string name(trim(raw_name));
    Role role = kNone;
    if (name == "Extend Z-Sense(nm)") role = kHeightExtend;
    else if (name == "Retract Z-Sense(nm)") role = kHeightRetract;
    else if (name == "Extend Force(nN)") role = kForceExtend;
    else if (name == "Retract Force(nN)") role = kForceRetract;
    else if (name == "Extend T-B(V)") role = kVoltsExtend;
    else if (name == "Retract T-B(V)") role = kVoltsRetract;
    roles.push_back(role);
  }
  const auto has = [&](Role role) { return std::find(roles.begin(), roles.end(), role) != roles.end(); };
  const bool volts = has(kVoltsExtend) || has(kVoltsRetract);
  if (!has(kHeightExtend) || !has(kHeightRetract)) fail(file, entry, "missing channel: Extend/Retract Z-Sense(nm) columns");
  if (!(has(kForceExtend) || has(kVoltsExtend)) || !(has(kForceRetract) || has(kVoltsRetract))) {
    fail(file, entry, "missing channel: no Extend/Retract Force(nN) or T-B(V) columns");
  }
  // Columns may end at different rows: each keeps its values up to its first empty field.
  std::vector<std::vector<double>> values(names.size());
  std::vector<bool> ended(names.size(), false);
  for (std::size_t i = column_line + 1; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const auto fields = split(lines[i], ',');
    for (std::size_t c = 0; c < names.size(); ++c) {
      if (c >= fields.size() || trim(fields[c]).empty()) {
        ended[c] = true;
        continue;
      }
      if (ended[c]) fail(file, entry, "line " + std::to_string(i + 1) + ": a value after an empty field in column " + std::to_string(c + 1));
      double v = 0.0;
      if (!parse_double(fields[c], v) || !std::isfinite(v)) {
        fail(file, entry, "line " + std::to_string(i + 1) + ": '" + std::string(trim(fields[c])) + "' is not a number");
      }
      values[c].push_back(v);
    }
  }
  const auto column = [&](Role a, Role b) -> const std::vector<double>& {
    for (std::size_t c = 0; c < roles.size(); ++c) if (roles[c] == a || roles[c] == b) return values[c];
    return values[0];
  };

  double file_k = 0.0, file_s = 0.0;
  bool has_k = false, has_s = false;
  if (auto it = header.find("Force Constant, nN/nm"); it != header.end() && parse_double(it->second, file_k) && file_k > 0 && file_k != 1.0) has_k = true;
  if (auto it = header.find("Light Lever Gain, mV/nm"); it != header.end() && parse_double(it->second, file_s) && file_s > 0 && file_s != 1.0) {
    file_s = 1.0 / (file_s * 1e6);  // mV/nm = 1e6 V/m -> m/V
    has_s = true;
  }
  const CalibrationChoice calibration = choose_calibration(user, has_k ? &file_k : nullptr, has_s ? &file_s : nullptr,
                                                           volts, volts, file, entry,
                                                           "the header has no 'Force Constant, nN/nm' / 'Light Lever Gain, mV/nm'");
  ForceCurve curve;
  const Role force_roles[2][2] = {{kForceExtend, kVoltsExtend}, {kForceRetract, kVoltsRetract}};
  const Role height_roles[2] = {kHeightExtend, kHeightRetract};
  for (int s = 0; s < 2; ++s) {
    const auto& z = column(height_roles[s], height_roles[s]);
    const auto& f = column(force_roles[s][0], force_roles[s][1]);
    const bool in_volts = has(force_roles[s][1]);
    if (z.size() != f.size()) {
      fail(file, entry, std::string(s == 0 ? "extend" : "retract") + " columns differ in length (" + std::to_string(z.size()) +
                            " heights, " + std::to_string(f.size()) + " forces)");
    }
    if (z.empty()) fail(file, entry, std::string("empty segment ") + (s == 0 ? "extend" : "retract"));
    Segment segment;
    segment.kind = s == 0 ? SegmentKind::kApproach : SegmentKind::kRetract;
    segment.name = s == 0 ? "Extend" : "Retract";
    segment.begin = curve.height_measured.size();
    for (std::size_t i = 0; i < z.size(); ++i) {
      curve.height_measured.push_back(-(z[i] / 1e9));
      if (calibration.complete) {
        curve.force.push_back(in_volts ? f[i] * calibration.sensitivity * calibration.spring_constant : f[i] / 1e9);
      }
    }
    segment.end = curve.height_measured.size();
    curve.segments.push_back(segment);
  }
  CurveMetadata& m = curve.metadata;
  set_calibration(m, calibration);
  m.vendor = "AFM Workshop";
  m.format = entry.empty() ? "AFM Workshop CSV (.csv)" : "AFM Workshop map (.zip of CSV)";
  m.source_file = file;
  m.entry = entry;
  if (auto it = header.find("Date"); it != header.end()) m.date = iso_date(it->second);
  if (auto it = header.find("Time"); it != header.end()) m.time = it->second;
  double position = 0.0;
  if (auto it = header.find("X, um"); it != header.end() && parse_double(it->second, position)) m.position_x = position / 1e6;
  if (auto it = header.find("Y, um"); it != header.end() && parse_double(it->second, position)) m.position_y = position / 1e6;
  if (auto it = header.find("Point"); it != header.end()) m.details.emplace_back("point", it->second);
  if (auto it = header.find("Mode"); it != header.end()) m.details.emplace_back("mode", it->second);
  m.details.emplace_back("height (measured) channel", "-Z-Sense(nm)");
  m.details.emplace_back("force channel", volts ? "T-B(V) x sensitivity x spring constant" : "Force(nN)");
  finish_curve(curve, file, entry);
  return {curve};
}

std::vector<ForceCurve> read_afm_workshop_zip(const std::string& bytes, const std::string& file, const Calibration& user) {
  const ZipArchive archive(bytes, file);
  std::vector<std::string> entries;
  for (const auto& name : archive.names()) {
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0) entries.push_back(name);
  }
  std::sort(entries.begin(), entries.end());
  if (entries.empty()) fail(file, "", "a zip archive without CSV curves");
  std::vector<ForceCurve> curves;
  for (const auto& entry : entries) {
    auto one = read_afm_workshop_csv(archive.read(entry), file, entry, user);
    curves.push_back(std::move(one.front()));
  }
  // Grid indices: the rank of each position among the map's distinct x and y.
  std::set<double> xs, ys;
  bool all = true;
  for (const auto& c : curves) {
    if (!c.metadata.position_x || !c.metadata.position_y) all = false;
    else {
      xs.insert(*c.metadata.position_x);
      ys.insert(*c.metadata.position_y);
    }
  }
  for (std::size_t i = 0; i < curves.size(); ++i) {
    CurveMetadata& m = curves[i].metadata;
    m.curve_index = i;
    m.curve_count = curves.size();
    if (all) {
      m.grid_shape_x = static_cast<long>(xs.size());
      m.grid_shape_y = static_cast<long>(ys.size());
      m.grid_index_x = static_cast<long>(std::distance(xs.begin(), xs.find(*m.position_x)));
      m.grid_index_y = static_cast<long>(std::distance(ys.begin(), ys.find(*m.position_y)));
    }
  }
  return curves;
}

std::vector<ForceCurve> read_ntmdt_text(const std::string& text, const std::string& file, const Calibration& user) {
  const auto lines = lines_of(text);
  std::vector<double> height, extend, retract;
  for (std::size_t i = 0; i < lines.size(); ++i) {
    if (trim(lines[i]).empty()) continue;
    const auto fields = split(lines[i], '\t');
    if (fields.size() != 3) fail(file, "", "line " + std::to_string(i + 1) + ": expected 3 tab-separated columns, found " + std::to_string(fields.size()));
    double v[3];
    for (int c = 0; c < 3; ++c) {
      std::string field(trim(fields[static_cast<std::size_t>(c)]));
      std::replace(field.begin(), field.end(), ',', '.');
      if (!parse_double(field, v[c]) || !std::isfinite(v[c])) {
        fail(file, "", "line " + std::to_string(i + 1) + ": '" + field + "' is not a number");
      }
    }
    height.push_back(v[0]);
    extend.push_back(v[1]);
    retract.push_back(v[2]);
  }
  if (height.empty()) fail(file, "", "empty segment: no data rows");
  const CalibrationChoice calibration = choose_calibration(user, nullptr, nullptr, true, true, file, "",
                                                           "NT-MDT text exports carry no calibration");
  // First row of the real data: one before the first change of the deflection.
  const auto first_row = [&](const std::vector<double>& deflection, const char* name) {
    for (std::size_t i = 1; i < deflection.size(); ++i) {
      if (deflection[i] != deflection[0]) return i - 1;
    }
    fail(file, "", std::string("empty segment: the ") + name + " deflection is constant (padding only)");
  };
  const std::size_t approach_start = first_row(extend, "extend");
  const std::size_t retract_start = first_row(retract, "retract");
  ForceCurve curve;
  const double force_per_signal = calibration.sensitivity * calibration.spring_constant;
  Segment approach;
  approach.kind = SegmentKind::kApproach;
  approach.name = "extend";
  for (std::size_t i = height.size(); i-- > approach_start;) {
    curve.height_piezo.push_back(height[i] / 1e9);
    if (calibration.complete) curve.force.push_back(extend[i] / 1e9 * force_per_signal);
  }
  approach.end = curve.height_piezo.size();
  Segment retraction;
  retraction.kind = SegmentKind::kRetract;
  retraction.name = "retract";
  retraction.begin = approach.end;
  for (std::size_t i = retract_start; i < height.size(); ++i) {
    curve.height_piezo.push_back(height[i] / 1e9);
    if (calibration.complete) curve.force.push_back(retract[i] / 1e9 * force_per_signal);
  }
  retraction.end = curve.height_piezo.size();
  curve.segments = {approach, retraction};
  CurveMetadata& m = curve.metadata;
  set_calibration(m, calibration);
  m.vendor = "NT-MDT";
  m.format = "NT-MDT Nova text export (.txt)";
  m.source_file = file;
  m.details.emplace_back("height (piezo) channel", "column 1 [nm]");
  m.details.emplace_back("force channel", "columns 2 (extend) and 3 (retract) [nA] x sensitivity [m/A] x spring constant");
  finish_curve(curve, file, "");
  return {curve};
}

}  // namespace coatcontact::afm::detail
