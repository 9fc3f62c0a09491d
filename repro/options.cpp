// The command-line interface shared by every program: strict parsing of option values, the option
// parser with its help and its echo of the effective values, the deterministic formatting of real
// numbers, atomic output files and the guard of main. See cli.hpp for the interface and for a
// complete example of a program's main function.
#include "cli.hpp"

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
#include <limits>
#include <sstream>
#include <system_error>
#include <type_traits>

#include <fcntl.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#ifndef MRM_VERSION
#define MRM_VERSION "unknown"
#endif

namespace mrm::cli {

TEST_SUITE_BEGIN("cli");

namespace {

// Text coming from the command line is shown in messages and written into data-file headers as a
// JSON string: between double quotes, with quotes, backslashes and control characters escaped.
// An empty value stays visible ("") and a stray newline cannot break a header line.
std::string json_string(std::string_view text) {
    std::string result = "\"";
    for (const char character : text) {
        switch (character) {
        case '"': result += "\\\""; break;
        case '\\': result += "\\\\"; break;
        case '\n': result += "\\n"; break;
        case '\t': result += "\\t"; break;
        case '\r': result += "\\r"; break;
        default:
            if (static_cast<unsigned char>(character) < 0x20) {
                char escape[8];
                std::snprintf(escape, sizeof escape, "\\u%04x",
                              static_cast<unsigned>(static_cast<unsigned char>(character)));
                result += escape;
            } else {
                result += character;
            }
        }
    }
    return result + "\"";
}

// std::from_chars, which does the strict parsing below, refuses a leading '+' although people
// write "+2" naturally. One '+' directly followed by a digit or a decimal point is skipped, so
// that "+2" and "+.5" are read but "+-2", "++2" and "+" still are not.
std::string_view without_plus_sign(std::string_view text) {
    if (text.size() >= 2 && text[0] == '+' &&
        (std::isdigit(static_cast<unsigned char>(text[1])) || text[1] == '.')) {
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
        throw UsageError(std::string(option) + ": " + json_string(text) +
                         " is out of the range of double-precision numbers");
    }
    if (error != std::errc() || stop != end || !std::isfinite(value)) {
        throw UsageError(std::string(option) + ": " + json_string(text) +
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

TEST_CASE("a malformed real number is rejected with the option's name") {
    for (const std::string text : {"", "1e", "12abc", " 1", "1 ", "0x10", "0x1p3", "+-1", "--1",
                                   "++1", "+", "-", "1,5", "1.2.3", "e3", "one"}) {
        CAPTURE(text);
        CHECK_THROWS_WITH_AS(parse_real("--dt", text),
                             ("--dt: " + json_string(text) +
                              " is not a finite decimal number (expected e.g. 0.25, -3 or 1e-3)")
                                 .c_str(),
                             UsageError);
    }
}

TEST_CASE("infinities and NaN are rejected as real values") {
    for (const std::string text : {"nan", "NaN", "-nan", "nan(1)", "inf", "-inf", "+inf",
                                   "infinity", "INF"}) {
        CAPTURE(text);
        CHECK_THROWS_WITH_AS(parse_real("--final-time", text),
                             doctest::Contains("--final-time: "), UsageError);
        CHECK_THROWS_WITH_AS(parse_real("--final-time", text),
                             doctest::Contains("is not a finite decimal number"), UsageError);
    }
}

TEST_CASE("a real number beyond the range of a double is rejected as out of range") {
    for (const std::string text : {"1e400", "-1e400", "1e-400"}) {
        CAPTURE(text);
        CHECK_THROWS_WITH_AS(parse_real("--dt", text),
                             ("--dt: " + json_string(text) +
                              " is out of the range of double-precision numbers")
                                 .c_str(),
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
        throw UsageError(std::string(option) + ": " + json_string(text) +
                         " is out of the integer range [" +
                         std::to_string(std::numeric_limits<long>::min()) + ", " +
                         std::to_string(std::numeric_limits<long>::max()) + "]");
    }
    if (error != std::errc() || stop != end) {
        throw UsageError(std::string(option) + ": " + json_string(text) +
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
    for (const std::string text : {"1.5", "1e3", "", "12abc", " 1", "1 ", "0x10", "+-1", "--1", "-",
                             "1,000", "nan"}) {
        CAPTURE(text);
        CHECK_THROWS_WITH_AS(parse_integer("--elements", text),
                             ("--elements: " + json_string(text) +
                              " is not an integer (expected base-10 digits, e.g. 42)")
                                 .c_str(),
                             UsageError);
    }
}

TEST_CASE("an integer that overflows a long is rejected with the allowed range") {
    for (const std::string text : {"9223372036854775808", "-9223372036854775809",
                             "99999999999999999999"}) {
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
std::string parse_choice(std::string_view option, std::string_view text,
                         const std::vector<std::string>& allowed) {
    if (std::find(allowed.begin(), allowed.end(), text) != allowed.end()) {
        return std::string(text);
    }
    std::string list;
    for (const std::string& value : allowed) {
        list += (list.empty() ? "" : ", ") + value;
    }
    throw UsageError(std::string(option) + ": unknown value " + json_string(text) + " (allowed: " +
                     list + ")");
}

TEST_CASE("a choice accepts exactly the listed words and names them when rejecting") {
    CHECK(parse_choice("--scheme", "be", {"cn", "be", "ps"}) == "be");
    CHECK_THROWS_WITH_AS(parse_choice("--scheme", "xx", {"cn", "be", "ps"}),
                         "--scheme: unknown value \"xx\" (allowed: cn, be, ps)", UsageError);
    CHECK_THROWS_WITH_AS(parse_choice("--scheme", "CN", {"cn", "be", "ps"}),
                         "--scheme: unknown value \"CN\" (allowed: cn, be, ps)", UsageError);
    CHECK_THROWS_AS(parse_choice("--scheme", "", {"cn", "be", "ps"}), UsageError);
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
         {0.1, 1.0 / 3.0, 2.0 / 3.0, 1e-300, -2.5e10, 0.0, -0.0, 1.0, 12.0, 123456789.125,
          std::nextafter(1.0, 2.0), std::numeric_limits<double>::denorm_min(),
          3 * std::numeric_limits<double>::denorm_min(), std::numeric_limits<double>::min() / 3,
          std::numeric_limits<double>::min(), std::numeric_limits<double>::max(),
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
        throw UsageError(std::string(option) + ": " + format_real(value) +
                         " is not allowed (expected a value > 0)");
    }
}

void require_at_least(std::string_view option, double value, double minimum) {
    if (!(value >= minimum)) {
        throw UsageError(std::string(option) + ": " + format_real(value) +
                         " is not allowed (expected a value >= " + format_real(minimum) + ")");
    }
}

void require_in_closed_range(std::string_view option, double value, double lowest,
                             double highest) {
    if (!(lowest <= value && value <= highest)) {
        throw UsageError(std::string(option) + ": " + format_real(value) +
                         " is outside the allowed range [" + format_real(lowest) + ", " +
                         format_real(highest) + "]");
    }
}

TEST_CASE("range requirements accept their bounds and name the option and the range otherwise") {
    const double nan = std::numeric_limits<double>::quiet_NaN();

    CHECK_NOTHROW(require_positive("--dt", 1e-300));
    CHECK_THROWS_WITH_AS(require_positive("--dt", 0.0),
                         "--dt: 0 is not allowed (expected a value > 0)", UsageError);
    CHECK_THROWS_WITH_AS(require_positive("--dt", -2.5),
                         "--dt: -2.5 is not allowed (expected a value > 0)", UsageError);
    CHECK_THROWS_AS(require_positive("--dt", nan), UsageError);

    CHECK_NOTHROW(require_at_least("--elements", 2, 2));
    CHECK_THROWS_WITH_AS(require_at_least("--elements", 1, 2),
                         "--elements: 1 is not allowed (expected a value >= 2)", UsageError);
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
    return [minimum](std::string_view option, double value) {
        require_at_least(option, value, minimum);
    };
}

Check in_closed_range(double lowest, double highest) {
    return [lowest, highest](std::string_view option, double value) {
        require_in_closed_range(option, value, lowest, highest);
    };
}

TEST_CASE("packaged checks apply the corresponding range requirement") {
    CHECK_NOTHROW(positive()("--dt", 0.5));
    CHECK_THROWS_WITH_AS(positive()("--dt", 0.0),
                         "--dt: 0 is not allowed (expected a value > 0)", UsageError);
    CHECK_NOTHROW(at_least(2)("--elements", 2));
    CHECK_THROWS_WITH_AS(at_least(2)("--elements", 1),
                         "--elements: 1 is not allowed (expected a value >= 2)", UsageError);
    CHECK_NOTHROW(in_closed_range(0, 1)("--restitution", 1));
    CHECK_THROWS_WITH_AS(in_closed_range(0, 1)("--restitution", 1.5),
                         "--restitution: 1.5 is outside the allowed range [0, 1]", UsageError);
}

namespace {

// Names of options. A long name is "--" followed by letters, digits and inner dashes; a short
// name is "-" and one letter (never a digit, so that a negative number is never taken for an
// option). The help and version options are built in.
bool is_long_name(std::string_view name) {
    if (name.size() < 3 || name.substr(0, 2) != "--" || name.back() == '-' || name[2] == '-') {
        return false;
    }
    return std::all_of(name.begin() + 2, name.end(), [](char character) {
        return std::isalnum(static_cast<unsigned char>(character)) || character == '-';
    });
}

bool is_short_name(std::string_view name) {
    return name.size() == 2 && name[0] == '-' && std::isalpha(static_cast<unsigned char>(name[1]));
}

bool is_builtin_name(std::string_view name) {
    return name == "--help" || name == "-h" || name == "--version";
}

// The key under which an option's value is echoed: "--final-time" gives "final_time".
std::string echo_key(std::string_view long_name) {
    std::string key(long_name.substr(2));
    std::replace(key.begin(), key.end(), '-', '_');
    return key;
}

// The description in the help is one paragraph, folded at word boundaries into lines of at most
// `width` characters (a longer word gets a line of its own).
std::string wrapped(std::string_view paragraph, std::size_t width) {
    std::istringstream words{std::string(paragraph)};
    std::string result, line, word;
    while (words >> word) {
        if (!line.empty() && line.size() + 1 + word.size() > width) {
            result += line + '\n';
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
    }
    if (!line.empty()) {
        result += line + '\n';
    }
    return result;
}

}  // namespace

TEST_CASE("option names are recognised by their form") {
    CHECK(is_long_name("--elements"));
    CHECK(is_long_name("--final-time"));
    CHECK(is_long_name("--p2"));
    CHECK_FALSE(is_long_name("--"));
    CHECK_FALSE(is_long_name("-elements"));
    CHECK_FALSE(is_long_name("--final_time"));
    CHECK_FALSE(is_long_name("--final-"));
    CHECK_FALSE(is_long_name("---x"));
    CHECK(is_short_name("-n"));
    CHECK_FALSE(is_short_name("-5"));
    CHECK_FALSE(is_short_name("-nn"));
    CHECK_FALSE(is_short_name("n"));
    CHECK(echo_key("--final-time") == "final_time");
}

TEST_CASE("a paragraph is folded at word boundaries within the width") {
    CHECK(wrapped("the  quick brown\nfox jumps", 10) == "the quick\nbrown fox\njumps\n");
    CHECK(wrapped("a verylongword b", 5) == "a\nverylongword\nb\n");
    CHECK(wrapped("", 10).empty());
}

// The parser keeps the program's name, its description and its sample runs for the help.
Parser::Parser(std::string program, std::string description,
               std::vector<std::string> sample_runs)
    : program_(std::move(program)),
      description_(std::move(description)),
      sample_runs_(std::move(sample_runs)) {}

// Every registration goes through add_option, which rejects the programming errors: malformed,
// reserved or duplicate names, a value option without a placeholder, a null variable. The
// default shown in the help is taken now, from the variable's value before any parsing.
void Parser::add_option(Option option) {
    const std::string& name = option.long_name;
    if (!is_long_name(name) || is_builtin_name(name)) {
        throw std::logic_error("Parser: invalid long option name " + json_string(name));
    }
    if (!option.short_name.empty() &&
        (!is_short_name(option.short_name) || is_builtin_name(option.short_name))) {
        throw std::logic_error("Parser: invalid short option name " +
                               json_string(option.short_name) + " for " + name);
    }
    if (find(name) != nullptr || (!option.short_name.empty() && find(option.short_name))) {
        throw std::logic_error("Parser: option " + name + " registered twice");
    }
    const bool is_flag = std::holds_alternative<bool*>(option.target);
    if (is_flag != option.metavar.empty()) {
        throw std::logic_error("Parser: " + name +
                               (is_flag ? " is a flag and takes no placeholder"
                                        : " needs a placeholder for its value"));
    }
    std::visit(
        [&](auto* target) {
            using Target = std::remove_pointer_t<decltype(target)>;
            if (target == nullptr) {
                throw std::logic_error("Parser: " + name + " is bound to a null pointer");
            }
            if constexpr (std::is_same_v<Target, double>) {
                option.default_text = format_real(*target);
            } else if constexpr (std::is_same_v<Target, long>) {
                option.default_text = std::to_string(*target);
            } else if constexpr (std::is_same_v<Target, std::string>) {
                option.default_text = *target;
            }
        },
        option.target);
    options_.push_back(std::move(option));
}

// The registration of each kind of option only fills in the description of the option: the kind
// is the type of the bound variable, a choice is a string with allowed values, a flag is the one
// kind without a placeholder.
void Parser::add_real(std::string long_name, std::string short_name, std::string metavar,
                      std::string help, double* target, Check check) {
    add_option({std::move(long_name), std::move(short_name), std::move(metavar), std::move(help),
                target, {}, std::move(check), {}, false});
}

void Parser::add_integer(std::string long_name, std::string short_name, std::string metavar,
                         std::string help, long* target, Check check) {
    add_option({std::move(long_name), std::move(short_name), std::move(metavar), std::move(help),
                target, {}, std::move(check), {}, false});
}

void Parser::add_string(std::string long_name, std::string short_name, std::string metavar,
                        std::string help, std::string* target) {
    add_option({std::move(long_name), std::move(short_name), std::move(metavar), std::move(help),
                target, {}, {}, {}, false});
}

// A choice is a string option with a non-empty list of allowed values; its default must be one of
// them.
void Parser::add_choice(std::string long_name, std::string short_name, std::string metavar,
                        std::string help, std::vector<std::string> allowed,
                        std::string* target) {
    if (allowed.empty() || (target != nullptr && std::find(allowed.begin(), allowed.end(),
                                                           *target) == allowed.end())) {
        throw std::logic_error("Parser: the default of " + long_name +
                               " is not one of its allowed values");
    }
    add_option({std::move(long_name), std::move(short_name), std::move(metavar), std::move(help),
                target, std::move(allowed), {}, {}, false});
}

void Parser::add_flag(std::string long_name, std::string short_name, std::string help,
                      bool* target) {
    add_option({std::move(long_name), std::move(short_name), {}, std::move(help), target, {}, {},
                {}, false});
}

// A conflict links two options that are already registered.
void Parser::add_conflict(std::string_view first_long_name, std::string_view second_long_name) {
    registered(first_long_name);
    registered(second_long_name);
    conflicts_.emplace_back(first_long_name, second_long_name);
}

// Looking up an option by its long or short name; `registered` is the lookup of a name that the
// program itself supplies, where an unknown name is a programming error.
Parser::Option* Parser::find(std::string_view name) {
    for (Option& option : options_) {
        if (option.long_name == name || (!option.short_name.empty() && option.short_name == name)) {
            return &option;
        }
    }
    return nullptr;
}

const Parser::Option& Parser::registered(std::string_view long_name) const {
    for (const Option& option : options_) {
        if (option.long_name == long_name) {
            return option;
        }
    }
    throw std::logic_error("Parser: no option " + json_string(long_name) + " is registered");
}

bool Parser::given(std::string_view long_name) const { return registered(long_name).given; }

// Storing the text given for an option into its variable, parsed according to the variable's type.
// The error messages name the option by its long name, whichever name the user typed.
void Parser::store(Option& option, std::string_view text) {
    std::visit(
        [&](auto* target) {
            using Target = std::remove_pointer_t<decltype(target)>;
            if constexpr (std::is_same_v<Target, double>) {
                *target = parse_real(option.long_name, text);
            } else if constexpr (std::is_same_v<Target, long>) {
                *target = parse_integer(option.long_name, text);
            } else if constexpr (std::is_same_v<Target, std::string>) {
                *target = option.allowed.empty()
                              ? std::string(text)
                              : parse_choice(option.long_name, text, option.allowed);
            } else {
                *target = true;
            }
        },
        option.target);
}

// Reading the command line, one argument at a time. A long option may carry its value after '=';
// otherwise the value is the next argument, unless that argument is itself an option (then the
// value is missing: "--output --elements 5" is an error, not a file named "--elements"). A negative
// number is not an option, since short names are letters. Help and version stop the reading at
// once. When all arguments are read, the conflicts and then the checks of the given options apply.
Outcome Parser::parse(const std::vector<std::string>& arguments, std::ostream& out) {
    for (Option& option : options_) {
        option.given = false;
    }
    const auto is_option = [this](std::string_view argument) {
        return is_builtin_name(argument) || argument.substr(0, 2) == "--" ||
               find(argument) != nullptr;
    };

    for (std::size_t index = 0; index < arguments.size(); ++index) {
        const std::string& argument = arguments[index];
        if (argument == "--help" || argument == "-h") {
            print_help(out);
            return Outcome::exit_success;
        }
        if (argument == "--version") {
            out << program_ << ' ' << MRM_VERSION << '\n';
            return Outcome::exit_success;
        }
        if (argument.size() < 2 || argument[0] != '-') {
            throw UsageError("unexpected argument " + json_string(argument) +
                             " (this program takes options only; see --help)");
        }

        std::string_view name = argument;
        const std::size_t equals = argument.find('=');
        const bool has_inline_value = argument.substr(0, 2) == "--" && equals != std::string::npos;
        if (has_inline_value) {
            name = name.substr(0, equals);
        }
        Option* const option = find(name);
        if (option == nullptr) {
            throw UsageError("unknown option " + json_string(name) + " (see --help)");
        }
        if (option->given) {
            throw UsageError(option->long_name + ": given more than once");
        }
        option->given = true;

        if (std::holds_alternative<bool*>(option->target)) {
            if (has_inline_value) {
                throw UsageError(option->long_name + ": takes no value (got " +
                                 json_string(argument) + ")");
            }
            store(*option, "");
        } else if (has_inline_value) {
            store(*option, std::string_view(argument).substr(equals + 1));
        } else if (index + 1 < arguments.size() && !is_option(arguments[index + 1])) {
            store(*option, arguments[++index]);
        } else {
            throw UsageError(option->long_name + ": missing value (expected " + option->metavar +
                             ")");
        }
    }

    for (const auto& [first, second] : conflicts_) {
        if (given(first) && given(second)) {
            throw UsageError(first + " and " + second + " cannot be given together");
        }
    }
    for (const Option& option : options_) {
        if (option.given && option.check) {
            if (const auto* real = std::get_if<double*>(&option.target)) {
                option.check(option.long_name, **real);
            } else if (const auto* integer = std::get_if<long*>(&option.target)) {
                option.check(option.long_name, static_cast<double>(**integer));
            }
        }
    }
    return Outcome::run;
}

Outcome Parser::parse(int argc, const char* const* argv, std::ostream& out) {
    return parse(std::vector<std::string>(argv + std::min(argc, 1), argv + argc), out);
}

// The help: usage line, description, one line per option with its default, and the sample runs.
// The option lines are aligned on the longest "-n, --name VALUE" column.
void Parser::print_help(std::ostream& out) const {
    const auto left_column = [](std::string_view short_name, std::string_view long_name,
                                std::string_view metavar) {
        std::string column = "  ";
        column += short_name.empty() ? "    " : std::string(short_name) + ", ";
        column += long_name;
        if (!metavar.empty()) {
            column += " " + std::string(metavar);
        }
        return column;
    };

    std::vector<std::pair<std::string, std::string>> lines;
    for (const Option& option : options_) {
        std::string help = option.help;
        if (!option.allowed.empty()) {
            std::string list;
            for (const std::string& value : option.allowed) {
                list += (list.empty() ? "" : ", ") + value;
            }
            help += " (one of: " + list + "; default: " + option.default_text + ")";
        } else if (!option.default_text.empty()) {
            help += " (default: " + option.default_text + ")";
        }
        lines.emplace_back(left_column(option.short_name, option.long_name, option.metavar), help);
    }
    lines.emplace_back(left_column("-h", "--help", ""), "print this help and exit");
    lines.emplace_back(left_column("", "--version", ""), "print the version and exit");

    std::size_t width = 0;
    for (const auto& line : lines) {
        width = std::max(width, line.first.size());
    }

    out << "Usage: " << program_ << " [options]\n";
    if (!description_.empty()) {
        out << '\n' << wrapped(description_, 80);
    }
    out << "\nOptions:\n";
    for (const auto& [column, help] : lines) {
        out << column << std::string(width + 2 - column.size(), ' ') << help << '\n';
    }
    if (!sample_runs_.empty()) {
        out << "\nSample runs:\n";
        for (const std::string& run : sample_runs_) {
            out << "  " << run << '\n';
        }
    }
}

// The effective values, one `key = value` line each, in registration order.
void Parser::echo(std::ostream& out, std::string_view prefix) const {
    for (const Option& option : options_) {
        out << prefix << echo_key(option.long_name) << " = ";
        std::visit(
            [&](const auto* target) {
                using Target = std::remove_cv_t<std::remove_pointer_t<decltype(target)>>;
                if constexpr (std::is_same_v<Target, double>) {
                    out << format_real(*target);
                } else if constexpr (std::is_same_v<Target, long>) {
                    out << *target;
                } else if constexpr (std::is_same_v<Target, std::string>) {
                    out << json_string(*target);
                } else {
                    out << (*target ? "true" : "false");
                }
            },
            option.target);
        out << '\n';
    }
}

namespace {

// The options of a small imaginary program, shared by the parser's tests below; `parse` reads a
// command line given as a vector and fails the test if anything is printed.
struct ExampleProgram {
    long elements = 100;
    double final_time = 12.0;
    double dt = 0.0;
    double courant = 0.5;
    double restitution = 0.0;
    std::string scheme = "cn";
    std::string output = "contact.dat";
    bool verbose = false;
    Parser parser{"contact", "Computes the motion of an elastic bar hitting a rigid obstacle.",
                  {"contact -n 400 --scheme be", "contact --dt 1e-4 -o run.dat"}};

    ExampleProgram() {
        parser.add_integer("--elements", "-n", "N", "number of elements of the mesh", &elements,
                           at_least(2));
        parser.add_real("--final-time", "-T", "T", "end of the simulated interval", &final_time,
                        positive());
        parser.add_real("--dt", "", "DT", "time step", &dt, positive());
        parser.add_real("--courant", "", "C", "time step as a fraction of the CFL limit",
                        &courant, positive());
        parser.add_real("--restitution", "-e", "E", "coefficient of restitution", &restitution,
                        in_closed_range(0, 1));
        parser.add_choice("--scheme", "", "S", "time integration scheme", {"cn", "be", "ps"},
                          &scheme);
        parser.add_string("--output", "-o", "FILE", "data file to write", &output);
        parser.add_flag("--verbose", "-v", "print the progress", &verbose);
        parser.add_conflict("--dt", "--courant");
    }

    Outcome parse(const std::vector<std::string>& arguments) {
        std::ostringstream printed;
        const Outcome outcome = parser.parse(arguments, printed);
        CHECK(printed.str().empty());
        return outcome;
    }
};

}  // namespace

TEST_CASE("without arguments every option keeps its default and the program runs") {
    ExampleProgram program;
    CHECK(program.parse({}) == Outcome::run);
    CHECK(program.elements == 100);
    CHECK(program.final_time == 12.0);
    CHECK(program.scheme == "cn");
    CHECK(program.output == "contact.dat");
    CHECK_FALSE(program.verbose);
    CHECK_FALSE(program.parser.given("--elements"));
    CHECK_FALSE(program.parser.given("--verbose"));
}

TEST_CASE("values are read after long names, short names and '='") {
    ExampleProgram program;
    SUBCASE("separate arguments") {
        CHECK(program.parse({"--elements", "400", "-T", "3.5", "--scheme", "be", "-o", "a.dat",
                             "-v"}) == Outcome::run);
    }
    SUBCASE("'=' after long names") {
        CHECK(program.parse({"--elements=400", "--final-time=3.5", "--scheme=be", "--output=a.dat",
                             "--verbose"}) == Outcome::run);
    }
    CHECK(program.elements == 400);
    CHECK(program.final_time == 3.5);
    CHECK(program.scheme == "be");
    CHECK(program.output == "a.dat");
    CHECK(program.verbose);
    CHECK(program.parser.given("--elements"));
    CHECK(program.parser.given("--verbose"));
    CHECK_FALSE(program.parser.given("--dt"));
}

TEST_CASE("a negative number is taken as the value of the option before it") {
    ExampleProgram program;
    program.parser.add_real("--shift", "", "X", "shift of the obstacle", &program.dt);
    CHECK(program.parse({"--shift", "-0.5"}) == Outcome::run);
    CHECK(program.dt == -0.5);
}

TEST_CASE("'=' may give an empty string or a string containing '='") {
    ExampleProgram program;
    SUBCASE("empty") {
        program.parse({"--output="});
        CHECK(program.output.empty());
    }
    SUBCASE("containing '='") {
        program.parse({"--output=a=b.dat"});
        CHECK(program.output == "a=b.dat");
    }
}

TEST_CASE("an unknown option is rejected with a pointer to the help") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(program.parse({"--foo"}), "unknown option \"--foo\" (see --help)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--foo=3"}), "unknown option \"--foo\" (see --help)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"-x", "1"}), "unknown option \"-x\" (see --help)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--elem", "1"}), "unknown option \"--elem\" (see --help)",
                         UsageError);
}

TEST_CASE("an option without its value is rejected with the expected placeholder") {
    ExampleProgram program;
    SUBCASE("at the end of the command line") {
        CHECK_THROWS_WITH_AS(program.parse({"--elements"}),
                             "--elements: missing value (expected N)", UsageError);
    }
    SUBCASE("followed by another option") {
        CHECK_THROWS_WITH_AS(program.parse({"--output", "--elements", "5"}),
                             "--output: missing value (expected FILE)", UsageError);
        CHECK_THROWS_WITH_AS(program.parse({"-o", "-v"}),
                             "--output: missing value (expected FILE)", UsageError);
    }
}

TEST_CASE("a malformed number on the command line is rejected with the option's name") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(
        program.parse({"-n", "12abc"}),
        "--elements: \"12abc\" is not an integer (expected base-10 digits, e.g. 42)", UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--final-time=nan"}),
                         doctest::Contains("--final-time: \"nan\" is not a finite decimal number"),
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--scheme", "xx"}),
                         "--scheme: unknown value \"xx\" (allowed: cn, be, ps)", UsageError);
}

TEST_CASE("an option given twice is rejected, whichever names are used") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(program.parse({"-n", "4", "--elements", "5"}),
                         "--elements: given more than once", UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"-v", "-v"}), "--verbose: given more than once",
                         UsageError);
}

TEST_CASE("conflicting options are rejected together but accepted alone") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(program.parse({"--dt", "1e-3", "--courant", "0.9"}),
                         "--dt and --courant cannot be given together", UsageError);
    CHECK(program.parse({"--dt", "1e-3"}) == Outcome::run);
    CHECK(program.parse({"--courant", "0.9"}) == Outcome::run);
    CHECK_FALSE(program.parser.given("--dt"));
}

TEST_CASE("positional arguments and values given to flags are rejected") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(program.parse({"-n", "4", "5"}),
                         "unexpected argument \"5\" (this program takes options only; see --help)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"-"}),
                         "unexpected argument \"-\" (this program takes options only; see --help)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--verbose=yes"}),
                         "--verbose: takes no value (got \"--verbose=yes\")", UsageError);
}

