/// @file sweep/job_grid.cpp
/// @brief The job grid of a sweep: its runs numbered, run in this process or written out as a job list, and its results merged back exactly or refused.
#include "sweep/job_grid.hpp"

#include "sweep/batched.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <future>
#include <iomanip>
#include <map>
#include <mutex>
#include <sstream>
#include <stdexcept>
#include <thread>
#include <tuple>
#include <type_traits>

#include <dirent.h>
#include <sys/stat.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include "measures/errors.hpp"
#include "exact/impact_solution.hpp"
#include "batched/batched_step.hpp"
#include "classes/contact_classes.hpp"
#include "fem/p1.hpp"
#include "fem/mass_redistribution.hpp"
#include "labels.hpp"
#include "options.hpp"
#include "parallel.hpp"
#include "run_limits.hpp"

namespace mrm::repro {

namespace {

// The index of run k along each axis (the last axis fastest).
struct Position {
  std::size_t scheme, mass, elements, courant;
};
Position position(const JobGrid& g, std::size_t k) {
  if (k >= g.size())
    throw std::out_of_range("sweep: no run " + std::to_string(k) + " in a grid of " + std::to_string(g.size()));
  Position p{};
  p.courant = k % g.courants.size();
  k /= g.courants.size();
  p.elements = k % g.elements.size();
  k /= g.elements.size();
  p.mass = k % g.masses.size();
  p.scheme = k / g.masses.size();
  return p;
}

template <typename T>
std::string joined(const std::vector<T>& values) {
  std::string text;
  for (const T& v : values) {
    if (!text.empty()) text += ',';
    if constexpr (std::is_same_v<T, double>)
      text += cli::format_real(v);
    else if constexpr (std::is_same_v<T, long>)
      text += std::to_string(v);
    else
      text += v;
  }
  return text;
}

// A word for the shell: in single quotes, a quote written '\''.
std::string shell_word(const std::string& word) {
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

}  // namespace

JobGrid JobGrid::run(std::size_t k) const {
  const Position p = position(*this, k);
  return {{schemes[p.scheme]}, {masses[p.mass]}, {elements[p.elements]}, {courants[p.courant]}, final_time};
}

Configuration JobGrid::configuration(std::size_t k) const {
  const Position p = position(*this, k);
  return paper_configuration(schemes[p.scheme], "algebraic", masses[p.mass], elements[p.elements], courants[p.courant],
                             final_time);
}

bool JobGrid::operator==(const JobGrid& other) const {
  return schemes == other.schemes && masses == other.masses && elements == other.elements &&
         courants == other.courants && final_time == other.final_time;
}

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> words;
  std::size_t start = 0;
  for (std::size_t comma; (comma = text.find(',', start)) != std::string::npos; start = comma + 1)
    words.push_back(text.substr(start, comma - start));
  words.push_back(text.substr(start));
  return words;
}

}  // namespace

// Every value as the other programs read theirs (options.hpp): each item of a list by the strict grammar of
// its kind, a word among the allowed ones, the user's text quoted in every message; then what makes a run
// possible at all (a mass on every mesh, at least one step), before any run.
JobGrid grid_from_lists(const std::string& schemes, const std::string& masses, const std::string& elements,
                        const std::string& courants, double final_time) {
  JobGrid grid;
  cli::require_in_closed_range("--final-time", final_time, 1e-300, sweep_max_final_time);
  grid.final_time = final_time;
  for (const std::string& s : split(schemes)) grid.schemes.push_back(cli::parse_choice("--schemes", s, scheme_ids()));
  for (double n : cli::parse_real_list("--elements", elements)) {
    if (!(n >= 2 && n <= static_cast<double>(sweep_max_elements) && n == std::floor(n)))
      throw cli::UsageError("--elements: " + cli::format_real(n) + " (allowed: integers in [2, 1e5])");
    grid.elements.push_back(static_cast<long>(n));
  }
  grid.courants = cli::parse_real_list("--courants", courants);
  for (double c : grid.courants) {
    cli::require_in_closed_range("--courants", c, 1e-300, sweep_max_courant);
    for (long n : grid.elements)
      cli::checked_steps("--final-time", final_time, c / static_cast<double>(n), "dt = C h (raise --courants)");
  }
  grid.masses = split(masses);
  const double runs = static_cast<double>(grid.schemes.size()) * static_cast<double>(grid.masses.size()) *
                      static_cast<double>(grid.elements.size()) * static_cast<double>(grid.courants.size());
  if (!(runs <= sweep_max_runs))
    throw cli::UsageError("--schemes, --masses, --elements, --courants: " + cli::format_real(runs) +
                          " runs (allowed: at most 1e6 runs in one grid)");
  for (const std::string& m : grid.masses)
    for (long n : grid.elements) (void)mass_from_option("--masses", m, UniformMesh(1.0, n));
  return grid;
}

