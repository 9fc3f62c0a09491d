// fig_smooth_convergence: convergence on the smooth benchmarks, every error measure against h.
//
// What it computes. The relative errors of mathematics.md §5 against the characteristic solution
// (mathematics.md §10) on the smooth benchmarks S1 (generic impact) and S2 (grazing contact) of
// mathematics.md §11, for Crank–Nicolson and backward Euler with Mod 1, 2 and 3, on the meshes
// N = N₀, 2N₀, …, 2^{K−1}N₀ with Δt = h and Δt = h/2, to T = 2; the observed order of each measure is the
// least-squares slope of log error against log h (mrm::fit_order), written beside the order predicted
// below; the report also quotes the local order between the two finest meshes (repro::local_orders).
//
// Predictions. The paper's benchmark has kinked data, so every measure converges at the regularity limit
// of its solution (mathematics.md §9), whatever the mass. These data are smooth, and what limits the
// order is, in turn:
//   - S2, no jump anywhere. Crank–Nicolson is second order; Mod 3 gives the new free end the inertia of
//     the removed element and moves the effective free length by O(h²) only (mathematics.md §8): order 2
//     in every measure but one. In free flight the contact row makes the first element rigid (u₀ = u₁),
//     so its slope is 0 where the exact u_x grows like x u_xx(0, t) (u_x(0, t) = 0 at a free end, and
//     u_xx = u_tt ≠ 0 there): an O(h) error of u_x on a width h, h^{3/2} in H¹. So u in H¹ (L∞ and L² in
//     time): order 3/2 with Mod 3 (the same element costs only O(h²) in u(0,·) and h^{5/2} in L²).
//     Mod 1 moves the free end by 2h/3, so the wave reflected by the free end, u(0,·)
//     before the touch and after the release, and the whole displacement and velocity behind it are
//     shifted by O(h): order 1; while the end is held Mod 1 is the consistent clamped bar (contact length
//     L + O(h²)) and λ = 2G′ is not shifted: order 2 for λ. Mod 2 scales the whole mass by 1 + O(h): the
//     waves are O(h) slow everywhere, in contact too: order 1 in every measure. Backward Euler is first
//     order: 1 everywhere.
//   - S1, an impact with non-zero velocity at t* = ½ (held until after T = 2): u_t and u_x jump along the
//     characteristic leaving (0, ½), and λ jumps in time at t*. λ in L²(0,T): a jump in time sampled on
//     the time grid costs √Δt, order ½, for every mass and scheme. The energy-type measures (u in H¹, u_t
//     in L²) carry the travelling jump smeared over W: order ⅓ for Crank–Nicolson (W ≈ (h²t)^{1/3}) and
//     ¼ for backward Euler (W ≈ (Δt t)^{1/2}). The displacement u has only a kink there: order 1 for
//     Crank–Nicolson (J W^{3/2} = h t^{1/2}, mathematics.md §9, and the O(h) shift of Mod 1 and Mod 2),
//     ¾ for backward Euler (W^{3/2}). u(0,·) is 0 after the impact and smooth before: order 2 with Mod 3
//     and Crank–Nicolson, 1 with Mod 1 and Mod 2 (the impact time moves by O(h)) and with backward Euler.
// A fitted order is said to agree with its prediction within ±0.25.
//
// The runs are independent; they are spread over --threads worker threads, and the results are written
// in a fixed order, so that the output does not depend on the number of threads.
//
// Sample runs:
//   fig_smooth_convergence --output output/data/fig_smooth_convergence.dat --tex output/data/fig_smooth_convergence.tex
//   fig_smooth_convergence --coarsest 50 --refinements 3 --threads 1 --output s.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the list of runs, longest first; (4) the runs, in
// parallel; (5) the data blocks; (6) the orders beside the predictions, the tables and the values the
// report quotes; (7) commit.
//
// Data file: block 2 (3 (2 b + s) + m) + c is benchmark b ∈ (smooth-impact, grazing), scheme s ∈ (cn, be),
// mass m ∈ (mod1, mod2, mod3), ratio c ∈ (Δt = h, Δt = h/2); columns N h dt and the eight errors.
#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "refinement.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"
#include "options.hpp"
#include "sweep.hpp"
#include "parallel.hpp"
#include "report_values.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "table.hpp"