TEST_CASE("checks reject given values out of range but not the defaults") {
    ExampleProgram program;
    CHECK_THROWS_WITH_AS(program.parse({"--restitution", "1.5"}),
                         "--restitution: 1.5 is outside the allowed range [0, 1]", UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"-n", "1"}),
                         "--elements: 1 is not allowed (expected a value >= 2)", UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"--dt=0"}), "--dt: 0 is not allowed (expected a value > 0)",
                         UsageError);
    ExampleProgram untouched;
    CHECK(untouched.dt == 0.0);
    CHECK(untouched.parse({}) == Outcome::run);
}

TEST_CASE("the help lists every option with its default and stops the program") {
    ExampleProgram program;
    program.elements = 7;
    for (const std::string help : {"--help", "-h"}) {
        CAPTURE(help);
        std::ostringstream printed;
        CHECK(program.parser.parse({"-n", "5", help, "--unknown"}, printed) ==
              Outcome::exit_success);
        CHECK(printed.str() ==
              "Usage: contact [options]\n"
              "\n"
              "Computes the motion of an elastic bar hitting a rigid obstacle.\n"
              "\n"
              "Options:\n"
              "  -n, --elements N     number of elements of the mesh (default: 100)\n"
              "  -T, --final-time T   end of the simulated interval (default: 12)\n"
              "      --dt DT          time step (default: 0)\n"
              "      --courant C      time step as a fraction of the CFL limit (default: 0.5)\n"
              "  -e, --restitution E  coefficient of restitution (default: 0)\n"
              "      --scheme S       time integration scheme (one of: cn, be, ps; default: "
              "cn)\n"
              "  -o, --output FILE    data file to write (default: contact.dat)\n"
              "  -v, --verbose        print the progress\n"
              "  -h, --help           print this help and exit\n"
              "      --version        print the version and exit\n"
              "\n"
              "Sample runs:\n"
              "  contact -n 400 --scheme be\n"
              "  contact --dt 1e-4 -o run.dat\n");
    }
}

