/// @file options/numbers.cpp
/// @brief The number grammar of the command line: strict reading of reals, integers, choices and lists, the shortest exact writing of reals, the range checks, and the quoting of user text.
#include "options.hpp"
#include "output_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <system_error>
#include <type_traits>

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mrm::cli {

TEST_SUITE_BEGIN("cli");

// Text coming from the command line is shown in messages and written into data-file headers as a
// JSON string: between double quotes, with quotes, backslashes and control characters escaped.
// An empty value stays visible ("") and a stray newline cannot break a header line.
std::string json_string(std::string_view text) {
  std::string result = "\"";
  for (const char character : text) {
    switch (character) {
      case '"':
        result += "\\\"";
        break;
      case '\\':
        result += "\\\\";
        break;
      case '\n':
        result += "\\n";
        break;
      case '\t':
        result += "\\t";
        break;
      case '\r':
        result += "\\r";
        break;
      default:
        if (static_cast<unsigned char>(character) < 0x20) {
          char escape[8];
          std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(character)));
          result += escape;
        } else {
          result += character;
        }
    }
  }
  return result + "\"";
}

// One line, short, whatever the user typed (options.hpp). A UTF-8 sequence is decoded only to tell a
// character from a byte that is not UTF-8 and to find the C1 controls (U+0080..U+009F); every other
// character is kept as it is, so that a file name in any script reads as typed.
std::string quoted_text(std::string_view text) {
  std::string result = "\"";
  std::size_t characters = 0, k = 0;
  const auto byte = [&](std::size_t at) { return static_cast<unsigned char>(text[at]); };
  for (; k < text.size() && characters < max_quoted; ++characters) {
    const unsigned char first = byte(k);
    // The length of a well-formed UTF-8 sequence starting here (no overlong form, no surrogate), 0 if none.
    std::size_t length = first < 0x80                     ? 1
                         : first >= 0xc2 && first <= 0xdf ? 2
                         : first >= 0xe0 && first <= 0xef ? 3
                         : first >= 0xf0 && first <= 0xf4 ? 4
                                                          : 0;
    for (std::size_t j = 1; j < length; ++j)
      if (k + j >= text.size() || (byte(k + j) & 0xc0) != 0x80) length = 0;
    if (length == 3 && ((first == 0xe0 && byte(k + 1) < 0xa0) || (first == 0xed && byte(k + 1) >= 0xa0))) length = 0;
    if (length == 4 && ((first == 0xf0 && byte(k + 1) < 0x90) || (first == 0xf4 && byte(k + 1) >= 0x90))) length = 0;
    char escape[8];
    if (length == 0) {
      std::snprintf(escape, sizeof escape, "\\x%02x", static_cast<unsigned>(first));
      result += escape;
      k += 1;
    } else if (length == 1 && (first < 0x20 || first == 0x7f || first == '"' || first == '\\')) {
      const std::string escaped = first == 0x7f ? "\"\\u007f\"" : json_string(text.substr(k, 1));
      result += escaped.substr(1, escaped.size() - 2);
      k += 1;
    } else if (length == 2 && first == 0xc2 && byte(k + 1) < 0xa0) {
      std::snprintf(escape, sizeof escape, "\\u%04x", static_cast<unsigned>(byte(k + 1)));
      result += escape;
      k += 2;
    } else {
      result += text.substr(k, length);
      k += length;
    }
  }
  result += '"';
  if (k < text.size()) {
    result.insert(result.size() - 1, "\u2026");
    result += " (" + std::to_string(text.size()) + " bytes)";
  }
  return result;
}

