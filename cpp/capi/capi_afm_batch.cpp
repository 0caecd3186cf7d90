// The C interface of the AFM batch (coatcontact_afm.h): afm_fit_batch over files, or
// afm_fit_curve_row over given curves, with the request of the one-curve fit; the rows kept in
// a handle or handed to the caller's sink chunk by chunk; the files of a run (folders expanded,
// surveyed). Runs inside capi::guard.
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>

#include "capi_afm.hpp"
#include "capi_guard.hpp"
#include "coatcontact/afm_batch_table.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"

using coatcontact::InputError;
namespace fit = coatcontact::fit;
using coatcontact::capi::checked_index;
using coatcontact::capi::copy_out;
using coatcontact::capi::guard;
using coatcontact::capi::require;

struct cc_afm_rows {
  std::vector<fit::AfmBatchParameter> parameters;
  std::vector<fit::AfmCurveRow> rows;
  // A run over files: what its table's header states (cc_afm_rows_write_table).
  std::optional<fit::AfmBatchSettings> settings;
  fit::AfmBatchTableRun run;
};

struct cc_afm_file_list {
  std::vector<std::string> paths;
  std::vector<fit::AfmFileSurvey> survey;  // empty: not surveyed
};

namespace {

const cc_afm_rows& rows_of(const cc_afm_rows* rows, const char* function) {
  require(rows, function, "rows");
  return *rows;
}

// The calling thread's progress hook (cc_set_progress_hook), read without changing it.
coatcontact::ProgressHook current_hook() {
  coatcontact::ProgressHook hook = coatcontact::exchange_progress_hook({});
  coatcontact::exchange_progress_hook(hook);
  return hook;
}

// The request as a batch's settings (a batch checks jump-ins unless the request says).
fit::AfmBatchSettings settings_of(const cc_afm_request& request, const cc_afm_batch_options* options, const char* function) {
  fit::AfmBatchSettings settings;
  const bool jump_in = settings.check_jump_in;
  if (request.depth_profile) throw InputError(std::string(function) + ": a depth profile is of one curve (cc_afm_fit_curve)");
  static_cast<fit::AfmCurveRequest&>(settings) = coatcontact::capi::resolve_request(request, function);
  settings.check_jump_in = request.check_jump_in.value_or(jump_in);
  settings.keep_traces = options && options->keep_traces != 0;
  return settings;
}

// Hands `chunk` to the caller's sink as a rows handle, or keeps it; a sink's non-zero return
// stops the run (Interrupted).
void deliver(cc_afm_rows& made, const std::vector<fit::AfmCurveRow>& chunk, const cc_afm_batch_options* options) {
  if (options && options->sink) {
    cc_afm_rows view;
    view.parameters = made.parameters;
    view.rows = chunk;
    if (options->sink(options->sink_user, &view) != 0) throw coatcontact::Interrupted("interrupted");
  } else {
    made.rows.insert(made.rows.end(), chunk.begin(), chunk.end());
  }
}

// The caller's survey (one entry per file), checked.
std::vector<fit::AfmFileSurvey> survey_of(const cc_afm_batch_options& options, std::size_t files, const char* f) {
  std::vector<fit::AfmFileSurvey> out;
  if (options.survey_count == 0) return out;
  require(options.survey, f, "options survey");
  if (options.survey_count != static_cast<long>(files)) {
    throw InputError(std::string(f) + ": options survey_count " + std::to_string(options.survey_count) +
                     " is not allowed; expected one entry per file (" + std::to_string(files) + ") or 0");
  }
  for (long i = 0; i < options.survey_count; ++i) {
    const cc_afm_file_survey& s = options.survey[i];
    if (s.curves < 0 || s.flag < 0 || s.flag >= fit::kAfmFlagCount) {
      throw InputError(std::string(f) + ": survey[" + std::to_string(i) + "] curves " + std::to_string(s.curves) + ", flag " +
                       std::to_string(s.flag) + " are not allowed; expected curves >= 0 and a flag 0.." +
                       std::to_string(fit::kAfmFlagCount - 1));
    }
    out.push_back({static_cast<std::size_t>(s.curves), s.unreadable ? s.unreadable : "", static_cast<fit::AfmFlag>(s.flag)});
  }
  return out;
}

std::vector<std::string> strings_of(const char* const* items, long count, const char* f, const char* what) {
  require(items, f, what);
  if (count < 1) throw InputError(std::string(f) + ": count " + std::to_string(count) + " is not allowed; expected >= 1");
  std::vector<std::string> out;
  for (long i = 0; i < count; ++i) {
    if (items[i] == nullptr) throw InputError(std::string(f) + ": " + what + "[" + std::to_string(i) + "] is NULL");
    out.emplace_back(items[i]);
  }
  return out;
}

const cc_afm_file_list& list_of(const cc_afm_file_list* files, const char* function) {
  require(files, function, "files");
  return *files;
}

}  // namespace