TEST_CASE("the version is printed after the program's name and stops the program") {
    ExampleProgram program;
    std::ostringstream printed;
    CHECK(program.parser.parse({"--version"}, printed) == Outcome::exit_success);
    CHECK(printed.str() == std::string("contact ") + MRM_VERSION + "\n");
}

TEST_CASE("argv is read without the program's own name") {
    ExampleProgram program;
    const char* const argv[] = {"/usr/bin/contact", "-n", "9", "--verbose"};
    std::ostringstream printed;
    CHECK(program.parser.parse(4, argv, printed) == Outcome::run);
    CHECK(program.elements == 9);
    CHECK(program.verbose);
    CHECK(program.parser.parse(1, argv, printed) == Outcome::run);
    CHECK(printed.str().empty());
}

TEST_CASE("the echo writes every effective value as a deterministic header line") {
    ExampleProgram program;
    program.parse({"-n", "400", "--dt", "0.1", "-o", "run \"1\".dat", "-v", "--scheme=ps"});
    std::ostringstream echoed;
    program.parser.echo(echoed);
    CHECK(echoed.str() ==
          "# elements = 400\n"
          "# final_time = 12\n"
          "# dt = 0.1\n"
          "# courant = 0.5\n"
          "# restitution = 0\n"
          "# scheme = \"ps\"\n"
          "# output = \"run \\\"1\\\".dat\"\n"
          "# verbose = true\n");
    std::ostringstream with_prefix;
    program.parser.echo(with_prefix, "% ");
    CHECK(with_prefix.str().substr(0, 17) == "% elements = 400\n");
}