TEST_CASE("user text in a message is one short line, whatever it holds") {
  CHECK(quoted_text("d.dat") == "\"d.dat\"");
  CHECK(quoted_text("") == "\"\"");
  CHECK(quoted_text("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(quoted_text("two\nlines\r\t") == "\"two\\nlines\\r\\t\"");
  CHECK(quoted_text("\x1b[31mred\x7f") == "\"\\u001b[31mred\\u007f\"");
  CHECK(quoted_text("\xc2\x9b"
                    "2J") == "\"\\u009b2J\"");  // C1 CSI, as UTF-8
  CHECK(quoted_text("\x9b"
                    "2J\xff") == "\"\\x9b2J\\xff\"");           // bytes that are not UTF-8
  CHECK(quoted_text("\xed\xa0\x80") == "\"\\xed\\xa0\\x80\"");  // a surrogate
  CHECK(quoted_text("Kr\xc4\x8d"
                    "ek \xe2\x80\x93 \xf0\x9f\x98\x80") ==
        "\"Kr\xc4\x8d"
        "ek \xe2\x80\x93 \xf0\x9f\x98\x80\"");
  const std::string long_text(50'000'000, 'x');
  const std::string shown = quoted_text(long_text);
  CHECK(shown == "\"" + std::string(max_quoted, 'x') + "\u2026\" (50000000 bytes)");
  CHECK(quoted_text(std::string(max_quoted, 'y')) == "\"" + std::string(max_quoted, 'y') + "\"");
  for (const std::string& text : {std::string("a\nb"), std::string(1000, '\n'), std::string("\x1b]0;title\x07")})
    CHECK(quoted_text(text).find_first_of(std::string("\n\r\x1b\x07", 4)) == std::string::npos);
}

namespace {

// std::from_chars, which does the strict parsing below, refuses a leading '+' although people
// write "+2" naturally. One '+' directly followed by a digit or a decimal point is skipped, so
// that "+2" and "+.5" are read but "+-2", "++2" and "+" still are not.
std::string_view without_plus_sign(std::string_view text) {
  if (text.size() >= 2 && text[0] == '+' && (std::isdigit(static_cast<unsigned char>(text[1])) || text[1] == '.')) {
    return text.substr(1);
  }
  return text;
}

}  // namespace

TEST_CASE("command-line text is quoted as a JSON string") {
  CHECK(json_string("results.dat") == "\"results.dat\"");
  CHECK(json_string("") == "\"\"");
  CHECK(json_string("a\"b\\c") == "\"a\\\"b\\\\c\"");
  CHECK(json_string("line\nbreak\t\x01") == "\"line\\nbreak\\t\\u0001\"");
}

// A real value must be a finite decimal number and nothing else. std::from_chars in its general
// format reads exactly that grammar (no leading space, no hexadecimal), except that it also reads
// "inf" and "nan", which the finiteness test rejects; and it tells a text that is a number too
// large or too small for a double apart from a text that is no number at all. The whole text must
// be consumed, so that "1e" or "12abc" are not read as 1 and 12.
double parse_real(std::string_view option, std::string_view text) {
  const std::string_view number = without_plus_sign(text);
  const char* const end = number.data() + number.size();
  double value = 0.0;
  const auto [stop, error] = std::from_chars(number.data(), end, value);
  if (error == std::errc::result_out_of_range && stop == end) {
    throw UsageError(std::string(option) + ": " + quoted_text(text) +
                     " is out of the range of double-precision numbers");
  }
  if (error != std::errc() || stop != end || !std::isfinite(value)) {
    throw UsageError(std::string(option) + ": " + quoted_text(text) +
                     " is not a finite decimal number (expected e.g. 0.25, -3 or 1e-3)");
  }
  return value;
}

TEST_CASE("decimal numbers in the usual forms are read exactly") {
  CHECK(parse_real("--dt", "1e-3") == 1e-3);
  CHECK(parse_real("--dt", "-0.5") == -0.5);
  CHECK(parse_real("--dt", "42") == 42.0);
  CHECK(parse_real("--dt", "+2.5") == 2.5);
  CHECK(parse_real("--dt", ".5") == 0.5);
  CHECK(parse_real("--dt", "1E3") == 1000.0);
  CHECK(parse_real("--dt", "0.1") == 0.1);
  CHECK(parse_real("--dt", "4.9e-324") == std::numeric_limits<double>::denorm_min());
}

TEST_CASE("a malformed real number, an infinity or NaN is rejected with the option's name") {
  for (const std::string text :
       {"",      "1e", "12abc", " 1",  "1 ",  "0x10", "0x1p3",  "+-1", "--1",  "++1",  "+",        "-",  "1,5",
        "1.2.3", "e3", "one",   "nan", "NaN", "-nan", "nan(1)", "inf", "-inf", "+inf", "infinity", "INF"}) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(
        parse_real("--dt", text),
        ("--dt: " + json_string(text) + " is not a finite decimal number (expected e.g. 0.25, -3 or 1e-3)").c_str(),
        UsageError);
  }
}

TEST_CASE("a real number beyond the range of a double is rejected as out of range") {
  for (const std::string text : {"1e400", "-1e400", "1e-400"}) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(parse_real("--dt", text),
                         ("--dt: " + json_string(text) + " is out of the range of double-precision numbers").c_str(),
                         UsageError);
  }
}

// An integer value must be a base-10 integer that fits in a long. std::from_chars reads exactly
// that and reports overflow separately; again the whole text must be consumed, so that "1.5" and
// "1e3" are errors instead of 1.
long parse_integer(std::string_view option, std::string_view text) {
  const std::string_view number = without_plus_sign(text);
  const char* const end = number.data() + number.size();
  long value = 0;
  const auto [stop, error] = std::from_chars(number.data(), end, value, 10);
  if (error == std::errc::result_out_of_range && stop == end) {
    throw UsageError(std::string(option) + ": " + quoted_text(text) + " is out of the integer range [" +
                     std::to_string(std::numeric_limits<long>::min()) + ", " +
                     std::to_string(std::numeric_limits<long>::max()) + "]");
  }
  if (error != std::errc() || stop != end) {
    throw UsageError(std::string(option) + ": " + quoted_text(text) +
                     " is not an integer (expected base-10 digits, e.g. 42)");
  }
  return value;
}

