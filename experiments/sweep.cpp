// sweep: a grid of runs of the paper's benchmark, in this process or as a job list that leaves it.
//
// What it computes. Every run of schemes × masses × N × Δt/h to T (repro/sweep.hpp), each one line of
// measures (steps, energy range, the eight errors of mathematics.md §5). Three ways, the same bytes:
//   in this process   --output FILE, the runs through the sweep layer (repro/sweep.hpp: in the lanes of
//                     --vector, on --threads workers), the lines in grid order;
//   as a job list     --job-list FILE --results DIR: one self-contained command per line, each this
//                     program with the grid's lists, --run K and --result DIR/run-NNNNNN.dat; run it with
//                     GNU parallel (`parallel --jobs 2 < jobs.txt`, across hosts with --sshloginfile) or
//                     a SLURM array (`sbatch --array=1-K --wrap 'sed -n "${SLURM_ARRAY_TASK_ID}p" jobs.txt | bash'`);
//                     each result file records its run and its grid (repro/sweep/job_grid.hpp, result_header);
//   merged            --merge DIR --output FILE: the grid read from the results (each grid option given must
//                     agree), every result exactly run K's of that grid or the merge fails naming the file
//                     (missing, extra, swapped, copied, of another grid, truncated, garbled); an output that
//                     is one of the results is refused.
// A run alone (--result FILE with --run K, or a grid of one) writes its result file only. The ctest entry
// sweep_job_list runs a grid both ways through GNU parallel and compares the bytes (the jobs are runs alone,
// the in-process runs share vector lanes), then damages the results in every way above and sees each merge
// fail; tests/sweep_widths.sh runs it in-process on every --vector and --threads and compares the bytes.
//
// Sample runs:
//   sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --final-time 3 --output s.dat
//   sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --final-time 3 --job-list jobs.txt
//         --results runs
//   parallel --jobs 2 < jobs.txt
//   sweep --merge runs --output m.dat
//
// Description. Steps: (1) options, every value of every list checked before any work, the options of
// another mode refused; (2) the one mode.
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <iostream>
#include <memory>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "configurations.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"
#include "sweep.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