TEST_CASE("registration mistakes are reported as logic errors") {
    long number = 0;
    double real = 0;
    bool flag = false;
    std::string text = "a";
    Parser parser("p", "", {});
    parser.add_integer("--elements", "-n", "N", "", &number);
    CHECK_THROWS_AS(parser.add_integer("--elements", "", "N", "", &number), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("--other", "-n", "X", "", &real), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("elements", "", "X", "", &real), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("--final_time", "", "X", "", &real), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("--x", "-5", "X", "", &real), std::logic_error);
    CHECK_THROWS_AS(parser.add_flag("--help", "", "", &flag), std::logic_error);
    CHECK_THROWS_AS(parser.add_flag("--quiet", "-h", "", &flag), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("--x", "", "", "", &real), std::logic_error);
    CHECK_THROWS_AS(parser.add_real("--x", "", "X", "", nullptr), std::logic_error);
    CHECK_THROWS_AS(parser.add_choice("--scheme", "", "S", "", {"cn", "be"}, &text),
                    std::logic_error);
    CHECK_THROWS_AS(parser.add_conflict("--elements", "--missing"), std::logic_error);
    CHECK_THROWS_AS(parser.given("--missing"), std::logic_error);
    CHECK_NOTHROW(parser.add_real("--x", "", "X", "", &real));
}

