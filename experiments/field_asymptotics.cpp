// field_asymptotics: the field's benchmarks on fine meshes, where their orders become asymptotic, which
// mass is the most accurate on which meshes, and the error of the release time that both come from.
//
// What it computes. Crank–Nicolson with Mod 1, 2 and 3, Δt = h/(2c) (c the wave speed at the contact
// end), on the five benchmarks of fig_benchmark_convergence (bouncing, impacting, gravity-paper, layered,
// two-bars) to their default horizons, on the meshes N = N₀, 2N₀, …, 2^{K−1}N₀ (by default 80 … 2560,
// eight times finer than make all's study, which stops at 320), through repro::run_batched (the
// harness's one path). For every run: the eight relative errors of mathematics.md §5 against the exact
// solution, and the error of the first release, t_h − t (the end of the run's first contact window
// minus the exact one, in the benchmark's time unit; gravity-paper keeps its contact and has none).
//
// The prediction (repro/field_conjecture.cpp, from lib/studies/smeared_orders.cpp): Crank–Nicolson
// smears a front over W ≈ (h² c t)^{1/3}, a release triggered by a smeared front is off by δ = O(W) =
// O(h^{2/3}), so on the bars with a release u is order 2/3 in L² and λ and the energy-type measures 1/3;
// on gravity-paper (no release) the kinks of u_x and u_t give 1, and 5/3 for u in L² (1 with Mod 2,
// whose uniformly heavier bar is off in phase by O(h)). Written after the first run of this program:
// the conjecture it replaces (fig_benchmark_convergence's, 1 and ½ with a release, 2 for u in L² on
// gravity-paper) is kept here for the comparison.
// The fitted order is that of the finest four meshes (N = 2^{K−4}N₀ … 2^{K−1}N₀; by default 320 … 2560),
// judged against the prediction within Student's 95 % interval of the fit (t quantile of two degrees of
// freedom, 4.30, times the order's standard error), as the phase-matched rows are: "consistent". That
// interval measures the scatter of the four errors about a line, not the drift of a pre-asymptotic order,
// so a second class (chosen after the first run of this program at N = 80 … 2560) says whether the
// errors are still on their way: "approaching" when the fit misses but each of the last three local
// orders is closer to the prediction than the one before; "not" otherwise. The same fits are also judged
// against the old conjecture within its ±0.25, to show what the revision changes.
//
// The ordering of the masses: for each benchmark, measure and mesh, the masses from the smallest error
// to the largest. A hypothesis stated before the first run: after the release the displacement error
// follows the release error, so of two masses the one with the smaller |δ| has the smaller error in
// u(0,·). The program counts the pairs (benchmark with a release, mesh, two masses) where that holds,
// and the ratio of Mod 3's error in u in L²(L²) to Mod 1's at the two finest meshes (the ordering of
// the two masses the paper compares).
//
// Cost: about 250 CPU-s at the default meshes (two minutes on two threads), so it is not part of
// `make all`: `make field-asymptotics` writes its output into doc/results/, committed, which the
// report reads; the ctest entry field_asymptotics_committed reruns the coarse meshes and compares them,
// byte for byte, with the committed rows.
//
// Sample runs:
//   field_asymptotics --output doc/results/field_asymptotics.dat --tex doc/results/field_asymptotics.tex
//   field_asymptotics --coarsest 20 --refinements 4 --threads 1 --output f.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the runs, in parallel, longest first; (4) data
// blocks; (5) orders, orderings, the mechanism's count and the values the report quotes; (6) commit.
//
// Data file: block 3b + m (b the benchmark in the order above, m ∈ mod1, mod2, mod3): columns N h dt and
// the eight errors, h and dt in units of L and L/c (two-bars: h = ℓ/N of one bar); block 15: the release
// errors, columns benchmark mass N t_exact t_h delta (gravity-paper has no row).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include <gsl/gsl_cdf.h>

#include "configurations.hpp"
#include "exact/impact_solution.hpp"
#include "field_conjecture.hpp"
#include "figure_program.hpp"
#include "labels.hpp"
#include "mass_spec.hpp"
#include "measures/errors.hpp"
#include "options.hpp"
#include "refinement.hpp"
#include "report_values.hpp"
#include "studies/convergence.hpp"
#include "sweep.hpp"
#include "table.hpp"

