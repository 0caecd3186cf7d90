// Internal helpers of the AFM readers (not a public header): errors naming the file, number
// parsing, calibration bookkeeping, and the readers' entry points.
#pragma once
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "coatcontact/afm_readers.hpp"
#include "coatcontact/errors.hpp"

namespace coatcontact::afm::detail {

// InputError "<file>: <message>" (or "<file>: <entry>: <message>" when entry is not empty).
[[noreturn]] void fail(const std::string& file, const std::string& entry, const std::string& message);

// Locale-independent decimal number occupying all of `text` (blanks around it ignored).
bool parse_double(std::string_view text, double& value);
std::string_view trim(std::string_view text);
// "%.17g"-free shortest text of a double for messages.
std::string number_text(double value);

// The calibration of one curve: the user's value over the file's. `need_k`/`need_s`: whether
// the force of this file needs the value; a needed value missing from both is an InputError
// naming the option that supplies it.
struct CalibrationChoice {
  double spring_constant = 0.0;
  CalibrationSource spring_constant_source = CalibrationSource::kNone;
  double sensitivity = 0.0;
  CalibrationSource sensitivity_source = CalibrationSource::kNone;
  bool complete = true;  // every value the force needs is known (else: allow_missing, no force)
};
CalibrationChoice choose_calibration(const Calibration& user, const double* file_spring_constant,
                                     const double* file_sensitivity, bool need_k, bool need_s,
                                     const std::string& file, const std::string& entry,
                                     const std::string& where);
void set_calibration(CurveMetadata& metadata, const CalibrationChoice& choice);

// Fills segment indices and checks the channel lengths and segments (non-empty, contiguous).
void finish_curve(ForceCurve& curve, const std::string& file, const std::string& entry);

// Readers on the file's bytes; `file` names it in messages and metadata.
std::vector<ForceCurve> read_jpk(const std::string& bytes, const std::string& file, const Calibration& user);
std::vector<ForceCurve> read_igor(const std::string& bytes, const std::string& file, const Calibration& user);
std::vector<ForceCurve> read_afm_workshop_csv(const std::string& text, const std::string& file,
                                              const std::string& entry, const Calibration& user);
std::vector<ForceCurve> read_afm_workshop_zip(const std::string& bytes, const std::string& file,
                                              const Calibration& user);
// The same, a curve that cannot be read left in its place (metadata: file and entry) with its
// InputError's message in errors[i] (empty for a curve read); MissingCalibration is thrown.
std::vector<ForceCurve> read_afm_workshop_entries(const std::string& bytes, const std::string& file,
                                                  const Calibration& user, std::vector<std::string>& errors);
std::vector<ForceCurve> read_ntmdt_text(const std::string& text, const std::string& file,
                                        const Calibration& user);

// The format of a file from its bytes and name (kJpk for any JPK archive).
FileFormat detect_format_of(const std::string& bytes, const std::string& file);

}  // namespace coatcontact::afm::detail
