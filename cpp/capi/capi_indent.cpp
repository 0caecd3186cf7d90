// The C interface of the nanoindentation readers (coatcontact_indent.h): one handle holding
// the tests of a file, getters for channels, metadata, vendor results and calibration. Every
// entry point runs inside capi::guard (status codes, no exception crosses).
#include <cmath>
#include <cstring>
#include <memory>
#include <iterator>

#include "capi_guard.hpp"
#include "capi_indent.hpp"
#include "coatcontact/errors.hpp"

using coatcontact::InputError;
using coatcontact::indent::IndentTest;

namespace {

void require(const void* pointer, const char* function, const char* argument) {
  if (pointer == nullptr) throw InputError(std::string(function) + ": " + argument + " is NULL");
}

std::vector<std::string> channel_names(const IndentTest& t) {
  std::vector<std::string> names;
  const std::pair<const char*, std::size_t> standard[] = {
      {"depth", t.depth.size()},         {"load", t.load.size()},         {"time", t.time.size()},
      {"stiffness", t.stiffness.size()}, {"hardness", t.hardness.size()}, {"modulus", t.modulus.size()},
      {"segment", t.segment.size()}};
  for (const auto& [name, size] : standard) if (size > 0) names.emplace_back(name);
  for (const auto& entry : t.extra) names.push_back(entry.first);
  return names;
}

const std::vector<double>* channel(const IndentTest& t, const std::string& name) {
  if (name == "depth") return &t.depth;
  if (name == "load") return &t.load;
  if (name == "time") return &t.time;
  if (name == "stiffness") return &t.stiffness;
  if (name == "hardness") return &t.hardness;
  if (name == "modulus") return &t.modulus;
  const auto found = t.extra.find(name);
  return found == t.extra.end() ? nullptr : &found->second;
}

void check_entry(long entry, std::size_t size, const char* function) {
  if (entry < 0 || static_cast<std::size_t>(entry) >= size) {
    throw InputError(std::string(function) + ": entry " + std::to_string(entry) + " is out of range 0.." +
                     std::to_string(static_cast<long>(size) - 1));
  }
}

}  // namespace

namespace coatcontact::capi {

const IndentTest& indent_test(const cc_indent_tests* tests, long index, const char* function) {
  require(tests, function, "tests");
  if (index < 0 || static_cast<std::size_t>(index) >= tests->tests.size()) {
    throw InputError(std::string(function) + ": test index " + std::to_string(index) + " is out of range 0.." +
                     std::to_string(static_cast<long>(tests->tests.size()) - 1));
  }
  return tests->tests[static_cast<std::size_t>(index)];
}

}  // namespace coatcontact::capi

using coatcontact::capi::guard;
using coatcontact::capi::indent_test;

extern "C" {

int cc_indent_read(const char* path, cc_indent_tests** tests) {
  return guard([&] {
    require(path, "cc_indent_read", "path");
    require(tests, "cc_indent_read", "tests");
    auto made = std::make_unique<cc_indent_tests>();
    made->tests = coatcontact::indent::read_indentation(path);
    for (const auto& t : made->tests) made->channel_names.push_back(channel_names(t));
    *tests = made.release();
  });
}

void cc_indent_tests_destroy(cc_indent_tests* tests) { delete tests; }

int cc_indent_count(const cc_indent_tests* tests, long* count) {
  return guard([&] {
    require(tests, "cc_indent_count", "tests");
    require(count, "cc_indent_count", "count");
    *count = static_cast<long>(tests->tests.size());
  });
}

int cc_indent_name(const cc_indent_tests* tests, long index, const char** name) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_name");
    require(name, "cc_indent_name", "name");
    *name = t.name.c_str();
  });
}

int cc_indent_points(const cc_indent_tests* tests, long index, long* points) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_points");
    require(points, "cc_indent_points", "points");
    *points = static_cast<long>(t.depth.size());
  });
}

