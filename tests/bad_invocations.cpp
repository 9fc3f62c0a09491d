// Bad command lines, given to every program of BIN_DIR: one driver process that starts each case
// directly (fork, exec) and checks what it did. ctest runs `bad_invocations BIN_DIR TABLE`; a
// program's name after them restricts the run to those programs. Every program shares
// mrm::cli::Parser, so every program must answer a bad command line the same way:
//
//   - exit status 2 (or the status listed for the case);
//   - one line on stderr, "<program>: ...", that contains the expected fragment (at least the
//     option's name);
//   - nothing on stdout;
//   - no file created, removed or changed in the working directory (name, type, size, inode and
//     modification time of every entry, hidden ones included: a file rewritten in place changes its
//     time, one replaced by a rename its inode), and an existing output file given with the bad
//     options left byte for byte as it was;
//
// and `--help`, `-h` and `--version` must exit 0 with their text on stdout and nothing on stderr.
//
// The cases come from two sources:
//
//   1. generic cases, derived for each program from its own `--help` (the format printed by
//      cli::Parser::print_help): unknown options, positional arguments, every option without its
//      value and given twice, every numeric option given malformed numbers ("", "1e", "nan", "inf",
//      "12abc", "1e400", ...: all 23 or 25 of them for the first integer and the first real option of
//      the program, one of each sort for the others, which go through the same parsing), every
//      choice given a value outside its list, every flag given a value (even "=true"), --threads
//      given 0, 257 and 2^32, every pair of options the help says exclude each other ("excludes
//      --x"), and every
//      output file option given a missing directory, a directory and an empty path. The kind of
//      each option (integer, real, choice, string) is found by probing: `--option zzz --zz-probe`
//      fails on the value for a number or a choice, with the message saying which, and on the
//      unknown option `--zz-probe` for a string, so the probe never runs the program. Programs added
//      later are covered without editing this file.
//   2. the table tests/bad_invocations.txt, one case per line,
//        program | arguments (shell words) | expected exit status | expected message fragment
//      for what cannot be derived from the help: values out of an option's range, contradictory
//      combinations, failures during the run. `$here` in the arguments is the table's directory.
//      Lines for programs that are not built are skipped.
//
// When a program has output file options (a FILE option whose name contains "output" or whose help
// says "write"), each case also gives every such option not already in the case an existing file
// with known content (appended after the case's arguments, so that the case's own error comes
// first), and checks that the file is left intact. Each run has a time limit (a hang fails).
//
// It prints the number of bad invocations tried for each program; bar1d must have at least 30.
// One case is one process (the old shell driver started about fifteen per case); the programs are
// checked two at a time (MRM_TEST_JOBS), each by a child of this driver in its own directory.
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fs = std::filesystem;
using Words = std::vector<std::string>;