TEST_CASE("base-10 integers are read exactly, up to the limits of a long") {
  CHECK(parse_integer("--elements", "42") == 42);
  CHECK(parse_integer("--elements", "-7") == -7);
  CHECK(parse_integer("--elements", "+3") == 3);
  CHECK(parse_integer("--elements", "0") == 0);
  CHECK(parse_integer("--elements", "9223372036854775807") == std::numeric_limits<long>::max());
  CHECK(parse_integer("--elements", "-9223372036854775808") == std::numeric_limits<long>::min());
}

TEST_CASE("a malformed integer is rejected with the option's name") {
  for (const std::string text : {"1.5", "1e3", "", "12abc", " 1", "1 ", "0x10", "+-1", "--1", "-", "1,000", "nan"}) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(
        parse_integer("--elements", text),
        ("--elements: " + json_string(text) + " is not an integer (expected base-10 digits, e.g. 42)").c_str(),
        UsageError);
  }
}

TEST_CASE("an integer that overflows a long is rejected with the allowed range") {
  for (const std::string text : {"9223372036854775808", "-9223372036854775809", "99999999999999999999"}) {
    CAPTURE(text);
    CHECK_THROWS_WITH_AS(parse_integer("--elements", text),
                         ("--elements: " + json_string(text) +
                          " is out of the integer range [-9223372036854775808, "
                          "9223372036854775807]")
                             .c_str(),
                         UsageError);
  }
}

// A choice is one of a fixed list of words. The message lists them all, so that the user does not
// have to look up the help.
std::string parse_choice(std::string_view option, std::string_view text, const std::vector<std::string>& allowed) {
  if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) {
    return std::string(text);
  }
  std::string list;
  for (const std::string& value : allowed) {
    list += (list.empty() ? "" : ", ") + value;
  }
  throw UsageError(std::string(option) + ": unknown value " + quoted_text(text) + " (allowed: " + list + ")");
}

TEST_CASE("a choice accepts exactly the listed words and names them when rejecting") {
  CHECK(parse_choice("--scheme", "rk4", {"rk2", "rk4", "euler"}) == "rk4");
  CHECK_THROWS_WITH_AS(parse_choice("--scheme", "xx", {"rk2", "rk4", "euler"}),
                       "--scheme: unknown value \"xx\" (allowed: rk2, rk4, euler)", UsageError);
  CHECK_THROWS_WITH_AS(parse_choice("--scheme", "RK2", {"rk2", "rk4", "euler"}),
                       "--scheme: unknown value \"RK2\" (allowed: rk2, rk4, euler)", UsageError);
  CHECK_THROWS_AS(parse_choice("--scheme", "", {"rk2", "rk4", "euler"}), UsageError);
}

// A list is split at every comma and each item read by parse_real, so that an item has exactly the
// grammar of a number given alone; an empty item is an error, not an item skipped.
std::vector<double> parse_real_list(std::string_view option, std::string_view text) {
  std::vector<double> values;
  for (std::size_t start = 0;;) {
    const std::size_t comma = std::min(text.find(',', start), text.size());
    if (comma == start)
      throw UsageError(std::string(option) + ": " + quoted_text(text) +
                       " has an empty item (expected numbers separated by commas, e.g. 0.5,1.5)");
    values.push_back(parse_real(option, text.substr(start, comma - start)));
    if (comma == text.size()) return values;
    start = comma + 1;
  }
}

TEST_CASE("a list of numbers has the grammar of one number in each item, and no empty item") {
  CHECK(parse_real_list("--instants", "0.5") == std::vector<double>{0.5});
  CHECK(parse_real_list("--instants", "0.5,1.5,+2,1e-3") == std::vector<double>{0.5, 1.5, 2, 1e-3});
  for (const char* text : {"", ",", "0.5,", ",0.5", "0.5,,1"})
    CHECK_THROWS_WITH_AS(parse_real_list("--instants", text), doctest::Contains("has an empty item"), UsageError);
  for (const char* text : {"0.5, 1", "0.5;1", "nan", "0.5,inf", "1,+-2", "1,0x10", "1,1e400"})
    CHECK_THROWS_AS(parse_real_list("--instants", text), UsageError);
}

