// A small assertion framework for the support tests: CHECK(cond), CHECK_THROWS(expr, Type,
// "fragment"...) and a failure count returned by check::finish() as the exit status.
#pragma once
#include <cmath>
#include <cstdio>
#include <exception>
#include <initializer_list>
#include <string>

namespace check {

inline int& failures() {
  static int count = 0;
  return count;
}

inline void fail(const char* file, int line, const std::string& what) {
  ++failures();
  std::fprintf(stderr, "%s:%d: FAILED: %s\n", file, line, what.c_str());
}

// |a - b| <= tol * max(|a|, |b|): relative agreement to a named tolerance tier.
inline bool close(double a, double b, double tol) {
  return std::fabs(a - b) <= tol * std::fmax(std::fabs(a), std::fabs(b));
}

inline bool contains_all(const std::string& text, std::initializer_list<const char*> fragments,
                         std::string& missing) {
  for (const char* fragment : fragments) {
    if (text.find(fragment) == std::string::npos) {
      missing = fragment;
      return false;
    }
  }
  return true;
}

inline int finish(const char* name) {
  if (failures() == 0) {
    std::printf("%s: all checks passed\n", name);
    return 0;
  }
  std::fprintf(stderr, "%s: %d check(s) failed\n", name, failures());
  return 1;
}

}  // namespace check

#define CHECK(cond)                                                  \
  do {                                                               \
    if (!(cond)) check::fail(__FILE__, __LINE__, "CHECK(" #cond ")"); \
  } while (0)

// The expression must throw `Type` whose what() contains every fragment.
#define CHECK_THROWS(expr, Type, ...)                                                           \
  do {                                                                                          \
    try {                                                                                       \
      (void)(expr);                                                                             \
      check::fail(__FILE__, __LINE__, "no exception from " #expr);                              \
    } catch (const Type& error_) {                                                              \
      std::string missing_;                                                                     \
      if (!check::contains_all(error_.what(), {__VA_ARGS__}, missing_)) {                       \
        check::fail(__FILE__, __LINE__,                                                         \
                    std::string("message of " #expr " lacks '") + missing_ + "': " + error_.what()); \
      }                                                                                         \
    } catch (const std::exception& other_) {                                                    \
      check::fail(__FILE__, __LINE__, std::string("wrong exception from " #expr ": ") + other_.what()); \
    }                                                                                           \
  } while (0)