// A program's main function delegates to guarded_main, which maps the exceptions to an exit
// status and a single line of message. The final check of the output stream catches a failure to
// write the results to standard output (a full disk, a closed pipe), which would otherwise go
// unnoticed, since a C++ stream reports write errors only through its state.
int guarded_main(std::string_view program, const std::function<int()>& body, std::ostream& output,
                 std::ostream& errors) {
    try {
        const int status = body();
        output.flush();
        if (!output) {
            errors << program << ": error: writing the standard output failed\n";
            return status != 0 ? status : 1;
        }
        return status;
    } catch (const UsageError& error) {
        errors << program << ": " << error.what() << '\n';
        return 2;
    } catch (const std::exception& error) {
        errors << program << ": error: " << error.what() << '\n';
        return 1;
    } catch (...) {
        errors << program << ": error: unknown exception\n";
        return 1;
    }
}

TEST_CASE("guarded_main maps usage errors to status 2 and other failures to status 1") {
    std::ostringstream output, errors;
    SUBCASE("success") {
        CHECK(guarded_main("p", [] { return 0; }, output, errors) == 0);
        CHECK(guarded_main("p", [] { return 3; }, output, errors) == 3);
        CHECK(errors.str().empty());
    }
    SUBCASE("usage error") {
        CHECK(guarded_main("p", []() -> int { throw UsageError("--dt: bad"); }, output, errors) ==
              2);
        CHECK(errors.str() == "p: --dt: bad\n");
    }
    SUBCASE("other error") {
        CHECK(guarded_main("p", []() -> int { throw std::runtime_error("no convergence"); },
                           output, errors) == 1);
        CHECK(errors.str() == "p: error: no convergence\n");
    }
    SUBCASE("not a standard exception") {
        CHECK(guarded_main("p", []() -> int { throw 42; }, output, errors) == 1);
        CHECK(errors.str() == "p: error: unknown exception\n");
    }
    SUBCASE("failed output") {
        output.setstate(std::ios::badbit);
        CHECK(guarded_main("p", [] { return 0; }, output, errors) == 1);
        CHECK(errors.str() == "p: error: writing the standard output failed\n");
    }
}

