// Tolerance tiers of the Maugis-Dugdale tests (THEORY.md section 13), shared by the
// homogeneous and the coated checks; the general tiers are tests/common/check.hpp's.
#pragma once

// Tolerances of the Maugis-Dugdale checks (relative to max(|expected|, 1)), THEORY.md section 13.
// Closed form solved in the test: the root c(a), the regularity condition and the gap formula
// agree to ~1e-13 on a homogeneous solid; 1e-9 is the target with margin for the root.
constexpr double kClosedFormTier = 1e-9;
// Maugis's published pull-offs carry 6 significant digits.
constexpr double kPublishedDigitsTier = 5e-6;
// a -> 0 end of the curve reached by a_bar = 1e-7: the next term is O(a_bar^(1/2)) ~ 3e-4 x 1e-2.
constexpr double kEndOfCurveTier = 1e-5;
// JKR (lambda = 100) and DMT limits approached at finite lambda: the 1/lambda^2 remainder.
constexpr double kLimitTier = 1e-4;
// Fitted exponent of |P_MD - P_JKR| over lambda = 10..300 (expected -2).
constexpr double kExponentFitTier = 0.05;