namespace cli = mrm::cli;

namespace {

const std::array<const char*, 5> benchmarks{"bouncing", "impacting", "gravity-paper", "layered", "two-bars"};
const std::array<const char*, 3> masses{"mod1", "mod2", "mod3"};
constexpr double courant = 0.5, old_agreement = 0.25, confidence = 0.95;
constexpr std::size_t fitted_meshes = 4;
enum Measure { u0_L2, lambda_L2, u_LinfL2, u_LinfH1, v_LinfL2, u_L2L2, u_L2H1, v_L2L2 };

// Whether benchmark b releases its contact (field_benchmark_releases, an exact solve), asked once each.
bool has_release(std::size_t b) {
  static const std::array<bool, benchmarks.size()> releases = [] {
    std::array<bool, benchmarks.size()> r{};
    for (std::size_t i = 0; i < benchmarks.size(); ++i) r[i] = mrm::repro::field_benchmark_releases(benchmarks[i]);
    return r;
  }();
  return releases[b];
}
bool displacement_in_L2(std::size_t k) { return k == u0_L2 || k == u_LinfL2 || k == u_L2L2; }

double predicted_order(std::size_t b, std::size_t m, std::size_t k) {
  return mrm::repro::field_conjectured_order(benchmarks[b], masses[m], k);
}

// The conjecture field_conjecture.cpp replaces, for the comparison.
double old_conjecture(std::size_t b, std::size_t k) {
  if (!has_release(b)) return displacement_in_L2(k) ? 2.0 : 1.0;
  if (k == lambda_L2) return 0.5;
  return displacement_in_L2(k) ? 1.0 : 1.0 / 3.0;
}

enum class Verdict { consistent, approaching, not_consistent };

// The verdict of a fit against the prediction (the classes above), from the fit and the local orders.
Verdict judge(double order, double half_width, const std::vector<double>& local, double predicted) {
  if (std::abs(order - predicted) <= half_width) return Verdict::consistent;
  const std::size_t n = local.size();
  const double a = std::abs(local[n - 3] - predicted), b = std::abs(local[n - 2] - predicted),
               c = std::abs(local[n - 1] - predicted);
  return c < b && b < a ? Verdict::approaching : Verdict::not_consistent;
}

std::string fraction(double order) {
  if (std::abs(order - 1.0 / 3.0) < 1e-12) return "1/3";
  if (std::abs(order - 2.0 / 3.0) < 1e-12) return "2/3";
  if (std::abs(order - 5.0 / 3.0) < 1e-12) return "5/3";
  if (std::abs(order - 0.5) < 1e-12) return "1/2";
  return mrm::tex_number(order, 1);
}

// The runs' results: errors and release error of benchmark b, mass m, mesh level l.
struct Results {
  std::size_t levels;
  std::vector<std::array<double, 8>> errors;
  std::vector<double> release_exact, release_measured;
  std::size_t index(std::size_t b, std::size_t m, std::size_t l) const { return (b * masses.size() + m) * levels + l; }
  const std::array<double, 8>& at(std::size_t b, std::size_t m, std::size_t l) const { return errors[index(b, m, l)]; }
  double delta(std::size_t b, std::size_t m, std::size_t l) const {
    return release_measured[index(b, m, l)] - release_exact[index(b, m, l)];
  }
};

// The fit over the finest four meshes of a positive series: order, its half-width at `confidence`.
struct FineFit {
  double order, half_width;
};
FineFit fine_fit(const mrm::repro::MeshRefinement& meshes, const std::vector<double>& series) {
  const std::size_t first = meshes.levels() - fitted_meshes;
  const std::vector<double> h(meshes.mesh_sizes().begin() + static_cast<long>(first), meshes.mesh_sizes().end());
  const std::vector<double> e(series.begin() + static_cast<long>(first), series.end());
  const mrm::OrderFit fit = mrm::fit_order(h, e);
  const double quantile = gsl_cdf_tdist_Pinv(0.5 + confidence / 2, static_cast<double>(fit.points - 2));
  return {fit.order, quantile * fit.order_std_error};
}

// The masses of benchmark b on level l ordered from the smallest value of `value(m)` to the largest,
// written "1 $<$ 3 $<$ 2" (Mod numbers, LaTeX).
template <class Value>
std::string ordering(Value value) {
  std::array<std::size_t, 3> order{0, 1, 2};
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t c) { return value(a) < value(c); });
  std::string text;
  for (const std::size_t m : order) text += (text.empty() ? "" : " $<$ ") + std::to_string(m + 1);
  return text;
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("field_asymptotics", [&] {
    // 1. Options.
    long coarsest = 80, refinements = 6, threads = 2;
    mrm::repro::FigureProgram program(
        "field_asymptotics",
        "Writes the relative errors and the release errors of cn with mod1, mod2, mod3 on the field's benchmarks "
        "(bouncing, impacting, gravity-paper, layered, two-bars) on fine meshes, the orders fitted over the finest "
        "four against the predicted ones, the masses' ordering on every mesh, and the count of the pairs whose "
        "displacement error follows their release error.",
        {"field_asymptotics --output doc/results/field_asymptotics.dat --tex doc/results/field_asymptotics.tex",
         "field_asymptotics --coarsest 20 --refinements 4 --threads 1 --output f.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0",
                               "number of elements of the coarsest mesh, a multiple of 5 (the layered bar's "
                               "interface is a node) in [5, 1000]",
                               &coarsest, cli::in_closed_range(5, 1000));
    program.parser.add_integer("--refinements", "-k", "K",
                               "number of meshes N0, 2 N0, ..., 2^(K-1) N0, in [4, 6] (the orders are fitted over the "
                               "finest four)",
                               &refinements, cli::in_closed_range(4, 6));
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the tables and values the report quotes")) return 0;
    const mrm::repro::MeshRefinement meshes(static_cast<mrm::Index>(coarsest), static_cast<std::size_t>(refinements));
    const std::size_t levels = meshes.levels();
    const auto configuration_of = [&](std::size_t b, const char* mass, mrm::Index elements) {
      return mrm::repro::study_configuration(benchmarks[b], mrm::Scheme::crank_nicolson,
                                             mrm::repro::mass_redistribution_from_spec(mass), elements, courant,
                                             mrm::impact_benchmark(benchmarks[b]).final_time);
    };
    // Every mesh is a multiple of the coarsest, so the library's refusal of an N that puts no node on a
    // material interface (chain_mesh, naming the allowed N) is asked of the coarsest, before any work.
    mrm::repro::as_usage_error({{"elements", "--coarsest"}}, [&] {
      for (std::size_t b = 0; b < benchmarks.size(); ++b)
        mrm::repro::configuration_mesh(configuration_of(b, masses.front(), meshes.coarsest()));
    });

    // 2. Outputs.
    program.open();

    // 3. The runs, through the sweep layer: the three masses of one benchmark and mesh make one batch
    // (fig_benchmark_convergence's grouping), each run's measures run_configuration's bit for bit.
    std::vector<mrm::repro::Configuration> configurations;
    std::vector<mrm::repro::BatchKey> keys;
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (const char* m : masses)
        for (std::size_t l = 0; l < levels; ++l) {
          configurations.push_back(configuration_of(b, m, meshes.elements(l)));
          keys.push_back({meshes.elements(l), static_cast<int>(b)});
        }
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::require_batched_memory("--coarsest", configurations, settings);  // before any run
    const auto start = std::chrono::steady_clock::now();
    const std::vector<mrm::repro::Measures> measures =
        mrm::repro::run_batched(configurations, settings, {}, keys, true);
    std::cerr << "field_asymptotics: " << configurations.size() << " runs in "
              << std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() << " s\n";

    // The exact first release of each benchmark (in its time unit: the same on every mesh).
    std::vector<double> exact_release(benchmarks.size(), 0.0);
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      if (has_release(b)) {
        const std::vector<mrm::ContactInterval> exact = mrm::repro::configuration_contact_windows(
            configurations[b * masses.size() * levels], mrm::impact_benchmark(benchmarks[b]).final_time);
        if (exact.empty() || exact.front().open)
          throw std::runtime_error(std::string(benchmarks[b]) + ": the exact solution has no first release");
        exact_release[b] = exact.front().end;
      }
    Results results{levels, {}, {}, {}};
    for (std::size_t i = 0; i < measures.size(); ++i) {
      const std::array<double, 8> row = mrm::ErrorAccumulator::values(measures[i].errors);
      if (!std::all_of(row.begin(), row.end(), [](double x) { return std::isfinite(x) && x >= 0; }))
        throw std::runtime_error("run " + std::to_string(i) + ": an error is not a finite number");
      results.errors.push_back(row);
      const std::size_t b = i / (masses.size() * levels);
      double exact_end = 0, measured_end = 0;
      if (has_release(b)) {
        if (measures[i].contact_windows.empty() || measures[i].contact_windows.front().open)
          throw std::runtime_error(std::string(benchmarks[b]) + ": the run with N = " +
                                   std::to_string(configurations[i].elements) + " has no first release");
        exact_end = exact_release[b];
        measured_end = measures[i].contact_windows.front().end;
      }
      results.release_exact.push_back(exact_end);
      results.release_measured.push_back(measured_end);
    }

    // 4. The data blocks.
    std::ostream& out = program.header("the field's benchmarks on fine meshes: errors and release errors");
    const std::size_t release_block = benchmarks.size() * masses.size();
    out << "# blocks: 3 b + m: benchmark b in (bouncing, impacting, gravity-paper, layered, two-bars), mass m in "
           "(mod1, mod2, mod3), scheme cn, dt = h/(2c); "
        << release_block << ": the first release's error\n";
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t m = 0; m < masses.size(); ++m) {
        out << (b + m ? "\n\n" : "") << "# block " << b * masses.size() + m << ": benchmark = " << benchmarks[b]
            << ", mass = " << masses[m] << ", scheme = cn\n";
        std::vector<mrm::repro::ErrorRow> rows;
        for (std::size_t l = 0; l < levels; ++l) rows.push_back({meshes.elements(l), results.at(b, m, l)});
        mrm::repro::write_error_rows(out, 1.0, courant, rows);
      }
    out << "\n\n# block " << release_block
        << ": the end of the first contact window, exact and computed, in the benchmark's time unit\n"
           "# columns: benchmark mass N t_exact t_h delta\n";
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      if (has_release(b))
        for (std::size_t m = 0; m < masses.size(); ++m)
          for (std::size_t l = 0; l < levels; ++l)
            out << benchmarks[b] << ' ' << masses[m] << ' ' << meshes.elements(l) << ' '
                << cli::format_real(results.release_exact[results.index(b, m, l)]) << ' '
                << cli::format_real(results.release_measured[results.index(b, m, l)]) << ' '
                << cli::format_real(results.delta(b, m, l)) << '\n';

    // 5. Orders over the finest four meshes, against the prediction and the old conjecture.
    std::ostream& defs = program.values();
    const mrm::Index fit_coarsest = meshes.elements(levels - fitted_meshes);
    mrm::tex_define(defs, "fieldasym:Nmin", std::to_string(meshes.coarsest()));
    mrm::tex_define(defs, "fieldasym:Nmax", std::to_string(meshes.finest()));
    mrm::tex_define(defs, "fieldasym:fit:Nmin", std::to_string(fit_coarsest));
    mrm::tex_define(defs, "fieldasym:fit:meshes", std::to_string(fitted_meshes));
    mrm::tex_define(defs, "fieldasym:quantile", mrm::tex_number(gsl_cdf_tdist_Pinv(0.5 + confidence / 2, 2.0), 3));
    mrm::tex_define(defs, "fieldasym:oldtolerance", mrm::tex_number(old_agreement, 2));
    std::cout << "orders over N = " << fit_coarsest << " ... " << meshes.finest() << " (fit ± 95 % half-width), "
              << "prediction, fig_benchmark_convergence's conjecture\n";
    std::vector<std::string> headers{"benchmark", "mass", "$t_h - t$"};
    for (const mrm::repro::Label& label : mrm::repro::measure_labels())
      headers.push_back("\\rotatebox{70}{" + label.latex + "}");
    mrm::repro::Table orders(headers);
    // One cell: the fit over the finest four meshes, its verdict, its text; counted in `tally`.
    struct Tally {
      long verdicts[3] = {0, 0, 0};
      long old_agreeing = 0, cases = 0;
      double farthest = 0;  ///< the largest |order − prediction| of a fit judged "not"
      std::string farthest_name;
    } tally, release_tally;
    // The range of the last local orders of each predicted order on the bars with a release.
    std::map<std::string, std::pair<double, double>> local_range;
    const char* const verdict_names[3] = {"consistent", "approaching", "not"};
    const auto cell = [&](const std::vector<double>& series, double predicted, Tally& t, const std::string& name,
                          const std::string& display) {
      const FineFit fit = fine_fit(meshes, series);
      const std::vector<double> local = mrm::repro::local_orders(meshes.mesh_sizes(), series);
      const Verdict verdict = judge(fit.order, fit.half_width, local, predicted);
      ++t.verdicts[static_cast<int>(verdict)];
      ++t.cases;
      if (verdict == Verdict::not_consistent && std::abs(fit.order - predicted) > t.farthest) {
        t.farthest = std::abs(fit.order - predicted);
        t.farthest_name = display;
      }
      if (name.rfind("gravity-paper", 0) != 0) {
        const std::string key = (name.find("release") != std::string::npos ? std::string("release")
                                 : predicted > 0.5                         ? "u"
                                                                           : "onethird");
        auto [it, inserted] = local_range.try_emplace(key, local.back(), local.back());
        it->second = {std::min(it->second.first, local.back()), std::max(it->second.second, local.back())};
      }
      mrm::tex_define(defs, "fieldasym:order:" + name, mrm::tex_number(fit.order, 2));
      mrm::tex_define(defs, "fieldasym:local:" + name, mrm::tex_number(local.back(), 2));
      mrm::tex_define(defs, "fieldasym:localbefore:" + name, mrm::tex_number(local[local.size() - 2], 2));
      std::cout << name << ' ' << cli::format_real(std::round(fit.order * 100) / 100) << " +- "
                << cli::format_real(std::round(fit.half_width * 100) / 100) << " local "
                << cli::format_real(std::round(local.back() * 100) / 100) << " (" << fraction(predicted) << ") "
                << verdict_names[static_cast<int>(verdict)];
      const std::string text = mrm::tex_number(fit.order, 2) + "{\\scriptsize$\\pm$" +
                               mrm::tex_number(fit.half_width, 1) + " [" + mrm::tex_number(local.back(), 2) + "] (" +
                               fraction(predicted) + ")}";
      switch (verdict) {
        case Verdict::consistent:
          return text;
        case Verdict::approaching:
          return text + "$^\\dagger$";
        default:
          return "\\textit{" + text + "}";
      }
    };
    // The release's conjectured order (repro/field_conjecture.cpp).
    const double release_order = mrm::repro::field_release_order();
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      const std::string key = benchmarks[b];
      for (std::size_t m = 0; m < masses.size(); ++m) {
        std::vector<std::string> row{m == 0 ? key : "", mrm::repro::mass_label(masses[m]).abbreviation};
        if (has_release(b)) {
          std::vector<double> deltas(levels);
          for (std::size_t l = 0; l < levels; ++l) deltas[l] = std::abs(results.delta(b, m, l));
          if (!std::all_of(deltas.begin(), deltas.end(), [](double d) { return d > 0; }))
            throw std::runtime_error(key + " " + masses[m] + ": a release computed exactly, no order to fit");
          row.push_back(cell(deltas, release_order, release_tally, key + ":" + masses[m] + ":release",
                             key + ", " + mrm::repro::mass_label(masses[m]).abbreviation + ", $|t_h - t|$"));
          std::cout << '\n';
          mrm::tex_define(defs, "fieldasym:release:delta:" + key + ":" + masses[m],
                          mrm::tex_number(results.delta(b, m, levels - 1), 2));
        } else {
          row.push_back("n/a");
        }
        for (std::size_t k = 0; k < 8; ++k) {
          const double predicted = predicted_order(b, m, k);
          std::vector<double> errors(levels);
          for (std::size_t l = 0; l < levels; ++l) errors[l] = results.at(b, m, l)[k];
          if (predicted == 0) {
            if (!std::all_of(errors.begin(), errors.end(), [](double e) { return e == 0; }))
              throw std::runtime_error(key + ": u(0,.) is not 0 in a run (its exact value is 0)");
            row.push_back("n/a");
            continue;
          }
          if (!std::all_of(errors.begin(), errors.end(), [](double e) { return e > 0; }))
            throw std::runtime_error("the errors of " + key + " " + masses[m] + " cannot be fitted (a zero error)");
          const std::string name = key + ":" + masses[m] + ":" + mrm::ErrorAccumulator::names[k];
          row.push_back(cell(errors, predicted, tally, name,
                             key + ", " + mrm::repro::mass_label(masses[m]).abbreviation + ", " +
                                 mrm::repro::measure_labels()[k].latex));
          const FineFit fit = fine_fit(meshes, errors);
          const bool old_holds = std::abs(fit.order - old_conjecture(b, k)) <= old_agreement;
          tally.old_agreeing += old_holds;
          std::cout << " [old " << fraction(old_conjecture(b, k)) << (old_holds ? " agrees" : " disagrees") << "]\n";
          mrm::tex_define(defs, "fieldasym:err:" + name, mrm::tex_number(errors.back(), 2));
        }
        orders.add_row(row);
      }
      if (b + 1 < benchmarks.size()) orders.add_rule();
    }
    for (int v = 0; v < 3; ++v) {
      mrm::tex_define(defs, std::string("fieldasym:") + verdict_names[v], std::to_string(tally.verdicts[v]));
      mrm::tex_define(defs, std::string("fieldasym:release:") + verdict_names[v],
                      std::to_string(release_tally.verdicts[v]));
    }
    mrm::tex_define(defs, "fieldasym:oldagreeing", std::to_string(tally.old_agreeing));
    for (const Tally* t : {&tally, &release_tally}) {
      const std::string prefix = t == &tally ? "fieldasym:not:" : "fieldasym:release:not:";
      mrm::tex_define(defs, prefix + "farthest", mrm::tex_number(t->farthest, 2));
      mrm::tex_define(defs, prefix + "farthestname", t->farthest_name);
    }
    for (const auto& [key, range] : local_range) {
      mrm::tex_define(defs, "fieldasym:localrange:" + key,
                      "[" + mrm::tex_number(range.first, 2) + ", " + mrm::tex_number(range.second, 2) + "]");
      std::cout << "last local orders, bars with a release, conjecture " << key << ": ["
                << cli::format_real(std::round(range.first * 100) / 100) << ", "
                << cli::format_real(std::round(range.second * 100) / 100) << "]\n";
    }
    mrm::tex_define(defs, "fieldasym:cases", std::to_string(tally.cases));
    mrm::tex_define(defs, "fieldasym:release:cases", std::to_string(release_tally.cases));
    std::cout << "errors: " << tally.verdicts[0] << " consistent, " << tally.verdicts[1] << " approaching, "
              << tally.verdicts[2] << " not, of " << tally.cases << "; " << tally.old_agreeing << " within "
              << old_agreement << " of the old conjecture; release: " << release_tally.verdicts[0] << " consistent, "
              << release_tally.verdicts[1] << " approaching, " << release_tally.verdicts[2] << " not, of "
              << release_tally.cases << '\n';
    for (std::size_t part = 0; part < 2; ++part) {
      std::vector<std::size_t> keep{0, 1};
      if (part == 0) keep.push_back(2);
      for (std::size_t k = 4 * part; k < 4 * part + 4; ++k) keep.push_back(3 + k);
      defs << "\\mrmdef{fieldasym:table:orders" << (part == 0 ? ":a" : ":b") << "}{"
           << mrm::repro::latex_tabular(orders.columns_subset(keep), "ll" + std::string(part == 0 ? 5 : 4, 'r'))
           << "}\n";
    }

    // The ordering of the masses on every mesh (u(0,·), λ, u in L²(L²) and in L²(H¹), and |t_h − t|),
    // and the mechanism's count: the pairs of masses whose u(0,·) errors are ordered as their |δ|.
    std::vector<std::string> ordering_headers{"benchmark", "measure"};
    for (std::size_t l = 0; l < levels; ++l)
      ordering_headers.push_back("$N = " + std::to_string(meshes.elements(l)) + "$");
    mrm::repro::Table orderings(ordering_headers);
    const std::array<std::size_t, 4> ordered_measures{u0_L2, lambda_L2, u_L2L2, u_L2H1};
    long follows = 0, pairs = 0;
    for (std::size_t b = 0; b < benchmarks.size(); ++b) {
      const std::string key = benchmarks[b];
      bool first = true;
      for (const std::size_t k : ordered_measures) {
        if (predicted_order(b, 0, k) == 0) continue;
        std::vector<std::string> row{first ? key : "", mrm::repro::measure_labels()[k].latex};
        first = false;
        for (std::size_t l = 0; l < levels; ++l)
          row.push_back(ordering([&](std::size_t m) { return results.at(b, m, l)[k]; }));
        mrm::tex_define(defs, "fieldasym:best:" + key + ":" + mrm::ErrorAccumulator::names[k], row.back().substr(0, 1));
        mrm::tex_define(defs, "fieldasym:bestcoarsest:" + key + ":" + mrm::ErrorAccumulator::names[k],
                        row[2].substr(0, 1));
        orderings.add_row(row);
      }
      if (has_release(b)) {
        std::vector<std::string> row{"", "$|t_h - t|$"};
        for (std::size_t l = 0; l < levels; ++l) {
          row.push_back(ordering([&](std::size_t m) { return std::abs(results.delta(b, m, l)); }));
          for (std::size_t i = 0; i < masses.size(); ++i)
            for (std::size_t j = i + 1; j < masses.size(); ++j) {
              const double dd = std::abs(results.delta(b, i, l)) - std::abs(results.delta(b, j, l));
              const double de = results.at(b, i, l)[u0_L2] - results.at(b, j, l)[u0_L2];
              follows += (dd < 0) == (de < 0);
              ++pairs;
            }
        }
        orderings.add_row(row);
      }
      if (b + 1 < benchmarks.size()) orderings.add_rule();
    }
    // On the bars with a release: how many have Mod 3 smallest in u(0,·) on the coarsest and the finest mesh.
    long releasing = 0, mod3_coarsest = 0, mod3_finest = 0;
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      if (has_release(b)) {
        const auto mod3_smallest = [&](std::size_t l) {
          return results.at(b, 2, l)[u0_L2] < std::min(results.at(b, 0, l)[u0_L2], results.at(b, 1, l)[u0_L2]);
        };
        ++releasing;
        mod3_coarsest += mod3_smallest(0);
        mod3_finest += mod3_smallest(levels - 1);
      }
    mrm::tex_define(defs, "fieldasym:releasing", std::to_string(releasing));
    mrm::tex_define(defs, "fieldasym:mod3best:coarsest", std::to_string(mod3_coarsest));
    mrm::tex_define(defs, "fieldasym:mod3best:finest", std::to_string(mod3_finest));
    mrm::tex_define(defs, "fieldasym:follows", std::to_string(follows));
    mrm::tex_define(defs, "fieldasym:pairs", std::to_string(pairs));
    std::cout << "u(0,.) errors ordered as the release errors: " << follows << " of " << pairs << " pairs\n";
    // Mod 3 against Mod 1 on the two finest meshes: the ratios of their errors in u in L²(L²), in λ and
    // of their |δ|.
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t l = levels - 2; l < levels; ++l) {
        const std::string at = std::string(benchmarks[b]) + ":" + (l + 1 == levels ? "finest" : "second");
        const double u_ratio = results.at(b, 2, l)[u_L2L2] / results.at(b, 0, l)[u_L2L2];
        const double lambda_ratio = results.at(b, 2, l)[lambda_L2] / results.at(b, 0, l)[lambda_L2];
        mrm::tex_define(defs, "fieldasym:ratio31:u:" + at, mrm::tex_number(u_ratio, 3));
        mrm::tex_define(defs, "fieldasym:ratio31:lambda:" + at, mrm::tex_number(lambda_ratio, 3));
        std::cout << benchmarks[b] << " N = " << meshes.elements(l) << ": Mod 3 / Mod 1, u in L2(L2) "
                  << cli::format_real(std::round(u_ratio * 1000) / 1000) << ", lambda "
                  << cli::format_real(std::round(lambda_ratio * 1000) / 1000);
        if (has_release(b)) {
          const double delta_ratio = std::abs(results.delta(b, 2, l) / results.delta(b, 0, l));
          mrm::tex_define(defs, "fieldasym:ratio31:delta:" + at, mrm::tex_number(delta_ratio, 3));
          std::cout << ", |delta| " << cli::format_real(std::round(delta_ratio * 1000) / 1000);
        }
        std::cout << '\n';
      }
    defs << "\\mrmdef{fieldasym:table:orderings}{"
         << mrm::repro::latex_tabular(orderings, "ll" + std::string(levels, 'c')) << "}\n";

    // 6. Commit.
    program.commit();
    return 0;
  });
}