void write_sweep_header(std::ostream& out, const JobGrid& grid) {
  out << "# sweep: the paper's benchmark, every scheme x mass x N x dt/h to T (repro/sweep.hpp)\n"
      << "# schemes = " << joined(grid.schemes) << "\n# masses = " << joined(grid.masses)
      << "\n# elements = " << joined(grid.elements) << "\n# courants = " << joined(grid.courants)
      << "\n# final_time = " << cli::format_real(grid.final_time) << "\n# columns: scheme mass N courant steps "
      << "energy_initial energy_min energy_max energy_final";
  for (const char* name : ErrorAccumulator::names) out << ' ' << name;
  out << '\n';
}

std::string sweep_line(const JobGrid& grid, std::size_t k, const Measures& m) {
  const Position p = position(grid, k);
  std::ostringstream line;
  line << grid.schemes[p.scheme] << ' ' << grid.masses[p.mass] << ' ' << grid.elements[p.elements] << ' '
       << cli::format_real(grid.courants[p.courant]) << ' ' << m.steps;
  for (double v : {m.energy_initial, m.energy_min, m.energy_max, m.energy_final}) line << ' ' << cli::format_real(v);
  for (double v : ErrorAccumulator::values(m.errors)) line << ' ' << cli::format_real(v);
  line << '\n';
  return line.str();
}

std::vector<std::string> run_sweep(const JobGrid& grid, unsigned threads) {
  std::vector<Configuration> configurations;
  for (std::size_t k = 0; k < grid.size(); ++k) configurations.push_back(grid.configuration(k));
  SweepSettings settings = sweep_settings();  // batched or not: the program's --vector
  settings.threads = threads;
  const std::vector<Measures> measures = run_batched(configurations, settings);
  std::vector<std::string> lines;
  for (std::size_t k = 0; k < grid.size(); ++k) lines.push_back(sweep_line(grid, k, measures[k]));
  return lines;
}

std::string result_file(const std::string& directory, std::size_t k) {
  std::ostringstream name;
  name << directory << "/run-" << std::setw(6) << std::setfill('0') << k << ".dat";
  return name.str();
}

std::string grid_identity(const JobGrid& grid) {
  std::ostringstream header;
  write_sweep_header(header, grid);
  std::uint64_t hash = 14695981039346656037ull;  // FNV-1a, 64 bits: offset basis and prime
  for (const char c : header.str()) {
    hash ^= static_cast<unsigned char>(c);
    hash *= 1099511628211ull;
  }
  std::ostringstream hex;
  hex << std::hex << std::setw(16) << std::setfill('0') << hash;
  return hex.str();
}

std::string result_header(const JobGrid& grid, std::size_t k) {
  std::ostringstream out;
  out << "# sweep result: run " << k << " of " << grid.size() << ", grid " << grid_identity(grid) << '\n';
  write_sweep_header(out, grid);
  return out.str();
}

void require_one_line(const std::string& option, const std::string& path) {
  for (const char c : path)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
      throw cli::UsageError(option + ": " + cli::quoted_text(path) +
                            " holds a control character, which would split or garble the job list's one command "
                            "per line (allowed: a path without control characters)");
}