namespace {

constexpr unsigned time_limit = 30;  // seconds, for any one run

std::string bin, scratch;
int failures = 0;

std::string read_file(const std::string& path) {
  std::ifstream file(path, std::ios::binary);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string shell_quoted(const Words& words) {
  std::string shown;
  for (const std::string& word : words) {
    const bool plain = !word.empty() && word.find_first_not_of(
                                            "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                            "0123456789-_=./:,+%") == std::string::npos;
    shown += (plain ? word : "'" + word + "'") + " ";
  }
  return shown;
}

// ---- One run ---------------------------------------------------------------------------------------

struct Run {
  int status = -1;  // exit status; -1 if it died by a signal
  bool timed_out = false;
  int signal = 0;
  std::string out, err;
};

// Runs BIN/program with `arguments` in `directory`, stdout and stderr to files, under the time limit
// (an alarm set before exec: SIGALRM ends a run that hangs).
Run run(const std::string& program, const Words& arguments, const std::string& directory) {
  const std::string out_path = directory + ".stdout", err_path = directory + ".stderr";
  const std::string path = bin + "/" + program;
  std::vector<char*> argv{const_cast<char*>(path.c_str())};
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  std::cout.flush();
  const pid_t child = ::fork();
  if (child < 0) {
    std::perror("bad_invocations: fork");
    std::exit(1);
  }
  if (child == 0) {
    const int out = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int err = ::open(err_path.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (out < 0 || err < 0 || ::dup2(out, 1) < 0 || ::dup2(err, 2) < 0 || ::chdir(directory.c_str()) != 0) ::_exit(126);
    ::close(out);
    ::close(err);
    ::alarm(time_limit);
    ::execv(path.c_str(), argv.data());
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(child, &status, 0) < 0 && errno == EINTR) {
  }
  Run result;
  if (WIFEXITED(status)) {
    result.status = WEXITSTATUS(status);
  } else if (WIFSIGNALED(status)) {
    result.signal = WTERMSIG(status);
    result.timed_out = result.signal == SIGALRM;
  }
  result.out = read_file(out_path);
  result.err = read_file(err_path);
  return result;
}

// The state of a directory: name, type, size, inode and modification time (to the nanosecond) of
// every entry, hidden ones included.
std::vector<std::string> snapshot(const std::string& directory) {
  std::vector<std::string> entries;
  for (const auto& entry : fs::recursive_directory_iterator(directory)) {
    struct stat status {};
    ::lstat(entry.path().c_str(), &status);
    entries.push_back(fs::relative(entry.path(), directory).string() + " " + std::to_string(status.st_mode) + " " +
                      std::to_string(status.st_size) + " " + std::to_string(status.st_ino) + " " +
                      std::to_string(status.st_mtim.tv_sec) + "." + std::to_string(status.st_mtim.tv_nsec));
  }
  std::sort(entries.begin(), entries.end());
  return entries;
}

std::vector<std::string> changes(const std::vector<std::string>& before, const std::vector<std::string>& after) {
  std::vector<std::string> changed;
  std::set_symmetric_difference(before.begin(), before.end(), after.begin(), after.end(), std::back_inserter(changed));
  return changed;
}

// ---- The options of a program, read from its help ------------------------------------------------

struct Option {
  std::string name, short_name, metavar, help, default_value, kind;
};

struct Program {
  std::string name, work;
  std::vector<Option> options;
  std::vector<std::string> output_options;
  std::vector<std::pair<std::string, std::string>> conflicts;
  int tried = 0, generic = 0, failed = 0;
};

void fail(Program& program, const std::string& what) {
  std::cout << "FAIL " << program.name << " " << what << '\n';
  ++failures;
  ++program.failed;
}

// An option's line, `  -n, --name META  description`; its description may go on over the lines below,
// indented to its column (a list of values one item a line, options.hpp), which are joined to it.
void read_options(Program& program, const std::string& help) {
  static const std::regex line_pattern(R"(^  (-[A-Za-z], |    )(--[A-Za-z0-9-]+)( ([^ ]+))?  +(.*)$)");
  static const std::regex continuation_pattern(R"(^ {8,}(\S.*)$)");
  static const std::regex choice_pattern(R"(\(one of: ([^;]*); default: ([^)]*)\))");
  static const std::regex default_pattern(R"(\(default: ([^)]*)\))");
  static const std::regex conflict_pattern(R"(excludes (--[A-Za-z0-9-]+))");
  std::istringstream lines(help);
  std::string line;
  bool in_options = false, skipped = false;  // skipped: the last option line read was --help or --version
  while (std::getline(lines, line)) {
    if (line == "Options:") {
      in_options = true;
      continue;
    }
    if (!in_options) continue;
    if (line.empty()) break;
    std::smatch match;
    if (std::regex_match(line, match, continuation_pattern)) {
      if (!skipped && !program.options.empty()) program.options.back().help += " " + match[1].str();
      continue;
    }
    if (!std::regex_match(line, match, line_pattern)) continue;
    Option option;
    option.name = match[2];
    skipped = option.name == "--help" || option.name == "--version";
    if (skipped) continue;
    option.short_name = match[1].str() == "    " ? "" : match[1].str().substr(0, 2);
    option.metavar = match[4];
    option.help = match[5];
    program.options.push_back(option);
  }
  for (Option& option : program.options) {
    // The default is the parser's own "(default: X)" or "(one of: ...; default: X)": the last one of the
    // help (its text may say "default" before it), at its end or before its list of values.
    for (const std::regex* pattern : {&default_pattern, &choice_pattern})
      for (std::sregex_iterator match(option.help.begin(), option.help.end(), *pattern), end; match != end; ++match)
        option.default_value = (*match)[match->size() - 1];
    std::smatch part;
    if (std::regex_search(option.help, part, conflict_pattern)) program.conflicts.emplace_back(option.name, part[1]);
    if (!option.metavar.empty() &&
        (option.name.find("output") != std::string::npos || option.help.find("write") != std::string::npos)) {
      program.output_options.push_back(option.name);
    }
  }
}

const Option* find_option(const Program& program, const std::string& name) {
  for (const Option& option : program.options) {
    if (option.name == name) return &option;
  }
  return nullptr;
}

std::string existing_file(const std::string& option) {
  std::string name = "existing" + option + ".dat";
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

// ---- One bad invocation --------------------------------------------------------------------------

void check_bad(Program& program, int expected_status, const std::string& fragment, Words arguments) {
  // Existing output files for the output options not in the case.
  for (const std::string& name : program.output_options) {
    const std::string& short_name = find_option(program, name)->short_name;
    const bool given = std::any_of(arguments.begin(), arguments.end(), [&](const std::string& argument) {
      return argument == name || argument.rfind(name + "=", 0) == 0 || (!short_name.empty() && argument == short_name);
    });
    if (!given) {
      arguments.push_back(name);
      arguments.push_back(program.work + "/" + existing_file(name));
    }
  }
  const auto before = snapshot(program.work);
  const Run result = run(program.name, arguments, program.work);
  const auto changed = changes(before, snapshot(program.work));
  ++program.tried;
  const std::string shown = shell_quoted(arguments) + ": ";
  if (result.timed_out) {
    fail(program, shown + "did not finish within " + std::to_string(time_limit) + " s");
  } else if (result.signal != 0) {
    fail(program, shown + "ended by signal " + std::to_string(result.signal));
  } else if (result.status != expected_status) {
    fail(program,
         shown + "exit status " + std::to_string(result.status) + ", expected " + std::to_string(expected_status));
  }
  if (!result.out.empty()) fail(program, shown + "wrote to stdout: " + result.out.substr(0, 200));
  const auto lines = std::count(result.err.begin(), result.err.end(), '\n');
  if (lines != 1) {
    fail(program, shown + "stderr has " + std::to_string(lines) + " lines, expected 1: " + result.err.substr(0, 400));
  }
  const std::string message = result.err.substr(0, result.err.find('\n'));
  if (message.rfind(program.name + ": ", 0) != 0) {
    fail(program, shown + "stderr does not start with \"" + program.name + ": \": " + message);
  }
  if (message.find(fragment) == std::string::npos) {
    fail(program, shown + "stderr does not contain \"" + fragment + "\": " + message);
  }
  if (!changed.empty()) fail(program, shown + "files changed: " + changed.front());
}

// ---- --help, -h and --version --------------------------------------------------------------------

void check_help_and_version(Program& program) {
  for (const std::string request : {"--help", "-h", "--version"}) {
    const auto before = snapshot(program.work);
    const Run result = run(program.name, {request}, program.work);
    if (result.status != 0) fail(program, request + ": exit status " + std::to_string(result.status) + ", expected 0");
    if (!result.err.empty()) fail(program, request + ": wrote to stderr: " + result.err.substr(0, 200));
    if (!changes(before, snapshot(program.work)).empty()) fail(program, request + ": files changed");
    if (request == "--version") {
      const std::regex version("^" + program.name + " [^ \n]*\n$");
      if (!std::regex_match(result.out, version)) {
        fail(program,
             "--version: expected one line \"" + program.name + " VERSION\", got: " + result.out.substr(0, 200));
      }
    } else if (result.out.rfind("Usage: " + program.name + " [options]\n", 0) != 0) {
      fail(program, request + ": the help does not start with \"Usage: " + program.name + " [options]\"");
    } else {
      // A terminal's width: every line of the help within 100 columns (characters, not bytes).
      std::istringstream lines(result.out);
      std::string line;
      while (std::getline(lines, line)) {
        const auto columns = std::count_if(line.begin(), line.end(), [](char c) { return (c & 0xC0) != 0x80; });
        if (columns > 100) fail(program, request + ": a help line of " + std::to_string(columns) + " columns: " + line);
      }
    }
  }
}

// ---- The generic cases ---------------------------------------------------------------------------

const Words malformed_numbers{"",   "1e", "nan", "NaN",  "inf", "-inf", "infinity", "12abc",  "abc", "0x10",
                              " 1", "1 ", "1,5", "1..2", "+-1", "--1",  "1e400",    "-1e400", "e5",  "."};
const Words malformed_integers{"1.5", "1e3", "99999999999999999999", "-99999999999999999999", "2."};
const Words malformed_reals{"1e-400", "1e+", "5%"};

// The kind of a value option, by the probe described at the top.
std::string probe_kind(const Program& program, const std::string& option) {
  const std::string message = run(program.name, {option, "zzz", "--zz-probe"}, program.work).err;
  if (message.find("is not an integer") != std::string::npos) return "integer";
  if (message.find("is not a finite decimal number") != std::string::npos) return "real";
  if (message.find("unknown value") != std::string::npos) return "choice";
  if (message.find("unknown option \"--zz-probe\"") != std::string::npos) return "string";
  return "unknown: " + message;
}

std::string upper(std::string text) {
  for (char& character : text) character = static_cast<char>(std::toupper(static_cast<unsigned char>(character)));
  return text;
}

void generic_cases(Program& program) {
  check_bad(program, 2, "\"--zz-no-such-option\"", {"--zz-no-such-option"});
  check_bad(program, 2, "\"--zz-no-such-option\"", {"--zz-no-such-option=1"});
  check_bad(program, 2, "\"positional\"", {"positional"});
  check_bad(program, 2, "\"-\"", {"-"});
  check_bad(program, 2, "\"--\"", {"--"});
  check_bad(program, 2, "\"--help\"", {"--help=yes"});
  for (const std::string letter : {"-Z", "-Q"}) {
    if (std::none_of(program.options.begin(), program.options.end(),
                     [&](const Option& option) { return option.short_name == letter; })) {
      check_bad(program, 2, "\"" + letter + "\"", {letter, "1"});
      break;
    }
  }
  std::set<std::string> first_of_kind;
  for (Option& option : program.options) {
    const std::string& name = option.name;
    if (option.metavar.empty()) {
      option.kind = "flag";
      check_bad(program, 2, name + ": takes no value", {name + "=1"});
      check_bad(program, 2, name + ": takes no value", {name + "=true"});  // not even the value it sets
      check_bad(program, 2, name + ": given more than once", {name, name});
      continue;
    }
    option.kind = probe_kind(program, name);
    if (option.kind.rfind("unknown", 0) == 0) {
      fail(program, name + ": cannot tell the kind of the option from the probe (" + option.kind + ")");
      continue;
    }
    // A valid value: the default, or a plain word for a string without default.
    std::string valid = option.default_value;
    if (valid.empty()) valid = option.kind == "string" ? "x" : option.kind == "integer" ? "2" : "1";
    check_bad(program, 2, name + ": missing value", {name});
    check_bad(program, 2, name + ": given more than once", {name, valid, name, valid});
    if (!option.short_name.empty()) {
      check_bad(program, 2, name + ": missing value", {option.short_name});
      check_bad(program, 2, name + ": given more than once", {option.short_name, valid, name + "=" + valid});
    }
    // The worker threads of every program that has them: one range, refused before any work
    // (run_limits.hpp, add_threads_option), also for a count that a 32-bit conversion would wrap.
    if (name == "--threads") {
      check_bad(program, 2, "--threads: 257 is outside the allowed range [1, 256]", {name, "257"});
      check_bad(program, 2, "--threads: 4294967296 is outside the allowed range [1, 256]", {name, "4294967296"});
      check_bad(program, 2, "--threads: 0 is outside the allowed range [1, 256]", {name + "=0"});
    }
    if (option.kind == "integer" || option.kind == "real") {
      // Every malformed number for the first option of each kind; a sample of them (one of each
      // sort: empty, not a number, trailing characters, overflow, and the kind's own) for the others,
      // which go through the same parsing.
      Words values = malformed_numbers;
      const Words& extra = option.kind == "integer" ? malformed_integers : malformed_reals;
      values.insert(values.end(), extra.begin(), extra.end());
      // The separate form too, for the values that are not taken for an option.
      Words separate{"", "nan", "12abc", "1e"};
      if (!first_of_kind.insert(option.kind).second) {
        values = {"", "nan", "12abc", "1e400", extra.front()};
        separate = {"nan"};
      }
      for (const std::string& value : values) check_bad(program, 2, name + ": ", {name + "=" + value});
      for (const std::string& value : separate) check_bad(program, 2, name + ": ", {name, value});
    } else if (option.kind == "choice") {
      for (const std::string& value :
           {std::string("zz-not-a-choice"), std::string(), upper(valid), valid + " ", valid + "," + valid}) {
        check_bad(program, 2, name + ": unknown value", {name + "=" + value});
      }
    }
  }
  for (const auto& [first, second] : program.conflicts) {
    const Option* a = find_option(program, first);
    const Option* b = find_option(program, second);
    const std::string value_a = a && !a->default_value.empty() ? a->default_value : "1";
    const std::string value_b = b && !b->default_value.empty() ? b->default_value : "1";
    check_bad(program, 2, first + " and " + second + " cannot be given together", {first, value_a, second, value_b});
  }
  for (const std::string& option : program.output_options) {
    check_bad(program, 2, option + ": cannot write", {option, scratch + "/missing-directory/x.dat"});
    check_bad(program, 2, option + ": cannot write", {option, program.work});
    check_bad(program, 2, option + ": cannot write", {option + "="});
  }
}

// ---- The table -----------------------------------------------------------------------------------

std::string trimmed(const std::string& text) {
  const auto begin = text.find_first_not_of(" \t");
  if (begin == std::string::npos) return "";
  return text.substr(begin, text.find_last_not_of(" \t") - begin + 1);
}

// Shell words: blanks separate, '...' and "..." quote, $'...' quotes with \n, \t, \r, \e and \xHH (bash's
// ANSI-C quoting, for control characters in a case), \ escapes outside single quotes, $here and
// ${here} expand outside single quotes. Throws on an unterminated quote.
Words shell_words(const std::string& text, const std::string& here) {
  Words words;
  std::string word;
  bool in_word = false;
  char quote = 0;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (quote == '\'') {
      if (c == '\'')
        quote = 0;
      else
        word += c;
      continue;
    }
    if (c == '$' && quote == 0 && i + 1 < text.size() && text[i + 1] == '\'') {
      // $'...' as in bash: \n, \t, \r, \e and \xHH stand for those bytes (control characters in a case).
      in_word = true;
      for (i += 2; i < text.size() && text[i] != '\''; ++i) {
        if (text[i] != '\\' || i + 1 >= text.size()) {
          word += text[i];
          continue;
        }
        const char e = text[++i];
        if (e == 'n')
          word += '\n';
        else if (e == 't')
          word += '\t';
        else if (e == 'r')
          word += '\r';
        else if (e == 'e')
          word += '\x1b';
        else if (e == 'x' && i + 2 < text.size())
          word += static_cast<char>(std::stoi(text.substr(i + 1, 2), nullptr, 16)), i += 2;
        else
          word += e;
      }
      if (i >= text.size()) throw std::runtime_error("unterminated quote");
    } else if (c == '$' && text.compare(i, 5, "$here") == 0) {
      word += here, in_word = true, i += 4;
    } else if (c == '$' && text.compare(i, 7, "${here}") == 0) {
      word += here, in_word = true, i += 6;
    } else if (c == '\\' && i + 1 < text.size()) {
      word += text[++i], in_word = true;
    } else if (quote == '"') {
      if (c == '"')
        quote = 0;
      else
        word += c;
    } else if (c == '\'' || c == '"') {
      quote = c, in_word = true;
    } else if (c == ' ' || c == '\t') {
      if (in_word) words.push_back(word);
      word.clear(), in_word = false;
    } else {
      word += c, in_word = true;
    }
  }
  if (quote != 0) throw std::runtime_error("unterminated quote");
  if (in_word) words.push_back(word);
  return words;
}

void table_cases(Program& program, const std::string& table) {
  std::ifstream file(table);
  const std::string here = fs::path(table).parent_path().string();
  std::string line;
  for (int number = 1; std::getline(file, line); ++number) {
    const std::string content = trimmed(line);
    if (content.empty() || content[0] == '#') continue;
    std::vector<std::string> fields;
    std::istringstream parts(line);
    for (std::string field; fields.size() < 3 && std::getline(parts, field, '|');) fields.push_back(field);
    std::string fragment;
    std::getline(parts, fragment);  // the rest, which may hold '|'
    if (fields.size() < 3 || trimmed(fields[0]) != program.name) continue;
    try {
      check_bad(program, std::stoi(trimmed(fields[2])), trimmed(fragment), shell_words(fields[1], here));
    } catch (const std::exception& error) {
      fail(program, table + ":" + std::to_string(number) + ": cannot read the case (" + error.what() + ")");
    }
  }
}

// Every check of one program; returns the number of failures.
int check_program(const std::string& name, const std::string& table) {
  Program program{name, scratch + "/work." + name, {}, {}, {}};
  fs::create_directory(program.work);
  const Run help = run(name, {"--help"}, program.work);
  read_options(program, help.out);
  if (program.options.empty() && help.status != 0) fail(program, "--help fails");
  for (const std::string& option : program.output_options) {
    std::ofstream(program.work + "/" + existing_file(option))
        << "known content of " << option << " for " << name << '\n';
  }
  check_help_and_version(program);
  generic_cases(program);
  program.generic = program.tried;
  table_cases(program, table);
  std::string kinds;
  for (const Option& option : program.options) kinds += " " + option.name + ":" + option.kind;
  if (name == "bar1d" && program.tried < 30) {
    fail(program, "only " + std::to_string(program.tried) + " bad invocations, expected at least 30");
  }
  std::cout << name << std::string(name.size() < 22 ? 22 - name.size() : 1, ' ') << program.tried
            << " bad invocations (" << program.generic << " generic, " << program.tried - program.generic
            << " from the table), " << program.failed << " failed; options:" << kinds << '\n';
  return program.failed;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3 || !fs::is_directory(argv[1]) || !fs::is_regular_file(argv[2])) {
    std::cerr << "usage: bad_invocations BIN_DIR TABLE [PROGRAM...]   (MRM_TEST_JOBS: programs checked at once, 2)\n";
    return 2;
  }
  const char* jobs_text = std::getenv("MRM_TEST_JOBS");
  const std::size_t jobs = jobs_text != nullptr && std::atoi(jobs_text) > 0 ? std::atoi(jobs_text) : 2;
  bin = fs::absolute(argv[1]).string();
  const std::string table = fs::absolute(argv[2]).string();
  const std::set<std::string> only(argv + 3, argv + argc);
  std::string pattern = (fs::temp_directory_path() / "bad_invocations.XXXXXX").string();
  if (::mkdtemp(pattern.data()) == nullptr) {
    std::perror("bad_invocations: mkdtemp");
    return 1;
  }
  scratch = pattern;

  std::vector<std::string> names;
  for (const auto& entry : fs::directory_iterator(bin)) {
    const std::string name = entry.path().filename().string();
    if (!entry.is_regular_file() || ::access(entry.path().c_str(), X_OK) != 0) continue;
    if (name == "doctests" || name == "bad_invocations" || (!only.empty() && only.count(name) == 0)) continue;
    names.push_back(name);
  }
  std::sort(names.begin(), names.end());
  // The programs are checked by `jobs` child processes of this driver at a time, one program each (its
  // own working directory); each writes its lines to a report that is printed in the programs' order.
  int total = 0;
  std::size_t next = 0, running = 0;
  std::map<pid_t, std::string> workers;
  while (next < names.size() || running > 0) {
    if (next < names.size() && running < jobs) {
      const std::string name = names[next++];
      std::cout.flush();
      const pid_t worker = ::fork();
      if (worker == 0) {
        std::ofstream report(scratch + "/report." + name);
        std::cout.rdbuf(report.rdbuf());
        const int failed = check_program(name, table);
        std::cout.flush();
        report.close();
        std::_Exit(failed == 0 ? 0 : 1);
      }
      workers[worker] = name;
      ++running;
      continue;
    }
    int status = 0;
    const pid_t ended = ::wait(&status);
    if (ended < 0) break;
    --running;
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) ++failures;
  }
  for (const std::string& name : names) {
    const std::string report = read_file(scratch + "/report." + name);
    std::cout << report;
    const auto counted = report.rfind(" bad invocations (");
    if (counted != std::string::npos) total += std::stoi(report.substr(report.rfind(name, counted) + name.size()));
  }
  fs::remove_all(scratch);
  std::printf("%zu programs, %d bad invocations, %d programs with failures\n", names.size(), total, failures);
  return failures == 0 && !names.empty() ? 0 : 1;
}
