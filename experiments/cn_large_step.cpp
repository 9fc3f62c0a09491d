// cn_large_step: how much energy Crank–Nicolson with a massless contact node gains when Δt ≫ h.
//
// What it computes. Crank–Nicolson with Mod 3 on the benchmark (mathematics.md §2) on a coarse mesh
// (N = 16) over 100 periods (T = 300), for the ratios Δt/h = 0.5, 2, 5, 10 and 40, and writes the
// largest discrete energy of each run relative to E_h(0) as the report's values
// `\mrmdef{large:C}{max_n E_hⁿ / E_h(0)}`. Crank–Nicolson conserves E_h while the contact status is
// unchanged; a release can add energy and an impact remove it (mathematics.md §4), so the ratio
// measures how far "unconditionally stable" fails for a massless contact node.
//
// Sample runs:
//   cn_large_step --tex output/data/cn_large_step.tex
//   cn_large_step --elements 32 --final-time 30 --tex large.tex
//
// Description. Steps: (1) read the options, check that every run takes a step; (2) open the output (a
// bad path fails before the runs); (3) run each ratio with repro/configurations' run_configuration;
// (4) write the values and commit.
#include <iostream>
#include <string>

#include "configurations.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "report_values.hpp"
#include "run_limits.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("cn_large_step", [&] {
    // 1. Options.
    long elements = 16;
    double final_time = 300;
    std::string tex = "cn_large_step.tex";
    cli::Parser parser("cn_large_step",
                       "Runs Crank-Nicolson with Mod 3 on the benchmark for dt/h = 0.5, 2, 5, 10, 40 and writes the "
                       "largest discrete energy of each run relative to E_h(0) as \\mrmdef lines for the report.",
                       {"cn_large_step --tex output/data/cn_large_step.tex"});
    parser.add_integer("--elements", "-n", "N", "number of elements N of the mesh, an integer in [2, 1e5]", &elements,
                       cli::in_closed_range(2, 1e5));
    parser.add_real("--final-time", "-T", "T", "final time, in (0, 1e4]; the period of the benchmark is 3", &final_time,
                    cli::in_closed_range(1e-300, 1e4));
    parser.add_output("--tex", "", "write the values for the report (\\mrmdef lines) to FILE", &tex);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    // Every run takes at least one step: the one with the largest step, dt = 40 h (the smallest,
    // dt = h/2, takes at most 1e4 / (0.5 / 1e5) = 2e9 steps by the ranges).
    cli::checked_steps("--final-time", final_time, 40.0 / static_cast<double>(elements),
                       "dt = 40 h (raise --elements)");

    // 2. The output, opened before the runs.
    cli::AtomicFile out(tex, "--tex");

    // 3-4. The runs and their values, and the run parameters the text states (the mesh, the horizon
    // in time and in periods of the benchmark, 3L with L = 1, and the lists of ratios and values).
    std::string ratios, values;
    for (const char* ratio : {"0.5", "2", "5", "10", "40"}) {
      const mrm::repro::Measures m = mrm::repro::run_configuration(mrm::repro::paper_configuration(
          mrm::Scheme::crank_nicolson, "algebraic", "mod3", elements, cli::parse_real("ratio", ratio), final_time));
      const std::string value = mrm::tex_magnitude(m.energy_max / m.energy_initial);
      mrm::tex_define(out.stream(), std::string("large:") + ratio, value);
      ratios += (ratios.empty() ? "" : ", ") + std::string(ratio);
      values += (values.empty() ? "" : ",\\ ") + value;
    }
    mrm::tex_define(out.stream(), "large:elements", std::to_string(elements));
    mrm::tex_define(out.stream(), "large:T", cli::format_real(final_time));
    mrm::tex_define(out.stream(), "large:periods", cli::format_real(final_time / 3));
    mrm::tex_define(out.stream(), "large:ratios", ratios);
    mrm::tex_define(out.stream(), "large:values", values);
    out.commit();
    return 0;
  });
}