void write_job_list(std::ostream& out, const std::string& program, const JobGrid& grid, const std::string& directory) {
  // The lists as the header writes them (they read back to the same grid), the same on every line.
  const std::string lists = " --schemes " + shell_word(joined(grid.schemes)) + " --masses " +
                            shell_word(joined(grid.masses)) + " --elements " + joined(grid.elements) + " --courants " +
                            joined(grid.courants) + " --final-time " + cli::format_real(grid.final_time);
  for (std::size_t k = 0; k < grid.size(); ++k)
    out << shell_word(program) << lists << " --run " << k << " --result " << shell_word(result_file(directory, k))
        << '\n';
}

namespace {

// ---- The merge -------------------------------------------------------------------------------------------
// A result file is exactly result_header(grid, k) followed by one line of run k as sweep_line writes it:
// the bytes are compared with what this grid's run k must hold, so that nothing but a result of this run of
// this grid is merged. The messages name the file and what is wrong with it, the bytes quoted (one line).

[[noreturn]] void refuse(const std::string& path, const std::string& what) {
  throw std::runtime_error("--merge: " + cli::quoted_text(path) + ": " + what);
}

// The run a result file is named for: run-NNNNNN.dat as result_file writes it (six digits, more without a
// leading zero), or none.
std::optional<std::size_t> run_of_name(const std::string& name) {
  if (name.size() < 14 || name.compare(0, 4, "run-") != 0 || name.compare(name.size() - 4, 4, ".dat") != 0)
    return std::nullopt;
  const std::string digits = name.substr(4, name.size() - 8);
  if (digits.size() < 6 || digits.size() > 15 || digits.find_first_not_of("0123456789") != std::string::npos ||
      (digits.size() > 6 && digits[0] == '0'))
    return std::nullopt;
  return static_cast<std::size_t>(std::stoull(digits));
}

// The bytes of a result file, at most `most` (a result of the grid is shorter): a regular file only (a FIFO
// would block the merge, a directory holds no bytes).
std::string result_bytes(const std::string& path, std::size_t most) {
  struct stat status {};
  if (::stat(path.c_str(), &status) != 0) refuse(path, std::string("cannot read it: ") + std::strerror(errno));
  if (!S_ISREG(status.st_mode)) refuse(path, "not a regular file (a result is a file a job wrote)");
  if (static_cast<std::size_t>(status.st_size) > most)
    refuse(path, std::to_string(status.st_size) + " bytes, more than a result of this grid holds (at most " +
                     std::to_string(most) + ")");
  std::ifstream in(path, std::ios::binary);
  std::string bytes(static_cast<std::size_t>(status.st_size), '\0');
  if (!in || !in.read(bytes.data(), static_cast<std::streamsize>(bytes.size())) || in.peek() != EOF)
    refuse(path, "cannot read it (it changed while being read)");
  return bytes;
}

// The lines of a text; the last one without its newline if it has none (`complete` says).
std::vector<std::string> lines_of(const std::string& text, bool& complete) {
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  complete = start == text.size();
  if (!complete) lines.push_back(text.substr(start));
  return lines;
}

// The grid a header records: the values of its list lines, read as the command line's (grid_from_lists).
JobGrid grid_of_header(const std::string& path, const std::vector<std::string>& lines) {
  const std::vector<std::string> keys{"schemes", "masses", "elements", "courants", "final_time"};
  std::vector<std::string> values;
  for (std::size_t j = 0; j < keys.size(); ++j) {
    const std::string prefix = "# " + keys[j] + " = ";
    if (lines.size() <= j + 2 || lines[j + 2].compare(0, prefix.size(), prefix) != 0)
      refuse(path, "line " + std::to_string(j + 3) + " is not the grid's " + keys[j] +
                       " (not a result file of this program, or truncated)");
    values.push_back(lines[j + 2].substr(prefix.size()));
  }
  try {
    return grid_from_lists(values[0], values[1], values[2], values[3], cli::parse_real("--final-time", values[4]));
  } catch (const cli::UsageError& e) {
    refuse(path, std::string("its grid does not read back: ") + e.what());
  }
}

// The first line of `text` that differs from `expected`, as a message.
std::string first_difference(const std::string& text, const std::string& expected) {
  bool complete = true, expected_complete = true;
  const std::vector<std::string> got = lines_of(text, complete), want = lines_of(expected, expected_complete);
  for (std::size_t j = 0; j < want.size(); ++j) {
    if (j >= got.size() || (j + 1 == got.size() && !complete && got[j] != want[j]))
      return "truncated at line " + std::to_string(j + 1) + " (expected " + cli::quoted_text(want[j]) + ")";
    if (got[j] != want[j])
      return "line " + std::to_string(j + 1) + " is " + cli::quoted_text(got[j]) + ", expected " +
             cli::quoted_text(want[j]);
  }
  return "truncated";
}

// Run k's result in `bytes`: its header exactly, then one line of run k; returns the line.
std::string result_line(const std::string& path, const std::string& bytes, const JobGrid& grid, std::size_t k,
                        const std::string& source) {
  const std::string header = result_header(grid, k);
  if (bytes.compare(0, header.size(), header) != 0 || bytes.size() < header.size()) {
    // Which run of which grid the file says it is, if it says so: the likeliest mistakes, named.
    bool complete = true;
    const std::vector<std::string> lines = lines_of(bytes, complete);
    std::size_t run = 0, runs = 0;
    char identity[17] = {};
    if (!lines.empty() &&
        std::sscanf(lines[0].c_str(), "# sweep result: run %zu of %zu, grid %16[0-9a-f]", &run, &runs, identity) == 3) {
      if (identity != grid_identity(grid))
        refuse(path, "the result of another grid (grid " + std::string(identity) + ", not " + grid_identity(grid) +
                         " of " + cli::quoted_text(source) + "): " + first_difference(bytes, header));
      if (run != k)
        refuse(path, "holds run " + std::to_string(run) + ", not run " + std::to_string(k) +
                         " (a result copied, moved or linked from another run's file)");
    }
    refuse(path, first_difference(bytes, header));
  }
  const std::string line = bytes.substr(header.size());
  if (line.empty()) refuse(path, "truncated: no result line after the header");
  const std::size_t newline = line.find('\n');
  if (newline == std::string::npos) refuse(path, "truncated: the result line does not end with a newline");
  if (newline + 1 != line.size())
    refuse(path, "more than one result line (" + cli::quoted_text(line.substr(newline + 1)) + " follows)");
  // The fields: the run's own scheme, mass, N and C as sweep_line writes them, then the steps and the
  // measures, each a number as cli::format_real writes it (so that it reads back to the same double).
  std::vector<std::string> fields;
  for (std::size_t start = 0; start < newline;) {
    const std::size_t space = std::min(line.find(' ', start), newline);
    fields.push_back(line.substr(start, space - start));
    start = space + 1;
  }
  const std::size_t expected = 5 + 4 + std::size(ErrorAccumulator::names);
  if (fields.size() != expected || line[0] == ' ' || line[newline - 1] == ' ')
    refuse(path,
           "the result line has " + std::to_string(fields.size()) + " fields, expected " + std::to_string(expected) +
               " (scheme mass N courant steps, 4 energies, 8 errors): " + cli::quoted_text(line.substr(0, newline)));
  const Position p = position(grid, k);
  const std::vector<std::string> own{grid.schemes[p.scheme], grid.masses[p.mass],
                                     std::to_string(grid.elements[p.elements]),
                                     cli::format_real(grid.courants[p.courant])};
  for (std::size_t j = 0; j < own.size(); ++j)
    if (fields[j] != own[j])
      refuse(path, "the result line is of " +
                       cli::quoted_text(fields[0] + " " + fields[1] + " " + fields[2] + " " + fields[3]) +
                       ", not of run " + std::to_string(k) + ": " + own[0] + " " + own[1] + " " + own[2] + " " +
                       own[3]);
  for (std::size_t j = 4; j < fields.size(); ++j) {
    bool exact = false;
    try {
      exact = j == 4 ? std::to_string(cli::parse_integer("steps", fields[j])) == fields[j]
                     : cli::format_real(cli::parse_real("value", fields[j])) == fields[j];
    } catch (const cli::UsageError&) {
    }
    if (!exact)
      refuse(path, "field " + std::to_string(j + 1) + " of the result line, " + cli::quoted_text(fields[j]) +
                       ", is not a number as this program writes it");
  }
  return line;
}

}  // namespace

