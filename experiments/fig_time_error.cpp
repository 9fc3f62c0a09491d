// fig_time_error: the error estimate in time, at a fixed mesh.
//
// What it computes. The paper states an error estimate in time for Crank–Nicolson applied to the
// semi-discrete problem (6) (its Section 2). To see it, the mesh is fixed (h = 1/N) and only Δt varies:
// Crank–Nicolson, and backward Euler for contrast, with Δt = h·2^j (j = 2, 1, 0, −1, …) are compared with
// a reference run of the same mesh and mass, Crank–Nicolson with a much smaller step Δt_ref = h/R, at
// the instants they share (mrm::ReferenceComparison). The reference stands for the semi-discrete
// solution; the differences are the errors of the time discretisation alone, in the eight measures of
// mathematics.md §5. The observed order is fitted by least squares (mrm::fit_order) over all steps and
// over the finer half, and the order between consecutive steps shows the range where it holds.
//
// Sample runs:
//   fig_time_error --output output/data/fig_time_error.dat --tex output/data/fig_time_error.tex
//   fig_time_error --elements 128 --reference-ratio 128 --mass mod1 --output t.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the reference and the runs in lockstep, every run
// compared at each of its levels; (4) the data blocks; (5) orders, the table and the quoted values;
// (6) commit.
//
// Data file: block 0 is Crank–Nicolson, block 1 backward Euler; columns dt dt_over_h and the eight
// relative differences (same names as the errors against the exact solution).
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "convergence.hpp"
#include "errors.hpp"
#include "configurations.hpp"
#include "report_values.hpp"
#include "table.hpp"
#include "schemes.hpp"

namespace cli = mrm::cli;

namespace {
const std::array<const char*, 8> measure_labels{
    "$u(0,\\cdot)$, $L^2_t$", "$\\lambda$, $L^2_t$",      "$u$, $L^\\infty_t L^2$", "$u$, $L^\\infty_t H^1$",
    "$u_t$, $L^\\infty_t L^2$", "$u$, $L^2_t L^2$", "$u$, $L^2_t H^1$",       "$u_t$, $L^2_t L^2$"};
}

