// The TSV table of a batch of AFM fits (coatcontact/afm_batch_table.hpp): the header, the row
// lines and the flagged count, written the same by the CLI and the C API.
#include "coatcontact/afm_batch_table.hpp"

#include <algorithm>
#include <sstream>

#include "coatcontact/afm_models.hpp"

namespace coatcontact::fit {

namespace {

std::string text_of(const std::optional<long>& v) { return v ? std::to_string(*v) : "-"; }
std::string text_of(const std::optional<double>& v, const std::string& column) { return v ? detail::table_value(*v, column) : "-"; }

// A warning as one cell: tabs and line ends would split the row.
std::string cell_text(std::string text) {
  for (char& c : text) {
    if (c == '\t' || c == '\n' || c == '\r') c = ' ';
  }
  return text.empty() ? "-" : text;
}

bool starts_with(const std::string& text, const std::string& head) { return text.compare(0, head.size(), head) == 0; }

std::string why_unreadable(const std::string& file, const AfmFileSurvey& survey) {
  std::string why = survey.unreadable;
  if (starts_with(why, file + ": ")) why.erase(0, file.size() + 2);
  std::replace_if(why.begin(), why.end(), [](char c) { return c == '\t' || c == '\n' || c == '\r'; }, ' ');
  return why;
}

// The header items of the run and the fit (the CLI's header since issue 35).
detail::HeaderItems header_items(const AfmBatchSettings& settings, const AfmBatchTableRun& run) {
  const std::vector<std::string>& files = run.files;
  const std::vector<AfmFileSurvey>& survey = run.survey;
  const afm::Calibration& calibration = run.calibration;
  const AfmModelInfo& model = settings.problem.model.info();
  detail::HeaderItems items = {
      {"coatcontact afm fit", "one row per curve: " + model.summary + " of each curve of the files (THEORY.md section 15)"}};
  items.push_back({"files", std::to_string(files.size())});
  for (std::size_t f = 0; f < files.size(); ++f) {
    items.push_back({"file " + std::to_string(f), files[f] + (survey[f].unreadable.empty()
                                                                   ? " (" + std::to_string(survey[f].curves) + " curves)"
                                                                   : std::string(" (") + afm_flag_name(survey[f].flag) + ", one flagged row: " +
                                                                         why_unreadable(files[f], survey[f]) + ")")});
  }
  items.push_back({"curves", std::to_string(run.total)});
  if (calibration.spring_constant) items.push_back({"spring constant [N/m]", detail::table_parameter(*calibration.spring_constant, "k") + " (user, every curve)"});
  if (calibration.sensitivity) items.push_back({"sensitivity [m/V]", detail::table_parameter(*calibration.sensitivity, "sensitivity") + " (user, every curve)"});
  items.push_back({"model", model.formula(settings.problem, true)});
  items.push_back({"tip", settings.problem.tip.description});
  if (settings.problem.coating && !settings.problem.coating->layers.empty()) {
    add_afm_stack_items(items, *settings.problem.coating);
  } else if (settings.problem.coating) {
    const AfmCoating& c = *settings.problem.coating;
    items.push_back({"sample", "coating: film E1 = " + detail::table_parameter(c.film.youngs_modulus, "E1") + " Pa, nu1 = " +
                                   detail::table_parameter(c.film.poisson_ratio, "nu1") + ", t = " + detail::table_parameter(c.thickness, "t") +
                                   " m, substrate " +
                                   (c.substrate.rigid ? std::string("rigid")
                                                      : "E0 = " + detail::table_parameter(c.substrate.material.youngs_modulus, "E0") +
                                                            " Pa, nu0 = " + detail::table_parameter(c.substrate.material.poisson_ratio, "nu0"))});
  } else {
    items.push_back({"sample", "homogeneous half-space, E = " + detail::table_parameter(settings.problem.modulus, "E") +
                                   " Pa (start or fixed value), nu = " + detail::table_parameter(settings.problem.poisson, "nu")});
  }
  items.push_back({"free", run.free_text});
  if (!settings.problem.free.contact_point) items.push_back({"contact point [m]", detail::table_parameter(settings.problem.contact_point, "z_c") + " (fixed)"});
  if (!settings.problem.free.baseline) items.push_back({"baseline [N]", detail::table_parameter(settings.problem.baseline, "b") + " (fixed)"});
  items.push_back({"segment", std::string(afm::segment_kind_name(settings.segment))});
  items.push_back({"fit range", afm_fit_range_text(settings.range) + " (relative ranges from each curve's preprocessing contact point and baseline)"});
  const bool tilt_step = settings.baseline == AfmBaselineModel::kTilt && !settings.problem.free.tilt;
  items.push_back({"preprocessing", std::string("tip position = height + F/k; baseline offset and tilt on the first half of the approach; ") +
                                        (tilt_step ? "baseline model tilt: the tilt subtracted from the fitted forces (b: the baseline at the reference contact point); "
                                                   : "baseline model offset: the forces as measured; ") +
                                        "reference contact point by piecewise-fit; chi2 noise = the baseline's residual sigma"});
  items.push_back({"flags", "0 fitted, 1 no_contact, 2 jump_in (approach below its baseline by > " +
                                detail::table_parameter(kJumpInSigmas, "sigmas") + " sigma and > " +
                                detail::table_parameter(kJumpInFraction, "fraction") +
                                " of its largest force), 3 no_convergence, 4 empty_segment, 5 missing_segment, 6 calibration, 7 too_few_points, "
                                "8 unreadable, 9 bad_data, 10 undetermined (a free E, E1, t or w with a standard error above its value), "
                                "11 no_detachment (the retract ends off the free-cantilever level); 10 and 11 keep their "
                                "estimates; '-' where a flagged curve has no value"});
  items.push_back({"rating", "0..10 from the residuals against the baseline noise, the signal over the noise, the points in "
                             "contact and the flags (docs/afm.md, \"Curve rating\"); 0 without estimates"});
  items.push_back({"pull-off", "measured: the retract's most tensile force against its free-cantilever baseline (a line on its last half), and its tip position"});
  if (model.needs_spring) {
    items.push_back({"model jump-off", "the fitted model's own jump-off through the spring: its force above the baseline and its indentation"});
  }
  return items;
}

}  // namespace

AfmBatchTable afm_batch_table(const AfmBatchSettings& settings, const AfmBatchTableRun& run) {
  AfmBatchTable table;
  table.parameters = afm_batch_parameters(settings.problem);
  table.contact_point_column = !settings.problem.free.contact_point;
  detail::HeaderItems items = header_items(settings, run);
  std::vector<std::string>& columns = table.columns;
  columns = {"file", "curve", "grid_x", "grid_y", "x", "y", "flag", "reason"};
  std::string units = "-\t-\t-\t-\tm\tm\t-\t-";
  for (const auto& p : table.parameters) {
    columns.push_back(p.name);
    columns.push_back(p.name + "_error");
    units += "\t" + p.unit + "\t" + p.unit;
  }
  if (table.contact_point_column) {
    columns.push_back("contact_point");
    units += "\tm";
  }
  for (const char* c : {"chi2", "chi2_per_dof", "residual_sigma", "pulloff", "pulloff_position", "model_jump_off_force",
                        "model_jump_off_indentation", "points", "rating", "tabor_mu", "maugis_lambda", "warnings"}) {
    columns.push_back(c);
  }
  units += "\t-\t-\tN\tN\tm\tN\tm\t-\t-\t-\t-\t-";
  items.push_back({"units", units});
  std::ostringstream header_stream;
  detail::write_table_header(header_stream, run.command_line, items, columns);
  table.header = header_stream.str();
  return table;
}

// One TSV line of a row; "-" where a curve has no value (its flag says why).
std::string afm_batch_row_line(const AfmCurveRow& row, const AfmBatchTable& table) {
  const std::size_t parameter_count = table.parameters.size();
  const bool contact_point_column = table.contact_point_column;
  std::string line = afm_table_file_name(row.source_file) + '\t' + std::to_string(row.curve_index) + '\t' + text_of(row.grid_x) + '\t' +
                     text_of(row.grid_y) + '\t' + text_of(row.position_x, "x") + '\t' + text_of(row.position_y, "y") + '\t' +
                     std::to_string(static_cast<int>(row.flag)) + '\t' + afm_flag_name(row.flag);
  const bool fitted = afm_flag_keeps_estimates(row.flag);
  for (std::size_t i = 0; i < parameter_count; ++i) {
    line += '\t' + (fitted ? detail::table_value(row.estimates[i], "estimate") : "-");
    line += '\t' + (fitted ? detail::table_value(row.errors[i], "error") : "-");
  }
  if (contact_point_column) line += '\t' + (fitted ? detail::table_value(row.contact_point, "contact_point") : "-");
  line += '\t' + (fitted ? detail::table_value(row.chi2, "chi2") : "-");
  line += '\t' + (fitted ? detail::table_value(row.chi2_per_dof, "chi2_per_dof") : "-");
  line += '\t' + (fitted ? detail::table_value(row.residual_sigma, "residual_sigma") : "-");
  line += '\t' + (fitted ? text_of(row.pulloff_force, "pulloff") : "-");
  line += '\t' + (fitted ? text_of(row.pulloff_position, "pulloff_position") : "-");
  line += '\t' + (fitted ? text_of(row.model_jump_off_force, "model_jump_off_force") : "-");
  line += '\t' + (fitted ? text_of(row.model_jump_off_indentation, "model_jump_off_indentation") : "-");
  line += '\t' + (fitted ? std::to_string(row.points) : "-");
  line += '\t' + detail::table_value(row.rating, "rating");
  line += '\t' + text_of(row.tabor_mu, "tabor_mu");
  line += '\t' + text_of(row.maugis_lambda, "maugis_lambda");
  line += '\t' + cell_text(row.warnings);
  line += '\n';
  return line;
}

std::string afm_batch_flagged_text(const std::size_t (&by_flag)[kAfmFlagCount], std::size_t total) {
  std::size_t flagged = 0;
  for (int f = 1; f < kAfmFlagCount; ++f) flagged += by_flag[f];
  std::string flag_text = std::to_string(flagged) + " of " + std::to_string(total);
  std::string reasons;
  for (int f = 1; f < kAfmFlagCount; ++f) {
    if (by_flag[f] > 0) reasons += (reasons.empty() ? "" : ", ") + std::string(afm_flag_name(static_cast<AfmFlag>(f))) + " " + std::to_string(by_flag[f]);
  }
  if (!reasons.empty()) flag_text += " (" + reasons + ")";
  return flag_text;
}

std::string afm_batch_final_header(const std::string& header, const std::string& flagged_text) {
  std::string out = header;
  out.insert(out.find("# columns:"), "# flagged curves: " + flagged_text + "\n");
  return out;
}

std::string afm_table_file_name(const std::string& path) { return !path.empty() && path[0] == '#' ? "./" + path : path; }

std::string afm_fit_range_text(const AfmRange& range) {
  std::string text = range.any() ? "" : "whole segment";
  const auto add = [&](const std::string& part) { text += (text.empty() ? "" : "; ") + part; };
  if (range.tip_min) add("tip position in [" + detail::table_parameter(*range.tip_min, "min") + ", " + detail::table_parameter(*range.tip_max, "max") + "] m");
  if (range.indentation_min) add("indentation >= " + detail::table_parameter(*range.indentation_min, "min") + " m");
  if (range.indentation_max) add("indentation <= " + detail::table_parameter(*range.indentation_max, "max") + " m");
  if (range.max_force) add("force - baseline <= " + detail::table_parameter(*range.max_force, "max force") + " N");
  return text;
}

void add_afm_stack_items(detail::HeaderItems& items, const AfmCoating& coating) {
  const Stack stack = coating.stack();
  items.push_back({"sample", "stack of " + std::to_string(stack.layers().size()) + " layers on a " +
                                 (stack.substrate().rigid ? std::string("rigid") : std::string("elastic")) +
                                 " substrate (THEORY.md sections 12, 15: tabled reduced variables in a/T and the free modulus)"});
  detail::add_stack_header_items(items, stack);
  const std::string k = std::to_string(coating.free_layer + 1);
  items.push_back({"free layer", k + " (its modulus E" + k + ", the free modulus, so named in the estimates, a map's columns and "
                                     "Python's results; the other layers fixed)"});
}

}  // namespace coatcontact::fit
