// Numbers for the report. A value is stored under a key by a line `\mrmdef{key}{value}` in a generated
// fragment and printed in the prose by `\mrm{key}` (paper/report.tex defines both), so that a sentence
// such as "the observed order is \mrm{conv:order:cn:mod3:1:err_u_L2L2}" cannot disagree with the
// computation. Rounding to a few significant digits happens here, once.
#include "report_values.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm {

std::string significant(double value, int digits) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, value);
  return buffer;
}

std::string decimals(double value, int places) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", places, value);
  return buffer;
}

TEST_CASE("plain-text numbers have their significant digits or their decimals") {
  CHECK(significant(0.012345) == "0.0123");
  CHECK(significant(1.5) == "1.5");
  CHECK(significant(1e-12) == "1e-12");
  CHECK(significant(287.46, 2) == "2.9e+02");
  CHECK(significant(std::numeric_limits<double>::infinity()) == "inf");
  CHECK(decimals(0.5, 2) == "0.50");
  CHECK(decimals(-4.0 / 3.0, 3) == "-1.333");
  CHECK(decimals(std::numeric_limits<double>::infinity(), 2) == "inf");
}

std::string tex_number(double value, int significant) {
  if (!std::isfinite(value)) return "n/a";
  if (value == 0.0) return "0";
  if (significant < 1) significant = 1;
  char buffer[64];
  // Round first, then read the exponent off the rounded value (0.000999 at 2 digits is 0.0010).
  std::snprintf(buffer, sizeof buffer, "%.*e", significant - 1, value);
  const double rounded = std::strtod(buffer, nullptr);
  const int exponent = static_cast<int>(std::floor(std::log10(std::abs(rounded))));
  if (exponent >= -3 && exponent < 4) {
    // An integer part is never rounded away (2048 stays 2048 at three digits).
    const int decimals = std::max(0, significant - 1 - exponent);
    std::snprintf(buffer, sizeof buffer, "%.*f", decimals, std::abs(decimals == 0 ? std::round(value) : rounded));
    return (rounded < 0 ? "\\ensuremath{-}" : "") + std::string(buffer);
  }
  std::snprintf(buffer, sizeof buffer, "%.*f", significant - 1, rounded / std::pow(10.0, exponent));
  return std::string("\\ensuremath{") + buffer + "\\cdot 10^{" + std::to_string(exponent) + "}}";
}

TEST_CASE("report numbers are rounded to their significant digits in fixed or scientific form") {
  CHECK(tex_number(0.012345) == "0.0123");
  CHECK(tex_number(1.5) == "1.50");
  CHECK(tex_number(-0.98765, 2) == "\\ensuremath{-}0.99");  // a minus sign, not a hyphen, in text
  CHECK(tex_number(2048, 3) == "2048");
  CHECK(tex_number(0.000999, 2) == "0.0010");
  CHECK(tex_number(1.234e-5) == "\\ensuremath{1.23\\cdot 10^{-5}}");
  CHECK(tex_number(98765.0, 2) == "\\ensuremath{9.9\\cdot 10^{4}}");
  CHECK(tex_number(0.0) == "0");
  CHECK(tex_number(std::nan("")) == "n/a");
}

std::string tex_magnitude(double x) {
  if (!(std::isfinite(x) && x > 0))
    throw std::invalid_argument("tex_magnitude: " + std::to_string(x) + " is not a finite positive number");
  if (x < 1000) return significant(x, 3);
  const int e = static_cast<int>(std::log(x) / std::log(10.0));
  return decimals(x / std::pow(10.0, e), 2) + "\\cdot 10^{" + std::to_string(e) + "}";
}

TEST_CASE("a magnitude has three digits below 1000 and a power of ten above") {
  CHECK(tex_magnitude(1.0) == "1");
  CHECK(tex_magnitude(1.0841) == "1.08");
  CHECK(tex_magnitude(287.46) == "287");
  CHECK(tex_magnitude(999.4) == "999");
  CHECK(tex_magnitude(1234.5) == "1.23\\cdot 10^{3}");
  CHECK(tex_magnitude(3.5678e5) == "3.57\\cdot 10^{5}");
  CHECK_THROWS_AS(tex_magnitude(0.0), std::invalid_argument);
  CHECK_THROWS_AS(tex_magnitude(std::nan("")), std::invalid_argument);
}

void tex_define(std::ostream& out, const std::string& key, const std::string& value) {
  if (key.empty()) throw std::invalid_argument("tex_define: empty key");
  for (char c : key) {
    const bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                    c == ':' || c == '.' || c == '_';
    if (!ok)
      throw std::invalid_argument("tex_define: key \"" + key +
                                  "\" has a character other than letters, digits, -, :, ., _");
  }
  out << "\\mrmdef{" << key << "}{" << value << "}\n";
}

TEST_CASE("a report value is defined under a key made of safe characters only") {
  std::ostringstream out;
  tex_define(out, "conv:order:cn:mod3:1:err_u0_L2", "0.98");
  CHECK(out.str() == "\\mrmdef{conv:order:cn:mod3:1:err_u0_L2}{0.98}\n");
  CHECK_THROWS_AS(tex_define(out, "a b", "1"), std::invalid_argument);
  CHECK_THROWS_AS(tex_define(out, "a}", "1"), std::invalid_argument);
  CHECK_THROWS_AS(tex_define(out, "", "1"), std::invalid_argument);
}

}  // namespace mrm
