/// @file initial_data_file.cpp
/// @brief Initial data read from a text file; see initial_data_file.hpp.
///
/// The checks on the samples are the library's (characteristics.cpp: initial_data_from_samples, which
/// names the offending row); this file only reads the numbers, remembers the line of every row, and
/// turns a row into a line in the message, so that a user sees "FILE:LINE: what is wrong".
#include "initial_data_file.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <system_error>
#include <sstream>
#include <vector>

#include <doctest/doctest.h>

#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"

namespace mrm::repro {

namespace {

// One whitespace-separated number, the whole token, by the options' one grammar of a number
// (cli::parse_real: a finite decimal; "nan", "inf", "0x10", "1e400" are not numbers).
bool read_number(const std::string& token, double& value) try {
  value = cli::parse_real("", token);
  return true;
} catch (const cli::UsageError&) {
  return false;
}

}  // namespace

InitialData read_initial_data(const std::string& path, std::string_view option) {
  const std::string where = std::string(option) + ": " + cli::quoted_text(path);
  // A regular file only: it is read twice (counted, then parsed), which a pipe cannot be, and a FIFO
  // without a writer would block the program.
  const std::string problem = cli::input_file_problem(path);
  if (problem == "is a directory, not a file") throw cli::UsageError(where + ": " + problem);
  if (!problem.empty() && problem.rfind("is ", 0) == 0)
    throw cli::UsageError(where + ": " + problem + " (allowed: a regular file of columns x u0 v0, read twice)");
  std::ifstream in(path);
  if (!problem.empty() || !in) throw cli::UsageError(where + ": cannot open the file (expected columns x u0 v0)");
  // The samples are counted first (a line that is not blank nor a comment), so that a file too large
  // for the memory is refused before it is read: a sample takes about 200 bytes here and in the
  // piecewise data (its numbers, its line, a piece with two polynomials), 512 with a margin.
  {
    double samples = 0;
    std::string text;
    while (std::getline(in, text)) {
      const std::size_t start = text.find_first_not_of(" \t\r");
      if (start != std::string::npos && text[start] != '#') ++samples;
      if (samples > cli::max_rows)
        throw cli::UsageError(where + ": more than 1e8 samples (allowed: at most 1e8 lines in a data file)");
    }
    cli::require_memory(option, 512 * samples, "reading " + cli::format_real(samples) + " samples");
    in.clear();
    in.seekg(0);
  }
  std::vector<double> x, u0, v0;
  std::vector<long> lines;  // the line of each sample
  std::string line;
  long number = 0;
  while (std::getline(in, line)) {
    ++number;
    const std::size_t hash = line.find('#');
    if (hash != std::string::npos) line.erase(hash);
    std::istringstream fields(line);
    std::vector<std::string> tokens;
    for (std::string token; fields >> token;) tokens.push_back(token);
    if (tokens.empty()) continue;
    if (tokens.size() != 3)
      throw cli::UsageError(where + ":" + std::to_string(number) + ": expected 3 columns x u0 v0, got " +
                            std::to_string(tokens.size()));
    double values[3];
    for (std::size_t k = 0; k < 3; ++k)
      if (!read_number(tokens[k], values[k]))
        throw cli::UsageError(where + ":" + std::to_string(number) + ": " + cli::quoted_text(tokens[k]) +
                              " is not a finite decimal number");
    x.push_back(values[0]);
    u0.push_back(values[1]);
    v0.push_back(values[2]);
    lines.push_back(number);
  }
  if (in.bad()) throw cli::UsageError(where + ": read error");
  // The scales (configurations.cpp, the scaling law): the method runs at L = 1 with the data divided
  // by a power of two near their amplitude max(|u0|/L, |v0|). Lengths and amplitudes within those of
  // bar1d's --length and --amplitude, [1e-100, 1e100], are scaled exactly and every quantity of the
  // run stays far from overflow and underflow; a file beyond is refused before the samples are
  // checked further (data at rest have nothing to measure an error against).
  if (x.size() >= 2 && x.back() > 0) {
    const double length = x.back();
    double amplitude = 0;
    for (std::size_t k = 0; k < x.size(); ++k)
      amplitude = std::max({amplitude, std::abs(u0[k]) / length, std::abs(v0[k])});
    const auto refuse = [&](const std::string& what) {
      throw cli::UsageError(where + ": " + what +
                            " (allowed: L, the last x, and the amplitude max(|u0|/L, |v0|) in [1e-100, 1e100])");
    };
    if (!(length >= 1e-100 && length <= 1e100)) refuse("L = " + cli::format_real(length) + " cannot be scaled to 1");
    if (amplitude == 0) refuse("the data are at rest (u0 = v0 = 0): no error can be measured");
    if (!(amplitude >= 1e-100 && amplitude <= 1e100))
      refuse("the amplitude " + cli::format_real(amplitude) + " cannot be scaled to 1");
  }
  try {
    return initial_data_from_samples(x, u0, v0);
  } catch (const SampleError& e) {
    const long at = e.row() < lines.size() ? lines[e.row()] : number;
    std::string what = e.what();
    const std::string prefix = "initial data: ";
    if (what.compare(0, prefix.size(), prefix) == 0) what.erase(0, prefix.size());
    throw cli::UsageError(where + ":" + std::to_string(at) + ": " + what);
  }
}

// ---------------------------------------------------------------------------------------------------

namespace {

// A file with the given text in the temporary directory, removed at the end of the scope.
struct TemporaryFile {
  std::string path;
  explicit TemporaryFile(const std::string& text) {
    char name[] = "/tmp/mrm-initial-data-XXXXXX";
    const int fd = mkstemp(name);
    REQUIRE(fd >= 0);
    path = name;
    std::FILE* f = fdopen(fd, "w");
    REQUIRE(f != nullptr);
    std::fputs(text.c_str(), f);
    std::fclose(f);
  }
  ~TemporaryFile() { std::remove(path.c_str()); }
};

[[maybe_unused]] std::string message_of(const std::string& text) {
  const TemporaryFile file(text);
  try {
    read_initial_data(file.path);
  } catch (const cli::UsageError& e) {
    const std::string what = e.what();
    // The message names the file; keep what follows it.
    const std::size_t at = what.find(file.path);
    REQUIRE(at != std::string::npos);
    return what.substr(at + file.path.size() + 1);  // after the closing quote
  }
  return "accepted";
}

}  // namespace

TEST_CASE("an initial-data file is read with comments and blank lines, and bad files are refused with their line") {
  const TemporaryFile good("# x u0 v0\n\n0 0.25 0   # the contact point\n0.5 0.1 -0.2\n\n1 0 0\n");
  const InitialData data = read_initial_data(good.path);
  CHECK(data.length() == 1.0);
  CHECK(std::abs(data.displacement(0.25) - 0.175) < 1e-16);
  CHECK(std::abs(data.velocity(0.75) + 0.1) < 1e-16);
  CHECK(message_of("# x u0 v0\n0 0.25 0\n0.5 0.1 0\n0.4 0.05 0\n1 0 0\n") ==
        ":4: x must increase strictly (0.4 after 0.5)");
  CHECK(message_of("0 0.25 0\n\n1 0.01 0\n").find(":3: u0(L) must be 0") == 0);
  CHECK(message_of("0 -0.1 0\n1 0 0\n").find(":1: u0(0) must be >= 0") == 0);
  CHECK(message_of("0 0.25 0\n0.5 nan 0\n1 0 0\n") == ":2: \"nan\" is not a finite decimal number");
  CHECK(message_of("0 0.25 0\n0.5 0.1 inf\n1 0 0\n") == ":2: \"inf\" is not a finite decimal number");
  CHECK(message_of("# one row\n0 0 0\n").find(":2: at least 2 rows are needed (got 1)") == 0);
  CHECK(message_of("# no row\n").find(":1: at least 2 rows are needed (got 0)") == 0);
  CHECK(message_of("0 0.25 0\n0.5 0.1\n1 0 0\n") == ":2: expected 3 columns x u0 v0, got 2");
  CHECK(message_of("0 0.25 0\n0.5 0.1x 0\n1 0 0\n") == ":2: \"0.1x\" is not a finite decimal number");
  // The one grammar of a number, and the scales that can be brought to L = 1.
  for (const char* token : {"0x10", "1e400", "+-1", "1,5", "nan", "inf"})
    CHECK(message_of(std::string("0 0.25 0\n0.5 ") + token + " 0\n1 0 0\n") ==
          ":2: " + cli::quoted_text(token) + " is not a finite decimal number");
  CHECK(message_of("0 +0.25 0\n1 0 0\n") == "accepted");
  CHECK(message_of("0 1e-300 0\n1 0 0\n").find("the amplitude 1e-300 cannot be scaled") != std::string::npos);
  CHECK(message_of("0 1e200 0\n1 0 0\n").find("the amplitude 1e+200 cannot be scaled") != std::string::npos);
  CHECK(message_of("0 1e-300 0\n1e-300 0 0\n").find("L = 1e-300 cannot be scaled") != std::string::npos);
  CHECK(message_of("0 0 0\n1 0 0\n").find("at rest") != std::string::npos);
  CHECK(message_of("0 1e-100 0\n1 0 0\n") == "accepted");
  CHECK(message_of("0 1 0\n1e100 0 0\n") == "accepted");
  CHECK(message_of("0.1 0.25 0\n1 0 0\n").find(":1: the first x must be 0") == 0);
  CHECK_THROWS_WITH_AS(read_initial_data("/tmp"), doctest::Contains("--initial-data: \"/tmp\": is a directory"),
                       cli::UsageError);
  CHECK_THROWS_WITH_AS(read_initial_data("/nonexistent/file.dat"),
                       doctest::Contains("--initial-data: \"/nonexistent/file.dat\": cannot open"), cli::UsageError);
}

}  // namespace mrm::repro
