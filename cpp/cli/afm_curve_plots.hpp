// `afm fit ... --curve-plots FILE.pdf`: one control-plot page per curve of a batch
// (gnuplot/afm_curve_plots.gp). The pages' data go to a private temporary file as the rows
// arrive (chunk by chunk), so a run holds no curve beyond its chunks; gnuplot draws them all at
// the end.
#pragma once
#include <fstream>
#include <string>
#include <vector>

#include "coatcontact/afm_batch.hpp"

namespace coatcontact::cli {

class AfmCurvePlots {
 public:
  // `parameters`: the batch's columns (afm_batch_parameters), named in each page's estimates line.
  explicit AfmCurvePlots(std::vector<fit::AfmBatchParameter> parameters, bool retract_fit);
  ~AfmCurvePlots();
  AfmCurvePlots(const AfmCurvePlots&) = delete;
  AfmCurvePlots& operator=(const AfmCurvePlots&) = delete;

  void add(const fit::AfmCurveRow& row);  // one page (rows in the table's order)
  std::size_t pages() const { return pages_; }
  // The PDF; NumericalError (exit 3) when gnuplot warns, InputError when it fails.
  std::string render();

 private:
  std::vector<fit::AfmBatchParameter> parameters_;
  bool retract_fit_;
  std::string data_path_;
  std::ofstream data_;
  std::string settings_;  // the per-page array assignments
  std::size_t pages_ = 0;
};

}  // namespace coatcontact::cli
