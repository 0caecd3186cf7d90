// The AFM handles' layouts and the argument checks the C API's AFM files share
// (capi_afm.cpp, capi_afm_fit.cpp, capi_afm_batch.cpp). Not a public header.
#pragma once
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_preprocess.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/coatcontact_afm.h"
#include "coatcontact/force_curve.hpp"

struct cc_afm_file {
  std::unique_ptr<coatcontact::afm::CurveSource> source;
};

struct cc_afm_curve {
  coatcontact::afm::ForceCurve curve;
  std::vector<std::pair<std::string, std::vector<double>>> channels;  // in coatcontact_afm.h's order
  std::vector<std::pair<std::string, std::string>> metadata;
};

// A request as set: what the setters fixed, the rest resolved by cc_afm_fit_curve / the batch
// (the defaults of free parameters and segment follow the model and the sample).
struct cc_afm_request {
  coatcontact::fit::AfmCurveRequest request;  // tip, sample, values, range, preprocessing
  std::string model = "hertz";
  bool has_tip = false, has_sample = false, coated = false;
  std::string free;  // empty: the model's default
  std::optional<coatcontact::afm::SegmentKind> segment;
  std::optional<coatcontact::fit::AfmBaselineModel> baseline;
  std::optional<bool> check_jump_in;  // unset: the one-curve fit's default (off), the batch's (on)
  bool depth_profile = false;         // cc_afm_fit_curve also fits the depth profile
  bool has_contact_point = false, has_baseline = false, has_work = false, has_tilt = false;
};

namespace coatcontact::capi {

// InputError "function: argument is NULL".
void require(const void* pointer, const char* function, const char* argument);
// InputError unless 0 <= index < size, naming the function, the argument and the range.
std::size_t checked_index(long index, std::size_t size, const char* function, const char* argument);
// Copies `data` to values[0..capacity) (values NULL: the length only) and sets *length.
void copy_out(const std::vector<double>& data, double* values, long capacity, long* length, const char* function,
              const std::string& what);
// The library's preprocessing options and calibration of the C structs, checked (NULL
// calibration: the files' own).
afm::PreprocessOptions afm_preprocess_options(const cc_afm_preprocess_options& options, const char* function);
afm::Calibration afm_calibration(const cc_afm_calibration* calibration, const char* function);
// The library's request of a C request, checked as a whole (InputError naming the setter).
fit::AfmCurveRequest resolve_request(const cc_afm_request& request, const char* function);

}  // namespace coatcontact::capi
