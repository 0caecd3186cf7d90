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
#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "coatcontact/errors.hpp"
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

// The InputErrors of one curve that a batch tells apart (coatcontact/afm_batch.hpp flags them):
// a calibration value the force needs is missing; a segment holds no points; a channel holds
// a value that is not finite (NaN, inf: the curve's data are bad, the file is readable).
class MissingCalibration : public InputError {
 public:
  using InputError::InputError;
};
class EmptySegment : public InputError {
 public:
  using InputError::InputError;
};
class NonFiniteValue : public InputError {
 public:
  using InputError::InputError;
};

// The curves of one file read one at a time: a JPK archive is opened from its file and each
// curve's entries are read on demand, so a map's memory is one curve (and the archive's
// directory), not the map; the other formats (one curve, or a small zipped map) are read whole
// when the source is opened. The constructor throws InputError when the file cannot be read at
// all (missing, not a regular file, unknown format, corrupt archive); read() throws InputError
// (MissingCalibration, EmptySegment) for that curve alone. One source per thread.
class CurveSource {
 public:
  explicit CurveSource(const std::string& path, const Calibration& calibration = {});
  ~CurveSource();
  CurveSource(const CurveSource&) = delete;
  CurveSource& operator=(const CurveSource&) = delete;
  const std::string& path() const;
  FileFormat format() const;
  std::size_t size() const;
  ForceCurve read(std::size_t index) const;
  // The grid index and position of curve `index` as far as they can be read without its
  // segments (a JPK map's curve header); only the index where nothing more is known. No throw.
  CurveMetadata place(std::size_t index) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// The AFM files directly inside `folder` (by extension: .jpk-force, .jpk-force-map,
// .jpk-qi-data, .jpk-qi-series, .ibw, .csv, .zip, .txt), sorted by name; InputError if none.
std::vector<std::string> afm_files_in_folder(const std::string& folder);

// Validates a user-supplied value (finite, > 0); `option` names it in the message.
void check_calibration(const Calibration& calibration);

}  // namespace coatcontact::afm