namespace {

// The reason for refusing an output path, as a UsageError naming the option, or, for a path that
// does not come from an option, as a plain runtime error.
[[noreturn]] void throw_cannot_write(std::string_view option, const std::string& path,
                                     int error_number) {
    const std::string message =
        "cannot write " + json_string(path) + ": " + std::strerror(error_number);
    if (option.empty()) {
        throw std::runtime_error(message);
    }
    throw UsageError(std::string(option) + ": " + message);
}

// Numbers the temporary files of one process, so that two AtomicFiles never share one.
std::atomic<unsigned long> temporary_file_count{0};

// Interrupted runs. A process ended by a signal runs no destructor, so an AtomicFile could not
// remove its temporary file. For the signals that end a process by default and that a user or a
// system sends to stop a run (SIGHUP, SIGINT, SIGQUIT, SIGTERM, and SIGPIPE, SIGXFSZ on a closed
// pipe or an exceeded file size), a handler removes the temporary files of the AtomicFiles not yet
// committed, then restores the default action and raises the signal again, so that the process
// ends exactly as it would have (same signal, same exit status for the shell). The handler must be
// async-signal-safe: it only reads a fixed table of paths prepared in advance, calls unlink(2) on
// them and raise(3). A slot holds a heap copy of the path, published and withdrawn by atomic
// exchange, so that the handler sees either a complete path or none. Each new AtomicFile installs
// the handler for the signals whose action is (still, or again) the default: a program that
// ignores a signal or handles it itself keeps its choice. SIGKILL cannot be caught: its temporary
// file stays, and the next AtomicFile for the same target removes it (remove_stale_temporaries).
constexpr std::size_t max_pending_temporaries = 64;
std::atomic<char*> pending_temporaries[max_pending_temporaries];
constexpr int cleanup_signals[] = {SIGHUP, SIGINT, SIGQUIT, SIGTERM, SIGPIPE, SIGXFSZ};

extern "C" void remove_pending_temporaries_and_reraise(int signal_number) {
    const int saved_errno = errno;
    for (std::atomic<char*>& slot : pending_temporaries) {
        if (const char* path = slot.load()) {
            ::unlink(path);
        }
    }
    ::signal(signal_number, SIG_DFL);  // already reset by SA_RESETHAND; stated for clarity
    ::raise(signal_number);            // delivered when the handler returns
    errno = saved_errno;
}

void install_cleanup_handlers() {
    for (const int signal_number : cleanup_signals) {
        struct sigaction current {};
        if (::sigaction(signal_number, nullptr, &current) != 0 ||
            (current.sa_flags & SA_SIGINFO) != 0 || current.sa_handler != SIG_DFL) {
            continue;
        }
        struct sigaction action {};
        action.sa_handler = remove_pending_temporaries_and_reraise;
        sigemptyset(&action.sa_mask);
        action.sa_flags = SA_RESETHAND;
        ::sigaction(signal_number, &action, nullptr);
    }
}

// Registers a temporary path with the handler; returns the slot, or max_pending_temporaries when
// the table is full (the file is then only removed by destructors, as without the handler).
std::size_t register_pending_temporary(const std::string& path) {
    install_cleanup_handlers();
    char* copy = ::strdup(path.c_str());
    if (copy == nullptr) {
        return max_pending_temporaries;
    }
    for (std::size_t slot = 0; slot < max_pending_temporaries; ++slot) {
        char* expected = nullptr;
        if (pending_temporaries[slot].compare_exchange_strong(expected, copy)) {
            return slot;
        }
    }
    std::free(copy);
    return max_pending_temporaries;
}

void withdraw_pending_temporary(std::size_t slot) noexcept {
    if (slot < max_pending_temporaries) {
        std::free(pending_temporaries[slot].exchange(nullptr));
    }
}

// Temporary files of the same target left by processes that no longer exist (killed by SIGKILL, or
// by a power cut) are removed when the target is written again. A temporary file of a live process
// (another run writing the same target at this moment) is left alone; its name carries its pid.
void remove_stale_temporaries(const std::filesystem::path& target) noexcept {
    try {
        namespace fs = std::filesystem;
        const std::string prefix = "." + target.filename().string() + ".tmp.";
        const fs::path directory = target.has_parent_path() ? target.parent_path() : fs::path(".");
        std::error_code error;
        std::vector<fs::path> stale;
        for (fs::directory_iterator entry(directory, error), end; !error && entry != end;
             entry.increment(error)) {
            const std::string name = entry->path().filename().string();
            if (name.compare(0, prefix.size(), prefix) != 0) {
                continue;
            }
            const std::string_view rest = std::string_view(name).substr(prefix.size());
            long pid = 0;
            const auto [end_of_pid, status] =
                std::from_chars(rest.data(), rest.data() + rest.size(), pid);
            if (status != std::errc() || end_of_pid == rest.data() ||
                end_of_pid == rest.data() + rest.size() || *end_of_pid != '.' || pid <= 0 ||
                pid == ::getpid()) {
                continue;
            }
            if (::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) {
                stale.push_back(entry->path());
            }
        }
        for (const fs::path& path : stale) {
            fs::remove(path, error);
        }
    } catch (...) {
    }
}

}  // namespace

