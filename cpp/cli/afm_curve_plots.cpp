// Control plots of a batch (afm_curve_plots.hpp, gnuplot/afm_curve_plots.gp).
#include "afm_curve_plots.hpp"

#include <stdlib.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <utility>

#include "afm_curve_plots_script.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/gnuplot_run.hpp"

namespace coatcontact::cli {

namespace {

// Points drawn per page at most (a page shows no more; longer curves are thinned evenly).
constexpr std::size_t kMaxPagePoints = 4000;

std::string number(double v) {
  if (!std::isfinite(v)) return "NaN";
  char text[40];
  std::snprintf(text, sizeof text, "%.9g", v);
  return text;
}

// Scale and SI prefix of an axis whose values reach `magnitude`.
std::pair<double, std::string> prefix(double magnitude, const char* unit) {
  static const char* names[] = {"f", "p", "n", "µ", "m", "", "k", "M"};
  int e = magnitude > 0.0 ? 3 * static_cast<int>(std::floor(std::log10(magnitude) / 3.0 + 1e-9)) : 0;
  e = std::clamp(e, -15, 6);
  return {std::pow(10.0, -e), std::string(names[(e + 15) / 3]) + unit};
}

// At most `width` characters of a message (a page's line), cut at a word with "...".
std::string clipped(const std::string& text, std::size_t width) {
  if (text.size() <= width) return text;
  std::size_t cut = text.rfind(' ', width - 3);
  if (cut == std::string::npos || cut < width / 2) cut = width - 3;
  return text.substr(0, cut) + "...";
}

// A file name as a gnuplot single-quoted string (gnuplot_string's escapes are for shown text).
std::string quoted_path(const std::string& path) {
  std::string out = "'";
  for (char c : path) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

// "5.001 ± 0.003 kPa": a value and its error with the value's prefix.
std::string with_error(double value, double error, const std::string& unit, int digits) {
  const auto [scale, name] = prefix(std::abs(value), unit.c_str());
  char text[120];
  std::snprintf(text, sizeof text, "%.*g ± %.2g %s", digits, value * scale, error * scale, name.c_str());
  return text;
}

}  // namespace

AfmCurvePlots::AfmCurvePlots(std::vector<fit::AfmBatchParameter> parameters, bool retract_fit)
    : parameters_(std::move(parameters)), retract_fit_(retract_fit) {
  const char* tmp = std::getenv("TMPDIR");
  std::string pattern = std::string(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") + "/coatcontact-curves.XXXXXX";
  std::vector<char> buffer(pattern.begin(), pattern.end());
  buffer.push_back('\0');
  const int fd = mkstemp(buffer.data());
  if (fd < 0) throw InputError("--curve-plots: cannot create a temporary file for the pages' data");
  ::close(fd);
  data_path_ = buffer.data();
  data_.open(data_path_, std::ios::binary | std::ios::trunc);
  if (!data_) throw InputError("--curve-plots: cannot write the temporary file " + data_path_);
}

AfmCurvePlots::~AfmCurvePlots() {
  data_.close();
  std::remove(data_path_.c_str());
}

void AfmCurvePlots::add(const fit::AfmCurveRow& row) {
  const fit::AfmCurveTrace* trace = row.trace.get();
  const bool has = trace != nullptr && !trace->z.empty();
  const bool estimates = fit::afm_flag_keeps_estimates(row.flag) && has;
  double z_big = 0.0, f_big = 0.0, z_low = INFINITY, z_high = -INFINITY;
  if (pages_ > 0) data_ << "\n\n";
  if (has) {
    const std::size_t n = trace->z.size();
    const std::size_t stride = (n + kMaxPagePoints - 1) / kMaxPagePoints;
    for (std::size_t i = 0; i < n; i += stride) {
      z_big = std::max(z_big, std::abs(trace->z[i]));
      z_low = std::min(z_low, trace->z[i]);
      z_high = std::max(z_high, trace->z[i]);
      f_big = std::max(f_big, std::abs(trace->force[i]));
      const double residual = trace->fitted[i] ? trace->model[i] - trace->force[i] : NAN;
      data_ << number(trace->z[i]) << '\t' << number(trace->force[i]) << '\t' << number(trace->model[i]) << '\t'
            << number(residual) << '\t' << trace->segment[i] << '\t' << static_cast<int>(trace->fitted[i]) << '\n';
    }
  } else {
    data_ << "NaN\tNaN\tNaN\tNaN\t0\t0\n";  // keeps the blocks' numbering
  }
  if (!data_) throw InputError("--curve-plots: cannot write the temporary file " + data_path_);
  ++pages_;
  std::string title = std::filesystem::path(row.source_file).filename().string() + " #" + std::to_string(row.curve_index);
  if (row.grid_x && row.grid_y) title += " (grid " + std::to_string(*row.grid_x) + ", " + std::to_string(*row.grid_y) + ")";
  char rating[64];
  std::snprintf(rating, sizeof rating, ", rating %.1f/10", row.rating);
  title += std::string(": ") + fit::afm_flag_name(row.flag) + rating;
  std::string key;
  if (fit::afm_flag_keeps_estimates(row.flag)) {
    for (std::size_t p = 0; p < parameters_.size() && p < row.estimates.size(); ++p) {
      // A location (contact point) needs the digits of its place, a scale those of its error.
      const bool location = parameters_[p].name == "contact_point" || parameters_[p].name == "baseline";
      key += (key.empty() ? "" : ", ") + parameters_[p].name + " = " +
             with_error(row.estimates[p], row.errors[p], parameters_[p].unit, location ? 7 : 4);
    }
    char chi[48];
    std::snprintf(chi, sizeof chi, ", χ²/dof = %.3g", row.chi2_per_dof);
    key += chi;
    if (row.flag != fit::AfmFlag::kFitted && !row.message.empty()) key += " — " + clipped(row.message, 60);
  } else {
    key = clipped(row.message, 125);
  }
  const auto [zs, zu] = prefix(z_big, "m");
  // The contact region, as the one-curve plot's middle panel: from the deepest point to two
  // largest indentations above the contact point (the data's whole range without estimates).
  if (estimates && std::isfinite(trace->contact_point) && trace->contact_point > z_low) {
    z_high = std::min(z_high, trace->contact_point + 2.0 * (trace->contact_point - z_low));
  }
  const auto [fs, fu] = prefix(f_big, "N");
  const std::string i = std::to_string(pages_);
  settings_ += "T[" + i + "]=" + gnuplot_string(title) + "; K[" + i + "]=" + gnuplot_string(key) + "; HAS[" + i + "]=" +
               (has ? "1" : "0") + "; RES[" + i + "]=" + (estimates ? "1" : "0") + "; RET[" + i + "]=" + (retract_fit_ ? "1" : "0") +
               "; ZS[" + i + "]=" + number(zs) + "; ZU[" + i + "]='" + zu + "'; FS[" + i + "]=" + number(fs) + "; FU[" + i + "]='" +
               fu + "'; ZC[" + i + "]=" + number(estimates ? trace->contact_point : NAN) + "; XLO[" + i + "]=" + number(has ? z_low * zs : 0.0) +
               "; XHI[" + i + "]=" + number(has ? z_high * zs : 1.0) + "\n";
}

std::string AfmCurvePlots::render() {
  data_.flush();
  if (!data_) throw InputError("--curve-plots: cannot write the temporary file " + data_path_);
  if (pages_ == 0) throw InputError("--curve-plots: the run fitted no curve (nothing to draw)");
  const std::string n = std::to_string(pages_);
  std::string arrays = "N=" + n + "\n";
  for (const char* name : {"T", "K", "HAS", "RES", "RET", "ZS", "ZU", "FS", "FU", "ZC", "XLO", "XHI"}) arrays += std::string("array ") + name + "[" + n + "]\n";
  return run_gnuplot({}, "afm_curve_plots.gp", kAfmCurvePlotsScript,
                     [&](const std::string&) { return "datafile=" + quoted_path(data_path_) + "\n" + arrays + settings_; },
                     "--curve-plots", true);
}

}  // namespace coatcontact::cli
