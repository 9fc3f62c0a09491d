/// @file options/parser.cpp
/// @brief The option parser: registration, the help, the parse with its refusals, the echo of the effective values.
#include "options.hpp"
#include "output_file.hpp"

#include <CLI/CLI.hpp>

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

#ifndef MRM_VERSION
#define MRM_VERSION "unknown"
#endif

namespace mrm::cli {

TEST_SUITE_BEGIN("cli");

namespace {

// Names of options. A long name is "--" followed by letters, digits and inner dashes (CLI11 would
// also take '_', which the echo keys keep for the dash); a short name is "-" and one letter (never
// a digit, so that a negative number is never taken for an option).
bool is_long_name(std::string_view name) {
  return name.size() >= 3 && name.substr(0, 2) == "--" && name[2] != '-' && name.back() != '-' &&
         std::all_of(name.begin() + 2, name.end(),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '-'; });
}

bool is_short_name(std::string_view name) {
  return name.size() == 2 && name[0] == '-' && std::isalpha(static_cast<unsigned char>(name[1]));
}

// The key under which an option's value is echoed: "--final-time" gives "final_time".
std::string echo_key(std::string_view long_name) {
  std::string key(long_name.substr(2));
  std::replace(key.begin(), key.end(), '-', '_');
  return key;
}

// The columns a UTF-8 text takes on a terminal: its characters (every byte but the continuation bytes
// 10xxxxxx of a multi-byte character).
std::size_t columns(std::string_view text) {
  return static_cast<std::size_t>(
      std::count_if(text.begin(), text.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

// The description in the help is one paragraph, folded at word boundaries into lines of at most
// `width` columns (a longer word gets a line of its own), the first line after `first`, the others
// after `rest` (the widths count them).
std::string wrapped(std::string_view paragraph, std::size_t width = 80, const std::string& first = "",
                    const std::string& rest = "") {
  std::istringstream words{std::string(paragraph)};
  std::string result, line = first, word;
  bool empty = true;  // no word on the current line yet
  while (words >> word) {
    if (!empty && columns(line) + 1 + columns(word) > width) {
      result += line + '\n';
      line = rest;
      empty = true;
    }
    line += (empty ? "" : " ") + word;
    empty = false;
  }
  return empty && result.empty() ? result : result + line + '\n';
}

// The widest line of a help (a terminal's 100 columns): an option's description is folded into the
// column after the names, each item of a list of values on a line of its own, folded under its start.
constexpr std::size_t help_width = 100;

// An option's help: its first line is a paragraph, and each further line ('\n'-separated) one item of
// a list of values ("cn = Crank–Nicolson ..."). `column` spaces precede the description.
std::string option_description(std::string_view help, std::size_t column) {
  const std::string indent(column, ' '), item_indent(column + 2, ' '), item_rest(column + 4, ' ');
  const std::size_t newline = help.find('\n');
  std::string text = wrapped(help.substr(0, newline), help_width, indent, indent);
  for (std::size_t start = newline; start != std::string_view::npos;) {
    const std::size_t end = help.find('\n', start + 1);
    text += wrapped(help.substr(start + 1, end == std::string_view::npos ? end : end - start - 1), help_width,
                    item_indent, item_rest);
    start = end;
  }
  return text;
}

// A sample run longer than the help's width, folded as a shell continues a command ("\\" at the end of a
// line, the next one indented).
std::string sample_run(const std::string& run) {
  const std::string text = wrapped(run, help_width - 2, "  ", "      ");
  std::string result;
  for (std::size_t start = 0; start < text.size();) {
    const std::size_t end = text.find('\n', start);
    result += text.substr(start, end - start) + (end + 1 < text.size() ? " \\\n" : "\n");
    start = end + 1;
  }
  return result;
}

std::string joined(const std::vector<std::string>& words) {
  std::string list;
  for (const std::string& word : words) list += (list.empty() ? "" : ", ") + word;
  return list;
}

// The help, as CLI11 formatters make it (one column of names aligned on the longest, then the
// description, which carries the default and the choices since registration), followed by the
// sample runs: the layout tests/bad_invocations.cpp reads.
class Help : public CLI::Formatter {
 public:
  explicit Help(std::vector<std::string> sample_runs) : sample_runs_(std::move(sample_runs)) {}
  std::string make_help(const CLI::App* app, std::string, CLI::AppFormatMode) const override {
    std::vector<std::pair<std::string, std::string>> lines;
    bool writes_files = false;
    std::vector<const CLI::Option*> options = app->get_options();  // help and version last
    std::rotate(options.begin(), options.begin() + 2, options.end());
    for (const CLI::Option* option : options) {
      const std::string metavar = option->get_type_name();
      std::string names = "  ";
      names += option->get_snames().empty() ? "    " : "-" + option->get_snames().front() + ", ";
      names += "--" + option->get_lnames().front() + (option->get_expected_max() > 0 ? " " + metavar : "");
      lines.emplace_back(names, option->get_description());
      writes_files = writes_files || metavar == "FILE";
    }
    std::size_t width = 0;
    for (const auto& line : lines) width = std::max(width, line.first.size());
    std::string help = "Usage: " + app->get_name() + " [options]\n";
    if (!app->get_description().empty()) help += '\n' + wrapped(app->get_description());
    help += "\nOptions:\n";
    for (const auto& [names, text] : lines)
      help +=
          names + std::string(width + 2 - names.size(), ' ') + option_description(text, width + 2).substr(width + 2);
    // What an output option does with the path it is given (output_file.hpp), said once.
    if (writes_files) help += "\nOutput files:\n" + wrapped(output_files_help);
    if (!sample_runs_.empty()) help += "\nSample runs:\n";
    for (const std::string& run : sample_runs_) help += sample_run(run);
    return help;
  }

 private:
  std::vector<std::string> sample_runs_;
};

}  // namespace

TEST_CASE("option names are recognised by their form") {
  CHECK(is_long_name("--final-time"));
  CHECK(is_long_name("--p2"));
  for (const char* name : {"--", "-elements", "--final_time", "--final-", "---x"}) CHECK_FALSE(is_long_name(name));
  CHECK(is_short_name("-n"));
  for (const char* name : {"-5", "-nn", "n"}) CHECK_FALSE(is_short_name(name));
  CHECK(echo_key("--final-time") == "final_time");
}

TEST_CASE("a paragraph is folded at word boundaries within the width") {
  CHECK(wrapped("the  quick brown\nfox jumps", 10) == "the quick\nbrown fox\njumps\n");
  CHECK(wrapped("θθθθ βββββ", 10) == "θθθθ βββββ\n");  // ten columns, eighteen bytes
  CHECK(columns("Crank–Nicolson") == 14);
  CHECK(wrapped("a verylongword b", 5) == "a\nverylongword\nb\n");
  CHECK(wrapped("", 10).empty());
}

// What the parser keeps of an option beside CLI11's record: the variable, the check, the choices,
// whether its value is the path of a file.
struct Parser::Option {
  std::string long_name;
  std::variant<double*, long*, std::string*, bool*> target;
  Check check;
  std::vector<std::string> allowed;
  bool path = false;
  CLI::Option* cli = nullptr;
  int file = 0;                    // 1: a file written (add_output), 2: a file read (add_input)
  std::string help, default_text;  // as registered, and the variable's value then
};

namespace {

// An option's description in the help: its help, with the default (the variable's value at
// registration) and, for a choice, the allowed values, appended to the help's first paragraph. A help
// that lists its values one a line (each after a '\n') lists the choices itself: "(default: cn)" then
// comes before the list, in place of a closing ':'.
std::string described(const std::string& help, const std::vector<std::string>& allowed, const std::string& default_text,
                      bool shows_default) {
  std::string suffix;
  const std::size_t newline = help.find('\n');
  if (!allowed.empty() && newline == std::string::npos)
    suffix = " (one of: " + joined(allowed) + "; default: " + default_text + ")";
  else if (!default_text.empty() && shows_default)
    suffix = " (default: " + default_text + ")";
  if (newline == std::string::npos) return help + suffix;
  const bool colon = newline > 0 && help[newline - 1] == ':';
  return help.substr(0, newline - colon) + suffix + (colon ? ":" : "") + help.substr(newline);
}

}  // namespace

TEST_CASE("an option's description carries its default, and its choices unless it lists them") {
  CHECK(described("time step", {}, "0.5", true) == "time step (default: 0.5)");
  CHECK(described("time step", {}, "0", false) == "time step");
  CHECK(described("output", {}, "", true) == "output");
  CHECK(described("scheme", {"a", "b"}, "a", true) == "scheme (one of: a, b; default: a)");
  CHECK(described("scheme:\na = first\nb = second", {"a", "b"}, "a", true) ==
        "scheme (default: a):\na = first\nb = second");
  CHECK(described("scheme\na = first", {"a"}, "a", true) == "scheme (default: a)\na = first");
}

TEST_CASE("an option's description is folded within the help's width, a list one item a line") {
  const std::string long_text(30, 'x');
  // Three words of 30 characters after a column of 20: two on a line (20 + 61 <= 100), the third below.
  CHECK(option_description(long_text + " " + long_text + " " + long_text, 20) ==
        std::string(20, ' ') + long_text + " " + long_text + "\n" + std::string(20, ' ') + long_text + "\n");
  CHECK(option_description("scheme:\na = first\nb = second", 4) == "    scheme:\n      a = first\n      b = second\n");
  CHECK(sample_run("run --a 1") == "  run --a 1\n");
  const std::string run = "bench --output " + std::string(50, 'o') + " --tex " + std::string(40, 't');
  CHECK(sample_run(run) ==
        "  bench --output " + std::string(50, 'o') + " --tex \\\n      " + std::string(40, 't') + "\n");
}

// CLI11 knows the help flag from the start; --version prints "<program> <version>".
Parser::Parser(std::string program, std::string description, std::vector<std::string> sample_runs)
    : program_(std::move(program)), app_(std::make_unique<CLI::App>(std::move(description), program_)) {
  app_->formatter(std::make_shared<Help>(std::move(sample_runs)));
  app_->set_help_flag("-h,--help", "print this help and exit")->disable_flag_override();
  app_->set_version_flag("--version", program_ + " " + MRM_VERSION, "print the version and exit")
      ->disable_flag_override();
}

Parser::~Parser() = default;

// Every registration goes through `add`, which rejects the programming errors (malformed, reserved
// or duplicate names, a null variable) and hands the option to CLI11 with its help line, which
// carries the default (the variable's value now) and the choices. A value given is read by the
// option's validator: the rule that a value which is itself an option means a missing value
// ("--output --elements 5"), then the strict grammar of its kind and the choices; the range (the
// check) applies after the parse.
void Parser::add(std::string long_name, std::string short_name, std::string metavar, std::string help, Target target,
                 Check check, std::vector<std::string> allowed, int file) {
  if (!is_long_name(long_name) || !(short_name.empty() || is_short_name(short_name)))
    throw std::logic_error("Parser: invalid option name " + json_string(long_name + " " + short_name));
  const bool flag = std::holds_alternative<bool*>(target);
  if (flag != metavar.empty()) throw std::logic_error("Parser: " + long_name + ": a placeholder for values only");
  std::string default_text;
  std::visit(
      [&](auto* variable) {
        using Type = std::remove_pointer_t<decltype(variable)>;
        if (variable == nullptr) throw std::logic_error("Parser: " + long_name + " is bound to a null pointer");
        if constexpr (std::is_same_v<Type, double>) default_text = format_real(*variable);
        if constexpr (std::is_same_v<Type, long>) default_text = std::to_string(*variable);
        if constexpr (std::is_same_v<Type, std::string>) default_text = *variable;
      },
      target);
  if (!allowed.empty() && std::find(allowed.begin(), allowed.end(), default_text) == allowed.end())
    throw std::logic_error("Parser: the default of " + long_name + " is not one of its allowed values");
  const std::string description = described(help, allowed, default_text, true);
  const std::string names = short_name.empty() ? long_name : short_name + "," + long_name;
  try {
    if (flag) {
      options_.push_back(
          {long_name, target, {}, {}, false, app_->add_flag(names)->description(description), 0, help, default_text});
      options_.back().cli->disable_flag_override();
      return;
    }
    options_.push_back({long_name, target, std::move(check), std::move(allowed), file != 0 || metavar == "FILE",
                        app_->add_option(names)->description(description), file, help, default_text});
  } catch (const CLI::ConstructionError& error) {
    throw std::logic_error("Parser: " + long_name + ": " + error.what());
  }
  options_.back().cli->type_name(metavar)->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  options_.back().cli->check(CLI::Validator(
      [this, index = options_.size() - 1](std::string& text) {
        const Option& option = options_[index];
        if (text.substr(0, 2) == "--" || (is_short_name(text) && app_->get_option_no_throw(text) != nullptr))
          throw UsageError(option.long_name + ": missing value (expected " + option.cli->get_type_name() + ")");
        std::visit(
            [&](auto* variable) {
              using Type = std::remove_pointer_t<decltype(variable)>;
              if constexpr (std::is_same_v<Type, double>) *variable = parse_real(option.long_name, text);
              if constexpr (std::is_same_v<Type, long>) *variable = parse_integer(option.long_name, text);
              if constexpr (std::is_same_v<Type, std::string>)
                *variable = option.allowed.empty() ? text : parse_choice(option.long_name, text, option.allowed);
            },
            option.target);
        return std::string();
      },
      ""));
}

void Parser::add_real(std::string long_name, std::string short_name, std::string metavar, std::string help,
                      double* target, Check check) {
  add(std::move(long_name), std::move(short_name), std::move(metavar), std::move(help), target, std::move(check));
}

void Parser::add_integer(std::string long_name, std::string short_name, std::string metavar, std::string help,
                         long* target, Check check) {
  add(std::move(long_name), std::move(short_name), std::move(metavar), std::move(help), target, std::move(check));
}

void Parser::add_string(std::string long_name, std::string short_name, std::string metavar, std::string help,
                        std::string* target) {
  add(std::move(long_name), std::move(short_name), std::move(metavar), std::move(help), target);
}

void Parser::add_choice(std::string long_name, std::string short_name, std::string metavar, std::string help,
                        std::vector<std::string> allowed, std::string* target) {
  if (allowed.empty()) throw std::logic_error("Parser: " + long_name + " has no allowed value");
  add(std::move(long_name), std::move(short_name), std::move(metavar), std::move(help), target, {}, std::move(allowed));
}

void Parser::add_output(std::string long_name, std::string short_name, std::string help, std::string* target) {
  add(std::move(long_name), std::move(short_name), "FILE", std::move(help), target, {}, {}, 1);
}

void Parser::add_input(std::string long_name, std::string short_name, std::string help, std::string* target) {
  add(std::move(long_name), std::move(short_name), "FILE", std::move(help), target, {}, {}, 2);
}

void Parser::add_flag(std::string long_name, std::string short_name, std::string help, bool* target) {
  add(std::move(long_name), std::move(short_name), {}, std::move(help), target);
}

// A conflict is CLI11's exclusion; the pair is kept to name the options in the order given.
void Parser::add_conflict(std::string_view first_long_name, std::string_view second_long_name) {
  registered(first_long_name).cli->excludes(registered(second_long_name).cli);
  conflicts_.emplace_back(first_long_name, second_long_name);
}

// An option that does not apply beside another (options.hpp): kept with its reason and its condition.
struct Parser::NotApplicable {
  std::string option, other, reason;
  std::function<bool()> when;
};

void Parser::add_not_applicable(std::string long_name, std::string other_long_name, std::string reason,
                                std::function<bool()> when) {
  registered(long_name);
  registered(other_long_name);
  not_applicable_.push_back({std::move(long_name), std::move(other_long_name), std::move(reason), std::move(when)});
}

// The other option's value as the message shows it: a choice as the word it is (one of its list), a
// number as format_real writes it, any other text quoted (quoted_text), a flag not at all.
void Parser::refuse_not_applicable() const {
  for (const NotApplicable& rule : not_applicable_) {
    if (!given(rule.option) || !given(rule.other) || (rule.when && !rule.when())) continue;
    const Option& other = registered(rule.other);
    std::string value;
    std::visit(
        [&](const auto* variable) {
          using Type = std::remove_cv_t<std::remove_pointer_t<decltype(variable)>>;
          if constexpr (std::is_same_v<Type, double>) value = " " + format_real(*variable);
          if constexpr (std::is_same_v<Type, long>) value = " " + std::to_string(*variable);
          if constexpr (std::is_same_v<Type, std::string>)
            value = " " + (other.allowed.empty() ? quoted_text(*variable) : *variable);
        },
        other.target);
    throw UsageError(rule.option + ": does not apply with " + rule.other + value + " (" + rule.reason + ")");
  }
}

const Parser::Option& Parser::registered(std::string_view long_name) const {
  for (const Option& option : options_)
    if (option.long_name == long_name) return option;
  throw std::logic_error("Parser: no option " + json_string(long_name) + " is registered");
}

bool Parser::given(std::string_view long_name) const { return registered(long_name).cli->count() > 0; }

void Parser::without_default(std::string_view long_name) {
  registered(long_name);  // a programming error if it is not
  for (Option& option : options_)
    if (option.long_name == long_name) {
      option.cli->description(described(option.help, option.allowed, option.default_text, false));
    }
}

// The parse loop is CLI11's; around it, what CLI11 would let through or word otherwise. Before:
// "--" (CLI11's end of options) is an unknown option, and "--name=" gives the empty value
// (CLI11 would take the next argument). During: the validators above read every value. After: each
// of CLI11's errors (unknown options, exclusions, missing values) becomes the one-line UsageError
// naming the option, an option given twice is refused (CLI11 would keep the last value), and the
// ranges apply, once the conflicts are known to be absent.
Outcome Parser::parse(const std::vector<std::string>& arguments, std::ostream& out) {
  // One spelling of a short option, "-n 5": CLI11's "-n5", "-nv" and "-n=5" are unknown options.
  for (std::size_t k = 0; k < arguments.size(); ++k) {
    const std::string& argument = arguments[k];
    const CLI::Option* option = app_->get_option_no_throw(argument.substr(0, argument.find('=')));
    if (option != nullptr && option->get_expected_max() > 0 && argument.find('=') == std::string::npos)
      ++k;  // its value follows
    else if (option != nullptr && option->get_expected_max() == 0 && argument.rfind("--", 0) == 0 &&
             argument.find('=') != std::string::npos) {
      // A flag takes no value, not even the one it sets ("--verbose=true"; CLI11 would take it).
      const std::string name = argument.substr(0, argument.find('='));
      throw UsageError(name + ": takes no value (write " + quoted_text(name) + " alone)");
    } else if (argument.size() > 2 && argument[0] == '-' && std::isalpha(static_cast<unsigned char>(argument[1])))
      throw UsageError("unknown option " + quoted_text(argument) + " (see --help)");
  }
  std::vector<std::string> reversed;
  for (auto argument = arguments.rbegin(); argument != arguments.rend(); ++argument) {
    if (*argument == "--") throw UsageError("unknown option \"--\" (see --help)");
    const bool empty_value = argument->size() > 3 && argument->substr(0, 2) == "--" && argument->back() == '=';
    if (empty_value) reversed.emplace_back();
    reversed.push_back(empty_value ? argument->substr(0, argument->size() - 1) : *argument);
  }
  try {
    app_->parse(std::move(reversed));
  } catch (const CLI::CallForHelp&) {
    print_help(out);
    return Outcome::exit_success;
  } catch (const CLI::CallForVersion& version) {
    out << version.what() << '\n';
    return Outcome::exit_success;
  } catch (const CLI::ExtrasError&) {
    const std::string extra = app_->remaining().front();
    if (extra.size() < 2 || extra[0] != '-')
      throw UsageError("unexpected argument " + quoted_text(extra) + " (this program takes options only; see --help)");
    throw UsageError("unknown option " + quoted_text(extra.substr(0, extra.find('='))) + " (see --help)");
  } catch (const CLI::ExcludesError&) {
    for (const auto& [first, second] : conflicts_)
      if (given(first) && given(second)) throw UsageError(first + " and " + second + " cannot be given together");
    throw;
  } catch (const CLI::ArgumentMismatch& error) {
    const std::string message = error.what(), word = message.substr(0, message.find_first_of(": "));
    const std::string name = word[0] == '-' ? word : "--" + word;
    if (message.find("flag override") != std::string::npos)
      throw UsageError(name + ": takes no value (write " + quoted_text(name) + " alone)");
    throw UsageError(name + ": missing value (expected " + registered(name).cli->get_type_name() + ")");
  }
  for (const Option& option : options_) {
    if (option.cli->count() > 1) throw UsageError(option.long_name + ": given more than once");
    if (auto* const flag = std::get_if<bool*>(&option.target); flag && option.cli->count() > 0) **flag = true;
  }
  for (const Option& option : options_) {
    if (option.cli->count() == 0 || !option.check) continue;
    if (auto* const real = std::get_if<double*>(&option.target)) option.check(option.long_name, **real);
    if (auto* const integer = std::get_if<long*>(&option.target))
      option.check(option.long_name, static_cast<double>(**integer));
  }
  refuse_not_applicable();
  refuse_shared_files();
  return Outcome::run;
}

namespace {

// The identity of the file a path names, as the programs use it: an existing path by stat (links
// followed: the file an input reads, the file an output replaces), a path to nothing yet by its
// directory's identity and its name (the file an output will create). A path whose directory cannot
// be examined has none (AtomicFile or the reader then refuses it with its own message).
struct FileIdentity {
  dev_t device = 0;
  ino_t inode = 0;
  std::string name;  // empty for an existing file
  bool operator==(const FileIdentity& other) const {
    return device == other.device && inode == other.inode && name == other.name;
  }
};

std::optional<FileIdentity> file_identity(const std::string& path) {
  struct stat status {};
  if (::stat(path.c_str(), &status) == 0) return FileIdentity{status.st_dev, status.st_ino, ""};
  if (errno != ENOENT) return std::nullopt;
  const std::filesystem::path p(path);
  if (!p.has_filename()) return std::nullopt;
  const std::string directory = p.has_parent_path() ? p.parent_path().string() : ".";
  if (::stat(directory.c_str(), &status) != 0) return std::nullopt;
  return FileIdentity{status.st_dev, status.st_ino, p.filename().string()};
}

}  // namespace

// Every output against every input and every other output, by identity (file_identity): an output
// that is an input would replace the data it is computed from; two outputs on one file would leave
// only the last one committed.
void Parser::refuse_shared_files() const {
  struct Named {
    const Option* option;
    std::string path;
    FileIdentity identity;
  };
  std::vector<Named> files;
  for (const Option& option : options_) {
    if (option.file == 0) continue;
    const std::string& path = **std::get_if<std::string*>(&option.target);
    if (path.empty() || path == "-") continue;
    if (const std::optional<FileIdentity> identity = file_identity(path)) files.push_back({&option, path, *identity});
  }
  for (const Named& output : files) {
    if (output.option->file != 1) continue;
    for (const Named& other : files) {
      if (&other == &output || !(other.identity == output.identity)) continue;
      if (other.option->file == 1 && other.option > output.option) continue;  // each pair once
      const bool input = other.option->file == 2;
      throw UsageError(
          output.option->long_name + ": " + quoted_text(output.path) + " is the file of " + other.option->long_name +
          " " + quoted_text(other.path) +
          (input ? " (allowed: an output that replaces no input)" : " (allowed: a different file for each output)"));
    }
  }
}

Outcome Parser::parse(int argc, const char* const* argv, std::ostream& out) {
  return parse(std::vector<std::string>(argv + std::min(argc, 1), argv + argc), out);
}

void Parser::print_help(std::ostream& out) const { out << app_->help(); }

// The effective values, one `key = value` line each, in registration order; the paths of files
// (placeholder FILE, read or written) are left out.
void Parser::echo(std::ostream& out, std::string_view prefix) const {
  for (const Option& option : options_) {
    if (option.path) continue;
    out << prefix << echo_key(option.long_name) << " = ";
    std::visit(
        [&](const auto* variable) {
          using Type = std::remove_cv_t<std::remove_pointer_t<decltype(variable)>>;
          if constexpr (std::is_same_v<Type, double>) out << format_real(*variable);
          if constexpr (std::is_same_v<Type, long>) out << *variable;
          if constexpr (std::is_same_v<Type, std::string>) out << json_string(*variable);
          if constexpr (std::is_same_v<Type, bool>) out << (*variable ? "true" : "false");
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
  std::string scheme = "rk2";
  std::string output = "contact.dat";
  bool verbose = false;
  Parser parser{"contact",
                "Computes the motion of an elastic bar hitting a rigid obstacle.",
                {"contact -n 400 --scheme rk4", "contact --dt 1e-4 -o run.dat"}};

  ExampleProgram() {
    parser.add_integer("--elements", "-n", "N", "number of elements of the mesh", &elements, at_least(2));
    parser.add_real("--final-time", "-T", "T", "end of the simulated interval", &final_time, positive());
    parser.add_real("--dt", "", "DT", "time step", &dt, positive());
    parser.add_real("--courant", "", "C", "time step as a fraction of the CFL limit", &courant, positive());
    parser.add_real("--restitution", "-e", "E", "coefficient of restitution", &restitution, in_closed_range(0, 1));
    parser.add_choice("--scheme", "", "S", "time integration scheme", {"rk2", "rk4", "euler"}, &scheme);
    parser.add_output("--output", "-o", "data file to write", &output);
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
  CHECK(program.scheme == "rk2");
  CHECK(program.output == "contact.dat");
  CHECK_FALSE(program.verbose);
  CHECK_FALSE(program.parser.given("--elements"));
  CHECK_FALSE(program.parser.given("--verbose"));
}

TEST_CASE("values are read after long names, short names and '='") {
  ExampleProgram program;
  SUBCASE("separate arguments") {
    CHECK(program.parse({"--elements", "400", "-T", "3.5", "--scheme", "rk4", "-o", "a.dat", "-v"}) == Outcome::run);
  }
  SUBCASE("'=' after long names") {
    CHECK(program.parse({"--elements=400", "--final-time=3.5", "--scheme=rk4", "--output=a.dat", "--verbose"}) ==
          Outcome::run);
  }
  CHECK(program.elements == 400);
  CHECK(program.final_time == 3.5);
  CHECK(program.scheme == "rk4");
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
  CHECK_THROWS_WITH_AS(program.parse({"--foo"}), "unknown option \"--foo\" (see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--foo=3"}), "unknown option \"--foo\" (see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-x", "1"}), "unknown option \"-x\" (see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--elem", "1"}), "unknown option \"--elem\" (see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-n5"}), "unknown option \"-n5\" (see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-T=1"}), "unknown option \"-T=1\" (see --help)", UsageError);
  CHECK(program.parse({"-o", "-abc"}) == Outcome::run);  // a value, not an option
}

