// libFuzzer target: every value parser and Arguments on arbitrary bytes. An InputError is the
// expected answer to bad input; anything else (crash, sanitizer report, another exception,
// a returned value outside the documented range) is a bug and aborts.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "coatcontact/cli_support.hpp"
#include "coatcontact/stack.hpp"

using namespace coatcontact;
using namespace coatcontact::cli;

namespace {

void require(bool condition, const char* what, const std::string& input) {
  if (!condition) {
    std::fprintf(stderr, "fuzz_parsers: %s for input of %zu bytes\n", what, input.size());
    std::abort();
  }
}

template <class Body>
void expect_input_error_only(Body body) {
  try {
    body();
  } catch (const InputError&) {
    // bad input, reported properly
  }
  // Any other exception escapes: libFuzzer reports it as a crash.
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);

  expect_input_error_only([&] {
    const double value = parse_number(text, "--x");
    require(std::isfinite(value), "parse_number returned a non-finite value", text);
    // Formatting a parsed value must work and round-trip.
    require(std::strtod(format_value(value, "x").c_str(), nullptr) == value, "format_value round trip", text);
  });
  expect_input_error_only([&] {
    const std::vector<double> values = parse_list(text, "--q");
    require(!values.empty() && values.size() <= 1000000, "parse_list size", text);
    for (double v : values) require(std::isfinite(v), "parse_list returned a non-finite value", text);
  });
  for (Quantity kind : {Quantity::kPressure, Quantity::kLength, Quantity::kEnergy, Quantity::kForce}) {
    expect_input_error_only([&] {
      const double value = parse_quantity(text, kind, "--v");
      require(std::isfinite(value) && value > 0.0, "parse_quantity returned a value not finite and > 0", text);
    });
  }
  expect_input_error_only([&] {
    const Material material = parse_material(text, "--film");
    validate(material, "film");  // what the parser accepts, validate must accept
    require(std::isfinite(material.reduced_modulus()), "parse_material: reduced modulus not finite", text);
  });
  expect_input_error_only([&] {
    const Substrate substrate = parse_substrate(text, "--substrate");
    validate(substrate);
  });

  // Arguments: the input split at newlines is an argument vector.
  std::vector<std::string> args;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = text.find('\n', start);
    args.push_back(text.substr(start, end == std::string::npos ? end : end - start));
    if (end == std::string::npos) break;
    start = end + 1;
  }
  static const std::vector<OptionSpec> spec = {
      {"--film", "E,nu", "film", true}, {"--q", "LIST", "q", false}, {"--flag", "", "flag", false}};
  expect_input_error_only([&] {
    const Arguments parsed(args, spec, 2);
    require(parsed.help() || parsed.has("--film"), "required option not enforced", text);
    require(parsed.positionals().size() <= 2, "too many positionals", text);
  });
  return 0;
}
