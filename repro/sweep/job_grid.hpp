/// @file sweep/job_grid.hpp
/// @brief The grid of a sweep: every scheme × mass × N × C to T, each run one result line, in this process or as a job list whose results carry their run and grid and merge back exactly or not at all.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include "configurations.hpp"
#include "options.hpp"

namespace mrm::repro {

/// The grid: every scheme × mass × N × C (Δt = C h) to T, in that nesting order (the last fastest).
struct JobGrid {
  std::vector<std::string> schemes;  ///< ids of the registry (scheme_by_name); PS is (¼, 0), algebraic row
  std::vector<std::string> masses;   ///< mass specs (mass_spec.hpp)
  std::vector<long> elements;        ///< numbers of elements N
  std::vector<double> courants;      ///< ratios Δt/h
  double final_time = 3.0;           ///< T

  /// The number of runs (the product of the lists' lengths).
  std::size_t size() const { return schemes.size() * masses.size() * elements.size() * courants.size(); }
  /// Run k of the grid (0 ≤ k < size()), as a grid of one: the options of its own command.
  JobGrid run(std::size_t k) const;
  /// The configuration of run k.
  Configuration configuration(std::size_t k) const;
  /// Whether two grids are the same runs in the same order (the same lists and T, bit for bit).
  bool operator==(const JobGrid& other) const;
};

/// The largest number of elements of a run, and the largest ratio Δt/h and final time of a sweep: the ranges
/// of the command line's lists (--elements, --courants, --final-time).
constexpr long sweep_max_elements = 100000;
constexpr double sweep_max_courant = 100, sweep_max_final_time = 1000;
/// The most runs of one grid: every run's configuration and result line are held at once (about 1 kB each),
/// and a job list of more lines than this is no longer one file to read.
constexpr double sweep_max_runs = 1e6;

/// The grid of the lists as the command line gives them (comma-separated: --schemes, --masses, --elements,
/// --courants; --final-time), every value checked before any run: scheme ids of the registry
/// (repro/labels.hpp), mass specs on every N (mass_from_option), N integers in [2, 1e5], C in (0, 100], T in
/// (0, 1000], at least one step for each C and N, at most sweep_max_runs runs. A bad value is a
/// cli::UsageError naming its option, the value quoted (cli::quoted_text).
JobGrid grid_from_lists(const std::string& schemes, const std::string& masses, const std::string& elements,
                        const std::string& courants, double final_time);

/// The header of a sweep's result file: the grid and the columns (the same for both ways).
void write_sweep_header(std::ostream& out, const JobGrid& grid);
/// The result line of run k: scheme, mass, N, C, the steps, the energy range and the eight errors
/// (numbers as cli::format_real writes them: the shortest text that reads back to the same double).
std::string sweep_line(const JobGrid& grid, std::size_t k, const Measures& measures);
/// Every run of the grid, in this process through the sweep layer (run_batched: in vector lanes unless
/// sweep_settings() says otherwise, on `threads` threads, 0: one per hardware thread): the result lines in
/// grid order.
std::vector<std::string> run_sweep(const JobGrid& grid, unsigned threads);

/// The identity of a grid: the 16 hexadecimal digits of the 64-bit FNV-1a hash of its header
/// (write_sweep_header), which holds every list and T as they read back.
std::string grid_identity(const JobGrid& grid);
/// What a result file records before its line: which run of which grid it is (its first line,
///   # sweep result: run 7 of 40, grid 3f2a9c0d51e4b687
/// ) and the grid's header, so that a result names its run and its grid whatever its file is called.
std::string result_header(const JobGrid& grid, std::size_t k);

/// The name of run k's result file in `directory`: run-000042.dat (six digits at least).
std::string result_file(const std::string& directory, std::size_t k);
/// A path that a job list writes on its lines, refused (cli::UsageError naming `option`) if it holds a
/// control character: a newline would split a command in two (GNU parallel and a SLURM array take one job
/// per line), and the others are not a path anyone types.
void require_one_line(const std::string& option, const std::string& path);
/// The job list: one line per run k, `program` with the grid's lists, `--run k` and --result naming run k's
/// file in `directory` (paths and mass specs quoted for the shell: each line one command, run from any
/// directory). Each job checks and runs its run alone and writes its result file (result_header and the
/// line).
void write_job_list(std::ostream& out, const std::string& program, const JobGrid& grid, const std::string& directory);

/// The result files of a job list's directory as the merge finds them: every entry named `run-*` (by its
/// run, or as a name that is no run's), and the grid, read from the header of the first result.
struct ResultFiles {
  std::string directory;                    ///< as given to --merge
  JobGrid grid;                             ///< the grid the first result records
  std::string grid_source;                  ///< the path of that result
  std::map<std::size_t, std::string> runs;  ///< run index → path, for every entry named as a result
  std::vector<std::string> strangers;       ///< the paths of entries named run-* that name no run
};
/// Lists `directory` and reads the grid from its first result (the lowest run). A directory that cannot
/// be listed is a cli::UsageError naming --merge; a directory without results, or whose first result
/// records no grid that reads back to the same bytes, a std::runtime_error naming it.
ResultFiles find_results(const std::string& directory);
/// A cli::UsageError naming `option` if `output` is one of the results' files: an existing file that is one
/// of them (by identity, device and inode: through ./, a symbolic or a hard link), or a path in their
/// directory named run-* (a result to come). A merge that wrote over a result would replace what it reads.
void refuse_output_among_results(const std::string& option, const std::string& output, const ResultFiles& results);
/// The merge: the header of the results' grid and the result lines in grid order, the same bytes as the
/// sweep in this process; or a std::runtime_error naming the first file that is not exactly run k's result
/// of this grid: missing, not a regular file, another run's (swapped, copied or linked), another grid's
/// (another T, mass or list), truncated, with more or other bytes than one result line (extra columns, a
/// carriage return, a NUL, numbers not as this program writes them), or a name run-* that is no run of the
/// grid (an extra result).
void merge_results(std::ostream& out, const ResultFiles& results);

}  // namespace mrm::repro
