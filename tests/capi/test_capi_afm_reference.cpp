// The C++ side of test_capi_afm.c: the same readings and fits called directly on the library
// (afm::read_force_curves, afm_fit_curve), for the C test to compare with the C API's.
#include <cstring>
#include <exception>
#include <string>

#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_readers.hpp"

namespace afm = coatcontact::afm;
namespace fit = coatcontact::fit;

extern "C" {

// Channel `name` ("force", "height_measured", "height_piezo", "time") of curve `index` into
// out[0..capacity); returns its length, -1 on failure.
long ref_channel(const char* path, long index, const char* name, double* out, long capacity) {
  try {
    const auto curves = afm::read_force_curves(path);
    const afm::ForceCurve& c = curves.at(static_cast<std::size_t>(index));
    const std::string n(name);
    const std::vector<double>& data = n == "force" ? c.force
                                      : n == "height_measured" ? c.height_measured
                                      : n == "height_piezo" ? c.height_piezo
                                                            : c.time;
    if (static_cast<long>(data.size()) > capacity) return -1;
    if (!data.empty()) std::memcpy(out, data.data(), data.size() * sizeof(double));
    return static_cast<long>(data.size());
  } catch (const std::exception&) {
    return -1;
  }
}

// afm_fit_curve on curve `index`: a paraboloid of radius R on a half-space (E start 1 kPa,
// nu 0.5); model "hertz" (E, contact_point, baseline free, approach) or "jkr" (E, w,
// contact_point, baseline, tilt free, retract). out: E, E_err, z_c, z_c_err, b, b_err, w, w_err,
// tilt, tilt_err. Returns 0, or -1 on failure.
int ref_fit(const char* path, long index, const char* model, double radius, double out[10]) {
  try {
    const auto curves = afm::read_force_curves(path);
    fit::AfmCurveRequest request;
    request.problem.tip = fit::afm_paraboloid(radius);
    request.problem.modulus = 1000.0;
    request.problem.poisson = 0.5;
    if (std::string(model) == "jkr") {
      request.problem.model = fit::AfmModel::kJkr;
      request.problem.free = {true, true, true, false, true, true};
      request.segment = afm::SegmentKind::kRetract;
    } else {
      request.problem.free = {true, true, true, false, false, false};
    }
    const fit::AfmCurveFit f = fit::afm_fit_curve(curves.at(static_cast<std::size_t>(index)), request);
    const fit::AfmFitResult& r = f.result;
    const double values[10] = {r.modulus, r.modulus_error, r.contact_point, r.contact_point_error, r.baseline,
                               r.baseline_error, r.work, r.work_error, r.tilt, r.tilt_error};
    std::memcpy(out, values, sizeof values);
    return 0;
  } catch (const std::exception&) {
    return -1;
  }
}

}  // extern "C"