int main(int argc, char** argv) {
  return cli::guarded_main("fig_time_error", [&] {
    // 1. Options.
    long elements = 256, reference_ratio = 128, largest = 4, steps_count = 6;
    double final_time = 3.0;
    std::string mass = "mod3";
    cli::Parser parser("fig_time_error",
                       "Writes the error of Crank-Nicolson and backward Euler against the time step at a fixed "
                       "mesh, measured against a Crank-Nicolson reference run of the same mesh with a much smaller "
                       "step, and the observed orders in time.",
                       {"fig_time_error --output output/data/fig_time_error.dat --tex output/data/fig_time_error.tex",
                        "fig_time_error --elements 128 --reference-ratio 128 --mass mod1 --output t.dat"});
    parser.add_integer("--elements", "-n", "N", "number of elements N (h = 1/N), >= 2", &elements, cli::at_least(2));
    parser.add_integer("--reference-ratio", "-r", "R", "reference step dt_ref = h/R; a power of 2, >= 2",
                       &reference_ratio, cli::at_least(2));
    parser.add_integer("--largest", "", "P", "largest step dt = P h; a power of 2, >= 1", &largest, cli::at_least(1));
    parser.add_integer("--steps", "-k", "K", "number of steps dt = P h, P h/2, ..., P h/2^(K-1) (>= 2)", &steps_count,
                       cli::at_least(2));
    parser.add_real("--final-time", "-T", "T", "final time (> 0); one period is 3", &final_time, cli::positive());
    parser.add_choice("--mass", "-m", "M", "mass choice", {"mod1", "mod2", "mod3"}, &mass);
    mrm::repro::FigureOutputs outputs(parser, "fig_time_error", "also write the table and values the report quotes");
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    auto power_of_two = [](long v) { return v > 0 && (v & (v - 1)) == 0; };
    if (!power_of_two(reference_ratio)) throw cli::UsageError("--reference-ratio: must be a power of 2");
    if (!power_of_two(largest)) throw cli::UsageError("--largest: must be a power of 2");
    // Every step Δt_j = P h / 2^j must be a multiple m_j = P R / 2^j ≥ 2 of the reference step.
    if (steps_count > 62 || ((largest * reference_ratio) >> (steps_count - 1)) < 2)
      throw cli::UsageError("--steps: the smallest step P h/2^(K-1) must be at least twice the reference step h/R");

    // 2. Outputs.
    outputs.open(parser);
    const mrm::UniformMesh mesh(1.0, elements);
    const double h = mesh.h();
    const double dt_ref = h / static_cast<double>(reference_ratio);
    const mrm::MassRedistribution redistribution = mrm::mass_redistribution_by_name(mass);

    // 3. The reference and every run in lockstep: run j makes one step every m_j reference steps and is
    // compared each time. T is rounded up to a whole number of the largest step so that all runs end
    // at the same instant.
    const std::vector<std::string> schemes{"cn", "be"};
    std::vector<long> ratio(static_cast<std::size_t>(steps_count));
    for (std::size_t j = 0; j < ratio.size(); ++j) ratio[j] = (largest * reference_ratio) >> j;
    const mrm::Index coarse_steps = mrm::steps_to_reach(final_time, static_cast<double>(ratio[0]) * dt_ref);
    const mrm::Index reference_steps = coarse_steps * ratio[0];
    mrm::BarSimulation reference(mrm::benchmark_problem(), mesh, redistribution,
                                 mrm::repro::scheme_parameters("cn", "algebraic", mass), dt_ref);
    std::vector<std::unique_ptr<mrm::BarSimulation>> runs;
    std::vector<mrm::ReferenceComparison> comparisons;
    for (const std::string& scheme : schemes)
      for (long m : ratio) {
        runs.push_back(std::make_unique<mrm::BarSimulation>(mrm::benchmark_problem(), mesh, redistribution,
                                                            mrm::repro::scheme_parameters(scheme, "algebraic", mass),
                                                            static_cast<double>(m) * dt_ref));
        comparisons.emplace_back(mesh);
        comparisons.back().add(runs.back()->sample(), reference.sample());
      }
    std::cerr << "fig_time_error: " << reference_steps << " reference steps\n";
    for (mrm::Index k = 1; k <= reference_steps; ++k) {
      reference.step();
      for (std::size_t r = 0; r < runs.size(); ++r) {
        const long m = ratio[r % ratio.size()];
        if (k % m != 0) continue;
        runs[r]->step();
        comparisons[r].add(runs[r]->sample(), reference.sample());
      }
    }

    // 4. Data blocks.
    std::ostream& out = outputs.data();
    out << "# fig_time_error: error in time at fixed h against a reference with dt_ref = h/R (problem.md sec. 5)\n";
    parser.echo(out);
    out << "# h = " << cli::format_real(h) << "\n# dt_ref = " << cli::format_real(dt_ref)
        << "\n# final_time_used = " << cli::format_real(static_cast<double>(reference_steps) * dt_ref)
        << "\n# reference: Crank-Nicolson with the same mesh and mass\n# blocks: 0 cn, 1 be\n";
    std::vector<std::array<double, 8>> differences(runs.size());
    for (std::size_t r = 0; r < runs.size(); ++r) differences[r] = comparisons[r].relative();
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      out << (s ? "\n\n" : "") << "# block " << s << ": scheme = " << schemes[s] << "\n# columns: dt dt_over_h";
      for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
      out << '\n';
      for (std::size_t j = 0; j < ratio.size(); ++j) {
        const double dt = static_cast<double>(ratio[j]) * dt_ref;
        out << cli::format_real(dt) << ' ' << cli::format_real(dt / h);
        for (double e : differences[s * ratio.size() + j]) out << ' ' << cli::format_real(e);
        out << '\n';
      }
    }

    // 5. Orders: the fit over all steps and over the finer half, and the order between consecutive
    // steps, log₂(e_j / e_{j+1}), in a table beside the errors.
    std::ostream& defs = outputs.values();
    mrm::tex_define(defs, "time:elements", std::to_string(elements));
    mrm::tex_define(defs, "time:R", std::to_string(reference_ratio));
    mrm::tex_define(defs, "time:mass", mass == "mod1" ? "Mod 1" : mass == "mod2" ? "Mod 2" : "Mod 3");
    mrm::tex_define(defs, "time:T", mrm::tex_number(static_cast<double>(reference_steps) * dt_ref, 3));
    // A step as a multiple of h, for the prose: "4h", "h", "h/8".
    auto step_text = [&](long m) {
      const double q = static_cast<double>(m) / static_cast<double>(reference_ratio);
      if (q == 1) return std::string("h");
      return q > 1 ? std::to_string(static_cast<long>(q)) + "h" : "h/" + std::to_string(static_cast<long>(1 / q));
    };
    mrm::tex_define(defs, "time:largest", step_text(ratio.front()));
    mrm::tex_define(defs, "time:smallest", step_text(ratio.back()));
    std::vector<std::string> headers{"scheme", "$\\Delta t/h$"};
    for (const char* label : measure_labels) headers.push_back(std::string("\\rotatebox{70}{") + label + "}");
    mrm::repro::Table table(headers);
    const std::size_t half = ratio.size() / 2;
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      for (std::size_t j = 0; j < ratio.size(); ++j) {
        const double q = static_cast<double>(ratio[j]) / static_cast<double>(reference_ratio);
        std::vector<std::string> cells{
            j == 0 ? mrm::repro::scheme_label(schemes[s]) : std::string(),
            q >= 1 ? std::to_string(static_cast<long>(q)) : "1/" + std::to_string(static_cast<long>(1 / q))};
        for (std::size_t k = 0; k < 8; ++k) {
          const double e = differences[s * ratio.size() + j][k];
          cells.push_back(mrm::tex_number(e, 2));
          if (j > 0) {  // the local order of this halving of the step (steps ratio[j−1] → ratio[j])
            const double previous = differences[s * ratio.size() + j - 1][k];
            const double local = mrm::repro::local_orders({static_cast<double>(ratio[j - 1]), static_cast<double>(ratio[j])},
                                                          {previous, e})[1];
            cells.back() += " (" + mrm::tex_number(local, 2) + ")";
          }
        }
        table.add_row(cells);
      }
      table.add_rule();
      for (std::size_t k = 0; k < 8; ++k) {
        std::vector<double> steps, errors, fine_steps, fine_errors;
        for (std::size_t j = 0; j < ratio.size(); ++j) {
          const double e = differences[s * ratio.size() + j][k];
          if (!(e > 0)) continue;
          steps.push_back(static_cast<double>(ratio[j]) * dt_ref);
          errors.push_back(e);
          if (j >= half) fine_steps.push_back(steps.back()), fine_errors.push_back(e);
        }
        const std::string key = schemes[s] + ":" + mrm::ErrorAccumulator::names[k];
        mrm::tex_define(defs, "time:order:" + key, steps.size() >= 2 ? mrm::tex_number(mrm::fit_order(steps, errors).order, 2) : "n/a");
        mrm::tex_define(defs, "time:orderfine:" + key,
                        fine_steps.size() >= 2 ? mrm::tex_number(mrm::fit_order(fine_steps, fine_errors).order, 2) : "n/a");
        mrm::tex_define(defs, "time:errfine:" + key, mrm::tex_number(differences[s * ratio.size() + ratio.size() - 1][k], 2));
      }
    }
    mrm::tex_define(defs, "time:finehalf", step_text(ratio[half]));
    // The table in two halves at the text size (measures 1-4, then 5-8 of mathematics.md §5), not shrunk.
    mrm::repro::LatexLayout layout;
    layout.columns = "ll" + std::string(4, 'r');
    layout.final_newline = false;
    for (std::size_t half = 0; half < 2; ++half) {
      std::vector<std::size_t> keep{0, 1};
      for (std::size_t k = 4 * half; k < 4 * half + 4; ++k) keep.push_back(2 + k);
      std::ostringstream tabular;
      table.columns_subset(keep).write_latex(tabular, layout);
      defs << "\\mrmdef{time:table" << (half == 0 ? ":a" : ":b") << "}{" << tabular.str() << "}\n";
    }

    // 6. Commit.
    outputs.commit();
    return 0;
  });
}
