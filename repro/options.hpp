// The command-line interface shared by every program of the project: the driver, the programs that
// compute one figure each and the benchmark. It gathers everything between the shell and the
// numerics, so that all programs behave alike:
//
//   - option values are parsed strictly (a typo is an error, never a silently different run) and
//     every error message names the option and says what would have been allowed;
//   - each program declares its options once, with help text and defaults, in a `Parser`, which
//     also writes the effective values as `# key = value` header lines into the data files;
//   - real numbers are written in the shortest form that reads back to the same double, so that
//     the data files are deterministic and exact;
//   - output files are written under a temporary name and renamed into place only when complete
//     (`AtomicFile`), so that an interrupted run never leaves a truncated data file behind;
//   - `guarded_main` turns exceptions into a one-line message and an exit status: 2 for a usage
//     error, 1 for any other failure.
//
// A program's main function looks like this:
//
//   int main(int argc, char** argv) {
//       return mrm::cli::guarded_main("contact_driver", [&] {
//           namespace cli = mrm::cli;
//           long elements = 100;
//           double restitution = 0.0;
//           std::string scheme = "rk2", output = "contact.dat";
//           cli::Parser parser("contact_driver",
//                              "Computes the motion of an elastic bar hitting a rigid obstacle.",
//                              {"contact_driver -n 400 --scheme rk4", "contact_driver --help"});
//           parser.add_integer("--elements", "-n", "N", "number of elements of the mesh",
//                              &elements, cli::at_least(2));
//           parser.add_real("--restitution", "-e", "E", "coefficient of restitution",
//                           &restitution, cli::in_closed_range(0, 1));
//           parser.add_choice("--scheme", "", "S", "time integration scheme",
//                             {"rk2", "rk4", "euler"}, &scheme);
//           parser.add_output("--output", "-o", "data file to write", &output);
//           if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
//
//           cli::AtomicFile data(output, "--output");  // fails now, not after the computation
//           parser.echo(data.stream());
//           ...                                         // compute and write into data.stream()
//           data.commit();
//           return 0;
//       });
//   }
#pragma once

#include <fstream>
#include <functional>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace mrm::cli {

// The error of a wrong command line: an unknown option, a malformed or out-of-range value, an
// unwritable output path. Its message starts with the option concerned and says what is allowed;
// `guarded_main` prints it after the program name and exits with status 2.
class UsageError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Strict parsing of one option value. `option` is the option's name, used only in the message of
// the UsageError thrown when `text` is not acceptable.
//
// parse_real accepts exactly a finite decimal number ("42", "-0.5", "1e-3", ".5", "+2"), and
// rejects everything else: "", "1e", "12abc", " 1", "nan", "inf", "0x10", and magnitudes that a
// double cannot hold ("1e400", "1e-400"; subnormal numbers are accepted).
// parse_integer accepts exactly a base-10 integer that fits in a long ("42", "-7", "+3"), and
// rejects "1.5", "1e3", "", "12abc" and overflow.
// parse_choice returns `text` if it is one of `allowed`:
//   --scheme: unknown value "xx" (allowed: rk2, rk4, euler)
double parse_real(std::string_view option, std::string_view text);
long parse_integer(std::string_view option, std::string_view text);
std::string parse_choice(std::string_view option, std::string_view text, const std::vector<std::string>& allowed);

// Range requirements on a parsed value, throwing a UsageError that names the option and the
// allowed range, e.g. `--restitution: 1.5 is outside the allowed range [0, 1]`. NaN never
// satisfies a requirement. They take doubles so that they serve integer options as well (every
// integer an option can reasonably hold converts exactly).
void require_positive(std::string_view option, double value);
void require_at_least(std::string_view option, double value, double minimum);
void require_in_closed_range(std::string_view option, double value, double lowest, double highest);

// The same requirements packaged as checks that `Parser::add_real` and `Parser::add_integer`
// attach to an option; any callable with this signature that throws UsageError will do.
using Check = std::function<void(std::string_view option, double value)>;
Check positive();
Check at_least(double minimum);
Check in_closed_range(double lowest, double highest);

