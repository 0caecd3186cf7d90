// Batch fit of AFM force curves (coatcontact/afm_batch.hpp, THEORY.md section 15, "Many curves"): the
// per-curve steps of `afm fit` (preprocessing, segment, range, afm_fit, pull-off) with every
// per-curve failure turned into a flag, over files read curve by curve in parallel chunks.
#include "coatcontact/afm_batch.hpp"

#include <sys/stat.h>
#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <thread>
#include <utility>

#include "coatcontact/afm_models.hpp"
#include "coatcontact/errors.hpp"
#include "coatcontact/progress.hpp"
#include "parallel.hpp"

#ifdef _OPENMP
#include <omp.h>
#endif

namespace coatcontact::fit {

std::string afm_result_parameter_name(const AfmParameterInfo& parameter, const AfmFitProblem& problem) {
  const bool coated = problem.coating.has_value();
  if (coated && parameter.value == &AfmFitResult::modulus) return problem.coating->free_modulus_name();
  return afm_parameter_name(parameter, coated);
}

std::vector<AfmBatchParameter> afm_batch_parameters(const AfmFitProblem& problem) {
  std::vector<AfmBatchParameter> parameters;
  for (const AfmParameterInfo& p : problem.model.info().parameters) {
    if (problem.free.*p.free) parameters.push_back({afm_result_parameter_name(p, problem), p.unit, p.value, p.error});
  }
  return parameters;
}

namespace {

AfmCurveRow row_of(const afm::CurveMetadata& m) {
  AfmCurveRow row;
  row.source_file = m.source_file;
  row.curve_index = m.curve_index;
  row.grid_x = m.grid_index_x;
  row.grid_y = m.grid_index_y;
  row.position_x = m.position_x;
  row.position_y = m.position_y;
  return row;
}

AfmCurveRow flagged(AfmCurveRow row, AfmFlag flag, const std::string& message) {
  row.flag = flag;
  row.message = message;
  return row;
}

}  // namespace

AfmCurveRow afm_unreadable_row(const afm::CurveMetadata& place, const std::exception& error) {
  AfmCurveRow row = row_of(place);
  AfmFlag flag = AfmFlag::kUnreadable;
  if (dynamic_cast<const afm::MissingCalibration*>(&error) != nullptr) flag = AfmFlag::kCalibration;
  else if (dynamic_cast<const afm::EmptySegment*>(&error) != nullptr) flag = AfmFlag::kEmptySegment;
  else if (dynamic_cast<const afm::NonFiniteValue*>(&error) != nullptr) flag = AfmFlag::kBadData;
  return flagged(std::move(row), flag, error.what());
}

AfmCurveRow afm_fit_curve_row(const afm::ForceCurve& curve, const AfmBatchSettings& settings) {
  AfmCurveRow row = row_of(curve.metadata);
  AfmCurveFit fitted;
  try {
    fitted = afm_fit_curve(curve, settings);
  } catch (const AfmCurveInputError& error) {
    if (settings.keep_traces) row.trace = afm_curve_trace(curve, settings, nullptr);
    return flagged(std::move(row), error.flag(), error.what());
  } catch (const AfmCurveNumericalError& error) {
    if (settings.keep_traces) row.trace = afm_curve_trace(curve, settings, nullptr);
    return flagged(std::move(row), error.flag(), error.what());
  }
  if (settings.keep_traces) row.trace = afm_curve_trace(curve, settings, &fitted);
  const AfmFitResult& r = fitted.result;
  for (const AfmBatchParameter& p : afm_batch_parameters(settings.problem)) {
    row.estimates.push_back(r.*p.value);
    row.errors.push_back(r.*p.error);
  }
  row.chi2 = r.chi2;
  row.chi2_per_dof = r.chi2_per_dof;
  row.residual_sigma = r.residual_sigma;
  row.contact_point = r.contact_point;
  row.points = r.points;
  row.flag = fitted.flag;
  row.rating = fitted.rating;
  if (!fitted.flag_warnings.empty()) row.message = fitted.flag_warnings.front();
  if (settings.problem.model.info().needs_spring) {
    row.tabor_mu = r.tabor_mu;
    row.maugis_lambda = r.maugis_lambda;
    row.model_jump_off_force = r.jump_off_force;
    row.model_jump_off_indentation = r.jump_off_indentation;
  }
  for (const std::vector<std::string>* list : {&std::as_const(fitted.flag_warnings), &r.warnings}) {
    for (const std::string& warning : *list) row.warnings += (row.warnings.empty() ? "" : "; ") + warning;
  }
  if (fitted.pulloff.found) {
    row.pulloff_force = fitted.pulloff.force;
    row.pulloff_position = fitted.pulloff.tip_position;
  }
  return row;
}

std::vector<AfmFileSurvey> afm_survey_files(const std::vector<std::string>& files, const afm::Calibration& calibration,
                                            bool tolerate) {
  std::vector<AfmFileSurvey> survey;
  for (const std::string& file : files) {
    AfmFileSurvey s;
    struct stat info {};
    if (tolerate && ::stat(file.c_str(), &info) == 0 && S_ISREG(info.st_mode)) {
      try {
        s.curves = afm::CurveSource(file, calibration).size();
      } catch (const afm::MissingCalibration& error) {
        s.curves = 1;
        s.unreadable = error.what();
        s.flag = AfmFlag::kCalibration;
      } catch (const InputError& error) {
        s.curves = 1;
        s.unreadable = error.what();
      } catch (const NumericalError& error) {
        s.curves = 1;
        s.unreadable = error.what();
      }
    } else {
      s.curves = afm::CurveSource(file, calibration).size();
    }
    survey.push_back(std::move(s));
  }
  return survey;
}

std::size_t afm_curve_bytes(const afm::ForceCurve& curve) {
  std::size_t bytes = sizeof curve;
  for (const std::vector<double>* v : {&curve.force, &curve.height_piezo, &curve.height_measured, &curve.time}) {
    bytes += v->capacity() * sizeof(double);
  }
  bytes += curve.segment.capacity() * sizeof(int) + curve.segments.capacity() * sizeof(afm::Segment);
  for (const afm::Segment& s : curve.segments) bytes += s.name.capacity();
  for (const auto& [key, value] : curve.metadata.details) bytes += key.capacity() + value.capacity();
  return bytes;
}

namespace {

// Sets the OpenMP thread count of the calling thread for the lifetime of the object.
class ScopedThreads {
 public:
  explicit ScopedThreads(unsigned jobs) {
#ifdef _OPENMP
    previous_ = omp_get_max_threads();
    omp_set_num_threads(static_cast<int>(jobs));
#else
    (void)jobs;
#endif
  }
  ~ScopedThreads() {
#ifdef _OPENMP
    omp_set_num_threads(previous_);
#endif
  }
  ScopedThreads(const ScopedThreads&) = delete;
  ScopedThreads& operator=(const ScopedThreads&) = delete;

