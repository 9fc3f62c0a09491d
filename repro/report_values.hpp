/// @file report_values.hpp
/// @brief Numbers and tables for the report: every number the report prints comes from a LaTeX
/// fragment written by a program, never typed by hand.
#pragma once

#include <ostream>
#include <string>

namespace mrm {

/// A number in plain text (the claims' rows, which the report prints as they are): `digits` significant
/// digits in C's "%.*g" form ("0.0123", "1.5", "1e-12", "inf"). Deterministic (no locale).
std::string significant(double value, int digits = 3);
/// A number in plain text with `places` decimals, C's "%.*f" ("0.50", "-1.333", "nan").
std::string decimals(double value, int places);

/// A number for prose and tables, rounded to `significant` digits (an integer part is never rounded): fixed notation for
/// 10⁻³ ≤ |v| < 10⁴ ("0.0123", "1.50", "2048"; a negative value starts with "\ensuremath{-}"), otherwise "\ensuremath{1.23\cdot 10^{-5}}";
/// "0" for zero, "n/a" for a non-finite value. Deterministic (no locale).
std::string tex_number(double value, int significant = 3);

/// A positive magnitude for math mode, as the report's large-step sentence prints it: three significant
/// digits ("%.3g": "1", "1.08", "287") below 1000, otherwise two decimals and a power of ten
/// ("3.57\cdot 10^{5}", written as tex_number writes one; the exponent ⌊log x / log 10⌋). Throws
/// std::invalid_argument unless x is finite and positive.
std::string tex_magnitude(double x);

/// One definition line `\mrmdef{key}{value}`; the report defines `\mrmdef` to store the value under the
/// key and `\mrm{key}` to print it (a missing key stops the build). Throws std::invalid_argument for a
/// key with characters other than letters, digits, '-', ':', '.' and '_'.
void tex_define(std::ostream& out, const std::string& key, const std::string& value);

}  // namespace mrm
