/// @file sweep/job_grid.cpp
/// @brief The job grid of a sweep: its runs numbered, run in this process or written out as a job list and merged back.
#include "sweep/job_grid.hpp"

#include "sweep/batched.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <fstream>
#include <future>
#include <map>
#include <mutex>
#include <thread>
#include <tuple>
#include <iomanip>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include <doctest/doctest.h>

#include "measures/errors.hpp"
#include "exact/impact_solution.hpp"
#include "batched/batched_step.hpp"
#include "classes/contact_classes.hpp"
#include "fem/p1.hpp"
#include "fem/mass_redistribution.hpp"
#include "options.hpp"
#include "parallel.hpp"

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

void write_job_list(std::ostream& out, const std::string& program, const JobGrid& grid, const std::string& directory) {
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const JobGrid one = grid.run(k);
    // The run's index in the whole grid is what names its result file; the run itself is a grid of one.
    out << shell_word(program) << " --schemes " << one.schemes[0] << " --masses " << shell_word(one.masses[0])
        << " --elements " << one.elements[0] << " --courants " << cli::format_real(one.courants[0]) << " --final-time "
        << cli::format_real(one.final_time) << " --result " << shell_word(result_file(directory, k)) << '\n';
  }
}

void merge_results(std::ostream& out, const JobGrid& grid, const std::string& directory) {
  write_sweep_header(out, grid);
  for (std::size_t k = 0; k < grid.size(); ++k) {
    const std::string path = result_file(directory, k);
    std::ifstream in(path, std::ios::binary);
    if (!in)
      throw std::runtime_error("sweep --merge: " + path + ": missing (the job of run " + std::to_string(k) +
                               " has not written its result)");
    std::ostringstream text;
    text << in.rdbuf();
    const std::string line = text.str();
    if (line.empty() || line.back() != '\n' || line.find('\n') != line.size() - 1)
      throw std::runtime_error("sweep --merge: " + path + ": not one complete result line");
    out << line;
  }
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
        "'/bin/sweep' --schemes cn --masses 'mod1' --elements 8 --courants 0.5 --final-time 1 --result "
        "'it'\\''s/run-000000.dat'");
}

}  // namespace mrm::repro
