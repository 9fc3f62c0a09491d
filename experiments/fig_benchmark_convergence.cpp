// fig_benchmark_convergence: convergence on the field's benchmarks, and the period law on graded meshes.
//
// What it computes. (1) On the field's benchmarks of lib/exact/impact_solution.hpp (bouncing, impacting,
// gravity-paper, layered, and two-bars: two meshes coupled by one contact multiplier, lib/time/two_bodies.hpp,
// N elements on each bar, each measure the larger of the two bars'), the eight relative errors of
// mathematics.md §5 against the chain's exact solution (ImpactReference, TwoBodyReference), for
// Crank–Nicolson with Mod 1, 2 and 3, on the meshes N = N₀, 2N₀, …, 2^{K−1}N₀ with Δt = h/(2c) (h and
// Δt refined together; c the wave speed at the contact end), each benchmark to its default horizon,
// through repro::run_configuration (the harness's one path: the benchmark's load, gap, material and
// free end, the scaling to the unit problem and back); the observed order of each measure is the
// least-squares slope of log error against log h (mrm::fit_order). (2) Δt alone: Crank–Nicolson with
// Mod 3 on the finest mesh with Δt = 2h/c, h/c, h/(2c). (3) The exact contact windows of each benchmark
// and those of the finest Mod 3 run. (4) The period law on graded meshes h_k = h₀ r^k: the drift per
// period of Mod 1, Mod 2 and equal shares over the N − 1 nodes (spread:N−1), each minus Mod 3's in the
// same set-up, measured on the paper's benchmark (lib/measures/phase.hpp: measure_benchmark_phase, the
// doctest's machinery) against the first-order prediction ΔP = Σ δmᵢ κ(xᵢ) (first_order_period_change).
//
// Predictions (conjectures: heuristic, from the regularity of the exact solutions and Crank–Nicolson's
// dispersion; repro/field_conjecture.cpp, derived in lib/studies/smeared_orders.cpp):
//   - bouncing, impacting, layered, two-bars: an impact with non-zero velocity (two-bars: at t = 0, the
//     bars touching with their velocities), then a release triggered by a returning front that
//     Crank–Nicolson smears over W ≈ (h²t)^{1/3}: the release is off by O(h^{2/3}), so u(0,·), u in
//     L∞(L²) and L²(L²) are order 2/3; λ jumps at the release and u_t, u_x jump across the
//     characteristics: order 1/3 for λ in L² and for the energy-type measures (u in H¹, u_t in L²).
//   - gravity-paper: a persistent contact; u_x and u_t have kinks on the characteristics from the ends
//     at t = 0: order 1 for λ and the energy-type measures, 5/3 for u in L² (1 with Mod 2, whose
//     uniformly heavier bar is off in phase by O(h)); u(0,·) ≡ 0 exactly and in every run (no measure).
//   These replace an earlier conjecture (1 for u and ½ for λ with a release, 2 for u in L²) that
//   field_asymptotics' runs up to N = 2560 refuted; these meshes (up to 320) are pre-asymptotic for
//   Mod 3, whose local orders there still rise.
// A fitted order "agrees" within ±0.25; disagreements are printed in italics, not hidden.
//   - graded meshes: the tolerance is the doctest's (lib/fem/period_law.cpp), the measurement's resolution
//     measured on the uniform mesh, 0.15 h₀.
//
// Sample runs:
//   fig_benchmark_convergence --output output/data/fig_benchmark_convergence.dat --tex output/data/fig_benchmark_convergence.tex
//   fig_benchmark_convergence --coarsest 20 --refinements 3 --threads 1 --output b.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the runs, in parallel, longest first; (4) data
// blocks; (5) orders, windows, graded table and the values the report quotes; (6) commit.
//
// Data file: block 3b + m (b the benchmark in the order above, m ∈ mod1, mod2, mod3): columns N h dt and
// the eight errors, h and dt in units of L and L/c (two-bars: h = ℓ/N of one bar, in units of ℓ); block
// 15: Δt alone (Mod 3, finest N; its Δt = h/(2c) row is block 3b + 2's finest run); block 16: the
// graded table (r, h_max/h0, member, predicted, measured, |difference|, all per period in units of h₀).
#include <algorithm>
#include <array>
#include <chrono>
#include <cstdio>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "claims.hpp"
#include "configurations.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"
#include "figure_program.hpp"
#include "refinement.hpp"
#include "exact/impact_solution.hpp"
#include "field_conjecture.hpp"
#include "labels.hpp"
#include "fem/mass_redistribution.hpp"
#include "mass_spec.hpp"
#include "options.hpp"
#include "measures/phase.hpp"
#include "report_values.hpp"
#include "sweep.hpp"
#include "table.hpp"
#include "time/two_bodies.hpp"

