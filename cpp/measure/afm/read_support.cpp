// Shared helpers of the AFM readers: messages, numbers, calibration choice, curve checks.
#include "read_support.hpp"

#include <charconv>
#include <cmath>
#include <cstdio>

namespace coatcontact::afm::detail {

void fail(const std::string& file, const std::string& entry, const std::string& message) {
  throw InputError(file + ": " + (entry.empty() ? std::string() : entry + ": ") + message);
}

std::string_view trim(std::string_view text) {
  const auto blank = [](char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n'; };
  while (!text.empty() && blank(text.front())) text.remove_prefix(1);
  while (!text.empty() && blank(text.back())) text.remove_suffix(1);
  return text;
}

bool parse_double(std::string_view text, double& value) {
  text = trim(text);
  if (!text.empty() && text.front() == '+') text.remove_prefix(1);
  if (text.empty()) return false;
  double parsed = 0.0;
  const auto result = std::from_chars(text.data(), text.data() + text.size(), parsed);
  if (result.ec != std::errc() || result.ptr != text.data() + text.size()) return false;
  value = parsed;
  return true;
}

std::string number_text(double value) {
  char buffer[32];
  for (int digits = 6; digits <= 17; ++digits) {
    std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
    double back = 0.0;
    if (parse_double(buffer, back) && back == value) break;
  }
  return buffer;
}

CalibrationChoice choose_calibration(const Calibration& user, const double* file_spring_constant,
                                     const double* file_sensitivity, bool need_k, bool need_s,
                                     const std::string& file, const std::string& entry,
                                     const std::string& where) {
  CalibrationChoice choice;
  if (user.spring_constant) {
    choice.spring_constant = *user.spring_constant;
    choice.spring_constant_source = CalibrationSource::kUser;
  } else if (file_spring_constant) {
    choice.spring_constant = *file_spring_constant;
    choice.spring_constant_source = CalibrationSource::kFile;
  }
  if (user.sensitivity) {
    choice.sensitivity = *user.sensitivity;
    choice.sensitivity_source = CalibrationSource::kUser;
  } else if (file_sensitivity) {
    choice.sensitivity = *file_sensitivity;
    choice.sensitivity_source = CalibrationSource::kFile;
  }
  // A file's value is held to the rule of the user's (check_calibration): 0 would give an
  // all-zero force, a negative one a flipped force.
  const auto check_file_value = [&](CalibrationSource source, double value, const char* name, const char* option,
                                    const char* unit) {
    if (source != CalibrationSource::kFile || (std::isfinite(value) && value > 0.0)) return;
    throw InputError(file + ": " + (entry.empty() ? std::string() : entry + ": ") + "the file's " + name + " " +
                     number_text(value) + " " + unit + " (" + where + ") is not allowed; it must be a finite number > 0: give the right value with " +
                     option);
  };
  check_file_value(choice.spring_constant_source, choice.spring_constant, "spring constant", "--spring-constant K[N/m] (Python: spring_constant=)", "N/m");
  check_file_value(choice.sensitivity_source, choice.sensitivity, "sensitivity", "--sensitivity S[m/V] (Python: sensitivity=)", "m/V");
  const bool missing_k = need_k && choice.spring_constant_source == CalibrationSource::kNone;
  const bool missing_s = need_s && choice.sensitivity_source == CalibrationSource::kNone;
  choice.complete = !(missing_k || missing_s);
  if (!choice.complete && !user.allow_missing) {
    std::string what, how;
    if (missing_k && missing_s) {
      what = "no spring constant and no sensitivity";
      how = "give them with --spring-constant K[N/m] and --sensitivity S[m/V] (Python: spring_constant=, sensitivity=)";
    } else if (missing_k) {
      what = "no spring constant";
      how = "give it with --spring-constant K[N/m] (Python: spring_constant=)";
    } else {
      what = "no sensitivity";
      how = "give it with --sensitivity S[m/V] (Python: sensitivity=)";
    }
    throw MissingCalibration(file + ": " + (entry.empty() ? std::string() : entry + ": ") + what + " in the file (" + where +
                             "); the force needs it: " + how);
  }
  return choice;
}

void set_calibration(CurveMetadata& metadata, const CalibrationChoice& choice) {
  metadata.spring_constant = choice.spring_constant;
  metadata.spring_constant_source = choice.spring_constant_source;
  metadata.sensitivity = choice.sensitivity;
  metadata.sensitivity_source = choice.sensitivity_source;
}

void finish_curve(ForceCurve& curve, const std::string& file, const std::string& entry) {
  if (curve.segments.empty()) fail(file, entry, "no segments");
  const std::size_t n = curve.segments.back().end;
  std::size_t expected_begin = 0;
  for (std::size_t s = 0; s < curve.segments.size(); ++s) {
    const Segment& segment = curve.segments[s];
    if (segment.begin != expected_begin || segment.end < segment.begin) {
      fail(file, entry, "segment " + std::to_string(s) + " is not contiguous with the previous one");
    }
    if (segment.size() == 0) {
      fail(file, entry, "segment " + std::to_string(s) + " (" + segment_kind_name(segment.kind) + ") is empty");
    }
    expected_begin = segment.end;
  }
  if (curve.force.empty() && !(curve.metadata.spring_constant_source == CalibrationSource::kNone ||
                               curve.metadata.sensitivity_source == CalibrationSource::kNone)) {
    fail(file, entry, "no force channel");
  }
  const auto check_length = [&](const std::vector<double>& channel, const char* name) {
    if (!channel.empty() && channel.size() != n) {
      fail(file, entry, std::string("channel ") + name + " has " + std::to_string(channel.size()) +
                            " points, the segments " + std::to_string(n));
    }
    for (double v : channel) {
      if (!std::isfinite(v)) {
        throw NonFiniteValue(file + ": " + (entry.empty() ? std::string() : entry + ": ") + "channel " + name +
                             " holds a value that is not finite");
      }
    }
  };
  check_length(curve.force, "force");
  check_length(curve.height_piezo, "height (piezo)");
  check_length(curve.height_measured, "height (measured)");
  check_length(curve.time, "time");
  if (!curve.has_height_piezo() && !curve.has_height_measured()) {
    fail(file, entry, "no height channel (neither piezo nor measured height)");
  }
  curve.segment.assign(n, 0);
  for (std::size_t s = 0; s < curve.segments.size(); ++s) {
    for (std::size_t i = curve.segments[s].begin; i < curve.segments[s].end; ++i) {
      curve.segment[i] = static_cast<int>(s);
    }
  }
}

}  // namespace coatcontact::afm::detail
