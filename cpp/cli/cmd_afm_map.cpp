// `coatcontact afm fit` over a map, several files or a folder (THEORY.md section 15, "Many curves"): one row
// per curve from the library's batch (coatcontact/afm_batch.hpp), flagged curves included.
// Output: with --output FILE the rows go, chunk by chunk, to FILE.partial (each chunk one
// write(2) of whole lines, so an interrupted or crashed run leaves a valid table there); at the
// end the header with the number of flagged curves and the rows are written to FILE atomically
// (temporary file renamed) and FILE.partial is removed. --resume reads FILE.partial, checks that
// its header is this run's, drops a cut last line and fits only the curves after its rows.
// Without --output the rows stream to stdout and the count closes the table as a # line.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "afm_curve_plots.hpp"
#include "afm_fit_map.hpp"
#include "afm_partial.hpp"
#include "afm_map_plot_script.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_batch_table.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/gnuplot_run.hpp"

namespace coatcontact::cli {

namespace {

bool is_folder(const std::string& path) {
  struct stat info {};
  return ::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode);
}

// The files of the run: each FILE, the AFM files of each FOLDER (sorted), in the order given.
std::vector<std::string> input_files(const std::vector<std::string>& positionals) {
  std::vector<std::string> files;
  for (const std::string& p : positionals) {
    if (is_folder(p)) {
      for (std::string& f : afm::afm_files_in_folder(p)) files.push_back(std::move(f));
    } else {
      files.push_back(p);
    }
  }
  std::set<std::string> seen;
  for (const std::string& f : files) {
    if (f.find_first_of("\t\n\r") != std::string::npos) {
      throw InputError("FILE: " + cli::quoted(f) + " is not allowed; a file name with a tab or a line break cannot be a table cell");
    }
    if (!seen.insert(f).second) throw InputError("FILE: " + cli::quoted(f) + " is given twice");
  }
  return files;
}

unsigned parse_jobs(const Arguments& arguments) {
  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const auto text = arguments.get("--jobs");
  if (!text) return cores;
  const double value = parse_number(*text, "--jobs");
  if (!(value >= 1.0 && value <= 1024.0) || value != std::floor(value)) {
    throw InputError("--jobs: " + cli::quoted(*text) + " is not allowed; expected a whole number of threads from 1 to 1024");
  }
  return static_cast<unsigned>(value);
}

// --sort-by rating: the rows (each ending in a line end) by their rating cell, highest first;
// equal ratings keep their order (stable).
void sort_rows_by_rating(std::vector<std::string>& rows, std::size_t rating_column) {
  std::vector<std::pair<double, std::string>> keyed;
  keyed.reserve(rows.size());
  for (std::string& row : rows) {
    std::size_t start = 0;
    for (std::size_t k = 0; k < rating_column && start != std::string::npos; ++k) {
      start = row.find('\t', start);
      if (start != std::string::npos) ++start;
    }
    const double rating = start == std::string::npos ? 0.0 : std::strtod(row.c_str() + start, nullptr);
    keyed.emplace_back(rating, std::move(row));
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first > b.first; });
  for (std::size_t i = 0; i < rows.size(); ++i) rows[i] = std::move(keyed[i].second);
}

// Appends whole chunks to FILE.partial with one write(2) each, so that the file ends on a line
// boundary unless the process dies inside that call. (Not synced: what a killed or crashed
// process wrote is in the page cache; a sync per chunk cost more than the fits.)
class PartialFile {
 public:
  PartialFile(const std::string& path, bool append) : path_(path) {
    fd_ = ::open(path.c_str(), O_WRONLY | O_CREAT | O_CLOEXEC | (append ? O_APPEND : O_TRUNC), 0666);
    if (fd_ < 0) throw InputError("--output: cannot write " + cli::quoted(path) + " (" + std::strerror(errno) + ")");
  }
  ~PartialFile() {
    if (fd_ >= 0) ::close(fd_);
  }
  PartialFile(const PartialFile&) = delete;
  PartialFile& operator=(const PartialFile&) = delete;
  void append(const std::string& text) {
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t n = ::write(fd_, text.data() + done, text.size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) throw InputError("--output: write to " + cli::quoted(path_) + " failed (" + std::strerror(errno) + ")");
      done += static_cast<std::size_t>(n);
    }
  }

 private:
  std::string path_;
  int fd_ = -1;
};