namespace cli = mrm::cli;

namespace {

const std::array<const char*, 5> benchmarks{"bouncing", "impacting", "gravity-paper", "layered", "two-bars"};
const std::array<const char*, 3> masses{"mod1", "mod2", "mod3"};
const std::array<double, 3> time_courants{2.0, 1.0, 0.5};  // Δt alone: Δt = C h/c on the finest mesh
const std::array<double, 4> ratios{1.0, 1.0025, 1.005, 1.01};
constexpr double courant = 0.5, agreement = 0.25, graded_tolerance = 0.15, graded_periods = 20;
constexpr long graded_elements = 200;

std::string fraction(double order) {
  if (std::abs(order - 1.0 / 3.0) < 1e-12) return "1/3";
  if (std::abs(order - 0.5) < 1e-12) return "1/2";
  if (std::abs(order - 2.0 / 3.0) < 1e-12) return "2/3";
  if (std::abs(order - 5.0 / 3.0) < 1e-12) return "5/3";
  return mrm::tex_number(order, 1);
}

std::string windows_text(const std::vector<mrm::ContactInterval>& windows, int digits) {
  std::string text;
  for (const mrm::ContactInterval& w : windows)
    text += (text.empty() ? "" : " ") +
            ("$[" + mrm::tex_number(w.start, digits) + ", " + mrm::tex_number(w.end, digits) + (w.open ? ")$" : "]$"));
  return text.empty() ? "none" : text;
}

mrm::repro::Configuration benchmark_configuration(const std::string& benchmark, const std::string& mass,
                                                  mrm::Index elements, double c) {
  mrm::repro::Configuration configuration =
      mrm::repro::paper_configuration(mrm::Scheme::crank_nicolson, "algebraic", mass, elements, c, 1.0);
  configuration.benchmark = benchmark;
  configuration.final_time = mrm::impact_benchmark(benchmark).final_time;
  return configuration;
}

// One run of the graded meshes' period law: the ratio r of h_k = h₀ r^k, the mass, its measured phase.
struct GradedRun {
  double ratio;
  std::string mass;
  mrm::MeasuredPhase phase{};
};

// The table of the benchmarks' data and the check of their exact windows against closed forms.
void write_data_table(std::ostream& defs) {
  // The data of each benchmark, from the registry (lib/exact/impact_solution.cpp), and its exact windows
  // against an independent closed form where one is derived (the doctests of impact_solution.cpp):
  // bouncing, the free fall to the floor √(2g₀/g) = 1 then contacts of 2L/c every 8L/c = [1 + 8k/3,
  // 5/3 + 8k/3]; impacting, [g₀/v, g₀/v + 2L/c]; gravity-paper, held over [0, T]; two-bars, [0, 2L/c];
  // layered, [g₀/v, g₀/v + 2ℓ₁/c₁ + 2ℓ₂/c₂], released by the tension wave from its free end (the derivation
  // and the stress on the window in the doctest of lib/exact/impact_closed_forms.cpp).
  mrm::repro::Table data_table(
      {"benchmark", "segments $(\\ell, E, \\rho)$", "load $f$", "far end", "gap $g_0$", "$v^0$", "$T$", "source"});
  for (const char* key : benchmarks) {
    const mrm::ImpactBenchmark& bench = mrm::impact_benchmark(key);
    std::string segments, loads;
    for (const mrm::BarSegment& segment : bench.configuration.segments) {
      segments += (segments.empty() ? "" : ", ") +
                  ("$(" + mrm::tex_number(segment.length, 3) + ", " + mrm::tex_number(segment.modulus, 4) + ", " +
                   mrm::tex_number(segment.density, 3) + ")$");
      loads += (loads.empty() ? "" : ", ") +
               (segment.load.empty() ? std::string("0") : "$" + mrm::tex_number(segment.load.front(), 3) + "$");
    }
    // Two bodies: the gap between them, and the velocity of each (the left bar's, then the right one's).
    const bool two = mrm::is_two_body_chain(bench.configuration);
    const double gap = two ? bench.configuration.junctions.front().gap : bench.configuration.obstacle_gap;
    const std::string velocity = two ? mrm::tex_number(bench.data.velocity(0.0), 3) + ", " +
                                           mrm::tex_number(bench.data.velocity(bench.configuration.length()), 3)
                                     : mrm::tex_number(bench.data.velocity(0.0), 3);
    data_table.add_row(
        {key, segments, loads, bench.configuration.far_end == mrm::FarEnd::free ? "free" : "clamped",
         "$" + mrm::tex_number(gap, 3) + "$", "$" + velocity + "$",
         "$" + mrm::tex_number(bench.final_time, 3) + "$" + (bench.time_unit.empty() ? "" : "~" + bench.time_unit),
         mrm::claims::latex_escape(bench.source)});  // "Code_Aster", "01_bouncingBar": text, not math
    const std::vector<mrm::ContactInterval> exact =
        mrm::exact_contact_windows(bench.configuration, bench.data, bench.final_time);
    std::vector<mrm::ContactInterval> closed;
    const mrm::BarSegment& bar = bench.configuration.segments.front();
    const double c = std::sqrt(bar.modulus / bar.density), length = bench.configuration.length();
    const std::string id = key;
    if (id == "bouncing")
      for (int k = 0; k < 3; ++k) closed.push_back({1 + 8.0 * k / 3, 5.0 / 3 + 8.0 * k / 3, false});
    if (id == "impacting") {
      const double t1 = bench.configuration.obstacle_gap / -bench.data.velocity(0.0);
      closed.push_back({t1, t1 + 2 * length / c, false});
    }
    if (id == "gravity-paper") closed.push_back({0.0, bench.final_time, true});
    if (id == "two-bars") closed.push_back({0.0, 2 * bench.configuration.segments.front().length / c, false});
    if (id == "layered") {
      const double t1 = bench.configuration.obstacle_gap / -bench.data.velocity(0.0);
      double transits = 0;  // ℓ₁/c₁ + ℓ₂/c₂
      for (const mrm::BarSegment& segment : bench.configuration.segments)
        transits += segment.length / std::sqrt(segment.modulus / segment.density);
      closed.push_back({t1, t1 + 2 * transits, false});
    }
    if (closed.empty()) throw std::logic_error(id + ": no closed form of its contact windows");
    double difference = exact.size() == closed.size() ? 0.0 : HUGE_VAL;
    for (std::size_t w = 0; w < std::min(exact.size(), closed.size()); ++w)
      difference =
          std::max({difference, std::abs(exact[w].start - closed[w].start), std::abs(exact[w].end - closed[w].end)});
    if (!std::isfinite(difference))
      throw std::runtime_error(id + ": the exact solution and its comparison have different numbers of windows");
    mrm::tex_define(defs, "benchconv:checkdiff:" + id, mrm::tex_number(difference, 2));
    std::cout << id << ": exact windows against the closed form: max |difference| = " << cli::format_real(difference)
              << '\n';
  }
  defs << "\\mrmdef{benchconv:table:data}{" << mrm::repro::latex_tabular(data_table, "llllrrrp{3.2cm}") << "}\n";
}

// The graded meshes' block of the data file and their table: each member's drift minus Mod 3's.
void write_graded(std::ostream& out, std::ostream& defs, const std::vector<GradedRun>& graded) {
  mrm::repro::Table graded_table(
      {"$r$", "$h_{\\max}/h_0$", "mass", "predicted $\\Delta P/h_0$", "measured $/h_0$", "$|$difference$|/h_0$"});
  double worst = 0;
  std::cout << "graded meshes (N = " << graded_elements << ", cn, dt = h0/2, " << graded_periods
            << " periods): drift per period minus Mod 3's, in units of h0\n"
            << "r h_max/h0 member predicted measured |difference|\n";
  for (std::size_t i = 0; i < graded.size(); ++i) {
    const GradedRun& g = graded[i];
    if (g.mass == "mod3") continue;
    const GradedRun& reference = graded[i - (i % 4)];
    const mrm::UniformMesh mesh = mrm::graded_mesh(1.0, graded_elements, g.ratio);
    const double h0 = mesh.h(0);
    const double predicted =
        mrm::first_order_period_change(mesh, mrm::repro::mass_redistribution_from_spec(g.mass, mesh));
    const double measured = g.phase.drift_per_period - reference.phase.drift_per_period;
    const double difference = std::abs(measured - predicted);
    worst = std::max(worst, difference / h0);
    out << cli::format_real(g.ratio) << ' ' << cli::format_real(mesh.h(graded_elements - 1) / h0) << ' ' << g.mass
        << ' ' << cli::format_real(predicted / h0) << ' ' << cli::format_real(measured / h0) << ' '
        << cli::format_real(difference / h0) << '\n';
    char line[160];
    std::snprintf(line, sizeof line, "%-7g %-9.3f %-11s %+9.4f %+9.4f %8.4f", g.ratio, mesh.h(graded_elements - 1) / h0,
                  g.mass.c_str(), predicted / h0, measured / h0, difference / h0);
    std::cout << line << '\n';
    graded_table.add_row({cli::format_real(g.ratio), mrm::tex_number(mesh.h(graded_elements - 1) / h0, 3),
                          mrm::repro::mass_label(g.mass).abbreviation, mrm::tex_number(predicted / h0, 3),
                          mrm::tex_number(measured / h0, 3), mrm::tex_number(difference / h0, 2)});
  }
  mrm::tex_define(defs, "benchconv:graded:N", std::to_string(graded_elements));
  mrm::tex_define(defs, "benchconv:graded:periods", mrm::tex_number(graded_periods, 2));
  mrm::tex_define(defs, "benchconv:graded:worst", mrm::tex_number(worst, 2));
  mrm::tex_define(defs, "benchconv:graded:tolerance", mrm::tex_number(graded_tolerance, 2));
  mrm::tex_define(defs, "benchconv:graded:verdict", worst <= graded_tolerance ? "within" : "not within");
  defs << "\\mrmdef{benchconv:table:graded}{" << mrm::repro::latex_tabular(graded_table, "rrlrrr") << "}\n";
}

// The measures of the h study's runs: benchmark b, mass m, mesh level l.
struct Study {
  const std::vector<mrm::repro::Measures>& measures;
  std::size_t levels;
  std::size_t time_study;  ///< the index of the Δt study's first run
  const mrm::repro::Measures& at(std::size_t b, std::size_t m, std::size_t l) const {
    return measures[(b * masses.size() + m) * levels + l];
  }
  // The Δt study's run c of benchmark b (the last ratio is the h study's finest Mod 3 run).
  const mrm::repro::Measures& time_run(std::size_t b, std::size_t c) const {
    return c + 1 < time_courants.size() ? measures[time_study + b * (time_courants.size() - 1) + c]
                                        : at(b, 2, levels - 1);
  }
};

// The data blocks of the h study (one per benchmark and mass) and the block of Δt alone.
void write_error_blocks(std::ostream& out, const Study& study, const mrm::repro::MeshRefinement& meshes) {
  const std::size_t time_block = benchmarks.size() * masses.size();
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t m = 0; m < masses.size(); ++m) {
      out << (b + m ? "\n\n" : "") << "# block " << b * masses.size() + m << ": benchmark = " << benchmarks[b]
          << ", mass = " << masses[m] << ", scheme = cn\n";
      std::vector<mrm::repro::ErrorRow> rows;
      for (std::size_t l = 0; l < study.levels; ++l)
        rows.push_back({meshes.elements(l), mrm::ErrorAccumulator::values(study.at(b, m, l).errors)});
      mrm::repro::write_error_rows(out, 1.0, courant, rows);
    }
  out << "\n\n# block " << time_block << ": dt alone, cn, mod3, N = " << meshes.finest()
      << "\n# columns: benchmark dt_over_h_over_c";
  for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
  out << '\n';
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t c = 0; c < time_courants.size(); ++c) {
      out << benchmarks[b] << ' ' << cli::format_real(time_courants[c]);
      for (const double e : mrm::ErrorAccumulator::values(study.time_run(b, c).errors))
        out << ' ' << cli::format_real(e);
      out << '\n';
    }
}