namespace cli = mrm::cli;

namespace {

const std::array<const char*, 2> benchmarks{"smooth-impact", "grazing"};
const std::array<const char*, 2> benchmark_keys{"s1", "s2"};
const std::array<const char*, 2> benchmark_labels{"S1", "S2"};
const std::array<mrm::Scheme, 2> schemes{mrm::Scheme::crank_nicolson, mrm::Scheme::backward_euler};
const std::array<double, 2> courants{1.0, 0.5};
const std::array<const char*, 2> courant_keys{"dth", "dth2"};
const std::array<const char*, 2> courant_labels{"$\\Delta t = h$", "$\\Delta t = h/2$"};
constexpr double agreement = 0.25;

enum Measure { u0_L2, lambda_L2, u_LinfL2, u_LinfH1, v_LinfL2, u_L2L2, u_L2H1, v_L2L2 };

// The predicted order of measure k (derivation above); b: 0 = S1, 1 = S2; s: 0 = CN, 1 = BE; m: 0..2 = Mod 1..3.
double predicted_order(std::size_t b, std::size_t s, std::size_t m, std::size_t k) {
  const bool cn = s == 0, mod3 = m == 2, mod1 = m == 0;
  if (b == 1) {  // S2: smooth
    if (!cn) return 1.0;
    if (mod3) return k == u_LinfH1 || k == u_L2H1 ? 1.5 : 2.0;
    return mod1 && k == lambda_L2 ? 2.0 : 1.0;
  }
  switch (k) {  // S1: the impact's jump
    case lambda_L2:
      return 0.5;
    case u0_L2:
      return cn && mod3 ? 2.0 : 1.0;
    case u_LinfL2:
    case u_L2L2:
      return cn ? 1.0 : 0.75;
    default:
      return cn ? 1.0 / 3.0 : 0.25;  // u in H¹, u_t in L²
  }
}

std::string fraction(double order) {
  if (std::abs(order - 1.0 / 3.0) < 1e-12) return "1/3";
  if (std::abs(order - 0.25) < 1e-12) return "1/4";
  if (std::abs(order - 0.5) < 1e-12) return "1/2";
  if (std::abs(order - 0.75) < 1e-12) return "3/4";
  if (std::abs(order - 1.5) < 1e-12) return "3/2";
  return mrm::tex_number(order, 1);
}

struct Run {
  std::size_t benchmark, scheme, mass, courant, level;
  mrm::Index elements;
  double cost;  // steps × unknowns, to start the longest runs first
  std::array<double, 8> errors{};
};

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_smooth_convergence", [&] {
    // 1. Options.
    long coarsest = 200, refinements = 5, threads = 2;
    mrm::repro::FigureProgram program(
        "fig_smooth_convergence",
        "Writes every relative error of mathematics.md sec. 5 against h on the smooth benchmarks S1 "
        "and S2 (sec. 11, against the characteristic solution of sec. 10), with dt = h and dt = h/2, "
        "for cn and be with mod1, mod2, mod3, and the observed orders beside the predicted ones.",
        {"fig_smooth_convergence --output output/data/fig_smooth_convergence.dat --tex "
         "output/data/fig_smooth_convergence.tex",
         "fig_smooth_convergence --coarsest 50 --refinements 3 --threads 1 --output s.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0", "number of elements of the coarsest mesh (>= 2)", &coarsest,
                               cli::at_least(2));
    program.parser.add_integer("--refinements", "-k", "K", "number of meshes N0, 2 N0, ..., 2^(K-1) N0, in [2, 12]",
                               &refinements, cli::in_closed_range(2, 12));
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the tables and values the report quotes")) return 0;
    if (!(static_cast<double>(coarsest) * std::ldexp(1.0, static_cast<int>(refinements - 1)) <= 1e5))
      throw cli::UsageError("--coarsest: the finest mesh N0 2^(K-1) must be at most 1e5 elements");

    // 2. Outputs.
    program.open();
    const auto& masses = mrm::repro::mass_names();
    const double final_time = mrm::smooth_benchmark(mrm::SmoothBenchmark::grazing).final_time;

    // 3. The runs, longest first.
    const mrm::repro::MeshRefinement meshes(static_cast<mrm::Index>(coarsest), static_cast<std::size_t>(refinements));
    std::vector<Run> runs;
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t s = 0; s < schemes.size(); ++s)
        for (std::size_t m = 0; m < masses.size(); ++m)
          for (std::size_t c = 0; c < courants.size(); ++c)
            for (std::size_t l = 0; l < meshes.levels(); ++l) {
              const mrm::Index n = meshes.elements(l);
              const double h = meshes.mesh_sizes()[l];
              runs.push_back(
                  {b, s, m, c, l, n, static_cast<double>(mrm::steps_to_reach(final_time, courants[c] * h)) * n, {}});
            }