ResultFiles find_results(const std::string& directory) {
  ResultFiles found;
  found.directory = directory;
  DIR* listing = ::opendir(directory.c_str());
  if (listing == nullptr)
    throw cli::UsageError("--merge: " + cli::quoted_text(directory) + ": cannot read the directory: " +
                          std::strerror(errno) + " (allowed: the --results directory of a job list)");
  const std::unique_ptr<DIR, int (*)(DIR*)> closing(listing, ::closedir);
  while (const dirent* entry = ::readdir(listing)) {
    const std::string name = entry->d_name;
    if (name.compare(0, 4, "run-") != 0) continue;  // not the job list's: ., .., hidden temporaries, notes
    const std::string path = directory + "/" + name;
    if (const std::optional<std::size_t> run = run_of_name(name))
      found.runs[*run] = path;
    else
      found.strangers.push_back(path);
  }
  std::sort(found.strangers.begin(), found.strangers.end());
  if (found.runs.empty())
    throw std::runtime_error("--merge: " + cli::quoted_text(directory) +
                             " holds no result file run-NNNNNN.dat (run the job list first)");
  // The grid: the first result's header, which must read back to the same bytes.
  found.grid_source = found.runs.begin()->second;
  const std::string bytes = result_bytes(found.grid_source, std::size_t(1) << 24);
  bool complete = true;
  found.grid = grid_of_header(found.grid_source, lines_of(bytes, complete));
  return found;
}

