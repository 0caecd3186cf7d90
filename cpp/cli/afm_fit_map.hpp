// `afm fit` over maps, several files or a folder (cmd_afm_map.cpp); the options it shares with
// the one-curve fit are parsed once (cmd_afm.cpp).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "coatcontact/afm_curve_fit.hpp"
#include "coatcontact/afm_fit.hpp"
#include "coatcontact/afm_readers.hpp"
#include "coatcontact/cli_support.hpp"
#include "coatcontact/force_curve.hpp"

namespace coatcontact::cli {

struct AfmFitSetup {
  fit::AfmFitProblem problem;
  bool coated = false;
  std::string modulus_name;  // "E" or "E1"
  std::string free_text;     // --free as given (or its default)
  std::string segment_name;  // "approach" or "retract"
  afm::SegmentKind kind = afm::SegmentKind::kApproach;
  fit::AfmRange range;
  fit::AfmBaselineModel baseline = fit::kAfmDefaultBaseline;  // --baseline-model
};

// The fit range options in words for a header ("whole segment" without any).
std::string fit_range_text(const fit::AfmRange& range);

// The header lines of a --layer stack: each layer (as other commands list a stack), the
// substrate and which layer's modulus is the fit's E1.
void add_afm_stack_lines(std::vector<std::pair<std::string, std::string>>& items, const fit::AfmCoating& coating);

// True when `afm fit` fits a batch: several FILEs, a FOLDER, --jobs/--resume/--map-plot, or one
// file of several curves without --index.
bool batch_mode(const Arguments& arguments, const afm::Calibration& calibration);

// One result row per curve (coatcontact/afm_batch.hpp) into one table.
int run_fit_map(const Arguments& arguments, const AfmFitSetup& setup, const afm::Calibration& calibration);

}  // namespace coatcontact::cli
