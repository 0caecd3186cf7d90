// Batch fit of many AFM force curves (maps, QI data, many files; THEORY.md section 15, "Many curves"): one
// result row per curve. A curve that cannot be fitted gets a flag and its reason, and the batch
// goes on; a file that cannot be opened at all stops it (InputError) unless the caller asks for
// it as a flagged row (AfmBatchOptions::unreadable_file_rows). The curves are read
// one at a time from each file (afm::CurveSource) in chunks: a chunk is fitted in parallel (the
// library's one parallel loop, one of whose units reads the next chunk meanwhile) and handed
// over in curve order. A chunk holds at most 16 curves per thread and at most
// AfmBatchOptions::chunk_bytes of curves (at least one curve), so the memory of a run is two
// chunks of curves, whatever --jobs, plus each busy thread's working set, the rows the caller
// keeps (and libzip's central directory of the archive being read: THEORY.md section 15,
// "Memory of a run"). The per-curve fit
// is afm_fit_curve (coatcontact/afm_curve_fit.hpp), the one-curve fit's pipeline, unchanged:
// every model and free parameter it supports runs in the batch; each free estimate has its
// column (afm_batch_parameters).
#pragma once
#include <cstddef>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_models.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/force_curve.hpp"

namespace coatcontact::fit {

// The settings of a batch are the request of the one-curve fit (afm_curve_fit.hpp); a batch
// checks jump-ins by default.
struct AfmBatchSettings : AfmCurveRequest {
  AfmBatchSettings() { check_jump_in = true; }
  bool keep_traces = false;  // each row gets its AfmCurveTrace (per-curve control plots)
};

// What a control plot of one curve draws (afm fit --curve-plots): the approach's points, and the
// retract's for a retract fit, on the tip-position axis, with the model over the fitted segment.
// Empty when the curve has no force or no tip position (unreadable, no calibration).
struct AfmCurveTrace {
  std::vector<double> z, force;  // [m] tip position, [N] force as measured
  std::vector<int> segment;      // 0 approach, 1 retract
  std::vector<double> model;     // [N] the model at z (the subtracted tilt added back); NaN off the fitted segment
  std::vector<char> fitted;      // 1: a fitted point (its residual is model - force)
  double contact_point = 0.0;    // [m] fitted; NaN without estimates
};
// The trace of a curve and its fit (nullptr: a curve without estimates).
std::shared_ptr<const AfmCurveTrace> afm_curve_trace(const afm::ForceCurve& curve, const AfmBatchSettings& settings,
                                                     const AfmCurveFit* fitted);

// One free estimate's column: its name, unit and where afm_fit puts it.
struct AfmBatchParameter {
  std::string name;  // "E", "E1" (a stack's E<K>), "t", "contact_point", "baseline"
  std::string unit;  // "Pa", "m", "N"
  double AfmFitResult::*value;
  double AfmFitResult::*error;
};
std::vector<AfmBatchParameter> afm_batch_parameters(const AfmFitProblem& problem);
// A parameter's name in the results (columns, the C API, Python): the registry's, except a
// stack's free modulus, named E<K> after its layer K (one film, and layer 1: E1).
std::string afm_result_parameter_name(const AfmParameterInfo& parameter, const AfmFitProblem& problem);

struct AfmCurveRow {
  std::string source_file;
  std::size_t curve_index = 0;
  std::optional<long> grid_x, grid_y;
  std::optional<double> position_x, position_y;  // [m]
  AfmFlag flag = AfmFlag::kFitted;
  std::string message;  // the reason in words (empty for a fitted curve)
  double rating = 0.0;  // afm_rating (0 for a curve without estimates)
  // The curves with estimates only (afm_flag_keeps_estimates: fitted, undetermined, no_detachment):
  std::optional<double> tabor_mu, maugis_lambda;  // adhesive models only
  // The model's own jump-off through the spring (AfmFitResult): force above the baseline [N],
  // indentation [m]; adhesive models only.
  std::optional<double> model_jump_off_force, model_jump_off_indentation;
  std::string warnings;  // the fit's warnings and the flag's reasons, "; "-separated (empty: none)
  std::vector<double> estimates, errors;  // in the order of afm_batch_parameters
  double chi2 = 0.0, chi2_per_dof = 0.0, residual_sigma = 0.0;
  double contact_point = 0.0;  // [m] fitted (or fixed) contact point on the tip-position axis
  std::size_t points = 0;      // fitted points
  // Measured pull-off of the retract segment less the fitted baseline (when there is one).
  std::optional<double> pulloff_force, pulloff_position;
  std::shared_ptr<const AfmCurveTrace> trace;  // with AfmBatchSettings::keep_traces (nullptr for an unreadable curve)
};

// Fits one curve; per-curve problems become the row's flag (never an exception, except
// Interrupted and allocation failure).
AfmCurveRow afm_fit_curve_row(const afm::ForceCurve& curve, const AfmBatchSettings& settings);

// The row of a curve that could not be read (flag from the reader's exception); `place`:
// what is known of the curve (afm::CurveSource::place).
AfmCurveRow afm_unreadable_row(const afm::CurveMetadata& place, const std::exception& error);

// What a run knows of one file before fitting: its curves, or why it cannot be read at all.
struct AfmFileSurvey {
  std::size_t curves = 0;  // 1 for an unreadable file: its one flagged row
  std::string unreadable;  // empty, or the reader's message (naming the file and why)
  // The flag of its one row: kCalibration when the file's curves lack a calibration the force
  // needs (afm::MissingCalibration, as for a curve of a file that opens), else kUnreadable.
  AfmFlag flag = AfmFlag::kUnreadable;
};

// Opens each file once to count its curves (the archive is closed again). A file that cannot
// be opened: InputError, or with `tolerate` an AfmFileSurvey with its reason (a file that does
// not exist or is not a regular file stays an InputError: the command line names it wrongly).
std::vector<AfmFileSurvey> afm_survey_files(const std::vector<std::string>& files, const afm::Calibration& calibration,
                                            bool tolerate);

struct AfmBatchOptions {
  unsigned jobs = 0;             // threads; 0: the machine's cores
  std::size_t chunk_curves = 0;  // curves per chunk; 0: 16 x jobs
  // The curves' bytes (afm_curve_bytes) a chunk holds at most; a chunk always takes one curve,
  // and stops at the curve that reaches this. 0: kAfmBatchChunkBytes.
  std::size_t chunk_bytes = 0;
  std::size_t skip = 0;          // the first `skip` curves of the run (over all files) are not fitted (resume)
  std::size_t count = static_cast<std::size_t>(-1);  // curves fitted after them at most (a share of the run)
  // The files' afm_survey_files, when the caller has it (a share of a run on a cluster: no file
  // is opened to be counted, and only the files of the share are opened); empty: surveyed here.
  std::vector<AfmFileSurvey> survey;
  // A file that cannot be opened (not a force-curve file, corrupt) becomes one row flagged
  // unreadable with the reason, and the run goes on; false: InputError (a single FILE named).
  bool unreadable_file_rows = false;
  // Rows of each chunk, in curve order. Called on the calling thread.
  std::function<void(const std::vector<AfmCurveRow>& rows)> sink;
  // (curves done including skipped, total); false stops the run (Interrupted after the last
  // whole chunk was handed to the sink). Called on the calling thread.
  std::function<bool(std::size_t done, std::size_t total)> progress;
};

// The default AfmBatchOptions::chunk_bytes: 32 curves of a real JPK map (12 030 points per
// segment, ~0.9 MB as read), so up to 16 threads share each chunk two curves apiece.
constexpr std::size_t kAfmBatchChunkBytes = std::size_t{32} << 20;

// The bytes of a curve as read (its per-point arrays and segments): what a chunk counts.
std::size_t afm_curve_bytes(const afm::ForceCurve& curve);

struct AfmBatchSummary {
  std::size_t curves = 0;   // in all files
  // The most curves, and curve bytes (afm_curve_bytes), held at once: the chunk being fitted
  // and the one being read, each counted whole (a curve is released once fitted).
  std::size_t peak_curves_held = 0, peak_curve_bytes = 0;
  std::size_t fitted = 0, flagged = 0;  // of the curves fitted in this call (not the skipped)
  std::size_t by_flag[kAfmFlagCount] = {};
  std::string first_message[kAfmFlagCount];  // the first reason of each flag, for a summary
};

AfmBatchSummary afm_fit_batch(const std::vector<std::string>& files, const afm::Calibration& calibration,
                              const AfmBatchSettings& settings, const AfmBatchOptions& options);

}  // namespace coatcontact::fit