std::vector<std::string> lines_of(const std::string& text) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  while (start < text.size()) {
    const std::size_t end = text.find('\n', start);
    if (end == std::string::npos) break;  // a cut last line is not a line
    lines.push_back(text.substr(start, end - start));
    start = end + 1;
  }
  return lines;
}

std::string read_whole(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("--resume: cannot read " + cli::quoted(path));
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

bool starts_with(const std::string& text, const std::string& head) { return text.compare(0, head.size(), head) == 0; }

std::vector<std::string> cells_of(const std::string& line) {
  std::vector<std::string> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t tab = line.find('\t', start);
    cells.push_back(line.substr(start, tab == std::string::npos ? std::string::npos : tab - start));
    if (tab == std::string::npos) return cells;
    start = tab + 1;
  }
}

// A file name as a gnuplot single-quoted string (gnuplot_string's escapes are for shown text).
std::string gp_path(const std::string& path) {
  std::string out = "'";
  for (char c : path) out += c == '\'' ? std::string("''") : std::string(1, c);
  return out + "'";
}

std::string gp_number(double v) {
  char text[40];
  std::snprintf(text, sizeof text, "%.17g", v);
  return text;
}

// The colour scale of the moduli panels: --color-range MIN,MAX (pressures) and --color-log.
struct MapColor {
  bool fixed = false, log = false;
  double low = 0.0, high = 0.0;
};

MapColor parse_map_color(const Arguments& arguments, bool plot) {
  MapColor color;
  color.log = arguments.has("--color-log");
  const auto range = arguments.get("--color-range");
  for (const char* option : {"--color-range", "--color-log"}) {
    if (arguments.has(option) && !plot) throw InputError(std::string(option) + ": sets the colours of --map-plot; add --map-plot FILE.png|pdf");
  }
  if (!range) return color;
  const std::size_t comma = range->find(',');
  if (comma == std::string::npos) throw InputError("--color-range: " + cli::quoted(*range) + " is not allowed; expected MIN,MAX (moduli, units as 1kPa,10kPa)");
  color.low = parse_quantity(range->substr(0, comma), Quantity::kPressure, "--color-range");
  color.high = parse_quantity(range->substr(comma + 1), Quantity::kPressure, "--color-range");
  if (!(color.low < color.high)) throw InputError("--color-range: " + cli::quoted(*range) + " is not allowed; MIN must be below MAX");
  color.fixed = true;
  return color;
}

