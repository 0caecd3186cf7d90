// JKR retract fits on a coating with E1 and w free (THEORY.md section 15, "The JKR search on a
// coating"): the coarse stage, the three nodes and the anchored model against the direct path
// (a reduced-solver sweep at every trial E1, AfmCoating::direct), and a map's rows against the
// single-curve fits.
//  - Real curves (spot3, Igor U3_3, flipsign; their retracts as a film of 10 kPa, nu 0.5,
//    t = 2 um on 1 MPa, R = 10 um): E1, w and z_c within 1/100 of their standard errors of the
//    direct path's, or, where the two searches end in different minima of a rough profile
//    (U3_3: E1 0.5 SE apart, both sums within 5e-5), the tabled estimates a lower point of the
//    direct path's own sum; the direct model at the tabled estimates has the tabled sum (2e-5).
//  - A synthetic coated map (make_afm_map --jkr: the library's JKR spring model, film 100 kPa,
//    t = 4 um on 1 MPa, E1 started 2.5x off), truth known: every batch row (afm_fit_curve_row,
//    shared nodes, the curves in map order) equals the single-curve fit (afm_fit_curve, nodes
//    dropped before it) bit for bit; on three fitted curves the tabled fit equals the direct one
//    within SE/100 and the truth within 3 SE.
// Usage: test_afm_jkr_coated_search DATA_DIR MAKE_AFM_MAP WORK_DIR
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "check.hpp"
#include "coatcontact/afm_batch.hpp"
#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_readers.hpp"

namespace fit = coatcontact::fit;
namespace afm = coatcontact::afm;

namespace {

fit::AfmBatchSettings jkr_request(double film, double thickness) {
  fit::AfmBatchSettings r;
  r.problem.model = fit::AfmModel::kJkr;
  r.problem.tip = fit::afm_paraboloid(10e-6);
  fit::AfmCoating c;
  c.film = {film, 0.5};
  c.substrate.material = {1e6, 0.3};
  c.thickness = thickness;
  r.problem.coating = c;
  r.problem.poisson = 0.5;
  r.problem.free.work = true;
  r.problem.free.tilt = true;
  r.segment = afm::SegmentKind::kRetract;
  r.check_jump_in = false;
  return r;
}

// The tabled fit (as the CLI runs it) and the direct path's on the same curve: E1, w, z_c within SE/100.
fit::AfmFitResult check_against_direct(const afm::ForceCurve& curve, fit::AfmBatchSettings request, const std::string& name) {
  const fit::AfmCurveFit tabled = fit::afm_fit_curve(curve, request);
  request.problem.coating->direct = true;
  const fit::AfmCurveFit direct = fit::afm_fit_curve(curve, request);
  const fit::AfmFitResult& a = tabled.result;
  const fit::AfmFitResult& b = direct.result;
  const double ze = (a.modulus - b.modulus) / b.modulus_error, zw = (a.work - b.work) / b.work_error;
  const double zc = (a.contact_point - b.contact_point) / b.contact_point_error;
  std::printf("%s: E1 %.8g (direct %.8g +- %.4g, %.2g SE) w %.8g (direct %.8g +- %.4g, %.2g SE) z_c %.2g SE; "
              "rss %.6g (direct %.6g); solves %ld (direct %ld), %.0f ms (direct %.0f ms)\n",
              name.c_str(), a.modulus, b.modulus, b.modulus_error, ze, a.work, b.work, b.work_error, zw, zc, a.rss, b.rss, a.solver_calls,
              b.solver_calls, 1e3 * a.seconds, 1e3 * b.seconds);
  // The direct model (a sweep at the estimate's E1) at the tabled estimates: its sum of squares
  // is the tabled fit's (the models agree, whatever minimum each search ends in).
  const std::vector<double> model = fit::afm_model_force(tabled.fitted, [&] {
    std::vector<double> z;
    for (std::size_t i : tabled.kept) z.push_back(tabled.z_segment[i]);
    return z;
  }());
  double rss = 0.0;
  for (std::size_t k = 0; k < model.size(); ++k) rss += std::pow(tabled.f_segment[tabled.kept[k]] - model[k], 2);
  std::printf("%s: the direct model's rss at the tabled estimates / the tabled rss - 1 = %.2g\n", name.c_str(), rss / a.rss - 1);
  // (the tables' ~1e-6 relative differences move a sum of n sigma^2 by ~1e-6..1e-5: measured <= 7e-6)
  check::below(std::abs(rss / a.rss - 1), 2e-5, name + ": the direct model at the tabled estimates has the tabled fit's rss");
  if (std::abs(ze) > 0.01 || std::abs(zw) > 0.01 || std::abs(zc) > 0.01) {
    // The searches' paths parted on a rough profile and ended in two minima: then the tabled
    // estimates must be the better point of the direct path's own sum.
    std::printf("%s: two minima; the direct sum at the tabled estimates / the direct fit's - 1 = %.2g\n", name.c_str(), rss / b.rss - 1);
    check::below(rss, b.rss, name + ": not within SE/100 of the direct fit, so a lower point of its own sum");
  }
  return a;
}

void check_real_curves(const std::string& data) {
  for (const char* file : {"fmt-jpk-fd_spot3-0192.jpk-force", "fmt-igor-fd_U3_3_p10004.ibw",
                           "fmt-jpk-fd_flipsign_2015.05.22-15.31.49.352.jpk-force"}) {
    fit::afm_clear_shared_sweeps();
    const afm::ForceCurve curve = afm::read_force_curves(data + "/" + file).at(0);
    check_against_direct(curve, jkr_request(10e3, 2e-6), file);
  }
}

struct Truth {
  double modulus = 0.0, work = 0.0;
  int flag = 0;
};

// The truth file of make_afm_map: curve, ..., E (column 4), ..., flag (8), w (9).
std::map<std::size_t, Truth> read_truth(const std::string& path) {
  std::map<std::size_t, Truth> out;
  std::ifstream in(path);
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream row(line);
    std::string cell;
    while (std::getline(row, cell, '\t')) cells.push_back(cell);
    if (cells.size() < 9) continue;
    out[std::stoul(cells[0])] = {std::stod(cells[3]), std::stod(cells[8]), std::stoi(cells[7])};
  }
  return out;
}