TEST_CASE("an option without its value is rejected with the expected placeholder") {
  ExampleProgram program;
  SUBCASE("at the end of the command line") {
    CHECK_THROWS_WITH_AS(program.parse({"--elements"}), "--elements: missing value (expected N)", UsageError);
  }
  SUBCASE("followed by another option") {
    CHECK_THROWS_WITH_AS(program.parse({"--output", "--elements", "5"}), "--output: missing value (expected FILE)",
                         UsageError);
    CHECK_THROWS_WITH_AS(program.parse({"-o", "-v"}), "--output: missing value (expected FILE)", UsageError);
  }
}

TEST_CASE("a malformed number on the command line is rejected with the option's name") {
  ExampleProgram program;
  CHECK_THROWS_WITH_AS(program.parse({"-n", "12abc"}),
                       "--elements: \"12abc\" is not an integer (expected base-10 digits, e.g. 42)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--final-time=nan"}),
                       doctest::Contains("--final-time: \"nan\" is not a finite decimal number"), UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--scheme", "xx"}), "--scheme: unknown value \"xx\" (allowed: rk2, rk4, euler)",
                       UsageError);
}

TEST_CASE("an option given twice is rejected, whichever names are used") {
  ExampleProgram program;
  CHECK_THROWS_WITH_AS(program.parse({"-n", "4", "--elements", "5"}), "--elements: given more than once", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-v", "-v"}), "--verbose: given more than once", UsageError);
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
                       "unexpected argument \"5\" (this program takes options only; see --help)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-"}), "unexpected argument \"-\" (this program takes options only; see --help)",
                       UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--verbose=yes"}), "--verbose: takes no value (write \"--verbose\" alone)",
                       UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--"}), "unknown option \"--\" (see --help)", UsageError);
  // Not even the value it sets, nor the help's and the version's.
  for (const char* argument : {"--verbose=true", "--verbose=false", "--verbose=", "--help=true", "--version=1"}) {
    const std::string name = std::string(argument).substr(0, std::string(argument).find('='));
    CHECK_THROWS_WITH_AS(program.parse({argument}), (name + ": takes no value (write \"" + name + "\" alone)").c_str(),
                         UsageError);
  }
}

