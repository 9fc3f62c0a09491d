// sweep: a grid of runs of the paper's benchmark, in this process or as a job list that leaves it.
//
// What it computes. Every run of schemes × masses × N × Δt/h to T (repro/sweep.hpp), each one line of
// measures (steps, energy range, the eight errors of mathematics.md §5). Three ways, the same bytes:
//   in this process   --output FILE, the runs through the sweep layer (repro/sweep.hpp: in the lanes of
//                     --vector, on --threads workers), the lines in grid order;
//   as a job list     --job-list FILE --results DIR: one self-contained command per line, each this
//                     program with the options of one run and --result DIR/run-NNNNNN.dat; run it with
//                     GNU parallel (`parallel --jobs 2 < jobs.txt`, across hosts with --sshloginfile) or
//                     a SLURM array (`sbatch --array=1-K --wrap 'sed -n "${SLURM_ARRAY_TASK_ID}p" jobs.txt | bash'`);
//   merged            --merge DIR --output FILE, with the grid options: the header and the result files in
//                     grid order (a missing or incomplete file is an error naming it).
// A run alone (a grid of one with --result FILE) writes its line only. The ctest entry sweep_job_list
// runs a small sweep both ways through GNU parallel and compares the bytes (the jobs are runs alone, the
// in-process runs share vector lanes); tests/sweep_widths.sh runs it in-process on every --vector and
// --threads and compares the bytes.
//
// Sample runs:
//   sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --final-time 3 --output s.dat
//   sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --final-time 3 --job-list jobs.txt
//         --results runs
//   parallel --jobs 2 < jobs.txt
//   sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --final-time 3 --merge runs --output m.dat
//
// Description. Steps: (1) options, every value of every list checked before any work; (2) the one mode.
#include <unistd.h>

#include <climits>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"
#include "sweep.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> words;
  std::string word;
  for (char c : text + ",") {
    if (c != ',') {
      word += c;
      continue;
    }
    words.push_back(word);
    word.clear();
  }
  return words;
}