namespace {

// The path of this program, for the job list's commands (they run from any directory).
std::string own_path(const char* argv0) {
  char buffer[PATH_MAX];
  const ssize_t length = readlink("/proc/self/exe", buffer, sizeof buffer - 1);
  if (length <= 0) return argv0;
  return std::string(buffer, static_cast<std::size_t>(length));
}

// The memory of a run's configuration and result line, held until the end of a sweep in this process.
constexpr double bytes_per_run = 1000;

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("sweep", [&] {
    // 1. Options.
    std::string schemes = "cn", masses = "mod3", elements = "16", courants = "0.5";
    std::string output, job_list, results, merge, result;
    double final_time = 3;
    long run = 0;
    repro::SweepOptions sweep_options;
    cli::Parser parser(
        "sweep",
        "Runs every scheme x mass x N x dt/h of the paper's benchmark to T and writes one line of measures per run: "
        "in this process (--output), as a job list of one command per run (--job-list, --results), or merges the "
        "results of such a list (--merge, --output) into the same bytes, reading the grid from the results (each "
        "records its run and its grid) and refusing any result that is not exactly its run's.",
        {"sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --output s.dat",
         "sweep --schemes cn,be --masses mod1,mod3 --elements 16,32 --courants 0.5,1 --job-list jobs.txt --results "
         "runs",
         "sweep --merge runs --output s.dat"});
    parser.add_string("--schemes", "", "LIST",
                      "schemes of the registry, comma-separated (cn, be, ps, ec, cn-switch, ...)", &schemes);
    parser.add_string("--masses", "", "LIST", "mass specs, comma-separated (mod1, mod2, mod3, consistent, ...)",
                      &masses);
    parser.add_string("--elements", "-n", "LIST", "numbers of elements N, comma-separated integers in [2, 1e5]",
                      &elements);
    parser.add_string("--courants", "", "LIST", "ratios dt/h, comma-separated, each in (0, 100]", &courants);
    parser.add_real("--final-time", "-T", "T", "final time, in (0, 1000]", &final_time,
                    cli::in_closed_range(1e-300, repro::sweep_max_final_time));
    repro::add_sweep_options(parser, sweep_options);
    parser.add_output("--output", "-o", "write the sweep (or, with --merge, the merged results) to FILE", &output);
    parser.add_output("--job-list", "", "write the job list (one command per run) to FILE instead of running",
                      &job_list);
    parser.add_string("--results", "", "DIR",
                      "the directory of the job list's result files (it must exist when the "
                      "jobs run)",
                      &results);
    parser.add_string("--merge", "", "DIR",
                      "merge the result files of DIR (with --output; the grid is the results', each grid option "
                      "given must agree)",
                      &merge);
    parser.add_output("--result", "", "one run (--run K, or a grid of one): write its result file to FILE", &result);
    parser.add_integer("--run", "", "K", "with --result: run K of the grid (0, 1, ...; a job list's line K + 1)", &run,
                       cli::at_least(0));
    // The options of another mode: the workers and the vector width run nothing in a job list, a merge or
    // a run alone (a job's runs are one run each, stepped alone: the same bytes as in lanes).
    for (const char* option : {"--threads", "--vector"})
      for (const char* mode : {"--merge", "--job-list", "--result"})
        parser.add_not_applicable(option, mode,
                                  std::string(mode) == "--merge" ? "the merge runs nothing; allowed: omit it"
                                  : std::string(mode) == "--job-list"
                                      ? "the jobs run one run each, alone; allowed: omit it"
                                      : "a run alone is stepped alone; allowed: omit it");
    parser.add_not_applicable("--run", "--job-list", "the job list numbers the runs itself; allowed: omit --run");
    parser.add_not_applicable("--run", "--merge", "the merge reads every run; allowed: omit --run");
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;

    // The grid's lists, every value checked first (the defaults of those not given are valid); with --merge
    // the grid is the results' (find_results), and each grid option given must be the results' own.
    const bool merging = parser.given("--merge");
    repro::JobGrid grid = repro::grid_from_lists(schemes, masses, elements, courants, final_time);
    std::optional<repro::ResultFiles> found;
    if (merging) {
      found = repro::find_results(merge);
      const repro::JobGrid asked = grid;
      grid = found->grid;
      const auto differs = [&](const char* option, bool same) {
        if (parser.given(option) && !same)
          throw cli::UsageError(std::string(option) + ": not the grid of the results (" +
                                cli::quoted_text(found->grid_source) + " records grid " + repro::grid_identity(grid) +
                                "; allowed: omit the grid options with --merge, or give the results' own)");
      };
      differs("--schemes", asked.schemes == grid.schemes);
      differs("--masses", asked.masses == grid.masses);
      differs("--elements", asked.elements == grid.elements);
      differs("--courants", asked.courants == grid.courants);
      differs("--final-time", asked.final_time == grid.final_time);
      repro::refuse_output_among_results("--output", output, *found);
    }
    if (parser.given("--run") && !(static_cast<std::size_t>(run) < grid.size()))
      throw cli::UsageError("--run: " + std::to_string(run) + " is not a run of the grid (allowed: 0 to " +
                            std::to_string(grid.size() - 1) + ")");
    // A scheme that refuses a mass (EC or the algebraic Paoli–Schatzman row with the consistent mass) is
    // refused now, by the library's own checks on each run's set-up (a run alone: its own).
    if (!merging) {
      const std::size_t first = parser.given("--run") ? static_cast<std::size_t>(run) : 0;
      const std::size_t last = parser.given("--run") ? first + 1 : grid.size();
      for (std::size_t k = first; k < last; ++k) {
        const repro::Configuration c = grid.configuration(k);
        try {
          const mrm::BarSimulation check(repro::configuration_problem(c), mrm::UniformMesh(c.bar_length(), c.elements),
                                         c.mass, c.scheme, c.step());
        } catch (const std::invalid_argument& e) {
          throw cli::UsageError("--schemes, --masses: " + mrm::to_string(c.scheme.scheme) + " with " + c.mass.name +
                                ": " + e.what());
        }
      }
    }
    // The memory of the runs in this process, before any of them: their batches on the workers
    // (require_batched_memory), and every run's configuration and result line, held until the end.
    if (parser.given("--output") && !merging) {
      std::vector<repro::Configuration> configurations;
      for (std::size_t k = 0; k < grid.size(); ++k) configurations.push_back(grid.configuration(k));
      repro::SweepSettings settings;
      settings.threads = static_cast<unsigned>(sweep_options.threads);
      settings.batched = sweep_options.vector != "none";
      repro::require_batched_memory("--elements", configurations, settings);
      cli::require_memory("--schemes, --masses, --elements, --courants",
                          static_cast<double>(grid.size()) * bytes_per_run,
                          "the configurations and result lines of " + std::to_string(grid.size()) + " runs");
    } else if (parser.given("--result")) {
      const std::size_t k = parser.given("--run") ? static_cast<std::size_t>(run) : 0;
      cli::require_mesh_memory("--elements", static_cast<double>(grid.configuration(k).elements),
                               repro::batched_bytes_per_lane_element);
    }
    // The outputs, opened before the work (a bad path is named now).
    std::unique_ptr<cli::AtomicFile> out, list, one;
    if (parser.given("--output")) out = std::make_unique<cli::AtomicFile>(output, "--output");
    if (parser.given("--job-list")) list = std::make_unique<cli::AtomicFile>(job_list, "--job-list");
    if (parser.given("--result")) one = std::make_unique<cli::AtomicFile>(result, "--result");
    // One mode: --output (in this process), --job-list with --results, --merge with --output, --result.
    if (one && !parser.given("--run") && grid.size() != 1)
      throw cli::UsageError("--result: one run only (every list of one value, or --run K), not " +
                            std::to_string(grid.size()));
    if ((list != nullptr) != parser.given("--results"))
      throw cli::UsageError("--results: needed with --job-list, and only with it");
    if (list) {
      repro::require_one_line("--results", results);
      if (results.empty()) throw cli::UsageError("--results: \"\" is no directory (allowed: a directory's path)");
    }
    if (parser.given("--run") && !one) throw cli::UsageError("--run: needs --result");
    if (merging && !out) throw cli::UsageError("--merge: needs --output");
    const int modes = (out && !merging) + (list != nullptr) + merging + (one != nullptr);
    if (modes != 1)
      throw cli::UsageError("--output, --job-list, --merge, --result: give one of them (--merge with --output)");

    // 2. The mode.
    if (list) {
      const std::string program = own_path(argv[0]);
      for (const char c : program)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
          throw cli::UsageError("--job-list: this program's path " + cli::quoted_text(program) +
                                " holds a control character, which would split its commands (allowed: run it "
                                "from a path without one)");
      repro::write_job_list(list->stream(), program, grid, results);
      list->commit();
    } else if (merging) {
      repro::merge_results(out->stream(), *found);
      out->commit();
    } else if (one) {
      // The run alone is the grid of one of its own command: the same line as in the whole grid.
      const std::size_t k = parser.given("--run") ? static_cast<std::size_t>(run) : 0;
      one->stream() << repro::result_header(grid, k) << repro::run_sweep(grid.run(k), 1).front();
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
