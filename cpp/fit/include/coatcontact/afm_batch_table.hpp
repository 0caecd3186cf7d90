// The TSV table of a batch of AFM fits (afm fit over maps, files, folders; THEORY.md section
// 15, "Many curves"): its header, one line per row (afm_batch.hpp's AfmCurveRow) and the
// flagged count that closes it. The CLI's `afm fit` and the C API (cc_afm_rows_write_table)
// write the table through these functions, so both write the same bytes.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "coatcontact/afm_batch.hpp"
#include "coatcontact/detail/table_text.hpp"

namespace coatcontact::fit {

// What the header states of the run besides the fit's settings.
struct AfmBatchTableRun {
  std::vector<std::string> files;
  std::vector<AfmFileSurvey> survey;  // one per file
  std::size_t total = 0;              // curves of the run
  afm::Calibration calibration;       // the user's values, for every curve
  std::string free_text;              // the free parameters as given (the CLI's --free)
  std::string command_line;           // the "# command:" line; empty: none
};

struct AfmBatchTable {
  std::vector<AfmBatchParameter> parameters;  // afm_batch_parameters
  bool contact_point_column = false;          // a fixed contact point has its own column
  std::vector<std::string> columns;
  std::string header;  // the header lines without the flagged count
  // The rating cell's column (the rows sort by it).
  std::size_t rating_column() const { return columns.size() - 4; }
};

AfmBatchTable afm_batch_table(const AfmBatchSettings& settings, const AfmBatchTableRun& run);

// One TSV line of a row, ending in a line end; "-" where a curve has no value (its flag says why).
std::string afm_batch_row_line(const AfmCurveRow& row, const AfmBatchTable& table);

// "N of M (no_contact 2, ...)": the flagged curves of a run from its rows' flags.
std::string afm_batch_flagged_text(const std::size_t (&by_flag)[kAfmFlagCount], std::size_t total);

// The header with "# flagged curves: TEXT" before its columns line (the finished table's).
std::string afm_batch_final_header(const std::string& header, const std::string& flagged_text);

// A file's name as a cell: one starting with '#' would read as a comment line ("./#x").
std::string afm_table_file_name(const std::string& path);

// The fit range in words for a header ("whole segment" without any).
std::string afm_fit_range_text(const AfmRange& range);

// The header lines of a stack sample: each layer (as every output lists a stack), the
// substrate and which layer's modulus is free.
void add_afm_stack_items(detail::HeaderItems& items, const AfmCoating& coating);

}  // namespace coatcontact::fit
