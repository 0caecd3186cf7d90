// The curve plots of the CLI (coatcontact/curve_plot.hpp).
#include "coatcontact/curve_plot.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <ostream>
#include <sstream>
#include <utility>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/gnuplot_run.hpp"

namespace coatcontact::cli {
namespace {

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

// The power of 1000 that puts `largest` in [1, 1000), within f .. T.
int prefix_exponent(double largest) {
  if (!(largest > 0.0) || !std::isfinite(largest)) return 0;
  const int e = 3 * static_cast<int>(std::floor(std::log10(largest) / 3.0 + 1e-9));
  return std::clamp(e, -15, 12);
}

std::string prefix_name(int e) {
  switch (e) {
    case -15: return "f";
    case -12: return "p";
    case -9: return "n";
    case -6: return "µ";
    case -3: return "m";
    case 3: return "k";
    case 6: return "M";
    case 9: return "G";
    case 12: return "T";
    default: return "";
  }
}

std::string text_of(double v) {
  char buffer[64];
  const auto r = std::to_chars(buffer, buffer + sizeof buffer, v);
  return std::string(buffer, r.ptr);
}

// The axis label "name (prefix unit)" and the factor that scales SI values to it.
std::pair<std::string, double> axis(const std::string& name, const std::string& unit, double largest) {
  if (unit.empty()) return {name, 1.0};
  const int e = prefix_exponent(largest);
  return {name + " (" + prefix_name(e) + unit + ")", std::pow(10.0, -e)};
}

double largest_abs(const PlotPanel& panel, bool x) {
  double m = 0.0;
  for (const auto& s : panel.series) {
    for (double v : x ? s.x : s.y) {
      if (std::isfinite(v)) m = std::max(m, std::fabs(v));
    }
  }
  return m;
}

}  // namespace

OptionSpec plot_option(const std::string& what) {
  return {"--plot", "FILE", "draw " + what + " to FILE.png or FILE.pdf (gnuplot), beside the homogeneous JKR reference",
          false};
}

void check_plot_path(const std::string& path) {
  if (!ends_with(path, ".png") && !ends_with(path, ".pdf")) {
    throw InputError("--plot: " + quoted(path) + " is neither a .png nor a .pdf file name");
  }
  check_output_path(path, "--plot");
}

std::string render_curve_plot(const std::vector<PlotPanel>& panels, const std::string& title,
                              const std::string& path) {
  const bool pdf = ends_with(path, ".pdf");
  std::vector<std::pair<std::string, std::string>> files;
  std::ostringstream script;
  const std::size_t n = panels.size();
  if (pdf) {
    script << "set terminal pdfcairo size " << (n > 1 ? "7in" : "3.6in") << ",2.9in enhanced font 'Sans,8'\n";
  } else {
    script << "set terminal pngcairo size " << (n > 1 ? 1400 : 760) << ",620 enhanced font 'Sans,11'\n";
  }
  script << "set encoding utf8\nset grid lc rgb '#dddddd'\nset key below vertical maxcols 1 samplen 2\n"
            "set datafile separator '\\t'\n";
  script << "set multiplot layout 1," << n << " title " << gnuplot_string(title) << "\n";
  for (std::size_t p = 0; p < n; ++p) {
    const PlotPanel& panel = panels[p];
    const auto [x_label, x_scale] = axis(panel.x_name, panel.x_unit, largest_abs(panel, true));
    const auto [y_label, y_scale] = axis(panel.y_name, panel.y_unit, largest_abs(panel, false));
    script << "unset logscale x\nunset label\nset autoscale\n";
    if (panel.log_x) script << "set logscale x\n";
    // The x range of the first series (the command's result); the others are drawn inside it.
    double lo = HUGE_VAL, hi = -HUGE_VAL;
    if (!panel.series.empty()) {
      for (double v : panel.series.front().x) {
        if (std::isfinite(v) && (!panel.log_x || v > 0.0)) {
          lo = std::min(lo, v * x_scale);
          hi = std::max(hi, v * x_scale);
        }
      }
    }
    if (lo < hi) {
      const double pad = panel.log_x ? 1.0 : 0.03 * (hi - lo);
      script << "set xrange [" << text_of(panel.log_x ? lo : lo - pad) << ":" << text_of(panel.log_x ? hi : hi + pad)
             << "]\n";
    }
    script << "set xlabel " << gnuplot_string(x_label) << "\nset ylabel " << gnuplot_string(y_label) << "\n";
    if (!panel.note.empty()) {
      script << "set label 1 " << gnuplot_string(panel.note) << " at graph 0.02, graph 0.04 left front\n";
    }
    std::string plot;
    for (std::size_t k = 0; k < panel.series.size(); ++k) {
      const PlotSeries& s = panel.series[k];
      std::string rows;
      for (std::size_t i = 0; i < std::min(s.x.size(), s.y.size()); ++i) {
        if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i]) || (panel.log_x && !(s.x[i] > 0.0))) continue;
        rows += text_of(s.x[i] * x_scale) + "\t" + text_of(s.y[i] * y_scale) + "\n";
      }
      if (rows.empty()) continue;
      const std::string name = "p" + std::to_string(p) + "s" + std::to_string(k) + ".tsv";
      files.emplace_back(name, rows);
      const std::string style =
          s.style == PlotSeries::Style::kPoints
              ? "with points pt 7 ps " + std::string(pdf ? "0.6" : "1.4")
              : "with lines lw " + std::string(pdf ? "1.5" : "2") + (s.style == PlotSeries::Style::kDashed ? " dt 2" : "");
      plot += std::string(plot.empty() ? "plot " : ", ") + "dir.'/" + name + "' using 1:2 " + style + " lc rgb '" +
              s.color + "' " + (s.label.empty() ? std::string("notitle") : "title " + gnuplot_string(s.label));
    }
    script << (plot.empty() ? "plot NaN notitle" : plot) << "\n";
  }
  script << "unset multiplot\n";
  return run_gnuplot(files, "plot.gp", script.str(), [](const std::string& dir) { return "dir=" + gnuplot_string(dir); });
}

std::optional<std::string> plot_path(const Arguments& args, const std::string& refusal) {
  const auto path = args.get("--plot");
  if (path && !refusal.empty()) throw InputError("--plot: " + refusal);
  if (path) check_plot_path(*path);
  return path;
}

void stage_plot(std::optional<Output>& slot, const std::string& path, const std::string& picture) {
  slot.emplace(path, "--plot");
  slot->stream().write(picture.data(), static_cast<std::streamsize>(picture.size()));
}

}  // namespace coatcontact::cli