void refuse_output_among_results(const std::string& option, const std::string& output, const ResultFiles& results) {
  if (output.empty() || output == "-") return;
  const auto same = [](const struct stat& a, const struct stat& b) {
    return a.st_dev == b.st_dev && a.st_ino == b.st_ino;
  };
  const auto refused = [&](const std::string& what) {
    throw cli::UsageError(option + ": " + cli::quoted_text(output) + " is " + what + " of --merge " +
                          cli::quoted_text(results.directory) + " (allowed: an output that replaces no result)");
  };
  struct stat target {
  }, entry{};
  if (::stat(output.c_str(), &target) == 0) {
    for (const auto& [run, path] : results.runs)
      if (::stat(path.c_str(), &entry) == 0 && same(target, entry))
        refused("the result file of run " + std::to_string(run));
    for (const std::string& path : results.strangers)
      if (::stat(path.c_str(), &entry) == 0 && same(target, entry)) refused("the file " + cli::quoted_text(path));
  }
  const std::filesystem::path p(output);
  const std::string parent = p.has_parent_path() ? p.parent_path().string() : ".";
  struct stat directory {};
  if (p.has_filename() && p.filename().string().compare(0, 4, "run-") == 0 && ::stat(parent.c_str(), &target) == 0 &&
      ::stat(results.directory.c_str(), &directory) == 0 && same(target, directory))
    refused("a result's name in the directory");
}

void merge_results(std::ostream& out, const ResultFiles& results) {
  const JobGrid& grid = results.grid;
  if (!results.strangers.empty())
    refuse(results.strangers.front(), "not the name of a result of this sweep (allowed in the directory: run-" +
                                          std::string("NNNNNN.dat for the grid's runs 0 to ") +
                                          std::to_string(grid.size() - 1) + ")");
  const std::size_t most = result_header(grid, grid.size() - 1).size() + 4096;
  std::ostringstream lines;
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const auto file = results.runs.find(k);
    if (file == results.runs.end())
      throw std::runtime_error("--merge: " + cli::quoted_text(result_file(results.directory, k)) +
                               ": missing (the job of run " + std::to_string(k) + " has not written its result)");
    lines << result_line(file->second, result_bytes(file->second, most), grid, k, results.grid_source);
  }
  const auto extra = results.runs.lower_bound(grid.size());
  if (extra != results.runs.end())
    refuse(extra->second, "run " + std::to_string(extra->first) + " is not in the grid of " +
                              std::to_string(grid.size()) + " runs that " + cli::quoted_text(results.grid_source) +
                              " records (an extra result)");
  write_sweep_header(out, grid);
  out << lines.str();
}

