// Mathematical constants of the library, defined once (C++17 has no std::numbers).
#pragma once

namespace coatcontact::detail {

inline constexpr double kPi = 3.14159265358979323846;

}  // namespace coatcontact::detail