// The picture of --map-plot: one heat map per free estimate, chi2/dof, the pull-off and the
// flags, on the grid's positions (or grid indices when the files give no positions); the
// colour range of each panel spans all its values (every cell counted) unless --color-range.
std::string render_map_plot(const std::vector<std::string>& rows, const std::vector<fit::AfmBatchParameter>& parameters,
                            bool contact_point_column, const std::string& term, const std::string& title,
                            const MapColor& color) {
  // Columns of the table (0-based): 4, 5 positions; 2, 3 grid indices; 6 flag; estimates from 8.
  const std::size_t first_estimate = 8;
  const std::size_t after = first_estimate + 2 * parameters.size() + (contact_point_column ? 1 : 0);
  std::ostringstream data;
  double x_min = INFINITY, x_max = -INFINITY, y_min = INFINITY, y_max = -INFINITY;
  long nx = 1, ny = 1;
  bool positions = true, any_position = false;
  for (const std::string& line : rows) {
    const std::vector<std::string> cells = cells_of(line);
    if (cells[4] != "-" && cells[5] != "-") any_position = true;
    else if (cells[2] != "-") positions = false;  // on the grid without a position
    if (cells[2] != "-") nx = std::max(nx, std::stol(cells[2]) + 1);
    if (cells[3] != "-") ny = std::max(ny, std::stol(cells[3]) + 1);
  }
  positions = positions && any_position;
  std::vector<double> largest(parameters.size() + 2, 0.0);
  std::vector<double> smallest_value(parameters.size() + 2, INFINITY), largest_value(parameters.size() + 2, -INFINITY);
  std::vector<bool> present(parameters.size() + 2, false);
  std::set<int> flags;
  for (const std::string& line : rows) {
    const std::vector<std::string> cells = cells_of(line);
    const std::string& xs = positions ? cells[4] : cells[2];
    const std::string& ys = positions ? cells[5] : cells[3];
    if (xs == "-" || ys == "-") continue;  // a curve without a place on the grid
    const double x = std::stod(xs), y = std::stod(ys);
    x_min = std::min(x_min, x);
    x_max = std::max(x_max, x);
    y_min = std::min(y_min, y);
    y_max = std::max(y_max, y);
    data << xs << '\t' << ys << '\t' << cells[6];
    flags.insert(std::stoi(cells[6]));
    std::vector<std::string> values;
    for (std::size_t p = 0; p < parameters.size(); ++p) values.push_back(cells[first_estimate + 2 * p]);
    values.push_back(cells[after + 1]);  // chi2/dof
    values.push_back(cells[after + 3]);  // pull-off
    for (std::size_t v = 0; v < values.size(); ++v) {
      data << '\t' << values[v];
      if (values[v] != "-") {
        present[v] = true;
        const double value = std::stod(values[v]);
        largest[v] = std::max(largest[v], std::abs(value));
        smallest_value[v] = std::min(smallest_value[v], value);
        largest_value[v] = std::max(largest_value[v], value);
      }
    }
    data << '\n';
  }
  // The unit prefix of each column (none for chi2/dof).
  std::string expos, present_text, vmin, vmax;
  for (std::size_t v = 0; v < largest.size(); ++v) {
    int e = 0;
    if (largest[v] > 0.0 && v != parameters.size()) {
      e = std::clamp(3 * static_cast<int>(std::floor(std::log10(largest[v]) / 3.0 + 1e-9)), -15, 9);
    }
    expos += (v ? " " : "") + std::to_string(e);
    present_text += (v ? " " : "") + std::string(present[v] ? "1" : "0");
    vmin += (v ? " " : "") + (present[v] ? gp_number(smallest_value[v]) : std::string("0"));
    vmax += (v ? " " : "") + (present[v] ? gp_number(largest_value[v]) : std::string("1"));
    if (color.log && v < parameters.size() && parameters[v].unit == "Pa" && present[v] && !(smallest_value[v] > 0.0)) {
      throw InputError("--color-log: " + parameters[v].name + " has the value " + gp_number(smallest_value[v]) +
                       " Pa; a log colour scale needs moduli > 0 (drop --color-log)");
    }
  }
  std::string flags_in, flag_names;
  for (int f : flags) flags_in += (flags_in.empty() ? "" : " ") + std::to_string(f);
  for (int f = 0; f < fit::kAfmFlagCount; ++f) flag_names += (f ? " " : "") + std::string(fit::afm_flag_name(static_cast<fit::AfmFlag>(f)));
  // One row (or one column) of cells is drawn as profiles against the position.
  const int profile = (ny == 1 && nx > 1) ? 1 : (nx == 1 && ny > 1) ? 2 : 0;
  // Tests read back each panel's range (the script appends it to this file).
  const char* range_file = std::getenv("COATCONTACT_MAP_PLOT_RANGES");
  if (!(x_min <= x_max)) throw InputError("--map-plot: no curve of the file has a grid position (is it a map?)");
  const double dx = nx > 1 ? (x_max - x_min) / static_cast<double>(nx - 1) : (positions ? 1e-6 : 1.0);
  const double dy = ny > 1 ? (y_max - y_min) / static_cast<double>(ny - 1) : dx;
  std::string names, units;
  for (const auto& p : parameters) {
    names += (names.empty() ? "" : " ") + p.name;
    units += (units.empty() ? "" : " ") + p.unit;
  }
  const std::string settings = "; term='" + term + "'; plottitle=" + gnuplot_string(title) + "; names='" + names +
                               "'; units='" + units + "'; expos='" + expos + "'; present='" + present_text +
                               "'; positions=" + (positions ? "1" : "0") + "; dx=" + gp_number(dx) + "; dy=" + gp_number(dy) +
                               "; xlo=" + gp_number(x_min - dx / 2) + "; xhi=" + gp_number(x_max + dx / 2) +
                               "; ylo=" + gp_number(y_min - dy / 2) + "; yhi=" + gp_number(y_max + dy / 2) +
                               "; vmin='" + vmin + "'; vmax='" + vmax + "'; cbfix=" + (color.fixed ? "1" : "0") +
                               "; cblo=" + gp_number(color.low) + "; cbhi=" + gp_number(color.high) +
                               "; cblog=" + (color.log ? "1" : "0") + "; flagsin='" + flags_in + "'; flagnames='" + flag_names +
                               "'; profile=" + std::to_string(profile) +
                               "; rangefile=" + gp_path(range_file != nullptr ? range_file : "");
  return run_gnuplot({{"map.tsv", data.str()}}, "afm_map_plot.gp", kAfmMapPlotScript,
                     [&](const std::string& dir) { return "mapfile=" + gp_path(dir + "/map.tsv") + settings; },
                     "--map-plot", true);
}