TEST_CASE("a sweep's grid numbers its runs with the last axis fastest, and a run's own grid is that run") {
  const JobGrid grid{{"cn", "be"}, {"mod1", "mod3", "consistent"}, {8, 16}, {0.5, 1.0}, 1.0};
  CHECK(grid.size() == 24);
  const JobGrid one = grid.run(13);  // 13 = ((1·3 + 0)·2 + 0)·2 + 1: be, mod1, 8, 1.0
  CHECK(one.schemes == std::vector<std::string>{"be"});
  CHECK(one.masses == std::vector<std::string>{"mod1"});
  CHECK(one.elements == std::vector<long>{8});
  CHECK(one.courants == std::vector<double>{1.0});
  CHECK(one.size() == 1);
  CHECK_THROWS_AS(grid.run(24), std::out_of_range);
  CHECK(result_file("d", 42) == "d/run-000042.dat");
  std::ostringstream list;
  write_job_list(list, "/bin/sweep", grid, "it's");
  std::istringstream lines(list.str());
  std::string first;
  std::getline(lines, first);
  CHECK(first ==
        "'/bin/sweep' --schemes 'cn,be' --masses 'mod1,mod3,consistent' --elements 8,16 --courants 0.5,1 "
        "--final-time 1 --run 0 --result 'it'\\''s/run-000000.dat'");
  const std::string text = list.str();
  CHECK(std::count(text.begin(), text.end(), '\n') == 24);
}

TEST_CASE("a result names its run and its grid, whose identity changes with any list or T") {
  const JobGrid grid{{"cn"}, {"mod1", "mod3"}, {16}, {0.5, 1.0}, 3.0};
  const std::string header = result_header(grid, 3);
  CHECK(header.rfind("# sweep result: run 3 of 4, grid " + grid_identity(grid) + "\n# sweep: ", 0) == 0);
  CHECK(grid_identity(grid).size() == 16);
  JobGrid other = grid;
  other.final_time = 3.0000000000000004;
  CHECK(grid_identity(other) != grid_identity(grid));
  other = grid;
  other.masses = {"mod1", "mod2"};
  CHECK(grid_identity(other) != grid_identity(grid));
  CHECK(run_of_name("run-000042.dat") == std::optional<std::size_t>(42));
  CHECK(run_of_name("run-1234567.dat") == std::optional<std::size_t>(1234567));
  for (const char* name : {"run-42.dat", "run-0000042.dat", "run-000042.dat~", "run-00004x.dat", "run-000042.txt"})
    CHECK_FALSE(run_of_name(name).has_value());
}

TEST_CASE("the grid of the command line's lists: every item read strictly and quoted in the messages") {
  const JobGrid grid = grid_from_lists("cn,be", "mod1,node1:7/6", "16,32", "0.5,1e-1", 3);
  CHECK(grid.size() == 16);
  CHECK(grid.courants == std::vector<double>{0.5, 0.1});
  CHECK(grid == grid_from_lists("cn,be", "mod1,node1:7/6", "16,32", "0.5,0.1", 3));
  CHECK_THROWS_WITH_AS(grid_from_lists("cn\x1b[31m", "mod3", "16", "0.5", 3),
                       doctest::Contains("--schemes: unknown value \"cn\\u001b[31m\""), cli::UsageError);
  CHECK_THROWS_WITH_AS(grid_from_lists(std::string(100000, 'c'), "mod3", "16", "0.5", 3),
                       doctest::Contains("\u2026\" (100000 bytes)"), cli::UsageError);
  CHECK_THROWS_WITH_AS(grid_from_lists("cn", "mod3", "16", "0.5", 1e-300), doctest::Contains("--final-time"),
                       cli::UsageError);
  CHECK_THROWS_WITH_AS(grid_from_lists("cn,", "mod3", "16", "0.5", 3),
                       doctest::Contains("--schemes: unknown value \"\""), cli::UsageError);
  CHECK_THROWS_WITH_AS(grid_from_lists("cn", "mod3", "16,2.5", "0.5", 3), doctest::Contains("--elements: 2.5"),
                       cli::UsageError);
}

}  // namespace mrm::repro