TEST_CASE("an option that does not apply beside another is refused, naming both and what is allowed") {
  ExampleProgram program;
  std::string mode = "batch";
  program.parser.add_choice("--mode", "", "M", "how to run", {"batch", "merge"}, &mode);
  program.parser.add_not_applicable("--restitution", "--mode", "allowed: omit it, or --mode batch",
                                    [&] { return mode == "merge"; });
  program.parser.add_not_applicable("--verbose", "--output", "the file is quiet; allowed: omit --verbose");
  program.parser.add_not_applicable("--scheme", "--dt", "allowed: omit --scheme");
  CHECK_THROWS_WITH_AS(program.parse({"--mode", "merge", "-e", "0.5"}),
                       "--restitution: does not apply with --mode merge (allowed: omit it, or --mode batch)",
                       UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-v", "-o", "a\nb"}),
                       "--verbose: does not apply with --output \"a\\nb\" (the file is quiet; allowed: omit --verbose)",
                       UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--dt", "0.5", "--scheme", "rk4"}),
                       "--scheme: does not apply with --dt 0.5 (allowed: omit --scheme)", UsageError);
  // Either alone, or the condition false: a run.
  CHECK(program.parse({"--mode", "batch", "-e", "0.5"}) == Outcome::run);
  CHECK(program.parse({"-e", "0.5"}) == Outcome::run);
  CHECK(program.parse({"--mode", "merge"}) == Outcome::run);
  CHECK(program.parse({"-v"}) == Outcome::run);
  CHECK_THROWS_AS(program.parser.add_not_applicable("--missing", "--dt", ""), std::logic_error);
}