// Real numbers are written by std::to_chars without a precision, which gives the shortest decimal
// text that reads back to the same double. Unlike printf with a fixed number of digits it is both
// exact and free of noise digits ("0.1", not "0.10000000000000001"), and it does not depend on the
// locale, so that the same values always give the same data-file headers.
std::string format_real(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc()) {
    throw std::logic_error("format_real: buffer too small");
  }
  return std::string(buffer, end);
}

TEST_CASE("real numbers are formatted in their shortest form") {
  CHECK(format_real(0.1) == "0.1");
  CHECK(format_real(12.0) == "12");
  CHECK(format_real(0.0) == "0");
  CHECK(format_real(-0.0) == "-0");
  CHECK(format_real(1.0 / 3.0) == "0.3333333333333333");
  CHECK(format_real(1e-300) == "1e-300");
  CHECK(format_real(-2.5e10) == "-2.5e+10");
  CHECK(format_real(std::numeric_limits<double>::infinity()) == "inf");
}

TEST_CASE("a formatted real number reads back to the same double bit for bit") {
  const auto bits = [](double value) {
    std::uint64_t representation = 0;
    std::memcpy(&representation, &value, sizeof value);
    return representation;
  };
  for (const double value :
       {0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, -2.5e10, 0.0, -0.0, 1.0, 12.0, 123456789.125, std::nextafter(1.0, 2.0),
        std::numeric_limits<double>::denorm_min(), 3 * std::numeric_limits<double>::denorm_min(),
        std::numeric_limits<double>::min() / 3, std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
        -std::numeric_limits<double>::max(), std::numeric_limits<double>::epsilon()}) {
    CAPTURE(value);
    CHECK(bits(parse_real("--x", format_real(value))) == bits(value));
  }
}

// The range requirements. The allowed range in the message is written with format_real, like every
// number the user sees, so that `[0, 1]` reads as the user would have typed it. The comparisons are
// written so that NaN fails every requirement.
void require_positive(std::string_view option, double value) {
  if (!(value > 0)) {
    throw UsageError(std::string(option) + ": " + format_real(value) + " is not allowed (expected a value > 0)");
  }
}

void require_at_least(std::string_view option, double value, double minimum) {
  if (!(value >= minimum)) {
    throw UsageError(std::string(option) + ": " + format_real(value) +
                     " is not allowed (expected a value >= " + format_real(minimum) + ")");
  }
}

void require_in_closed_range(std::string_view option, double value, double lowest, double highest) {
  if (!(lowest <= value && value <= highest)) {
    throw UsageError(std::string(option) + ": " + format_real(value) + " is outside the allowed range [" +
                     format_real(lowest) + ", " + format_real(highest) + "]");
  }
}

TEST_CASE("range requirements accept their bounds and name the option and the range otherwise") {
  const double nan = std::numeric_limits<double>::quiet_NaN();

  CHECK_NOTHROW(require_positive("--dt", 1e-300));
  CHECK_THROWS_WITH_AS(require_positive("--dt", 0.0), "--dt: 0 is not allowed (expected a value > 0)", UsageError);
  CHECK_THROWS_WITH_AS(require_positive("--dt", -2.5), "--dt: -2.5 is not allowed (expected a value > 0)", UsageError);
  CHECK_THROWS_AS(require_positive("--dt", nan), UsageError);

  CHECK_NOTHROW(require_at_least("--elements", 2, 2));
  CHECK_THROWS_WITH_AS(require_at_least("--elements", 1, 2), "--elements: 1 is not allowed (expected a value >= 2)",
                       UsageError);
  CHECK_THROWS_AS(require_at_least("--elements", nan, 2), UsageError);

  CHECK_NOTHROW(require_in_closed_range("--restitution", 0.0, 0, 1));
  CHECK_NOTHROW(require_in_closed_range("--restitution", 1.0, 0, 1));
  CHECK_THROWS_WITH_AS(require_in_closed_range("--restitution", 1.5, 0, 1),
                       "--restitution: 1.5 is outside the allowed range [0, 1]", UsageError);
  CHECK_THROWS_WITH_AS(require_in_closed_range("--restitution", -0.1, 0, 1),
                       "--restitution: -0.1 is outside the allowed range [0, 1]", UsageError);
  CHECK_THROWS_AS(require_in_closed_range("--restitution", nan, 0, 1), UsageError);
}

// The same requirements as checks to attach to an option when registering it; the parser passes
// the option's long name and its value.
Check positive() {
  return [](std::string_view option, double value) { require_positive(option, value); };
}

Check at_least(double minimum) {
  return [minimum](std::string_view option, double value) { require_at_least(option, value, minimum); };
}

Check in_closed_range(double lowest, double highest) {
  return [lowest, highest](std::string_view option, double value) {
    require_in_closed_range(option, value, lowest, highest);
  };
}

TEST_SUITE_END();

}  // namespace mrm::cli