// --map-plot over the run: one image per file with grid positions (several images would draw
// over each other on one grid). One such file: FILE as given; several: NAME-K.EXT, K the file's
// place among the run's files (1-based). Returns (path, picture) pairs.
std::vector<std::pair<std::string, std::string>> render_map_plots(const std::vector<std::string>& rows,
                                                                  const std::vector<fit::AfmBatchParameter>& parameters,
                                                                  bool contact_point_column, const std::string& term,
                                                                  const std::string& plot_path, const std::vector<std::string>& files,
                                                                  const std::string& tip, const MapColor& color) {
  std::vector<std::vector<std::string>> groups(files.size());
  std::vector<bool> on_grid(files.size(), false);
  std::size_t next = 0;  // rows come file by file, in the order of `files`
  for (const std::string& line : rows) {
    const std::vector<std::string> cells = cells_of(line);
    while (next < files.size() && files[next] != cells[0]) ++next;
    if (next == files.size()) throw NumericalError("--map-plot: a row of the table names a file outside the run: " + cells[0]);
    groups[next].push_back(line);
    if (cells[2] != "-" && cells[3] != "-") on_grid[next] = true;
  }
  const auto maps = static_cast<std::size_t>(std::count(on_grid.begin(), on_grid.end(), true));
  if (maps == 0) throw InputError("--map-plot (--plot of a batch): no curve of the run has a grid position (is it a map?); "
                                  "each curve's own picture: --curve-plots FILE.pdf");
  const std::size_t dot = plot_path.rfind('.');
  std::vector<std::pair<std::string, std::string>> pictures;
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (!on_grid[f]) continue;
    const std::string path = maps == 1 ? plot_path : plot_path.substr(0, dot) + "-" + std::to_string(f + 1) + plot_path.substr(dot);
    const std::string title = std::filesystem::path(files[f]).filename().string() + ": " + tip;
    pictures.emplace_back(path, render_map_plot(groups[f], parameters, contact_point_column, term, title, color));
  }
  return pictures;
}

}  // namespace

std::string fit_range_text(const fit::AfmRange& range) { return fit::afm_fit_range_text(range); }

bool batch_mode(const Arguments& arguments, const afm::Calibration& calibration) {
  const auto& positionals = arguments.positionals();
  const bool batch_option = arguments.has("--jobs") || arguments.has("--resume") || arguments.has("--map-plot") ||
                            arguments.has("--sort-by") || arguments.has("--curve-plots");
  if (arguments.has("--index")) {
    if (positionals.size() > 1 || is_folder(positionals.front()) || batch_option) {
      throw InputError("--index: selects one curve of one FILE; without it every curve of the FILEs and FOLDERs is fitted "
                       "(--jobs, --resume and --map-plot are for that batch)");
    }
    return false;
  }
  if (positionals.size() > 1 || is_folder(positionals.front()) || batch_option) return true;
  return afm::CurveSource(positionals.front(), calibration).size() > 1;
}

// The rows an interrupted run left in FILE.partial: checks that its header is this run's (the
// command line aside), counts its rows by flag (and keeps them for the map plot), and cuts a
// last line the process died inside. InputError when the file is not this run's.
struct ResumedRows {
  std::size_t skip = 0;
  fit::AfmBatchSummary before;  // the flags of the rows kept
  std::vector<std::string> kept_rows;
};