TEST_CASE("checks reject given values out of range but not the defaults") {
  ExampleProgram program;
  CHECK_THROWS_WITH_AS(program.parse({"--restitution", "1.5"}),
                       "--restitution: 1.5 is outside the allowed range [0, 1]", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-n", "1"}), "--elements: 1 is not allowed (expected a value >= 2)", UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"--dt=0"}), "--dt: 0 is not allowed (expected a value > 0)", UsageError);
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
    CHECK(program.parser.parse({"-n", "5", help, "--unknown"}, printed) == Outcome::exit_success);
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
          "      --scheme S       time integration scheme (one of: rk2, rk4, euler; default: "
          "rk2)\n"
          "  -o, --output FILE    data file to write (default: contact.dat)\n"
          "  -v, --verbose        print the progress\n"
          "  -h, --help           print this help and exit\n"
          "      --version        print the version and exit\n"
          "\n"
          "Output files:\n"
          "Each FILE is written under a hidden temporary name in its directory and renamed\n"
          "over FILE only when complete: a failed run leaves FILE as it was, an interrupted\n"
          "one at most a hidden .FILE.tmp.* beside it. A replaced FILE keeps its\n"
          "permissions; a symbolic link to a file is followed. FILE - is the standard\n"
          "output. A FILE that exists and is not a regular file (a directory, a device) is\n"
          "refused.\n"
          "\n"
          "Sample runs:\n"
          "  contact -n 400 --scheme rk4\n"
          "  contact --dt 1e-4 -o run.dat\n");
  }
}