// Opening: the temporary file is created next to the target, because rename is atomic only within
// one file system. It is created with open(2) rather than by the stream, because open reliably sets
// errno, which gives the reason of a failure. A target that is a directory is refused here: the
// rename would fail only at the end.
AtomicFile::AtomicFile(std::string path, std::string_view option) : path_(std::move(path)) {
    namespace fs = std::filesystem;
    const fs::path target(path_);
    if (path_.empty()) {
        throw_cannot_write(option, path_, ENOENT);
    }
    std::error_code ignored;
    if (!target.has_filename() || fs::is_directory(target, ignored)) {
        throw_cannot_write(option, path_, EISDIR);
    }
    const std::string name = "." + target.filename().string() + ".tmp." +
                             std::to_string(::getpid()) + "." +
                             std::to_string(temporary_file_count++);
    temporary_path_ = (target.parent_path() / name).string();

    const int descriptor =
        ::open(temporary_path_.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (descriptor < 0) {
        throw_cannot_write(option, path_, errno);
    }
    ::close(descriptor);
    pending_slot_ = register_pending_temporary(temporary_path_);
    remove_stale_temporaries(target);
    stream_.open(temporary_path_, std::ios::binary | std::ios::trunc);
    if (!stream_) {
        const int error_number = errno != 0 ? errno : EIO;
        std::remove(temporary_path_.c_str());
        withdraw_pending_temporary(pending_slot_);
        throw_cannot_write(option, path_, error_number);
    }
}

// Committing: a stream records a failed write (a full disk, an I/O error) only in its state, so
// the state is checked after the last flush and after closing; only then does the file replace the
// target. On any failure the temporary file is removed and the target keeps its old content.
void AtomicFile::commit() {
    if (finished_) {
        throw std::logic_error("AtomicFile: " + json_string(path_) + " is already committed");
    }
    stream_.flush();
    const bool written = !stream_.fail();
    stream_.close();
    if (!written || stream_.fail()) {
        discard();
        throw std::runtime_error("cannot write " + json_string(path_) +
                                 ": writing the data failed (is the disk full?)");
    }
    if (std::rename(temporary_path_.c_str(), path_.c_str()) != 0) {
        const int error_number = errno;
        discard();
        throw std::runtime_error("cannot write " + json_string(path_) + ": renaming " +
                                 json_string(temporary_path_) + " failed: " +
                                 std::strerror(error_number));
    }
    withdraw_pending_temporary(pending_slot_);
    finished_ = true;
}

// Discarding: close the stream and remove the temporary file, without ever throwing, since this
// runs in the destructor, possibly during the unwinding of another exception.
void AtomicFile::discard() noexcept {
    finished_ = true;
    try {
        stream_.close();
    } catch (...) {
    }
    std::remove(temporary_path_.c_str());
    withdraw_pending_temporary(pending_slot_);
}

AtomicFile::~AtomicFile() {
    if (!finished_) {
        discard();
    }
}

namespace {

// A fresh directory for the tests of AtomicFile, removed with its content when the test ends,
// whether it passes or not.
class ScratchDirectory {
public:
    ScratchDirectory()
        : path_(std::filesystem::temp_directory_path() /
                ("mrm_cli_test." + std::to_string(::getpid()) + "." +
                 std::to_string(temporary_file_count++))) {
        std::filesystem::create_directory(path_);
    }
    ~ScratchDirectory() {
        std::error_code ignored;
        std::filesystem::remove_all(path_, ignored);
    }
    ScratchDirectory(const ScratchDirectory&) = delete;
    ScratchDirectory& operator=(const ScratchDirectory&) = delete;

    std::string file(std::string_view name) const { return (path_ / name).string(); }

    std::vector<std::string> entries() const {
        std::vector<std::string> names;
        for (const auto& entry : std::filesystem::directory_iterator(path_)) {
            names.push_back(entry.path().filename().string());
        }
        std::sort(names.begin(), names.end());
        return names;
    }

    static std::string content(const std::string& path) {
        std::ifstream file(path, std::ios::binary);
        std::ostringstream text;
        text << file.rdbuf();
        return text.str();
    }

    static void write(const std::string& path, std::string_view text) {
        std::ofstream(path, std::ios::binary) << text;
    }

private:
    std::filesystem::path path_;
};

}  // namespace

TEST_CASE("a committed AtomicFile replaces the target with the complete content") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    SUBCASE("new target") {}
    SUBCASE("existing target") { ScratchDirectory::write(target, "old content\n"); }

    AtomicFile file(target, "--output");
    CHECK(std::filesystem::path(file.temporary_path()).parent_path() ==
          std::filesystem::path(target).parent_path());
    CHECK(std::filesystem::path(file.temporary_path()).filename().string().rfind(
              ".results.dat.tmp." + std::to_string(::getpid()) + ".", 0) == 0);
    CHECK(std::filesystem::exists(file.temporary_path()));
    file.stream() << "# elements = 4\n1 2\n";
    file.commit();
    CHECK(ScratchDirectory::content(target) == "# elements = 4\n1 2\n");
    CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
    CHECK_THROWS_AS(file.commit(), std::logic_error);
}