ResumedRows resume_partial(const std::string& partial_path, const std::string& header, const std::vector<std::string>& columns,
                           std::size_t total, bool keep_rows) {
  ResumedRows resumed;
  std::size_t& skip = resumed.skip;
  fit::AfmBatchSummary& before = resumed.before;
  std::vector<std::string>& kept_rows = resumed.kept_rows;
  const std::string text = read_whole(partial_path);
  const std::vector<std::string> lines = lines_of(text);
  const std::vector<std::string> expected = lines_of(header);
  std::size_t h = 0;
  std::size_t e = 0;
  while (h < lines.size() && starts_with(lines[h], "#")) {
    if (starts_with(lines[h], "# command:")) {
      ++h;
      continue;
    }
    while (e < expected.size() && starts_with(expected[e], "# command:")) ++e;
    if (e >= expected.size() || lines[h] != expected[e]) {
      throw InputError("--resume: " + cli::quoted(partial_path) + " was written by another run (header line " + cli::quoted(lines[h]) +
                       " differs); remove it or give the same FILEs and options");
    }
    ++h;
    ++e;
  }
  while (e < expected.size() && starts_with(expected[e], "# command:")) ++e;
  if (e != expected.size()) throw InputError("--resume: " + cli::quoted(partial_path) + " has no complete header; remove it");
  for (std::size_t i = h; i < lines.size(); ++i) {
    const std::size_t tab1 = lines[i].find('\t');
    std::size_t field = 0, start = 0;
    int flag = -1;
    for (std::size_t pos = 0; pos <= lines[i].size(); ++pos) {
      if (pos == lines[i].size() || lines[i][pos] == '\t') {
        if (field == 6) flag = std::atoi(lines[i].substr(start, pos - start).c_str());
        ++field;
        start = pos + 1;
      }
    }
    if (tab1 == std::string::npos || field != columns.size() || flag < 0 || flag >= fit::kAfmFlagCount) {
      throw InputError("--resume: row " + std::to_string(i - h + 1) + " of " + cli::quoted(partial_path) + " is not a row of this table; remove the file");
    }
    ++before.by_flag[flag];
    ++skip;
    if (keep_rows) kept_rows.push_back(lines[i]);
  }
  if (skip > total) throw InputError("--resume: " + cli::quoted(partial_path) + " holds more rows than the run has curves");
  // Drop a cut last line (the process died inside a write).
  std::size_t keep_bytes = 0;
  for (std::size_t i = 0; i < lines.size(); ++i) keep_bytes += lines[i].size() + 1;
  if (keep_bytes != text.size() && ::truncate(partial_path.c_str(), static_cast<off_t>(keep_bytes)) != 0) {
    throw InputError("--resume: cannot cut the last partial line of " + cli::quoted(partial_path));
  }
  std::cerr << "coatcontact afm fit: resuming after " << skip << " of " << total << " curves in " << partial_path << "\n";

  return resumed;
}




// The run's table (header, columns, row lines: the fit floor's afm_batch_table, the C API's too).
fit::AfmBatchTable batch_table(const std::vector<std::string>& files, const std::vector<fit::AfmFileSurvey>& survey,
                               std::size_t total, const afm::Calibration& calibration, const AfmFitSetup& setup,
                               const fit::AfmBatchSettings& settings) {
  fit::AfmBatchTableRun run;
  run.files = files;
  run.survey = survey;
  run.total = total;
  run.calibration = calibration;
  run.free_text = setup.free_text;
  run.command_line = command_line();
  return fit::afm_batch_table(settings, run);
}

// "N of M (no_contact 2, ...)": the flagged curves of the run, those of a resumed part included.
std::string flagged_text(const fit::AfmBatchSummary& summary, const fit::AfmBatchSummary& before, std::size_t total) {
  std::size_t by_flag[fit::kAfmFlagCount];
  for (int f = 0; f < fit::kAfmFlagCount; ++f) by_flag[f] = summary.by_flag[f] + before.by_flag[f];
  return fit::afm_batch_flagged_text(by_flag, total);
}

