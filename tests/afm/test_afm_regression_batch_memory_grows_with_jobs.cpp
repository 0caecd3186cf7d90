// Regression of issue 40 item 3, "batch memory grows with --jobs" (1.7 GB at 16 jobs): a chunk
// of a batch held 16 curves per thread, two chunks at once, so the curves held grew with the
// threads (32 x jobs curves of ~0.9 MB on a real JPK map). Now a chunk also ends at
// AfmBatchOptions::chunk_bytes of curves. The map is made here of the real curves of
// data/afm/fmt-jpk-fd_map2x2_extracted.jpk-force-map (its curves 0 and 1, 24 060 points each,
// copied to index/0..11 through libzip). The batch's own accounting (AfmBatchSummary: curves
// and curve bytes held at once) is checked against bounds computed here from the curves as
// read, at 1, 4, 16 and 64 jobs; the rows must not depend on the jobs. No timing, no RSS.
// Usage: test_afm_regression_batch_memory_grows_with_jobs DATA_DIR WORK_DIR
#include <zip.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "check.hpp"
#include "zip_entries.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_readers.hpp"

namespace afm = coatcontact::afm;
namespace fit = coatcontact::fit;

namespace {

constexpr std::size_t kCurves = 12;

using Entry = coatcontact_test::ZipEntry;

// The real map's own entries, and index/N/... copied from index/(N % 2)/... for N < kCurves
// (stored uncompressed: the test fits, it does not time compression).
std::string make_map(const std::string& data_dir, const std::string& work) {
  const std::vector<Entry> source = coatcontact_test::zip_entries(data_dir + "/fmt-jpk-fd_map2x2_extracted.jpk-force-map");
  std::vector<Entry> entries;
  for (const Entry& e : source) {
    if (e.name.rfind("index/", 0) != 0) entries.push_back(e);
  }
  for (std::size_t n = 0; n < kCurves; ++n) {
    const std::string from = "index/" + std::to_string(n % 2) + "/";
    for (const Entry& e : source) {
      if (e.name.rfind(from, 0) == 0) entries.push_back({"index/" + std::to_string(n) + "/" + e.name.substr(from.size()), e.data});
    }
  }
  const std::string path = work + "/real12.jpk-force-map";
  coatcontact_test::write_zip(path, entries, true);
  return path;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: test_afm_regression_batch_memory_grows_with_jobs DATA_DIR WORK_DIR\n");
    return 2;
  }
  std::filesystem::create_directories(argv[2]);
  const std::string map = make_map(argv[1], argv[2]);

  // The curves as read: each at least its per-point arrays (counted here from the point count
  // and the channels the curve has), at most afm_curve_bytes; all of one size here.
  const afm::CurveSource source(map, {});
  check::that(source.size() == kCurves, "the map made here has 12 curves");
  std::size_t curve_bytes = 0, floor_bytes = 0;
  for (std::size_t i = 0; i < source.size(); ++i) {
    const afm::ForceCurve c = source.read(i);
    const std::size_t arrays = !c.force.empty() + !c.height_piezo.empty() + !c.height_measured.empty() + !c.time.empty();
    floor_bytes = std::max(floor_bytes, c.point_count() * (arrays * sizeof(double) + sizeof(int)));
    curve_bytes = std::max(curve_bytes, fit::afm_curve_bytes(c));
  }
  check::that(floor_bytes >= 24060 * (sizeof(double) + sizeof(int)), "a real curve holds its 24 060 points");
  check::that(curve_bytes >= floor_bytes, "afm_curve_bytes counts at least the per-point arrays");

  // A budget of 2.5 curves: a chunk takes 3 curves (it stops at the curve that reaches the
  // budget), so at most 6 are held whatever the jobs; before, 16 x jobs per chunk held all 12
  // from 1 job on (2 chunks of 16 > 12).
  fit::AfmBatchSettings settings;
  settings.problem.tip = fit::afm_paraboloid(5e-6);
  settings.problem.modulus = 1e3;
  fit::AfmBatchOptions options;
  options.chunk_bytes = curve_bytes * 5 / 2;
  std::vector<double> first_estimates;
  for (const unsigned jobs : {1u, 4u, 16u, 64u}) {
    options.jobs = jobs;
    std::vector<double> estimates;
    options.sink = [&](const std::vector<fit::AfmCurveRow>& rows) {
      for (const fit::AfmCurveRow& r : rows) estimates.insert(estimates.end(), r.estimates.begin(), r.estimates.end());
    };
    const fit::AfmBatchSummary s = fit::afm_fit_batch({map}, {}, settings, options);
    const std::string at = " at --jobs " + std::to_string(jobs);
    check::that(s.fitted == kCurves, "every curve fitted" + at);
    check::that(s.peak_curves_held <= 6, "at most two chunks of 3 curves held" + at + " (held " +
                                              std::to_string(s.peak_curves_held) + ")");
    check::that(s.peak_curve_bytes <= 2 * (options.chunk_bytes + curve_bytes),
                "curve bytes held within two chunks' budget" + at + " (held " + std::to_string(s.peak_curve_bytes) + ")");
    check::that(s.peak_curve_bytes >= 2 * floor_bytes, "the accounting counts the curves held" + at);
    if (first_estimates.empty()) first_estimates = estimates;
    check::that(estimates == first_estimates, "the rows do not depend on the jobs" + at);
  }
  check::that(first_estimates.size() == 3 * kCurves, "E, contact point and baseline of every curve");

  // The default budget: 32 curves of a real map, far below what 16 jobs held before (~460 MB).
  check::that(fit::kAfmBatchChunkBytes <= 40 * curve_bytes, "the default chunk budget holds about 32 real curves");
  return check::exit_code();
}
