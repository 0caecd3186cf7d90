// The C interface of the AFM batch (coatcontact_afm.h): afm_fit_batch over files with the
// request of the one-curve fit, its rows kept in a handle. Runs inside capi::guard.
#include <cmath>

#include "capi_afm.hpp"
#include "capi_guard.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"

using coatcontact::InputError;
namespace fit = coatcontact::fit;
using coatcontact::capi::checked_index;
using coatcontact::capi::guard;
using coatcontact::capi::require;

struct cc_afm_rows {
  std::vector<fit::AfmBatchParameter> parameters;
  std::vector<fit::AfmCurveRow> rows;
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
    std::vector<std::string> paths;
    for (long i = 0; i < file_count; ++i) {
      if (files[i] == nullptr) throw InputError(std::string(f) + ": files[" + std::to_string(i) + "] is NULL");
      paths.emplace_back(files[i]);
    }
    fit::AfmBatchSettings settings;
    const bool jump_in = settings.check_jump_in;
    static_cast<fit::AfmCurveRequest&>(settings) = coatcontact::capi::resolve_request(*request, f);
    settings.check_jump_in = request->check_jump_in.value_or(jump_in);
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
    }
    batch.sink = [&](const std::vector<fit::AfmCurveRow>& chunk) {
      made->rows.insert(made->rows.end(), chunk.begin(), chunk.end());
    };
    if (coatcontact::ProgressHook hook = current_hook()) batch.progress = hook;
    fit::afm_fit_batch(paths, cal, settings, batch);
    *rows = made.release();
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
    *out = o;
  });
}

}  // extern "C"