// --sort-by: "rating" or none (InputError for another key).
bool sort_by_rating(const Arguments& arguments) {
  const std::optional<std::string> sort_by = arguments.get("--sort-by");
  if (sort_by && *sort_by != "rating") {
    throw InputError("--sort-by: " + cli::quoted(*sort_by) + " is not allowed; expected rating (rows by their rating, highest first)");
  }
  return sort_by.has_value();
}

// The rows of `text` (whole lines) sorted by rating to `out`.
void write_sorted(const std::string& text, std::ostream& out, std::size_t rating_column) {
  std::vector<std::string> rows;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);) rows.push_back(line + '\n');
  sort_rows_by_rating(rows, rating_column);
  for (const std::string& row : rows) out << row;
}

// The run's summary on stderr: curves, flagged count, each unreadable file and why, the first
// reason of each other flag.
void report_run(const std::vector<std::string>& files, const std::vector<fit::AfmFileSurvey>& survey, std::size_t total,
                const std::string& flag_text, const fit::AfmBatchSummary& summary) {
  std::string first_unreadable_file;
  for (const fit::AfmFileSurvey& s : survey) {
    if (!s.unreadable.empty()) {
      first_unreadable_file = s.unreadable;
      break;
    }
  }
  std::cerr << "coatcontact afm fit: " << total << " curves in " << files.size() << (files.size() == 1 ? " file" : " files")
            << "; flagged: " << flag_text << "\n";
  for (std::size_t f = 0; f < files.size(); ++f) {
    if (!survey[f].unreadable.empty()) {
      std::cerr << "  " << (survey[f].flag == fit::AfmFlag::kCalibration ? "file without calibration: " : "unreadable file: ")
                << survey[f].unreadable << "\n";
    }
  }
  for (int f = 1; f < fit::kAfmFlagCount; ++f) {
    if (f == static_cast<int>(fit::AfmFlag::kUnreadable) && summary.first_message[f] == first_unreadable_file) continue;
    if (!summary.first_message[f].empty()) {
      std::cerr << "  first " << fit::afm_flag_name(static_cast<fit::AfmFlag>(f)) << ": " << summary.first_message[f] << "\n";
    }
  }
}

namespace {

// The pictures of a batch: --map-plot (or --plot, the same option for a batch) and --curve-plots.
struct BatchPictures {
  std::string map_plot_option;       // "--map-plot" or "--plot", as given
  std::optional<std::string> map_plot, curve_plots;
  std::string term;                  // of the map images: "png" or "pdf"
};

BatchPictures parse_batch_pictures(const Arguments& arguments, bool resume) {
  if (arguments.has("--depth-profile")) {
    throw InputError("--depth-profile: profiles one curve (FILE --index N of a map); per-curve pictures of a batch: --curve-plots FILE.pdf");
  }
  // --plot of a batch is --map-plot (the map images; docs/afm.md), so one option draws what a run fits.
  if (arguments.has("--plot") && arguments.has("--map-plot")) {
    throw InputError("--plot: of a batch it is --map-plot (the map images); give one of them");
  }
  BatchPictures p;
  p.map_plot_option = arguments.has("--plot") ? "--plot" : "--map-plot";
  p.map_plot = arguments.get(p.map_plot_option);
  if (p.map_plot) {
    const std::size_t dot = p.map_plot->rfind('.');
    p.term = dot == std::string::npos ? "" : p.map_plot->substr(dot + 1);
    if (p.term != "png" && p.term != "pdf") {
      throw InputError(p.map_plot_option + ": " + cli::quoted(*p.map_plot) + " is not allowed; it must end in .png or .pdf (the format follows the extension)");
    }
  }
  p.curve_plots = arguments.get("--curve-plots");
  if (p.curve_plots) {
    const std::string& c = *p.curve_plots;
    if (c.size() < 5 || c.compare(c.size() - 4, 4, ".pdf") != 0) {
      throw InputError("--curve-plots: " + cli::quoted(c) + " is not allowed; it must end in .pdf (one page per curve)");
    }
    if (resume) throw InputError("--curve-plots: draws every curve of a run; a --resume does not fit the curves of FILE.partial again");
  }
  return p;
}

}  // namespace

