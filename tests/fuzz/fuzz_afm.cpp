// libFuzzer target: the AFM readers (cpp/measure/afm) on arbitrary bytes. The input is read
// as a file named "input.ibw", so the content decides the format (zip: JPK or AFM Workshop
// map; "Force-Distance Curve": AFM Workshop CSV; tab-separated numbers: NT-MDT; version 5
// header: Igor). An InputError is the expected answer to bad input; anything else (another
// exception, a crash, a sanitizer report) is a bug and aborts. The readers' limits
// (cpp/measure/afm/read_limits.hpp) are checked on what they return; `make fuzz` runs this
// target with -malloc_limit_mb=256, so a bomb or a lying size that drives one allocation past
// the limits (the largest allowed: a 64 MiB CSV entry, a curve's 8 Mi-point channels growing)
// is a reported bug too.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"
#include "read_limits.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  coatcontact::afm::Calibration calibration;
  calibration.spring_constant = 0.1;  // so that files without calibration reach their data
  calibration.sensitivity = 5e-8;
  try {
    const auto curves = coatcontact::afm::read_force_curves_from_bytes(bytes, "input.ibw", calibration);
    for (const auto& c : curves) {
      // What a reader returns is complete: channels as long as the segments, finite values.
      if (c.force.size() != c.point_count()) std::abort();
      if (c.point_count() > coatcontact::afm::detail::kMaxCurvePoints) std::abort();
      if (c.segments.size() > static_cast<std::size_t>(coatcontact::afm::detail::kMaxSegments)) std::abort();
      for (double f : c.force) {
        if (!std::isfinite(f)) std::abort();
      }
    }
  } catch (const coatcontact::InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_afm: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