// `text` as a JSON string: between double quotes, with quotes, backslashes and control characters
// escaped (data-file headers: the whole text, so that it reads back).
std::string json_string(std::string_view text);

// User text (a value, a file name, a token of a data file) as every message shows it: between double
// quotes, one line whatever it holds, and short. Quotes and backslashes are escaped, control characters
// (C0, DEL and the C1 range, which terminals read as escape sequences) are written \n, \t, \r or
// \uXXXX, a byte that is not UTF-8 \xHH; a text of more than `max_quoted` characters is cut there with
// an ellipsis and its size in bytes: "aaaa…" (52428800 bytes). The one quoting of every message that
// echoes user text.
constexpr std::size_t max_quoted = 60;
std::string quoted_text(std::string_view text);

// A comma-separated list of numbers, each read by parse_real ("0.5,1.5,2.5"); an empty list or an
// empty item ("0.5,", ",1", "1,,2") is a UsageError naming the option.
std::vector<double> parse_real_list(std::string_view option, std::string_view text);

// The shortest decimal text that parse_real (or any correct reader) turns back into exactly the
// same double: "0.1", "0.3333333333333333", "1e-300", "-2.5e+10", "12", "-0". Non-finite values
// give "inf", "-inf" and "nan".
std::string format_real(double value);

// What the program should do once `Parser::parse` has returned: run, or stop successfully because
// the help or the version has been printed.
enum class Outcome { run, exit_success };

// The options of one program, on CLI11 (the field's common C++ parser: registration, the parse
// loop, the help and version flags, exclusions), with this project's rules on top: values read by
// the strict grammar above (CLI11 alone reads "nan", takes "010" for 8 and exits 105), ranges,
// the echo of the effective values into data headers, and every mistake a UsageError of one line
// naming the option (exit 2).
//
// Each option has a long name ("--elements"), an optional short name ("-n", or "" for none), a
// placeholder for its value in the help ("N"), one paragraph of help (folded within 100 columns; each
// further line after a '\n' is one item of a list of values, shown one a line), and is bound to the variable
// that receives its value; the variable's value at registration is the default shown in the help
// (an empty string shows none). On the command line a value follows its option as the next
// argument or after '=' ("--elements 400", "--elements=400", "-n 400"). `--help`/`-h` and
// `--version` are always available. A program takes options only: any other argument is an error.
//
// Registration mistakes (a malformed or duplicate name, a null variable, a choice default that is
// not allowed) are programming errors and throw std::logic_error.
class Parser {
 public:
  // `description` is one paragraph saying what the program computes; `sample_runs` are complete
  // command lines, shown in the help as they are.
  Parser(std::string program, std::string description, std::vector<std::string> sample_runs);
  ~Parser();
  Parser(const Parser&) = delete;
  Parser& operator=(const Parser&) = delete;

  // Options with a value. The check, if any, is applied to a value given on the command line
  // (not to the default).
  void add_real(std::string long_name, std::string short_name, std::string metavar, std::string help, double* target,
                Check check = {});
  void add_integer(std::string long_name, std::string short_name, std::string metavar, std::string help, long* target,
                   Check check = {});
  void add_string(std::string long_name, std::string short_name, std::string metavar, std::string help,
                  std::string* target);
  void add_choice(std::string long_name, std::string short_name, std::string metavar, std::string help,
                  std::vector<std::string> allowed, std::string* target);
  // A file the program writes: a string option with the placeholder FILE.
  void add_output(std::string long_name, std::string short_name, std::string help, std::string* target);
  // A file the program reads: a string option with the placeholder FILE. After the parse, no output
  // option may name the same file as an input option, nor two output options one file (compared by
  // identity, st_dev and st_ino, not by spelling: "./d.dat", a symbolic or hard link, a path through
  // a linked directory; a file not yet there by its directory's identity and its name). A clash is a
  // UsageError, before any work, such as
  //   --output: "./d.dat" is the file of --initial-data "d.dat" (allowed: an output that replaces no input)
  // Outputs and inputs count when given or when they have a default ("" and "-" never).
  void add_input(std::string long_name, std::string short_name, std::string help, std::string* target);