    // 4. The runs (repro/configurations: the scheme against the characteristic solution, tabulated on the
    // lattice of h and Δt) through the sweep layer (repro/sweep.hpp): batched in vector lanes on `threads`
    // workers, the characteristic solution of each benchmark, mesh and Δt computed once for the three
    // masses; each run's measures are its own, bit for bit, in the order of `runs`.
    const auto start = std::chrono::steady_clock::now();
    std::vector<mrm::repro::Configuration> configurations;
    for (const Run& r : runs) {
      configurations.push_back(mrm::repro::paper_configuration(schemes[r.scheme], "algebraic", masses[r.mass],
                                                               r.elements, courants[r.courant], final_time));
      configurations.back().benchmark = benchmarks[r.benchmark];
    }
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::require_batched_memory("--coarsest", configurations, settings);  // before any run
    const std::vector<mrm::repro::Measures> measures = mrm::repro::run_batched(configurations, settings);
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].errors = mrm::ErrorAccumulator::values(measures[k].errors);
    std::cerr << "fig_smooth_convergence: " << runs.size() << " runs in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";

    // 5. The data blocks, in the fixed order of `runs` (benchmark, scheme, mass, ratio, mesh).
    std::ostream& out = program.header("relative errors against h on the smooth benchmarks (mathematics.md sec. 11)");
    out << "# final_time = " << cli::format_real(final_time) << '\n'
        << "# blocks: 2 (3 (2 b + s) + m) + c: benchmark b in (smooth-impact, grazing), scheme s in ("
        << mrm::to_string(schemes[0]) << ", " << mrm::to_string(schemes[1])
        << "), "
           "mass m in (mod1, mod2, mod3), c in (dt = h, dt = h/2)\n";
    const std::size_t levels = meshes.levels();
    auto at = [&](std::size_t b, std::size_t s, std::size_t m, std::size_t c, std::size_t l) -> const Run& {
      return runs[(((b * schemes.size() + s) * masses.size() + m) * courants.size() + c) * levels + l];
    };
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t s = 0; s < schemes.size(); ++s)
        for (std::size_t m = 0; m < masses.size(); ++m)
          for (std::size_t c = 0; c < courants.size(); ++c) {
            const std::size_t block = ((b * schemes.size() + s) * masses.size() + m) * courants.size() + c;
            out << (block ? "\n\n" : "") << "# block " << block << ": benchmark = " << benchmarks[b]
                << ", scheme = " << mrm::to_string(schemes[s]) << ", mass = " << masses[m]
                << ", dt/h = " << cli::format_real(courants[c]) << '\n';
            std::vector<mrm::repro::ErrorRow> rows;
            for (std::size_t l = 0; l < levels; ++l)
              rows.push_back({at(b, s, m, c, l).elements, at(b, s, m, c, l).errors});
            mrm::repro::write_error_rows(out, 1.0, courants[c], rows);
          }

    // 6. Orders (fit over all meshes) beside the predictions, the tables, and the values of the prose.
    std::ostream& defs = program.values();
    const mrm::Index finest = meshes.finest();
    mrm::tex_define(defs, "smooth:Nmin", std::to_string(coarsest));
    mrm::tex_define(defs, "smooth:Nmax", std::to_string(finest));
    mrm::tex_define(defs, "smooth:meshes", std::to_string(levels));
    mrm::tex_define(defs, "smooth:T", cli::format_real(final_time));
    mrm::tex_define(defs, "smooth:tolerance", mrm::tex_number(agreement, 2));
    // The steps of the study, for the prose ("\mrm{smooth:dt:dth2}" prints "$\Delta t = h/2$").
    for (std::size_t c = 0; c < courants.size(); ++c)
      mrm::tex_define(defs, std::string("smooth:dt:") + courant_keys[c], courant_labels[c]);
    std::vector<std::string> headers{"data", "scheme", "mass", "$\\Delta t$"};
    for (const mrm::repro::Label& label : mrm::repro::measure_labels())
      headers.push_back("\\rotatebox{70}{" + label.latex + "}");
    mrm::repro::Table orders_table(headers);
    long agreeing = 0, cases = 0;
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      for (std::size_t s = 0; s < schemes.size(); ++s)
        for (std::size_t m = 0; m < masses.size(); ++m)
          for (std::size_t c = 0; c < courants.size(); ++c) {
            std::vector<std::string> row{s == 0 && m == 0 && c == 0 ? benchmark_labels[b] : "",
                                         m == 0 && c == 0 ? mrm::repro::scheme_label(schemes[s]).latex : "",
                                         c == 0 ? mrm::repro::mass_label(masses[m]).abbreviation : "",
                                         courant_labels[c]};
            for (std::size_t k = 0; k < 8; ++k) {
              std::vector<double> errors(levels);
              for (std::size_t l = 0; l < levels; ++l) errors[l] = at(b, s, m, c, l).errors[k];
              const std::string key = std::string(benchmark_keys[b]) + ":" + mrm::to_string(schemes[s]) + ":" +
                                      masses[m] + ":" + courant_keys[c] + ":" + mrm::ErrorAccumulator::names[k];
              const double predicted = predicted_order(b, s, m, k);
              mrm::tex_define(defs, "smooth:predicted:" + key, fraction(predicted));
              if (!std::all_of(errors.begin(), errors.end(), [](double e) { return e > 0 && std::isfinite(e); }))
                throw std::runtime_error("the errors of " + key + " cannot be fitted (a zero or non-finite error)");
              const mrm::OrderFit fit = meshes.fit(errors);
              const bool agrees = std::abs(fit.order - predicted) <= agreement;
              agreeing += agrees;
              ++cases;
              const std::string fitted = mrm::tex_number(fit.order, 2);
              row.push_back((agrees ? fitted : "\\textit{" + fitted + "}") + " {\\scriptsize(" + fraction(predicted) +
                            ")}");
              mrm::tex_define(defs, "smooth:order:" + key, fitted);
              mrm::tex_define(defs, "smooth:local:" + key, mrm::tex_number(meshes.finest_local_order(errors), 2));
              mrm::tex_define(defs, "smooth:stderr:" + key, mrm::tex_number(fit.order_std_error, 1));
              mrm::tex_define(defs, "smooth:err:" + key, mrm::tex_number(errors.back(), 2));
            }
            orders_table.add_row(row);
          }
      if (b + 1 < benchmarks.size()) orders_table.add_rule();
    }
    mrm::tex_define(defs, "smooth:agreeing", std::to_string(agreeing));
    mrm::tex_define(defs, "smooth:cases", std::to_string(cases));
    // In two halves at the text size (measures 1-4, then 5-8 of mathematics.md §5), not shrunk.
    for (std::size_t part = 0; part < 2; ++part) {
      std::vector<std::size_t> keep{0, 1, 2, 3};
      for (std::size_t k = 4 * part; k < 4 * part + 4; ++k) keep.push_back(4 + k);
      defs << "\\mrmdef{smooth:table:orders" << (part == 0 ? ":a" : ":b") << "}{"
           << mrm::repro::latex_tabular(orders_table.columns_subset(keep), "llll" + std::string(4, 'r')) << "}\n";
    }

    // 7. Commit.
    program.commit();
    return 0;
  });
}
