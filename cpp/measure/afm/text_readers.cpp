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
#include "read_limits.hpp"
#include "zip_archive.hpp"

namespace coatcontact::afm::detail {

namespace {

// The lines of a text one at a time, as views into it (a text's lines are never copied: one
// long row must not cost a multiple of the file). `number` counts from 1; '\r' of CRLF dropped.
class Lines {
 public:
  explicit Lines(std::string_view text) : text_(text) {}
  bool next(std::string_view& line) {
    if (pos_ >= text_.size()) return false;
    std::size_t end = text_.find('\n', pos_);
    last_ended_ = end != std::string_view::npos;
    if (!last_ended_) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    pos_ = end + 1;
    ++number_;
    return true;
  }
  std::size_t number() const { return number_; }
  // Whether the line last returned ended with a line break (a file cut mid-row has none).
  bool last_ended() const { return last_ended_; }

 private:
  std::string_view text_;
  std::size_t pos_ = 0, number_ = 0;
  bool last_ended_ = true;
};

// Calls visit(index, field) for each `separator`-separated field of `line`, without copies.
template <class Visit>
void for_each_field(std::string_view line, char separator, const Visit& visit) {
  std::size_t start = 0, index = 0;
  while (true) {
    const std::size_t end = line.find(separator, start);
    visit(index++, line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start));
    if (end == std::string_view::npos) return;
    start = end + 1;
  }
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

namespace {

// The header lines the reader uses (no other line is kept: a file of many "key: value" lines
// must not grow a map).
const char* const kWorkshopKeys[] = {"Date", "Time", "Mode", "Point", "X, um", "Y, um", "Force Constant, nN/nm",
                                     "Light Lever Gain, mV/nm"};

enum Role { kNone, kHeightExtend, kHeightRetract, kForceExtend, kForceRetract, kVoltsExtend, kVoltsRetract };

Role role_of(std::string_view name) {
  name = trim(name);
  if (name == "Extend Z-Sense(nm)") return kHeightExtend;
  if (name == "Retract Z-Sense(nm)") return kHeightRetract;
  if (name == "Extend Force(nN)") return kForceExtend;
  if (name == "Retract Force(nN)") return kForceRetract;
  if (name == "Extend T-B(V)") return kVoltsExtend;
  if (name == "Retract T-B(V)") return kVoltsRetract;
  return kNone;
}

// The data rows after the column line: each column keeps its values up to its first empty
// field (columns may end at different rows). Refused, naming the line: a row with more fields
// than the column line (a decimal-comma export), a value after an empty field, a field that is
// not a number, and a last row without its line end (a file cut mid-row).
void read_workshop_rows(Lines& lines, const std::vector<Role>& roles, std::vector<std::vector<double>>& values,
                        const std::string& file, const std::string& entry) {
  std::vector<bool> ended(roles.size(), false);
  std::string_view row;
  while (lines.next(row)) {
    if (trim(row).empty()) continue;
    const std::string where = "line " + std::to_string(lines.number());
    if (!lines.last_ended()) fail(file, entry, where + ": the file ends inside this row (no line end): truncated");
    const std::size_t fields = static_cast<std::size_t>(std::count(row.begin(), row.end(), ',')) + 1;
    if (fields > roles.size()) {
      fail(file, entry, where + ": " + std::to_string(fields) + " fields, the column line has " + std::to_string(roles.size()) +
                            " (decimal commas? the AFM Workshop export writes decimal points)");
    }
    for (std::size_t c = fields; c < roles.size(); ++c) ended[c] = true;
    for_each_field(row, ',', [&](std::size_t c, std::string_view field) {
      if (trim(field).empty()) {
        ended[c] = true;
        return;
      }
      if (ended[c]) fail(file, entry, where + ": a value after an empty field in column " + std::to_string(c + 1));
      if (roles[c] == kNone) return;
      double v = 0.0;
      if (!parse_double(field, v) || !std::isfinite(v)) {
        fail(file, entry, where + ": '" + std::string(trim(field)) + "' is not a number");
      }
      values[c].push_back(v);
    });
  }
}

}  // namespace

std::vector<ForceCurve> read_afm_workshop_csv(const std::string& text, const std::string& file,
                                              const std::string& entry, const Calibration& user) {
  Lines lines(text);
  std::map<std::string, std::string> header;
  std::string_view line, column_line;
  bool found = false;
  while (!found && lines.next(line)) {
    if (std::count(line.begin(), line.end(), ',') >= 3 && line.find("Z-Sense") != std::string_view::npos) {
      column_line = line;
      found = true;
      break;
    }
    const std::size_t colon = line.find(':');
    if (colon == std::string_view::npos) continue;
    const std::string_view key = trim(line.substr(0, colon));
    for (const char* known : kWorkshopKeys) {
      if (key == known) header.emplace(std::string(key), std::string(trim(line.substr(colon + 1))));
    }
  }
  if (!found) fail(file, entry, "no column line (Extend Z-Sense(nm),...) in the AFM Workshop CSV");
  const std::size_t column_count = static_cast<std::size_t>(std::count(column_line.begin(), column_line.end(), ',')) + 1;
  if (column_count > kMaxCsvColumns) {
    fail(file, entry, "line " + std::to_string(lines.number()) + ": " + std::to_string(column_count) + " columns, more than the limit of " +
                          std::to_string(kMaxCsvColumns) + " (an AFM Workshop curve has 4)");
  }
  std::vector<Role> roles;
  for_each_field(column_line, ',', [&](std::size_t, std::string_view name) { roles.push_back(role_of(name)); });
  const auto has = [&](Role role) { return std::find(roles.begin(), roles.end(), role) != roles.end(); };
  const bool volts = has(kVoltsExtend) || has(kVoltsRetract);
  if (!has(kHeightExtend) || !has(kHeightRetract)) fail(file, entry, "missing channel: Extend/Retract Z-Sense(nm) columns");
  if (!(has(kForceExtend) || has(kVoltsExtend)) || !(has(kForceRetract) || has(kVoltsRetract))) {
    fail(file, entry, "missing channel: no Extend/Retract Force(nN) or T-B(V) columns");
  }
  std::vector<std::vector<double>> values(roles.size());
  read_workshop_rows(lines, roles, values, file, entry);
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
  std::vector<std::string> errors;
  std::vector<ForceCurve> curves = read_afm_workshop_entries(bytes, file, user, errors);
  for (const std::string& error : errors) {
    if (!error.empty()) throw InputError(error);
  }
  return curves;
}

std::vector<ForceCurve> read_afm_workshop_entries(const std::string& bytes, const std::string& file, const Calibration& user,
                                                  std::vector<std::string>& errors) {
  const ZipArchive archive(bytes, file);
  std::vector<std::string> entries;
  for (const auto& name : archive.names()) {
    if (name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0) entries.push_back(name);
  }
  std::sort(entries.begin(), entries.end());
  if (entries.empty()) fail(file, "", "a zip archive without CSV curves");
  std::uint64_t total = 0;
  for (const auto& entry : entries) total += std::min(archive.size_of(entry), kMaxWholeFileBytes + 1);
  if (total > kMaxWholeFileBytes) {
    fail(file, "", "its CSV curves hold more than " + std::to_string(kMaxWholeFileBytes) + " bytes uncompressed (the limit of a zipped map); corrupt or not an instrument's file");
  }
  std::vector<ForceCurve> curves;
  errors.assign(entries.size(), std::string());
  for (std::size_t i = 0; i < entries.size(); ++i) {
    // A curve that cannot be read keeps its place (its entry named) and its reason.
    try {
      auto one = read_afm_workshop_csv(archive.read(entries[i], kMaxCsvEntryBytes, "an AFM Workshop CSV curve"), file, entries[i], user);
      curves.push_back(std::move(one.front()));
    } catch (const MissingCalibration&) {
      throw;  // the file's calibration, the same for every curve
    } catch (const InputError& error) {
      errors[i] = error.what();
      curves.emplace_back();
      curves.back().metadata.source_file = file;
      curves.back().metadata.entry = entries[i];
    }
  }
  // Grid indices: the rank of each position among the map's distinct x and y.
  std::set<double> xs, ys;
  bool all = true;
  for (std::size_t i = 0; i < curves.size(); ++i) {
    const ForceCurve& c = curves[i];
    if (!errors[i].empty()) continue;
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
    if (all && errors[i].empty()) {
      m.grid_shape_x = static_cast<long>(xs.size());
      m.grid_shape_y = static_cast<long>(ys.size());
      m.grid_index_x = static_cast<long>(std::distance(xs.begin(), xs.find(*m.position_x)));
      m.grid_index_y = static_cast<long>(std::distance(ys.begin(), ys.find(*m.position_y)));
    }
  }
  return curves;
}

std::vector<ForceCurve> read_ntmdt_text(const std::string& text, const std::string& file, const Calibration& user) {
  Lines lines(text);
  std::string_view row;
  std::vector<double> height, extend, retract;
  while (lines.next(row)) {
    if (trim(row).empty()) continue;
    const std::string where = "line " + std::to_string(lines.number());
    const auto tabs = std::count(row.begin(), row.end(), '\t');
    if (tabs != 2) fail(file, "", where + ": expected 3 tab-separated columns, found " + std::to_string(tabs + 1));
    if (!lines.last_ended()) fail(file, "", where + ": the file ends inside this row (no line end): truncated");
    double v[3];
    for_each_field(row, '\t', [&](std::size_t c, std::string_view text_field) {
      std::string field(trim(text_field));
      std::replace(field.begin(), field.end(), ',', '.');
      if (!parse_double(field, v[c]) || !std::isfinite(v[c])) fail(file, "", where + ": '" + field + "' is not a number");
    });
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
