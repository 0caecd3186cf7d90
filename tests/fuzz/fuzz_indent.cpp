// libFuzzer target: the nanoindentation text and archive readers (cpp/measure/indent) on
// arbitrary bytes, read as a file named "input.txt" so the content decides the format (zip:
// Micromaterials; "File Version: Hysitron": .hld; "Number of Points =": Hysitron text;
// "Name of the application": FischerScope). An InputError is the expected answer to bad
// input; anything else (another exception, a crash, a sanitizer report) is a bug and aborts.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "coatcontact/errors.hpp"
#include "coatcontact/indentation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  try {
    const auto tests = coatcontact::indent::read_indentation_from_bytes(bytes, "input.txt");
    for (const auto& t : tests) {
      // What a reader returns is complete: depth and load of one non-zero length, the others
      // empty or as long.
      const std::size_t n = t.depth.size();
      if (n == 0 || t.load.size() != n || (!t.time.empty() && t.time.size() != n)) std::abort();
      if (!t.segment.empty() && t.segment.size() != n) std::abort();
      for (const auto& [name, values] : t.extra) {
        if (values.size() != n) std::abort();
      }
    }
  } catch (const coatcontact::InputError&) {
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fuzz_indent: unexpected exception: %s\n", e.what());
    std::abort();
  }
  return 0;
}