// The row of benchmark b in the table of orders in Δt alone: the order from the three steps (fit), Mod 3
// on the finest mesh.
std::vector<std::string> time_orders_row(const Study& study, std::size_t b) {
  std::vector<std::string> time_row{benchmarks[b], "Mod 3"};
  std::vector<double> dts(time_courants.begin(), time_courants.end());
  for (std::size_t k = 0; k < 8; ++k) {
    std::vector<double> errors;
    for (std::size_t c = 0; c < time_courants.size(); ++c)
      errors.push_back(mrm::ErrorAccumulator::values(study.time_run(b, c).errors)[k]);
    if (std::all_of(errors.begin(), errors.end(), [](double e) { return e == 0; })) {
      time_row.push_back("n/a");
      continue;
    }
    time_row.push_back(mrm::tex_number(mrm::fit_order(dts, errors).order, 2));
  }
  return time_row;
}

// The contact windows of benchmark `key`: exact (in the benchmark's units) and the finest Mod 3 run's
// (N = finest), on standard output and as values of the prose, with the shift of the first window's ends.
void write_windows(std::ostream& defs, const std::string& key, const std::vector<mrm::ContactInterval>& exact,
                   const mrm::repro::Measures& fine, mrm::Index finest) {
  mrm::tex_define(defs, "benchconv:windows:exact:" + key, windows_text(exact, 6));
  mrm::tex_define(defs, "benchconv:windows:measured:" + key, windows_text(fine.contact_windows, 6));
  std::cout << key << " exact_contact_windows =";
  for (const auto& w : exact) std::cout << " [" << cli::format_real(w.start) << ", " << cli::format_real(w.end) << "]";
  std::cout << "\n" << key << " measured_contact_windows (cn, mod3, N = " << finest << ") =";
  for (const auto& w : fine.contact_windows)
    std::cout << " [" << cli::format_real(w.start) << ", " << cli::format_real(w.end) << "]";
  std::cout << '\n';
  if (!exact.empty() && !fine.contact_windows.empty()) {
    mrm::tex_define(defs, "benchconv:firststart:" + key,
                    mrm::tex_number(fine.contact_windows.front().start - exact.front().start, 2));
    mrm::tex_define(defs, "benchconv:firstend:" + key,
                    mrm::tex_number(fine.contact_windows.front().end - exact.front().end, 2));
  }
}