int cc_indent_channel_count(const cc_indent_tests* tests, long index, long* count) {
  return guard([&] {
    indent_test(tests, index, "cc_indent_channel_count");
    require(count, "cc_indent_channel_count", "count");
    *count = static_cast<long>(tests->channel_names[static_cast<std::size_t>(index)].size());
  });
}

int cc_indent_channel_name(const cc_indent_tests* tests, long index, long channel, const char** name) {
  return guard([&] {
    indent_test(tests, index, "cc_indent_channel_name");
    require(name, "cc_indent_channel_name", "name");
    const auto& names = tests->channel_names[static_cast<std::size_t>(index)];
    check_entry(channel, names.size(), "cc_indent_channel_name");
    *name = names[static_cast<std::size_t>(channel)].c_str();
  });
}

int cc_indent_channel(const cc_indent_tests* tests, long index, const char* name, double* values, long capacity,
                      long* length) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_channel");
    require(name, "cc_indent_channel", "name");
    require(length, "cc_indent_channel", "length");
    const std::string wanted(name);
    std::vector<double> segment;
    const std::vector<double>* data = channel(t, wanted);
    if (wanted == "segment" && !t.segment.empty()) {
      segment.assign(t.segment.begin(), t.segment.end());
      data = &segment;
    }
    if (data == nullptr || data->empty()) {
      throw InputError("cc_indent_channel: test '" + t.name + "' has no channel '" + wanted + "'");
    }
    if (capacity < static_cast<long>(data->size())) {
      throw InputError("cc_indent_channel: capacity " + std::to_string(capacity) + " is below the " +
                       std::to_string(data->size()) + " points of '" + wanted + "'");
    }
    require(values, "cc_indent_channel", "values");
    std::memcpy(values, data->data(), data->size() * sizeof(double));
    *length = static_cast<long>(data->size());
  });
}

int cc_indent_metadata_count(const cc_indent_tests* tests, long index, long* count) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_metadata_count");
    require(count, "cc_indent_metadata_count", "count");
    *count = static_cast<long>(t.metadata.size());
  });
}

int cc_indent_metadata_entry(const cc_indent_tests* tests, long index, long entry, const char** key, const char** value) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_metadata_entry");
    require(key, "cc_indent_metadata_entry", "key");
    require(value, "cc_indent_metadata_entry", "value");
    check_entry(entry, t.metadata.size(), "cc_indent_metadata_entry");
    const auto it = std::next(t.metadata.begin(), entry);
    *key = it->first.c_str();
    *value = it->second.c_str();
  });
}

int cc_indent_result_count(const cc_indent_tests* tests, long index, long* count) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_result_count");
    require(count, "cc_indent_result_count", "count");
    *count = static_cast<long>(t.vendor_results.size());
  });
}

int cc_indent_result_entry(const cc_indent_tests* tests, long index, long entry, const char** key, double* value) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_result_entry");
    require(key, "cc_indent_result_entry", "key");
    require(value, "cc_indent_result_entry", "value");
    check_entry(entry, t.vendor_results.size(), "cc_indent_result_entry");
    const auto it = std::next(t.vendor_results.begin(), entry);
    *key = it->first.c_str();
    *value = it->second;
  });
}

int cc_indent_calibration_get(const cc_indent_tests* tests, long index, cc_indent_calibration* calibration) {
  return guard([&] {
    const auto& t = indent_test(tests, index, "cc_indent_calibration_get");
    require(calibration, "cc_indent_calibration_get", "calibration");
    const auto& c = t.calibration;
    cc_indent_calibration out{};
    out.area_coefficients = c.area.coefficients.empty() ? nullptr : c.area.coefficients.data();
    out.area_count = static_cast<long>(c.area.coefficients.size());
    out.frame_stiffness = c.frame_stiffness;
    out.poisson = c.poisson;
    out.beta = c.beta;
    out.eps = c.eps;
    out.range_min = c.range_min;
    out.range_max = c.range_max;
    out.tip = c.tip.c_str();
    out.source = c.source.c_str();
    *calibration = out;
  });
}

}  // extern "C"