extern "C" {

int cc_afm_fit_batch(const char* const* files, long file_count, const cc_afm_calibration* calibration,
                     const cc_afm_request* request, const cc_afm_batch_options* options, cc_afm_rows** rows) {
  return guard([&] {
    const char* f = "cc_afm_fit_batch";
    require(files, f, "files");
    require(request, f, "request");
    require(rows, f, "rows");
    if (file_count < 1) throw InputError(std::string(f) + ": file_count " + std::to_string(file_count) + " is not allowed; expected >= 1");
    const std::vector<std::string> paths = strings_of(files, file_count, f, "files");
    const fit::AfmBatchSettings settings = settings_of(*request, options, f);
    const coatcontact::afm::Calibration cal = coatcontact::capi::afm_calibration(calibration, f);
    auto made = std::make_unique<cc_afm_rows>();
    made->parameters = fit::afm_batch_parameters(settings.problem);
    fit::AfmBatchOptions batch;
    if (options) {
      batch.jobs = options->jobs;
      batch.unreadable_file_rows = options->unreadable_file_rows != 0;
      if (options->skip < 0 || options->count < 0) {
        throw InputError(std::string(f) + ": options skip " + std::to_string(options->skip) + ", count " +
                         std::to_string(options->count) + " are not allowed; expected skip >= 0 and count >= 0 (0: all)");
      }
      batch.skip = static_cast<std::size_t>(options->skip);
      if (options->count > 0) batch.count = static_cast<std::size_t>(options->count);
      batch.survey = survey_of(*options, paths.size(), f);
    }
    // Surveyed here when the caller has no survey (as afm_fit_batch would): the table's header
    // names each file's curves.
    if (batch.survey.empty()) batch.survey = fit::afm_survey_files(paths, cal, batch.unreadable_file_rows);
    made->settings = settings;
    made->run.files = paths;
    made->run.survey = batch.survey;
    for (const fit::AfmFileSurvey& s : batch.survey) made->run.total += s.curves;
    made->run.calibration = cal;
    const fit::AfmModelInfo& info = settings.problem.model.info();
    made->run.free_text = request->free.empty() ? fit::afm_free_default(info, request->coated) : request->free;
    batch.sink = [&](const std::vector<fit::AfmCurveRow>& chunk) { deliver(*made, chunk, options); };
    if (coatcontact::ProgressHook hook = current_hook()) batch.progress = hook;
    fit::afm_fit_batch(paths, cal, settings, batch);
    *rows = made.release();
  });
}

int cc_afm_fit_curves(const cc_afm_curve* const* curves, long count, const cc_afm_request* request,
                      const cc_afm_batch_options* options, cc_afm_rows** rows) {
  return guard([&] {
    const char* f = "cc_afm_fit_curves";
    if (count > 0) require(curves, f, "curves");
    require(request, f, "request");
    require(rows, f, "rows");
    if (count < 0) throw InputError(std::string(f) + ": count " + std::to_string(count) + " is not allowed; expected >= 0");
    for (long i = 0; i < count; ++i) {
      if (curves[i] == nullptr) throw InputError(std::string(f) + ": curves[" + std::to_string(i) + "] is NULL");
    }
    const fit::AfmBatchSettings settings = settings_of(*request, options, f);
    auto made = std::make_unique<cc_afm_rows>();
    made->parameters = fit::afm_batch_parameters(settings.problem);
    const coatcontact::ProgressHook hook = current_hook();
    for (long i = 0; i < count; ++i) {
      if (hook && !hook(static_cast<std::size_t>(i), static_cast<std::size_t>(count))) throw coatcontact::Interrupted("interrupted");
      deliver(*made, {fit::afm_fit_curve_row(curves[i]->curve, settings)}, options);
    }
    *rows = made.release();
  });
}

int cc_afm_expand_paths(const char* const* paths, long count, cc_afm_file_list** files) {
  return guard([&] {
    const char* f = "cc_afm_expand_paths";
    require(files, f, "files");
    auto made = std::make_unique<cc_afm_file_list>();
    for (const std::string& p : strings_of(paths, count, f, "paths")) {
      struct stat info {};
      if (::stat(p.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) {
        for (std::string& file : coatcontact::afm::afm_files_in_folder(p)) made->paths.push_back(std::move(file));
      } else {
        made->paths.push_back(p);
      }
    }
    *files = made.release();
  });
}

int cc_afm_survey_files(const char* const* files, long count, const cc_afm_calibration* calibration, int tolerate,
                        cc_afm_file_list** survey) {
  return guard([&] {
    const char* f = "cc_afm_survey_files";
    require(survey, f, "survey");
    auto made = std::make_unique<cc_afm_file_list>();
    made->paths = strings_of(files, count, f, "files");
    made->survey = fit::afm_survey_files(made->paths, coatcontact::capi::afm_calibration(calibration, f), tolerate != 0);
    *survey = made.release();
  });
}

void cc_afm_file_list_destroy(cc_afm_file_list* files) { delete files; }

int cc_afm_file_list_count(const cc_afm_file_list* files, long* count) {
  return guard([&] {
    const cc_afm_file_list& l = list_of(files, "cc_afm_file_list_count");
    require(count, "cc_afm_file_list_count", "count");
    *count = static_cast<long>(l.paths.size());
  });
}

int cc_afm_file_list_get(const cc_afm_file_list* files, long file, cc_afm_file_survey* out) {
  return guard([&] {
    const char* f = "cc_afm_file_list_get";
    const cc_afm_file_list& l = list_of(files, f);
    require(out, f, "out");
    const std::size_t i = checked_index(file, l.paths.size(), f, "file");
    cc_afm_file_survey o{};
    o.path = l.paths[i].c_str();
    o.curves = l.survey.empty() ? -1 : static_cast<long>(l.survey[i].curves);
    o.unreadable = l.survey.empty() ? "" : l.survey[i].unreadable.c_str();
    o.flag = l.survey.empty() ? 0 : static_cast<int>(l.survey[i].flag);
    *out = o;
  });
}

void cc_afm_rows_destroy(cc_afm_rows* rows) { delete rows; }

int cc_afm_rows_count(const cc_afm_rows* rows, long* count) {
  return guard([&] {
    const cc_afm_rows& r = rows_of(rows, "cc_afm_rows_count");
    require(count, "cc_afm_rows_count", "count");
    *count = static_cast<long>(r.rows.size());
  });
}

int cc_afm_rows_parameter_count(const cc_afm_rows* rows, long* count) {
  return guard([&] {
    const cc_afm_rows& r = rows_of(rows, "cc_afm_rows_parameter_count");
    require(count, "cc_afm_rows_parameter_count", "count");
    *count = static_cast<long>(r.parameters.size());
  });
}

int cc_afm_rows_parameter_name(const cc_afm_rows* rows, long parameter, const char** name, const char** unit) {
  return guard([&] {
    const cc_afm_rows& r = rows_of(rows, "cc_afm_rows_parameter_name");
    require(name, "cc_afm_rows_parameter_name", "name");
    const auto& p = r.parameters[checked_index(parameter, r.parameters.size(), "cc_afm_rows_parameter_name", "parameter")];
    *name = p.name.c_str();
    if (unit) *unit = p.unit.c_str();
  });
}

int cc_afm_rows_get(const cc_afm_rows* rows, long row, cc_afm_row* out) {
  return guard([&] {
    const cc_afm_rows& r = rows_of(rows, "cc_afm_rows_get");
    require(out, "cc_afm_rows_get", "out");
    const fit::AfmCurveRow& c = r.rows[checked_index(row, r.rows.size(), "cc_afm_rows_get", "row")];
    cc_afm_row o{};
    o.file = c.source_file.c_str();
    o.curve = static_cast<long>(c.curve_index);
    o.has_grid = c.grid_x && c.grid_y;
    if (o.has_grid) {
      o.grid_x = *c.grid_x;
      o.grid_y = *c.grid_y;
    }
    o.has_position = c.position_x && c.position_y;
    if (o.has_position) {
      o.position_x = *c.position_x;
      o.position_y = *c.position_y;
    }
    o.flag = static_cast<int>(c.flag);
    o.flag_name = fit::afm_flag_name(c.flag);
    o.message = c.message.c_str();
    o.has_estimates = fit::afm_flag_keeps_estimates(c.flag);
    o.rating = c.rating;
    o.chi2 = c.chi2;
    o.chi2_per_dof = c.chi2_per_dof;
    o.residual_sigma = c.residual_sigma;
    o.contact_point = c.contact_point;
    o.points = static_cast<long>(c.points);
    o.has_pulloff = c.pulloff_force.has_value();
    o.pulloff_force = c.pulloff_force.value_or(0.0);
    o.pulloff_position = c.pulloff_position.value_or(0.0);
    o.has_adhesion = c.tabor_mu && c.maugis_lambda;
    o.tabor_mu = c.tabor_mu.value_or(0.0);
    o.maugis_lambda = c.maugis_lambda.value_or(0.0);
    o.warnings = c.warnings.c_str();
    const bool estimates = o.has_estimates && c.estimates.size() == r.parameters.size() && !c.estimates.empty();
    o.estimates = estimates ? c.estimates.data() : nullptr;
    o.errors = estimates ? c.errors.data() : nullptr;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    o.grid_x_or_none = c.grid_x.value_or(-1);
    o.grid_y_or_none = c.grid_y.value_or(-1);
    o.position_x_or_nan = c.position_x.value_or(nan);
    o.position_y_or_nan = c.position_y.value_or(nan);
    o.has_model_jump_off = c.model_jump_off_force.has_value();
    o.model_jump_off_force = c.model_jump_off_force.value_or(0.0);
    o.model_jump_off_indentation = c.model_jump_off_indentation.value_or(0.0);
    o.has_trace = c.trace && !c.trace->z.empty();
    o.trace_contact_point = o.has_trace ? c.trace->contact_point : nan;
    *out = o;
  });
}

int cc_afm_rows_trace(const cc_afm_rows* rows, long row, const char* name, double* values, long capacity, long* length) {
  return guard([&] {
    const char* f = "cc_afm_rows_trace";
    const cc_afm_rows& r = rows_of(rows, f);
    require(name, f, "name");
    const fit::AfmCurveRow& c = r.rows[checked_index(row, r.rows.size(), f, "row")];
    if (!c.trace || c.trace->z.empty()) {
      throw InputError(std::string(f) + ": row " + std::to_string(row) + " has no trace (options keep_traces, a curve with data)");
    }
    const fit::AfmCurveTrace& t = *c.trace;
    const std::string n(name);
    if (n == "z") return copy_out(t.z, values, capacity, length, f, n);
    if (n == "force") return copy_out(t.force, values, capacity, length, f, n);
    if (n == "model") return copy_out(t.model, values, capacity, length, f, n);
    if (n == "segment") return copy_out(std::vector<double>(t.segment.begin(), t.segment.end()), values, capacity, length, f, n);
    if (n == "fitted") return copy_out(std::vector<double>(t.fitted.begin(), t.fitted.end()), values, capacity, length, f, n);
    throw InputError(std::string(f) + ": name '" + n.substr(0, 60) + "' is not a trace array; allowed: z, force, model, segment, fitted");
  });
}

int cc_afm_rows_write_table(const cc_afm_rows* rows, const char* path) {
  return guard([&] {
    const char* f = "cc_afm_rows_write_table";
    const cc_afm_rows& r = rows_of(rows, f);
    require(path, f, "path");
    if (!r.settings) {
      throw InputError(std::string(f) + ": the rows are not a run over files (cc_afm_fit_batch without a sink); their table has no header");
    }
    const fit::AfmBatchTable table = fit::afm_batch_table(*r.settings, r.run);
    std::size_t by_flag[fit::kAfmFlagCount] = {};
    for (const fit::AfmCurveRow& row : r.rows) ++by_flag[static_cast<int>(row.flag)];
    std::string text = fit::afm_batch_final_header(table.header, fit::afm_batch_flagged_text(by_flag, r.run.total));
    for (const fit::AfmCurveRow& row : r.rows) text += fit::afm_batch_row_line(row, table);
    // Atomic: a temporary file beside it, renamed.
    const std::string temporary = std::string(path) + ".tmp";
    {
      std::ofstream out(temporary, std::ios::binary | std::ios::trunc);
      out << text;
      out.close();
      if (!out) {
        std::remove(temporary.c_str());
        throw InputError(std::string(f) + ": cannot write '" + std::string(path).substr(0, 200) + "'");
      }
    }
    if (std::rename(temporary.c_str(), path) != 0) {
      std::remove(temporary.c_str());
      throw InputError(std::string(f) + ": cannot replace '" + std::string(path).substr(0, 200) + "'");
    }
  });
}

}  // extern "C"