// The row of benchmark b and mass m in the table of orders: each measure's fitted order over every mesh,
// the local order between the two finest and the conjectured order, with their values; counts the
// measures whose fit agrees with the conjecture.
std::vector<std::string> mass_orders_row(std::ostream& defs, const Study& study,
                                         const mrm::repro::MeshRefinement& meshes, std::size_t b, std::size_t m,
                                         long& agreeing, long& cases) {
  const std::string key = benchmarks[b];
  const std::size_t levels = study.levels;
  std::vector<std::string> row{m == 0 ? key : "", mrm::repro::mass_label(masses[m]).abbreviation};
  for (std::size_t k = 0; k < 8; ++k) {
    const double predicted = mrm::repro::field_conjectured_order(key, masses[m], k);
    std::vector<double> errors(levels);
    for (std::size_t l = 0; l < levels; ++l) errors[l] = mrm::ErrorAccumulator::values(study.at(b, m, l).errors)[k];
    if (predicted == 0) {
      if (!std::all_of(errors.begin(), errors.end(), [](double e) { return e == 0; }))
        throw std::runtime_error(key + ": u(0,.) is not 0 in a run (its exact value is 0)");
      row.push_back("n/a");
      continue;
    }
    if (!std::all_of(errors.begin(), errors.end(), [](double e) { return e > 0 && std::isfinite(e); }))
      throw std::runtime_error("the errors of " + key + " " + masses[m] + " cannot be fitted");
    // The fit over all meshes and the local order between the two finest (a fit that disagrees
    // with the local order says the errors are not yet in their asymptotic regime).
    const mrm::OrderFit fit = meshes.fit(errors);
    const double local = meshes.finest_local_order(errors);
    const bool agrees = std::abs(fit.order - predicted) <= agreement;
    agreeing += agrees;
    ++cases;
    const std::string fitted = mrm::tex_number(fit.order, 2);
    row.push_back((agrees ? fitted : "\\textit{" + fitted + "}") + " {\\scriptsize[" + mrm::tex_number(local, 2) +
                  "] (" + fraction(predicted) + ")}");
    mrm::tex_define(defs, "benchconv:local:" + key + ":" + masses[m] + ":" + mrm::ErrorAccumulator::names[k],
                    mrm::tex_number(local, 2));
    const std::string name = key + ":" + masses[m] + ":" + mrm::ErrorAccumulator::names[k];
    mrm::tex_define(defs, "benchconv:order:" + name, fitted);
    mrm::tex_define(defs, "benchconv:err:" + name, mrm::tex_number(errors.back(), 2));
    std::cout << key << ' ' << masses[m] << ' ' << mrm::ErrorAccumulator::names[k] << " order "
              << cli::format_real(std::round(fit.order * 100) / 100) << " local "
              << cli::format_real(std::round(local * 100) / 100) << " (conjecture " << fraction(predicted) << ")"
              << (agrees ? "" : " DISAGREES") << '\n';
  }
  return row;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_benchmark_convergence", [&] {
    // 1. Options.
    long coarsest = 40, refinements = 4, threads = 2;
    mrm::repro::FigureProgram program(
        "fig_benchmark_convergence",
        "Writes the relative errors against h on the field's benchmarks (bouncing, impacting, gravity-paper, "
        "layered, two-bars) for cn with mod1, mod2, mod3 against their exact solutions, the observed orders beside the "
        "conjectured ones, the exact and measured contact windows, and the period law on graded meshes.",
        {"fig_benchmark_convergence --output output/data/fig_benchmark_convergence.dat --tex "
         "output/data/fig_benchmark_convergence.tex",
         "fig_benchmark_convergence --coarsest 20 --refinements 3 --threads 1 --output b.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0",
                               "number of elements of the coarsest mesh, a multiple of 5 (the layered bar's "
                               "interface is a node) in [5, 1000]",
                               &coarsest, cli::in_closed_range(5, 1000));
    program.parser.add_integer("--refinements", "-k", "K", "number of meshes N0, 2 N0, ..., 2^(K-1) N0, in [2, 6]",
                               &refinements, cli::in_closed_range(2, 6));
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the tables and values the report quotes")) return 0;
    // Every mesh is a multiple of the coarsest, so the library's refusal of an N that puts no node on a
    // material interface (chain_mesh, naming the allowed N) is asked of the coarsest, before any work.
    mrm::repro::as_usage_error({{"elements", "--coarsest"}}, [&] {
      for (const char* b : benchmarks)
        mrm::repro::configuration_mesh(benchmark_configuration(b, "mod1", static_cast<mrm::Index>(coarsest), courant));
    });

    // 2. Outputs.
    program.open();
    const mrm::repro::MeshRefinement meshes(static_cast<mrm::Index>(coarsest), static_cast<std::size_t>(refinements));
    const std::size_t levels = meshes.levels();
    const mrm::Index finest = meshes.finest();

    // 3. The runs: the convergence study, Δt alone, and the graded meshes; longest first.
    std::vector<mrm::repro::Configuration> configurations;
    for (const char* b : benchmarks)
      for (const char* m : masses)
        for (std::size_t l = 0; l < levels; ++l)
          configurations.push_back(benchmark_configuration(b, m, meshes.elements(l), courant));
    const std::size_t time_study = configurations.size();
    for (const char* b : benchmarks)
      for (std::size_t c = 0; c + 1 < time_courants.size(); ++c)
        configurations.push_back(benchmark_configuration(b, "mod3", finest, time_courants[c]));
    std::vector<GradedRun> graded;
    for (const double r : ratios)
      for (const std::string m : {"mod3", "mod1", "mod2", "spread:199"}) graded.push_back({r, m});
    const std::size_t total = configurations.size() + graded.size();
    // Through the sweep layer (repro/sweep.hpp, run_batched), keyed by group: the three masses of one
    // benchmark and mesh (the h study's runs, Δt = h/(2c)) make one batch, in vector lanes where the
    // batched step takes them (a benchmark's steady load included: batched_step.cpp), and ask the same
    // exact solution the same questions at the same instants: it is made once for the sweep
    // (ReferenceCache) and evaluated once per instant for the batch (ErrorAccumulator::add_lanes). The Δt
    // study's two runs of a benchmark make one batch (2h/c and h/c, each at its own rate). Two-bars' runs
    // are two bodies, run whole; the graded runs are the sweep's own tasks (they are not configurations).
    // Each run's measures are run_configuration's, bit for bit, on any thread count and vector width.
    std::vector<mrm::repro::BatchKey> keys;
    for (std::size_t k = 0; k < configurations.size(); ++k) {
      const int benchmark = static_cast<int>(k < time_study ? k / (levels * masses.size())
                                                            : (k - time_study) / (time_courants.size() - 1));
      keys.push_back({configurations[k].elements, k < time_study ? benchmark : 100 + benchmark});
    }
    std::vector<mrm::repro::SweepTask> tasks;
    for (GradedRun& g : graded) {
      const mrm::UniformMesh mesh = mrm::graded_mesh(1.0, graded_elements, g.ratio);
      tasks.push_back({graded_elements * 3 * graded_periods / (0.5 * mesh.h(0)), [&g] {
                         const mrm::UniformMesh m = mrm::graded_mesh(1.0, graded_elements, g.ratio);
                         g.phase = mrm::measure_benchmark_phase(m, mrm::repro::mass_redistribution_from_spec(g.mass, m),
                                                                0.5, graded_periods);
                       }});
    }
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::require_batched_memory("--coarsest", configurations, settings);  // before any run
    const auto start = std::chrono::steady_clock::now();
    const std::vector<mrm::repro::Measures> measures =
        mrm::repro::run_batched(configurations, settings, {}, keys, true, tasks);
    std::cerr << "fig_benchmark_convergence: " << total << " runs in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";

    // 4. The data blocks.
    std::ostream& out = program.header("relative errors against h on the field's benchmarks; graded period law");
    const std::size_t time_block = benchmarks.size() * masses.size(), graded_block = time_block + 1;
    out << "# blocks: 3 b + m: benchmark b in (bouncing, impacting, gravity-paper, layered, two-bars), mass m in "
           "(mod1, mod2, mod3), scheme cn, dt = h/(2c); "
        << time_block << ": dt alone (mod3, N = " << finest << "); " << graded_block << ": graded meshes\n";
    const Study study{measures, levels, time_study};
    write_error_blocks(out, study, meshes);
    out << "\n\n# block " << graded_block << ": graded meshes h_k = h0 r^k, N = " << graded_elements
        << ", cn, dt = h0/2, " << graded_periods << " periods; drifts per period in units of h0, each minus Mod 3's\n"
        << "# columns: r h_max_over_h0 member predicted measured difference\n";

    // 5. Orders, windows, the graded table and the values of the prose.
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "benchconv:Nmin", std::to_string(coarsest));
    mrm::tex_define(defs, "benchconv:Nmax", std::to_string(finest));
    mrm::tex_define(defs, "benchconv:meshes", std::to_string(levels));
    mrm::tex_define(defs, "benchconv:tolerance", mrm::tex_number(agreement, 2));
    std::vector<std::string> headers{"benchmark", "mass"};
    for (const mrm::repro::Label& label : mrm::repro::measure_labels())
      headers.push_back("\\rotatebox{70}{" + label.latex + "}");
    mrm::repro::Table orders(headers), time_orders(headers);
    long agreeing = 0, cases = 0;
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      const std::string key = benchmarks[b];
      for (std::size_t m = 0; m < masses.size(); ++m) {
        orders.add_row(mass_orders_row(defs, study, meshes, b, m, agreeing, cases));
      }
      if (b + 1 < benchmarks.size()) orders.add_rule();
      time_orders.add_row(time_orders_row(study, b));
      // The windows: exact (in the benchmark's units) and the finest Mod 3 run's.
      write_windows(defs, key,
                    mrm::repro::configuration_contact_windows(configurations[(b * masses.size() + 2) * levels],
                                                              mrm::impact_benchmark(key).final_time),
                    study.at(b, 2, levels - 1), finest);
    }
    write_data_table(defs);
    mrm::tex_define(defs, "benchconv:agreeing", std::to_string(agreeing));
    mrm::tex_define(defs, "benchconv:cases", std::to_string(cases));
    for (std::size_t part = 0; part < 2; ++part) {
      std::vector<std::size_t> keep{0, 1};
      for (std::size_t k = 4 * part; k < 4 * part + 4; ++k) keep.push_back(2 + k);
      defs << "\\mrmdef{benchconv:table:orders" << (part == 0 ? ":a" : ":b") << "}{"
           << mrm::repro::latex_tabular(orders.columns_subset(keep), "ll" + std::string(4, 'r')) << "}\n";
      defs << "\\mrmdef{benchconv:table:dtorders" << (part == 0 ? ":a" : ":b") << "}{"
           << mrm::repro::latex_tabular(time_orders.columns_subset(keep), "ll" + std::string(4, 'r')) << "}\n";
    }

    // The graded table: each member's drift minus Mod 3's against Σ δmᵢ κ(xᵢ), in units of h₀.
    write_graded(out, defs, graded);

    // 6. Commit.
    program.commit();
    return 0;
  });
}