void check_map(const std::string& make_map, const std::string& work) {
  const std::string map = work + "/jkr.jpk-force-map", truth_file = work + "/jkr_truth.tsv";
  const std::string command = "'" + make_map + "' '" + map + "' 4 4 --seed 5 --jkr --truth '" + truth_file + "'";
  check::that(std::system(command.c_str()) == 0, "make_afm_map --jkr");
  const std::map<std::size_t, Truth> truth = read_truth(truth_file);
  const fit::AfmBatchSettings request = jkr_request(250e3, 4e-6);
  // The batch's rows (two threads, nodes shared by the curves).
  fit::afm_clear_shared_sweeps();
  std::vector<fit::AfmCurveRow> rows;
  fit::AfmBatchOptions options;
  options.jobs = 2;
  options.sink = [&](const std::vector<fit::AfmCurveRow>& chunk) { rows.insert(rows.end(), chunk.begin(), chunk.end()); };
  fit::afm_fit_batch({map}, {}, request, options);
  check::that(rows.size() == 16 && truth.size() == 16, "a 4 x 4 map and its truth");
  const afm::CurveSource source(map);
  int compared = 0, checked_direct = 0;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].flag != fit::AfmFlag::kFitted) continue;
    const afm::ForceCurve curve = source.read(rows[i].curve_index);
    fit::afm_clear_shared_sweeps();  // the single fit from no shared nodes
    const fit::AfmCurveFit single = fit::afm_fit_curve(curve, request);
    const std::vector<fit::AfmBatchParameter> parameters = fit::afm_batch_parameters(request.problem);
    bool equal = rows[i].estimates.size() == parameters.size() && parameters.size() == 5;
    for (std::size_t k = 0; equal && k < parameters.size(); ++k) {
      equal = rows[i].estimates[k] == single.result.*parameters[k].value && rows[i].errors[k] == single.result.*parameters[k].error;
    }
    check::that(equal, "curve " + std::to_string(i) + ": the map row equals the single-curve fit bit for bit");
    ++compared;
    if (checked_direct < 3) {
      ++checked_direct;
      fit::afm_clear_shared_sweeps();
      const fit::AfmFitResult r = check_against_direct(curve, request, "map curve " + std::to_string(i));
      const Truth& t = truth.at(rows[i].curve_index);
      std::printf("map curve %zu: E1 %.2f SE, w %.2f SE from the truth\n", i, (r.modulus - t.modulus) / r.modulus_error,
                  (r.work - t.work) / r.work_error);
      check::below(std::abs(r.modulus - t.modulus), 3.0 * r.modulus_error, "map curve " + std::to_string(i) + ": E1 within 3 SE of the truth");
      check::below(std::abs(r.work - t.work), 3.0 * r.work_error, "map curve " + std::to_string(i) + ": w within 3 SE of the truth");
    }
  }
  std::printf("map: %d fitted rows compared with their single fits\n", compared);
  check::that(compared >= 10, "most curves of the map fitted");
}

}  // namespace

int main(int argc, char** argv) {
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  if (argc != 4) {
    std::fprintf(stderr, "usage: test_afm_jkr_coated_search DATA_DIR MAKE_AFM_MAP WORK_DIR\n");
    return 2;
  }
  std::filesystem::create_directories(argv[3]);
  check_real_curves(argv[1]);
  check_map(argv[2], argv[3]);
  return check::exit_code();
}