// The path of this program, for the job list's commands (they run from any directory).
std::string own_path(const char* argv0) {
  char buffer[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (length <= 0) return argv0;
  return std::string(buffer, static_cast<std::size_t>(length));
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("sweep", [&] {
    // 1. Options.
    std::string schemes = "cn", masses = "mod3", elements = "16", courants = "0.5";
    std::string output, job_list, results, merge, result;
    double final_time = 3;
    repro::SweepOptions sweep_options;
    cli::Parser parser(
        "sweep",
        "Runs every scheme x mass x N x dt/h of the paper's benchmark to T and writes one line of measures per run: "
        "in this process (--output), as a job list of one command per run (--job-list, --results), or merges the "
        "results of such a list (--merge, --output) into the same bytes.",
        {"sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --output s.dat",
         "sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --job-list jobs.txt --results "
         "runs",
         "sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --merge runs --output s.dat"});
    parser.add_string("--schemes", "", "LIST", "schemes of the registry, comma-separated (cn, be, ps, ec, cn-switch)",
                      &schemes);
    parser.add_string("--masses", "", "LIST", "mass specs, comma-separated (mod1, mod2, mod3, consistent, ...)",
                      &masses);
    parser.add_string("--elements", "-n", "LIST", "numbers of elements N, comma-separated integers in [2, 1e5]",
                      &elements);
    parser.add_string("--courants", "", "LIST", "ratios dt/h, comma-separated, each in (0, 100]", &courants);
    parser.add_real("--final-time", "-T", "T", "final time, in (0, 1000]", &final_time,
                    cli::in_closed_range(1e-300, 1000));
    repro::add_sweep_options(parser, sweep_options);
    parser.add_output("--output", "-o", "write the sweep (or, with --merge, the merged results) to FILE", &output);
    parser.add_output("--job-list", "", "write the job list (one command per run) to FILE instead of running",
                      &job_list);
    parser.add_string("--results", "", "DIR",
                      "the directory of the job list's result files (it must exist when the "
                      "jobs run)",
                      &results);
    parser.add_string("--merge", "", "DIR", "merge the result files of DIR (with --output)", &merge);
    parser.add_output("--result", "", "one run (a grid of one): write its line alone to FILE", &result);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;

    repro::JobGrid grid;
    grid.final_time = final_time;
    grid.schemes = split(schemes);
    for (const std::string& s : grid.schemes) {
      try {
        (void)mrm::scheme_by_name(s);
      } catch (const std::exception& e) {
        throw cli::UsageError(std::string("--schemes: ") + e.what());
      }
    }
    for (double n : cli::parse_real_list("--elements", elements)) {
      if (!(n >= 2 && n <= 1e5 && n == std::floor(n)))
        throw cli::UsageError("--elements: " + cli::format_real(n) + " (allowed: integers in [2, 1e5])");
      grid.elements.push_back(static_cast<long>(n));
    }
    grid.masses = split(masses);
    for (const std::string& m : grid.masses)
      for (long n : grid.elements) (void)repro::mass_from_option("--masses", m, mrm::UniformMesh(1.0, n));
    grid.courants = cli::parse_real_list("--courants", courants);
    for (double c : grid.courants) {
      cli::require_in_closed_range("--courants", c, 1e-300, 100);
      for (long n : grid.elements)
        cli::checked_steps("--final-time", final_time, c / static_cast<double>(n), "dt = C h (raise --courants)");
    }
    // A scheme that refuses a mass (EC or the algebraic Paoli–Schatzman row with the consistent mass) is
    // refused now, by the library's own checks on each run's set-up.
    for (std::size_t k = 0; k < grid.size(); ++k) {
      const repro::Configuration c = grid.configuration(k);
      try {
        const mrm::BarSimulation check(repro::configuration_problem(c), mrm::UniformMesh(c.bar_length(), c.elements),
                                       c.mass, c.scheme, c.step());
      } catch (const std::invalid_argument& e) {
        throw cli::UsageError("--schemes, --masses: " + mrm::to_string(c.scheme.scheme) + " with " + c.mass.name +
                              ": " + e.what());
      }
    }
    // The outputs, opened before anything else is refused (a bad path is named first).
    std::unique_ptr<cli::AtomicFile> out, list, one;
    if (parser.given("--output")) out = std::make_unique<cli::AtomicFile>(output, "--output");
    if (parser.given("--job-list")) list = std::make_unique<cli::AtomicFile>(job_list, "--job-list");
    if (parser.given("--result")) one = std::make_unique<cli::AtomicFile>(result, "--result");
    // One mode: --output (in this process), --job-list with --results, --merge with --output, --result.
    const bool merging = parser.given("--merge");
    if (one && grid.size() != 1)
      throw cli::UsageError("--result: one run only (every list of one value), not " + std::to_string(grid.size()));
    if ((list != nullptr) != parser.given("--results"))
      throw cli::UsageError("--results: needed with --job-list, and only with it");
    if (merging && !out) throw cli::UsageError("--merge: needs --output");
    const int modes = (out && !merging) + (list != nullptr) + merging + (one != nullptr);
    if (modes != 1)
      throw cli::UsageError("--output, --job-list, --merge, --result: give one of them (--merge with --output)");

    // 2. The mode.
    if (list) {
      repro::write_job_list(list->stream(), own_path(argv[0]), grid, results);
      list->commit();
    } else if (merging) {
      repro::merge_results(out->stream(), grid, merge);
      out->commit();
    } else if (one) {
      one->stream() << repro::run_sweep(grid, 1).front();
      one->commit();
    } else {
      repro::write_sweep_header(out->stream(), grid);
      repro::apply_sweep_options(sweep_options);
      for (const std::string& line : repro::run_sweep(grid, repro::sweep_settings().threads)) out->stream() << line;
      out->commit();
    }
    return 0;
  });
}
