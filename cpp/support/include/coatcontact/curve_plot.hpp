// `--plot FILE.png|FILE.pdf` of the commands that compute curves (sphere, contact, pulloff,
// kinetics): one or two panels of lines and markers, drawn by gnuplot (gnuplot_run.hpp) from
// the values the command also writes. Axes in SI units with the prefix that suits their range.
// Private to the program, not installed.
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"

namespace coatcontact::cli {

// The colours of every --plot: the coated result, and the homogeneous JKR reference beside it.
inline constexpr const char* kPlotCoated = "#1f77b4";
inline constexpr const char* kPlotReference = "#555555";
inline constexpr const char* kPlotSecond = "#d62728";  // a second coated quantity (displacement control)

// The --plot FILE option line of a command that draws `what`.
OptionSpec plot_option(const std::string& what);

struct PlotSeries {
  enum class Style { kLine, kDashed, kPoints };
  std::string label;         // legend entry ("" for none)
  std::vector<double> x, y;  // SI (non-finite pairs are skipped)
  Style style = Style::kLine;
  std::string color = "#1f77b4";  // '#rrggbb'
};

struct PlotPanel {
  std::string x_name, x_unit;  // "contact radius a", "m" (SI unit, prefixed on the axis; "" none)
  std::string y_name, y_unit;
  bool log_x = false;
  std::vector<PlotSeries> series;
  std::string note;  // a line of text inside the panel, bottom left ("" none)
};

// InputError naming --plot unless `path` ends in .png or .pdf.
void check_plot_path(const std::string& path);
// The picture (PNG or PDF by the extension of `path`) of the panels side by side, under
// `title`; InputError naming --plot when gnuplot fails.
std::string render_curve_plot(const std::vector<PlotPanel>& panels, const std::string& title,
                              const std::string& path);
// --plot of `args`, checked (check_plot_path); `refusal` non-empty: --plot is refused with it
// (e.g. "not with --lambda (JKR pull-offs only)").
std::optional<std::string> plot_path(const Arguments& args, const std::string& refusal = "");
// The picture in a pending Output (option --plot) `slot`, published with the command's other
// outputs (all or none: cli_support.hpp, Output).
void stage_plot(std::optional<Output>& slot, const std::string& path, const std::string& picture);

}  // namespace coatcontact::cli
