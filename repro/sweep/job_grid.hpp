/// @file sweep/job_grid.hpp
/// @brief The grid of a sweep: every scheme × mass × N × C to T, each run one result line, in this process or as a job list.
#pragma once

#include <cstddef>
#include <functional>
#include <utility>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "options.hpp"

namespace mrm::repro {

/// The grid: every scheme × mass × N × C (Δt = C h) to T, in that nesting order (the last fastest).
struct JobGrid {
  std::vector<std::string> schemes;  ///< ids of the registry (scheme_by_name); PS is (¼, 0), algebraic row
  std::vector<std::string> masses;   ///< mass specs (mass_spec.hpp)
  std::vector<long> elements;
  std::vector<double> courants;
  double final_time = 3.0;

  std::size_t size() const { return schemes.size() * masses.size() * elements.size() * courants.size(); }
  /// Run k of the grid (0 ≤ k < size()), as a grid of one: the options of its own command.
  JobGrid run(std::size_t k) const;
  /// The configuration of run k.
  Configuration configuration(std::size_t k) const;
};

/// The header of a sweep's result file: the grid and the columns (the same for both ways).
void write_sweep_header(std::ostream& out, const JobGrid& grid);
/// The result line of run k: scheme, mass, N, C, the steps, the energy range and the eight errors
/// (numbers as cli::format_real writes them: the shortest text that reads back to the same double).
std::string sweep_line(const JobGrid& grid, std::size_t k, const Measures& measures);
/// Every run of the grid, in this process through the sweep layer (run_batched: in vector lanes unless
/// sweep_settings() says otherwise, on `threads` threads, 0: one per hardware thread): the result lines in
/// grid order.
std::vector<std::string> run_sweep(const JobGrid& grid, unsigned threads);
/// The name of run k's result file in `directory`: run-000042.dat.
std::string result_file(const std::string& directory, std::size_t k);
/// The job list: one line per run, `program` with the options of that run alone and --result naming its
/// result file in `directory` (paths quoted for the shell).
void write_job_list(std::ostream& out, const std::string& program, const JobGrid& grid, const std::string& directory);
/// The header and the lines of the result files of every run, in grid order; throws std::runtime_error
/// naming the first file that is missing or is not one complete line.
void merge_results(std::ostream& out, const JobGrid& grid, const std::string& directory);

}  // namespace mrm::repro