  // An option without a value: giving it sets the variable to true.
  void add_flag(std::string long_name, std::string short_name, std::string help, bool* target);

  // A registered option whose variable's value at registration means "not given" (a time step that
  // --courant sets otherwise): the help shows no default for it.
  void without_default(std::string_view long_name);

  // Two registered options that exclude each other:
  //   --dt and --courant cannot be given together
  void add_conflict(std::string_view first_long_name, std::string_view second_long_name);

  // An option that does not apply when another one is given (a mode of the program that does not use
  // it, a preset that fixes what it would change): the two given together are refused after the parse,
  // with one line naming both, the other's value and what is allowed (`reason`), e.g.
  //   --threads: does not apply with --merge "runs" (the merge runs nothing; allowed: omit --threads)
  // `when`, if set, is asked after the parse whether the rule holds (for some values of `other` only).
  // The rules are checked in the order of declaration, after the ranges.
  void add_not_applicable(std::string long_name, std::string other_long_name, std::string reason,
                          std::function<bool()> when = {});

  // Reads the arguments (argv[0] is the program's own name and is skipped; the vector form has
  // the arguments only). Prints the help or the version on `out` and returns exit_success if
  // asked to; otherwise stores the values, applies the checks and the conflicts, and returns
  // run. Throws UsageError on: an unknown option, a missing value, an option given twice, a
  // malformed or rejected value, a value given to a flag ("--verbose=true" too), a positional
  // argument, an option that does not apply (add_not_applicable).
  Outcome parse(int argc, const char* const* argv, std::ostream& out);
  Outcome parse(const std::vector<std::string>& arguments, std::ostream& out);

  // Whether the option was given on the command line by the last parse.
  bool given(std::string_view long_name) const;

  void print_help(std::ostream& out) const;

  // One line per option, in registration order, with its effective value, except the paths of
  // files (placeholder FILE), so that the same run gives the same bytes wherever its files are:
  // `# elements = 400`. The key is the long name without its dashes and with '-' turned into
  // '_'; the value is a JSON literal (numbers as by format_real, strings quoted, flags
  // true/false), so that the header lines of a data file are deterministic and easy to read back.
  void echo(std::ostream& out, std::string_view prefix = "# ") const;

  const std::string& program() const { return program_; }

 private:
  struct Option;
  using Target = std::variant<double*, long*, std::string*, bool*>;
  void add(std::string long_name, std::string short_name, std::string metavar, std::string help, Target target,
           Check check = {}, std::vector<std::string> allowed = {}, int file = 0);
  void refuse_shared_files() const;
  const Option& registered(std::string_view long_name) const;

  std::string program_;
  std::unique_ptr<CLI::App> app_;
  std::vector<Option> options_;
  std::vector<std::pair<std::string, std::string>> conflicts_;
  struct NotApplicable;
  std::vector<NotApplicable> not_applicable_;
  void refuse_not_applicable() const;
};

// Runs a program's body and turns its exceptions into an exit status and one line on `errors`:
//   UsageError            "<program>: <message>"         status 2
//   std::bad_alloc        "<program>: error: out of memory: ..."  status 1
//   other std::exception  "<program>: error: <what>"     status 1
// A body that succeeds but whose writes to `output` (standard output) failed, for example on a
// full disk or a closed standard output, also ends with status 1, and so does one whose writes to
// `errors` failed. Otherwise the body's own return value is returned. Before the body runs, closed
// standard descriptors are reopened (prepare_standard_descriptors, output_file.hpp), and SIGXFSZ is
// ignored, so that a write beyond the file-size limit (ulimit -f) fails as a write error (status 1, the
// output named) instead of killing the program.
int guarded_main(std::string_view program, const std::function<int()>& body, std::ostream& output = std::cout,
                 std::ostream& errors = std::cerr);

}  // namespace mrm::cli