int run_fit_map(const Arguments& arguments, const AfmFitSetup& setup, const afm::Calibration& calibration) {
  const std::vector<std::string> files = input_files(arguments.positionals());
  for (const std::string& f : files) register_input(f, "AFM file");
  const unsigned jobs = parse_jobs(arguments);
  const std::string output_path = arguments.get("--output").value_or("");
  // Rows streamed as they come (no FILE.partial) unless the output is a regular file.
  const bool to_stdout = !cli::output_is_regular_file(output_path);
  const bool resume = arguments.has("--resume");
  if (resume && to_stdout) throw InputError("--resume: needs --output FILE, a regular file (the rows of the interrupted run are in FILE.partial)");
  const BatchPictures batch_pictures = parse_batch_pictures(arguments, resume);
  const std::string& map_plot_option = batch_pictures.map_plot_option;
  const std::optional<std::string>& plot_path = batch_pictures.map_plot;
  const std::string& term = batch_pictures.term;
  const std::optional<std::string>& curve_plots_path = batch_pictures.curve_plots;
  const MapColor color = parse_map_color(arguments, plot_path.has_value());
  const bool sort_by = sort_by_rating(arguments);
  const std::string partial_path = to_stdout ? std::string() : output_path + ".partial";
  check_output_paths({{"--output", output_path}, {map_plot_option, plot_path.value_or("")}, {"--curve-plots", curve_plots_path.value_or("")}});
  if (!to_stdout) check_output_path(partial_path, "--output");
  if (!to_stdout && !resume && std::filesystem::exists(partial_path)) {
    throw InputError("--output: " + cli::quoted(partial_path) + " exists (the rows of an interrupted run); continue it with --resume or remove it");
  }

  fit::AfmBatchSettings settings;
  settings.problem = setup.problem;
  settings.segment = setup.kind;
  settings.range = setup.range;
  settings.baseline = setup.baseline;
  settings.keep_traces = curve_plots_path.has_value();
  const std::vector<fit::AfmBatchParameter> parameters = fit::afm_batch_parameters(settings.problem);
  std::unique_ptr<AfmCurvePlots> curve_plots;
  if (curve_plots_path) curve_plots = std::make_unique<AfmCurvePlots>(parameters, settings.segment == afm::SegmentKind::kRetract);
  const bool contact_point_column = !settings.problem.free.contact_point;
  // A file that cannot be read is a flagged row when the run has several files or a folder; a
  // single FILE named is the run's input (exit 2).
  const auto& positionals = arguments.positionals();
  const bool tolerate = positionals.size() > 1 || is_folder(positionals.front());
  const std::vector<fit::AfmFileSurvey> survey = fit::afm_survey_files(files, calibration, tolerate);
  std::size_t total = 0;
  for (const fit::AfmFileSurvey& s : survey) total += s.curves;

  const fit::AfmBatchTable table = batch_table(files, survey, total, calibration, setup, settings);
  const std::vector<std::string>& columns = table.columns;
  const std::string& header = table.header;

  // One run at a time on FILE.partial; a resume checks its rows against the run's curves.
  const bool partial_existed = !to_stdout && std::filesystem::exists(partial_path);
  std::optional<PartialLock> lock;
  if (!to_stdout) lock.emplace(partial_path, partial_existed);
  // Resume: the rows already in FILE.partial.
  ResumedRows resumed;
  if (resume && partial_existed) {
    resumed = resume_partial(partial_path, header, columns, total, plot_path.has_value());
    check_partial_rows(partial_path, files, survey);
  }
  const std::size_t skip = resumed.skip;
  const fit::AfmBatchSummary before = resumed.before;
  std::vector<std::string> kept_rows = std::move(resumed.kept_rows);

  std::unique_ptr<PartialFile> partial;
  // A device or descriptor named by --output (/dev/null, /dev/stderr) gets the streamed rows.
  const bool device = to_stdout && !output_path.empty() && output_path != "-" && output_path != "/dev/stdout";
  const std::unique_ptr<Output> stream_output = device ? std::make_unique<Output>(output_path) : nullptr;
  std::ostream& rows_out = stream_output ? stream_output->stream() : std::cout;
  if (!to_stdout) {
    const bool append = resume && partial_existed;
    partial = std::make_unique<PartialFile>(partial_path, append);
    if (!append) partial->append(header);
  } else {
    rows_out << header << std::flush;
  }
  std::vector<std::string> plot_rows;
  if (plot_path) plot_rows = kept_rows;
  std::string sorted_rows;  // --sort-by on stdout: the rows until the end
  fit::AfmBatchOptions options;
  options.jobs = jobs;
  options.skip = skip;
  options.survey = survey;
  options.unreadable_file_rows = tolerate;
  options.sink = [&](const std::vector<fit::AfmCurveRow>& rows) {
    std::string text;
    for (const auto& row : rows) {
      std::string line = fit::afm_batch_row_line(row, table);
      if (plot_path) plot_rows.push_back(line.substr(0, line.size() - 1));
      if (curve_plots) curve_plots->add(row);
      text += line;
    }
    if (partial) partial->append(text);
    else if (sort_by) sorted_rows += text;  // printed sorted at the end
    else rows_out << text << std::flush;
  };
  options.progress = [&](std::size_t done, std::size_t all) {
    progress_step(done, all);
    return true;
  };
  const fit::AfmBatchSummary summary = fit::afm_fit_batch(files, calibration, settings, options);
  const std::string flag_text = flagged_text(summary, before, total);
  progress_pause();

  std::vector<std::pair<std::string, std::string>> pictures;
  if (plot_path) {
    pictures = render_map_plots(plot_rows, parameters, contact_point_column, term, *plot_path, files,
                                settings.problem.tip.description, color);
  }
  const std::size_t map_images = pictures.size();
  if (curve_plots) pictures.emplace_back(*curve_plots_path, curve_plots->render());  // the last picture
  const auto option_of = [&](std::size_t k) { return k < map_images ? map_plot_option : std::string("--curve-plots"); };
  const std::size_t rating_column = table.rating_column();
  if (to_stdout) {
    if (sort_by) write_sorted(sorted_rows, rows_out, rating_column);
    rows_out << "# flagged curves: " << flag_text << "\n" << std::flush;
    if (stream_output) stream_output->commit();
  } else {
    // The final table: the header with the count, then the rows of FILE.partial.
    // (Copied as a stream: the table is never held in memory.)
    partial.reset();
    std::ifstream rows_in(partial_path, std::ios::binary);
    std::string line;
    while (std::getline(rows_in, line) && !starts_with(line, "# columns:")) {
    }
    if (!rows_in) throw InputError("--output: " + cli::quoted(partial_path) + " lost its header while the run went on");
    const std::string final_header = fit::afm_batch_final_header(header, flag_text);
    Output output(output_path);
    output.stream() << final_header;
    if (sort_by) write_sorted(std::string(std::istreambuf_iterator<char>(rows_in), {}), output.stream(), rating_column);
    else if (rows_in.peek() != std::char_traits<char>::eof()) output.stream() << rows_in.rdbuf();
    std::vector<std::unique_ptr<Output>> plot_outputs;  // alive until the table's commit: all or none
    for (std::size_t k = 0; k < pictures.size(); ++k) {
      plot_outputs.push_back(std::make_unique<Output>(pictures[k].first, option_of(k)));
      plot_outputs.back()->stream().write(pictures[k].second.data(), static_cast<std::streamsize>(pictures[k].second.size()));
      plot_outputs.back()->commit();
    }
    output.commit();
    std::remove(partial_path.c_str());
  }
  // All made before any commit, so that they are published together (all or none).
  std::vector<std::unique_ptr<Output>> plot_outputs;
  for (std::size_t k = 0; k < pictures.size() && to_stdout; ++k) {  // (else written with the table above)
    plot_outputs.push_back(std::make_unique<Output>(pictures[k].first, option_of(k)));
    plot_outputs.back()->stream().write(pictures[k].second.data(), static_cast<std::streamsize>(pictures[k].second.size()));
  }
  for (const auto& plot_output : plot_outputs) plot_output->commit();
  if (map_images > 1) std::cerr << "coatcontact afm fit: " << map_images << " map images, " << pictures.front().first << " ...\n";
  if (curve_plots) std::cerr << "coatcontact afm fit: " << curve_plots->pages() << " control-plot pages in " << *curve_plots_path << "\n";
  report_run(files, survey, total, flag_text, summary);
  return kExitSuccess;
}

}  // namespace coatcontact::cli