 private:
  int previous_ = 1;
};

}  // namespace

AfmBatchSummary afm_fit_batch(const std::vector<std::string>& files, const afm::Calibration& calibration,
                              const AfmBatchSettings& settings, const AfmBatchOptions& options) {
  AfmBatchSummary summary;
  const std::vector<AfmFileSurvey> survey =
      options.survey.empty() ? afm_survey_files(files, calibration, options.unreadable_file_rows) : options.survey;
  if (survey.size() != files.size()) throw InputError("afm_fit_batch: the survey does not match the files");
  for (const AfmFileSurvey& s : survey) {
    if (!s.unreadable.empty() && !options.unreadable_file_rows) throw InputError(s.unreadable);
    summary.curves += s.curves;
  }
  if (options.jobs > 0) coatcontact::detail::check_thread_count(static_cast<long>(options.jobs), "jobs");
  const unsigned jobs = options.jobs > 0 ? options.jobs : std::max(1u, std::thread::hardware_concurrency());
  const std::size_t chunk = options.chunk_curves > 0 ? options.chunk_curves : 16 * static_cast<std::size_t>(jobs);
  const std::size_t chunk_bytes = options.chunk_bytes > 0 ? options.chunk_bytes : kAfmBatchChunkBytes;
  const ScopedThreads threads(jobs);
  std::size_t done = std::min(options.skip, summary.curves);
  const std::size_t stop = done + std::min(options.count, summary.curves - done);  // one past the last curve fitted
  if (options.progress && !options.progress(done, summary.curves)) throw Interrupted("interrupted before the first curve");

  // Work of one chunk: a curve as read, or the row of a curve that could not be read.
  struct Item {
    std::optional<afm::ForceCurve> curve;
    AfmCurveRow row;
  };
  struct Chunk {
    std::vector<Item> items;
    std::size_t bytes = 0;  // of its curves as read
  };
  // The curves from `next` on (over all files, in order), one chunk at a time.
  std::size_t next = done, file = 0, first_of_file = 0;
  std::unique_ptr<afm::CurveSource> source;
  // A chunk ends at `chunk` curves or at the curve that brings its bytes to chunk_bytes, so
  // the curves held do not grow with the threads (issue 40: 1.7 GB at --jobs 16).
  const auto read_chunk = [&]() {
    Chunk read;
    std::vector<Item>& items = read.items;
    while (items.size() < chunk && read.bytes < chunk_bytes && next < stop) {
      while (next >= first_of_file + survey[file].curves) {
        first_of_file += survey[file++].curves;
        source.reset();
      }
      Item item;
      if (!survey[file].unreadable.empty()) {
        afm::CurveMetadata place;
        place.source_file = files[file];
        item.row = flagged(row_of(place), survey[file].flag, survey[file].unreadable);
        items.push_back(std::move(item));
        ++next;
        continue;
      }
      if (!source) source = std::make_unique<afm::CurveSource>(files[file], calibration);
      const std::size_t i = next - first_of_file;
      try {
        item.curve = source->read(i);
        read.bytes += afm_curve_bytes(*item.curve);
      } catch (const InputError& error) {
        item.row = afm_unreadable_row(source->place(i), error);
      } catch (const NumericalError& error) {
        item.row = afm_unreadable_row(source->place(i), error);
      }
      items.push_back(std::move(item));
      ++next;
    }
    return read;
  };
  // Unit 0 of each parallel loop reads the next chunk while the others fit this one (the
  // source is used by one unit at a time), so reading overlaps fitting.
  Chunk current = read_chunk();
  std::vector<Item>& items = current.items;
  while (!items.empty()) {
    Chunk following;
    const std::size_t chunk_done = done;
    const ScopedProgressHook hook([&](std::size_t finished, std::size_t) {
      return !options.progress || options.progress(chunk_done + std::min(finished, items.size()), summary.curves);
    });
    detail::parallel_for(items.size() + 1, [&](std::size_t unit) {
      if (unit == 0) {
        following = read_chunk();
        return;
      }
      Item& item = items[unit - 1];
      if (item.curve) {
        item.row = afm_fit_curve_row(*item.curve, settings);
        item.curve.reset();
      }
    });
    // Both chunks whole: an upper bound of what the loop held at once.
    summary.peak_curves_held = std::max(summary.peak_curves_held, items.size() + following.items.size());
    summary.peak_curve_bytes = std::max(summary.peak_curve_bytes, current.bytes + following.bytes);
    std::vector<AfmCurveRow> rows;
    rows.reserve(items.size());
    for (Item& item : items) {
      const auto flag = static_cast<std::size_t>(item.row.flag);
      ++summary.by_flag[flag];
      if (item.row.flag == AfmFlag::kFitted) ++summary.fitted;
      else {
        ++summary.flagged;
        if (summary.first_message[flag].empty()) summary.first_message[flag] = item.row.message;
      }
      rows.push_back(std::move(item.row));
    }
    if (options.sink) options.sink(rows);
    done += items.size();
    current = std::move(following);
#ifdef __GLIBC__
    // The curves were read on whichever thread ran unit 0, so the freed ones sit in up to
    // `jobs` malloc arenas, each kept at its own peak: give that memory back once per chunk, or
    // the RSS grows with the threads all the same (glibc; cheap against a chunk's fits).
    malloc_trim(0);
#endif
  }
  return summary;
}

}  // namespace coatcontact::fit
