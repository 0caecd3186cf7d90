// Readers of AFM force-curve files (cpp/measure/afm/): one entry point, the format chosen by
// content and extension. Every reader converts to SI and fills the same ForceCurve.
//   JPK        .jpk-force, .jpk-force-map, .jpk-qi-data, .jpk-qi-series (zip archives)
//   Asylum     .ibw (Igor binary wave, version 5)
//   AFM Workshop  .csv (one curve) and .zip (a map of such CSVs)
//   NT-MDT     .txt (Nova text export: height, extend and retract deflection, decimal commas)
// Errors are InputError naming the file (and archive entry) and the reason: unknown format,
// truncated or corrupt archive, missing channel, empty segment, and missing calibration (the
// message names --spring-constant / --sensitivity, Python spring_constant= / sensitivity=).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/force_curve.hpp"

namespace coatcontact::afm {

// Values given by the user; each one overrides the file's and is marked kUser in the metadata.
struct Calibration {
  std::optional<double> spring_constant;  // [N/m]
  std::optional<double> sensitivity;      // [m/V]
  // true: a file without the calibration its force needs is read all the same, with an empty
  // force channel (for listing what a file holds); false: that is an InputError.
  bool allow_missing = false;
};

enum class FileFormat { kJpk, kIgorBinaryWave, kAfmWorkshopCsv, kAfmWorkshopZip, kNtmdtText };
const char* file_format_name(FileFormat format);

// The format of `path` from its first bytes and its extension; InputError if none fits.
FileFormat detect_format(const std::string& path);

// Every curve in the file, in file order (one for single-curve files).
std::vector<ForceCurve> read_force_curves(const std::string& path, const Calibration& calibration = {});

// The same on a file's bytes held in memory; `name` stands for the file in messages and
// decides the format where the content alone does not (.ibw).
std::vector<ForceCurve> read_force_curves_from_bytes(const std::string& bytes, const std::string& name,
                                                     const Calibration& calibration = {});

// Validates a user-supplied value (finite, > 0); `option` names it in the message.
void check_calibration(const Calibration& calibration);

}  // namespace coatcontact::afm