TEST_CASE("the version is printed after the program's name and stops the program") {
  ExampleProgram program;
  std::ostringstream printed;
  CHECK(program.parser.parse({"--version"}, printed) == Outcome::exit_success);
  CHECK(printed.str() == std::string("contact ") + MRM_VERSION + "\n");
}

TEST_CASE("an output naming an input's file, or another output's, is refused whatever the spelling") {
  // In a scratch directory: d.dat (the input), its hard link, a symbolic link to it, a linked
  // directory; each spelling of the same file as an output is refused, each other file accepted.
  namespace fs = std::filesystem;
  std::string pattern = (fs::temp_directory_path() / "mrm_identity_test.XXXXXX").string();
  const fs::path scratch = ::mkdtemp(pattern.data());
  const fs::path here = fs::current_path();
  fs::current_path(scratch);
  std::ofstream("d.dat") << "0 0.5 0\n1 0 0\n";
  fs::create_directory("sub");
  fs::create_hard_link("d.dat", "hard.dat");
  fs::create_symlink("d.dat", "soft.dat");
  fs::create_directory_symlink(".", "same_dir");
  const std::string absolute = (scratch / "d.dat").string();
  std::string input, output = "out.dat", tex;
  int cases = 0;
  const auto parse = [&](const std::vector<std::string>& arguments) {
    Parser parser("p", "", {});
    parser.add_input("--initial-data", "", "read", &input);
    parser.add_output("--output", "-o", "write", &output);
    parser.add_output("--tex", "", "write", &tex);
    input.clear();
    output = "out.dat";
    tex.clear();
    ++cases;
    std::ostringstream printed;
    return parser.parse(arguments, printed);
  };
  for (const std::string& same : std::vector<std::string>{"d.dat", "./d.dat", "sub/../d.dat", "same_dir/d.dat",
                                                          "hard.dat", "soft.dat", absolute, ".//d.dat"}) {
    CAPTURE(same);
    CHECK_THROWS_WITH_AS(parse({"--initial-data", "d.dat", "--output", same}),
                         ("--output: " + quoted_text(same) +
                          " is the file of --initial-data \"d.dat\" (allowed: an output that replaces no input)")
                             .c_str(),
                         UsageError);
    CHECK_THROWS_WITH_AS(parse({"--initial-data", same, "--tex", "d.dat"}),
                         doctest::Contains("--tex: \"d.dat\" is the file of --initial-data"), UsageError);
  }
  // The default output counts: an input that is the default output's file.
  CHECK_THROWS_WITH_AS(parse({"--initial-data", "./out.dat"}),
                       doctest::Contains("--output: \"out.dat\" is the file of --initial-data"), UsageError);
  // Two outputs on one file, existing or new.
  for (const auto& [first, second] : std::vector<std::pair<std::string, std::string>>{
           {"new.dat", "new.dat"}, {"new.dat", "./new.dat"}, {"new.dat", "same_dir/new.dat"}, {"d.dat", "soft.dat"}}) {
    CAPTURE(second);
    CHECK_THROWS_WITH_AS(parse({"--output", first, "--tex", second}),
                         doctest::Contains("(allowed: a different file for each output)"), UsageError);
  }
  // Different files, "-" and missing directories are not this check's.
  for (const std::vector<std::string>& fine :
       std::vector<std::vector<std::string>>{{"--initial-data", "d.dat", "--output", "sub/d.dat"},
                                             {"--initial-data", "d.dat", "--output", "-", "--tex", "-"},
                                             {"--initial-data", "d.dat", "--output", "missing/d.dat"},
                                             {"--output", "a.dat", "--tex", "b.dat"}}) {
    CHECK(parse(fine) == Outcome::run);
  }
  CHECK(cases == 25);
  fs::current_path(here);
  fs::remove_all(scratch);
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

TEST_CASE("CLI11's own readings of numbers are not the project's") {
  ExampleProgram program;
  CHECK(program.parse({"-n", "010"}) == Outcome::run);
  CHECK(program.elements == 10);  // CLI11 alone reads 8
  CHECK_THROWS_WITH_AS(program.parse({"-T", "nan"}), doctest::Contains("--final-time: \"nan\" is not a finite"),
                       UsageError);
  CHECK_THROWS_WITH_AS(program.parse({"-n", "0x10"}), doctest::Contains("--elements: \"0x10\" is not an integer"),
                       UsageError);
}

TEST_CASE("the echo writes every effective value but the outputs as a deterministic header line") {
  ExampleProgram program;
  program.parse({"-n", "400", "--dt", "0.1", "-o", "run \"1\".dat", "-v", "--scheme=euler"});
  std::ostringstream echoed;
  program.parser.echo(echoed);
  CHECK(echoed.str() ==
        "# elements = 400\n"
        "# final_time = 12\n"
        "# dt = 0.1\n"
        "# courant = 0.5\n"
        "# restitution = 0\n"
        "# scheme = \"euler\"\n"
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
  CHECK_THROWS_AS(parser.add_choice("--scheme", "", "S", "", {"rk2", "rk4"}, &text), std::logic_error);
  CHECK_THROWS_AS(parser.add_conflict("--elements", "--missing"), std::logic_error);
  CHECK_THROWS_AS(parser.given("--missing"), std::logic_error);
  CHECK_NOTHROW(parser.add_real("--x", "", "X", "", &real));
}

TEST_SUITE_END();

}  // namespace mrm::cli