TEST_CASE("an AtomicFile destroyed without commit leaves no file and the old target intact") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    SUBCASE("new target") {
        {
            AtomicFile file(target);
            file.stream() << "half of the data";
        }
        CHECK(directory.entries().empty());
    }
    SUBCASE("existing target") {
        ScratchDirectory::write(target, "old content\n");
        {
            AtomicFile file(target);
            file.stream() << "half of the data";
        }
        CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
        CHECK(ScratchDirectory::content(target) == "old content\n");
    }
}

TEST_CASE("a failed write makes the commit throw and leaves the old target intact") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    ScratchDirectory::write(target, "old content\n");
    AtomicFile file(target, "--output");
    file.stream() << "new content\n";
    file.stream().setstate(std::ios::badbit);
    CHECK_THROWS_WITH_AS(file.commit(),
                         ("cannot write " + json_string(target) +
                          ": writing the data failed (is the disk full?)")
                             .c_str(),
                         std::runtime_error);
    CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
    CHECK(ScratchDirectory::content(target) == "old content\n");
}

TEST_CASE("an unwritable output path is refused at once with the option's name and the reason") {
    ScratchDirectory directory;
    SUBCASE("missing directory") {
        const std::string path = directory.file("missing/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) +
                              ": No such file or directory")
                                 .c_str(),
                             UsageError);
    }
    SUBCASE("path is a directory") {
        const std::string path = directory.file("");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) + ": Is a directory")
                                 .c_str(),
                             UsageError);
        const std::string without_slash = directory.file(".");
        CHECK_THROWS_WITH_AS(AtomicFile(without_slash, "--output"),
                             doctest::Contains(": Is a directory"), UsageError);
    }
    SUBCASE("parent is a file") {
        ScratchDirectory::write(directory.file("plain"), "");
        const std::string path = directory.file("plain/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                             ("--output: cannot write " + json_string(path) + ": Not a directory")
                                 .c_str(),
                             UsageError);
    }
    SUBCASE("empty path") {
        CHECK_THROWS_WITH_AS(AtomicFile("", "--output"),
                             "--output: cannot write \"\": No such file or directory", UsageError);
    }
    SUBCASE("directory without write permission") {
        std::filesystem::permissions(directory.file(""), std::filesystem::perms::owner_read |
                                                             std::filesystem::perms::owner_exec);
        if (::geteuid() == 0) {
            MESSAGE("skipped: permissions do not apply to root");
        } else {
            const std::string path = directory.file("x.dat");
            CHECK_THROWS_WITH_AS(AtomicFile(path, "--output"),
                                 ("--output: cannot write " + json_string(path) +
                                  ": Permission denied")
                                     .c_str(),
                                 UsageError);
        }
        std::filesystem::permissions(directory.file(""), std::filesystem::perms::owner_all);
    }
    SUBCASE("a path not given by an option") {
        const std::string path = directory.file("missing/x.dat");
        CHECK_THROWS_WITH_AS(AtomicFile{path},
                             ("cannot write " + json_string(path) + ": No such file or directory")
                                 .c_str(),
                             std::runtime_error);
        bool usage_error = false;
        try {
            AtomicFile file(path);
        } catch (const UsageError&) {
            usage_error = true;
        } catch (const std::runtime_error&) {
        }
        CHECK_FALSE(usage_error);
    }
    for (const std::string& name : directory.entries()) {
        CAPTURE(name);
        CHECK(name.rfind(".", 0) != 0);
    }
}

// The signal handler is checked in a child process, which creates an AtomicFile over an existing
// target, writes part of its data and is then stopped by the signal, as a run interrupted by the
// user or the system would be. The parent checks how the child ended and what is left on disk.
TEST_CASE("a run stopped by a signal leaves the old target intact and no temporary file") {
    for (const int signal_number : {SIGTERM, SIGINT, SIGHUP, SIGPIPE}) {
        CAPTURE(signal_number);
        ScratchDirectory directory;
        const std::string target = directory.file("results.dat");
        ScratchDirectory::write(target, "old content\n");
        std::cout.flush();
        const pid_t child = ::fork();
        REQUIRE(child >= 0);
        if (child == 0) {
            // The child inherits the test runner's handlers; the test is about a program that
            // left the default action.
            ::signal(signal_number, SIG_DFL);
            {
                AtomicFile file(target, "--output");
                file.stream() << "half of the new data" << std::flush;
                ::raise(signal_number);
            }
            ::_exit(0);  // not reached if the handler ended the process
        }
        int status = 0;
        REQUIRE(::waitpid(child, &status, 0) == child);
        CHECK(WIFSIGNALED(status));
        CHECK(WTERMSIG(status) == signal_number);
        CHECK(directory.entries() == std::vector<std::string>{"results.dat"});
        CHECK(ScratchDirectory::content(target) == "old content\n");
    }
}

TEST_CASE("a temporary file left by a process that no longer exists is removed on the next write") {
    ScratchDirectory directory;
    const std::string target = directory.file("results.dat");
    ScratchDirectory::write(target, "old content\n");
    // A pid that no longer exists: a child that has ended and has been waited for.
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
        ::_exit(0);
    }
    REQUIRE(::waitpid(child, nullptr, 0) == child);
    const std::string stale = ".results.dat.tmp." + std::to_string(child) + ".0";
    const std::string live = ".results.dat.tmp." + std::to_string(::getppid()) + ".0";
    const std::string other = ".other.dat.tmp." + std::to_string(child) + ".0";
    for (const std::string& name : {stale, live, other}) {
        ScratchDirectory::write(directory.file(name), "left over");
    }
    AtomicFile file(target, "--output");
    file.stream() << "new content\n";
    file.commit();
    std::vector<std::string> expected{live, other, "results.dat"};
    std::sort(expected.begin(), expected.end());
    CHECK(directory.entries() == expected);
    CHECK(ScratchDirectory::content(target) == "new content\n");
}

TEST_SUITE_END();

}  // namespace mrm::cli
