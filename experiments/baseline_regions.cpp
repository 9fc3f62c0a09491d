// baseline_regions: what mass redistribution buys against the baseline the report names, over regions.
//
// What it computes. The baseline is Paoli–Schatzman (¼, 0) with the consistent mass (its literal contact
// row: the contact node keeps its inertia). Against it: Crank–Nicolson with Mod 3 (the method), and the
// two energy schemes of mathematics.md §12 with Mod 3, EC and CN-switch (θ = 1). On the benchmark of
// mathematics.md §2, for N ∈ {25, 100, 400, 1600} and Δt/h ∈ {¼, ½, 1}, over 1, 10, 30 and 1000 periods:
// each of the eight relative errors of mathematics.md §5 as a ratio to Crank–Nicolson + Mod 3's (and their
// geometric mean), the total variation of λ over the run against the exact λ's at the same instants
// (TV(λ)/TV(λ_exact): how much the multiplier oscillates), the smallest λ against the exact one, and the
// discrete energy at the horizon relative to E_h(0).
//
// The region computed, and why. A run costs about nodes × steps = N · 3N/(Δt/h) per period, ~11 ns per
// node and step with the error measures (bar1d, N = 400, loaded machine): the four schemes and three
// ratios, 84 N² node-steps per period, are 1.3e10 node-steps (~150 s) for N = 400 over 1000 periods and
// 6.5e9 (~70 s) for N = 1600 over 30. To keep `make all` within about 40 s more at -j2, every run goes
// to the longest horizon its mesh allows: 1000 periods on N = 25 and 100 (~10 s), 30 on N = 400 (~5 s),
// 1 on N = 1600 (~2.5 s). The data and the table leave the other cells out and say so.
//
// Sample runs:
//   baseline_regions --output output/data/baseline_regions.dat --tex output/data/baseline_regions.tex
//   baseline_regions --threads 1 --output b.dat
//
// Description. Steps: (1) options; (2) outputs; (3) one run per (scheme, N, Δt/h) to the longest horizon
// of its mesh, measuring at every shorter one (the errors from run_configuration's horizons, the rest
// from the samples), through the sweep layer (repro/sweep.hpp: the twelve runs of one mesh in one batch,
// each Δt at its own rate, which share the closed form's evaluation), costliest first, on --threads
// workers; (4) the data (one line per cell and scheme), the tables and the conclusion for the report;
// (5) commit.
//
// Data file: columns elements courant periods scheme, the eight error ratios to cn + mod3 (in
// ErrorAccumulator::names order), their geometric mean, the geometric mean of the scheme's own relative
// errors, tv_ratio (TV(λ)/TV(λ_exact)), min_lambda,
// min_lambda_exact, energy_ratio (E_h(T)/E_h(0)).
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "labels.hpp"
#include "options.hpp"
#include "parallel.hpp"
#include "sweep.hpp"
#include "report_values.hpp"
#include "table.hpp"

#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

namespace {

// The schemes compared: the baseline first, then the method (the reference of the ratios), then the
// energy schemes.
struct ComparedScheme {
  std::string id;
  mrm::Scheme scheme;
  std::string ps_form, mass;
};
const std::vector<ComparedScheme>& cases() {
  static const std::vector<ComparedScheme> c = {
      {"ps-consistent", mrm::Scheme::paoli_schatzman, "literal", "consistent"},
      {"cn", mrm::Scheme::crank_nicolson, "algebraic", "mod3"},
      {"ec", mrm::Scheme::energy_conserving, "algebraic", "mod3"},
      {"cn-switch", mrm::Scheme::switching, "algebraic", "mod3"}};
  return c;
}
constexpr std::size_t baseline = 0, method = 1;

// What one run measures at one horizon.
struct HorizonMeasures {
  bool computed = false;
  std::array<double, 8> errors{};
  double tv = 0, tv_exact = 0, min_lambda = 0, min_lambda_exact = 0, energy_ratio = 0;
};

double geometric_mean(const std::array<double, 8>& ratios) {
  double log_sum = 0;
  for (double r : ratios) log_sum += std::log(r);
  return std::exp(log_sum / 8);
}

std::string range(double lo, double hi) {
  return mrm::tex_number(lo, 3) == mrm::tex_number(hi, 3) ? mrm::tex_number(lo, 3)
                                                          : mrm::tex_number(lo, 3) + "--" + mrm::tex_number(hi, 3);
}

// The grid: the meshes, how far each is run (periods), the ratios Δt/h and the horizons (periods).
const std::vector<mrm::Index> meshes{25, 100, 400, 1600};
const std::vector<double> reach{1000, 1000, 30, 1};  // periods, per mesh
const std::vector<double> courants{0.25, 0.5, 1.0};
const std::vector<double> horizons{1, 10, 30, 1000};

// The measures of every run at every horizon, in the order (scheme, mesh, Δt/h).
struct Study {
  const std::vector<std::vector<HorizonMeasures>>& results;
  const HorizonMeasures& cell(std::size_t s, std::size_t a, std::size_t b, std::size_t h) const {
    return results[(s * meshes.size() + a) * courants.size() + b][h];
  }
  // The errors of scheme s relative to the method's in the same cell.
  std::array<double, 8> ratios(std::size_t s, std::size_t a, std::size_t b, std::size_t h) const {
    std::array<double, 8> r{};
    for (std::size_t q = 0; q < 8; ++q) r[q] = cell(s, a, b, h).errors[q] / cell(method, a, b, h).errors[q];
    return r;
  }
};

// The accuracy table: per (N, Δt/h), the baseline's geometric mean at each horizon, its λ ratio and the
// TV ratios of every scheme at the longest horizon computed up to 30 periods.
void write_accuracy_table(std::ostream& defs, const Study& study) {
  const auto label = [](std::size_t s) { return repro::scheme_label(cases()[s].scheme).abbreviation; };
  {
    std::vector<std::string> head = {"$N$", "$\\Delta t/h$"};
    for (double p : horizons) head.push_back("$g$, " + cli::format_real(p) + "p");
    head.push_back("$\\lambda$ ratio");
    for (std::size_t s = 0; s < cases().size(); ++s)
      head.push_back("TV " + label(s) + (s == baseline ? " (cons.)" : ""));
    repro::Table table(head);
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b) {
        std::vector<std::string> row = {std::to_string(meshes[a]), cli::format_real(courants[b])};
        std::size_t last = 0;  // the longest horizon ≤ 30 periods computed
        for (std::size_t h = 0; h < horizons.size(); ++h) {
          const bool computed = study.cell(baseline, a, b, h).computed;
          row.push_back(computed ? mrm::tex_number(geometric_mean(study.ratios(baseline, a, b, h)), 3) : "--");
          if (computed && horizons[h] <= 30) last = h;
        }
        row.push_back(mrm::tex_number(study.ratios(baseline, a, b, last)[1], 3));
        for (std::size_t s = 0; s < cases().size(); ++s)
          row.push_back(mrm::tex_number(study.cell(s, a, b, last).tv / study.cell(s, a, b, last).tv_exact, 3));
        table.add_row(row);
      }
    std::ostringstream tex;
    repro::LatexLayout layout;
    layout.columns = "rr" + std::string(horizons.size() + 1 + cases().size(), 'r');
    table.write_latex(tex, layout);
    mrm::tex_define(defs, "baseline:accuracy", tex.str());
  }
}

// The energy table: per (N, Δt/h) run to 1000 periods, E_h(T)/E_h(0) of every scheme and the smallest λ
// of the baseline and the method against the exact one.
void write_energy_table(std::ostream& defs, const Study& study) {
  const auto label = [](std::size_t s) { return repro::scheme_label(cases()[s].scheme).abbreviation; };
  {
    const std::size_t h = horizons.size() - 1;
    std::vector<std::string> head = {"$N$", "$\\Delta t/h$"};
    // Two-line headers (the quantity over the scheme): on one line the table is wider than the page.
    const auto stacked = [](const std::string& top, const std::string& bottom) {
      return "\\shortstack[r]{" + top + "\\\\" + bottom + "}";
    };
    for (std::size_t s = 0; s < cases().size(); ++s) head.push_back(stacked("$E_h(T)/E_h(0)$", label(s)));
    head.push_back(stacked("min $\\lambda$", label(baseline)));
    head.push_back(stacked("min $\\lambda$", label(method)));
    head.push_back(stacked("min $\\lambda$", "exact"));
    repro::Table table(head);
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b) {
        if (!study.cell(baseline, a, b, h).computed) continue;
        std::vector<std::string> row = {std::to_string(meshes[a]), cli::format_real(courants[b])};
        for (std::size_t s = 0; s < cases().size(); ++s)
          row.push_back(mrm::tex_number(study.cell(s, a, b, h).energy_ratio, 3));
        row.push_back(mrm::tex_number(study.cell(baseline, a, b, h).min_lambda, 3));
        row.push_back(mrm::tex_number(study.cell(method, a, b, h).min_lambda, 3));
        row.push_back(mrm::tex_number(study.cell(method, a, b, h).min_lambda_exact, 3));
        table.add_row(row);
      }
    std::ostringstream tex;
    repro::LatexLayout layout;
    layout.columns = "rr" + std::string(cases().size() + 3, 'r');
    table.write_latex(tex, layout);
    mrm::tex_define(defs, "baseline:energy", tex.str());
  }
}

// The conclusion, from the numbers. Up to 30 periods, per mesh and per Δt/h ≤ ½ or = 1, the range of
// the baseline's geometric mean and the word it supports: the baseline's errors larger by more than
// 10 % in every cell ("accuracy"), within 10 % in every cell ("nothing"), or either ("in part"); the
// range of its λ ratio where it is below 1. At 1000 periods, the geometric means and how large the
// errors themselves are (every scheme's relative errors are then O(1)); the energy after 1000 periods.
// Then the region computed and the grid itself, for the report's sentences.
void write_conclusion(std::ostream& defs, const Study& study) {
  const auto word = [](double lo, double hi) {
    return lo >= 1.1 ? "accuracy" : hi < 1.1 && lo > 0.9 ? "nothing" : "accuracy in part";
  };
  const std::size_t long_h = horizons.size() - 1;
  double lambda_lo = INFINITY, lambda_hi = 0, long_lo = INFINITY, long_hi = 0, error_lo = INFINITY, error_hi = 0;
  for (std::size_t a = 0; a < meshes.size(); ++a) {
    for (const bool large : {false, true}) {
      double lo = INFINITY, hi = 0;
      for (std::size_t b = 0; b < courants.size(); ++b)
        for (std::size_t h = 0; h < long_h; ++h) {
          if (!study.cell(baseline, a, b, h).computed || (courants[b] > 0.5) != large) continue;
          const double g = geometric_mean(study.ratios(baseline, a, b, h)), l = study.ratios(baseline, a, b, h)[1];
          lo = std::min(lo, g), hi = std::max(hi, g);
          if (l < 1) lambda_lo = std::min(lambda_lo, l), lambda_hi = std::max(lambda_hi, l);
        }
      const std::string key = "baseline:N" + std::to_string(meshes[a]) + (large ? ":c1" : ":chalf");
      mrm::tex_define(defs, key + ":range", range(lo, hi));
      mrm::tex_define(defs, key + ":word", word(lo, hi));
    }
    for (std::size_t b = 0; b < courants.size(); ++b)
      if (study.cell(baseline, a, b, long_h).computed) {
        const double g = geometric_mean(study.ratios(baseline, a, b, long_h));
        long_lo = std::min(long_lo, g), long_hi = std::max(long_hi, g);
        for (std::size_t s : {baseline, method}) {
          const double e = geometric_mean(study.cell(s, a, b, long_h).errors);
          error_lo = std::min(error_lo, e), error_hi = std::max(error_hi, e);
        }
      }
  }
  mrm::tex_define(defs, "baseline:lambda:better", lambda_hi > 0 ? range(lambda_lo, lambda_hi) : "none");
  mrm::tex_define(defs, "baseline:long:ratio", range(long_lo, long_hi));
  mrm::tex_define(defs, "baseline:long:error", range(error_lo, error_hi));
  for (std::size_t s = 0; s < cases().size(); ++s) {
    double lo = INFINITY, hi = 0;
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b)
        if (study.cell(s, a, b, long_h).computed) {
          lo = std::min(lo, study.cell(s, a, b, long_h).energy_ratio);
          hi = std::max(hi, study.cell(s, a, b, long_h).energy_ratio);
        }
    mrm::tex_define(defs, "baseline:energy:" + cases()[s].id, mrm::tex_number(lo, 2) + " to " + mrm::tex_number(hi, 2));
  }
  std::string computed;
  for (std::size_t a = 0; a < meshes.size(); ++a)
    computed += (a ? ", " : "") + ("$N=" + std::to_string(meshes[a]) + "$ to " + cli::format_real(reach[a]));
  mrm::tex_define(defs, "baseline:region", computed);
  // The grid itself, for the report's sentences: "25, 100, 400 and 1600", "0.25, 0.5 and 1", ...
  const auto list = [](const auto& values, const auto& format) {
    std::string text;
    for (std::size_t k = 0; k < values.size(); ++k)
      text += (k ? (k + 1 == values.size() ? " and " : ", ") : "") + format(values[k]);
    return text;
  };
  mrm::tex_define(defs, "baseline:meshes", list(meshes, [](mrm::Index n) { return std::to_string(n); }));
  mrm::tex_define(defs, "baseline:courants", list(courants, [](double c) { return cli::format_real(c); }));
  mrm::tex_define(defs, "baseline:horizons", list(horizons, [](double p) { return cli::format_real(p); }));
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("baseline_regions", [&] {
    // 1. Options.
    long threads = 2;
    repro::FigureProgram program(
        "baseline_regions",
        "Writes the errors of Paoli-Schatzman (1/4, 0) with the consistent mass, EC and CN-switch relative to "
        "Crank-Nicolson with Mod 3, TV(lambda)/TV(lambda_exact), the smallest lambda and E_h(T)/E_h(0), for N = 25, "
        "100, 400, 1600, dt/h = 1/4, 1/2, 1, over 1, 10, 30 and 1000 periods (as far as each mesh's cost allows).",
        {"baseline_regions --output output/data/baseline_regions.dat --tex output/data/baseline_regions.tex",
         "baseline_regions --threads 1 --output b.dat"});
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the tables and the values the report quotes")) return 0;

    // 2. Outputs, and the grid with the longest horizon each mesh allows (the cost, above).
    program.open();
    const mrm::ExactSolution exact;  // L = 1, u⁰ = (1 − x)/2: period 3
    std::ostream& out = program.header("the baseline, PS (1/4, 0) with the consistent mass, against CN + Mod 3");
    out << "# region: every run to the longest horizon its mesh allows (cost, baseline_regions.cpp): N = 25, 100: "
           "1000 periods; N = 400: 30; N = 1600: 1\n";

    // 3. The runs: one per (scheme, mesh, ratio), through the sweep layer. The twelve runs of one mesh make
    // one batch: the three Δt of a scheme (Δt/h = ¼, ½, 1) share vector lanes, each stepping at its own
    // rate (1, 2, 4 steps of the smallest), so that all twelve reach the same instants at the same batch
    // step and their error measures evaluate the closed form once per instant (ErrorAccumulator::add_lanes);
    // the observer reads only λ and the energy, so the lanes are read in place. Batches costliest first.
    struct Job {
      std::size_t scheme, mesh, courant;
    };
    std::vector<Job> jobs;
    for (std::size_t s = 0; s < cases().size(); ++s)
      for (std::size_t a = 0; a < meshes.size(); ++a)
        for (std::size_t b = 0; b < courants.size(); ++b) jobs.push_back({s, a, b});
    std::vector<std::vector<HorizonMeasures>> results(jobs.size(), std::vector<HorizonMeasures>(horizons.size()));
    // What each run follows sample by sample: TV(λ), TV(λ_exact) and the smallest values, read off at the
    // level at which each horizon is reached (run_configuration's rule).
    struct Follow {
      std::vector<mrm::Index> levels;
      double tv = 0, tv_exact = 0, lambda = 0, lambda_exact = 0, min_lambda = 0, min_exact = 0, e0 = 0;
      bool first = true;
      std::size_t next = 0;
    };
    std::vector<Follow> follow(jobs.size());
    std::vector<repro::Configuration> configurations;
    std::vector<repro::BatchKey> keys;
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const Job& job = jobs[k];
      const ComparedScheme& c = cases()[job.scheme];
      configurations.push_back(repro::paper_configuration(c.scheme, c.ps_form, c.mass, meshes[job.mesh],
                                                          courants[job.courant], exact.period() * reach[job.mesh]));
      repro::Configuration& configuration = configurations.back();
      for (double periods : horizons)
        if (periods <= reach[job.mesh]) {
          follow[k].levels.push_back(mrm::steps_to_reach(exact.period() * periods, configuration.step()));
          if (periods < reach[job.mesh]) configuration.horizons.push_back(exact.period() * periods);
        }
      keys.push_back({meshes[job.mesh], 0});
    }
    repro::SweepSettings settings;
    settings.threads = static_cast<unsigned>(threads);
    const std::vector<repro::Measures> measures = repro::run_batched(
        configurations, settings,
        [&](std::size_t k, const mrm::Sample& s) {
          Follow& f = follow[k];
          if (s.level == 0) f.e0 = s.energy;
          if (s.has_multiplier) {
            const double exact_lambda = exact.contact_multiplier(s.multiplier_time);
            if (!f.first)
              f.tv += std::abs(s.multiplier - f.lambda), f.tv_exact += std::abs(exact_lambda - f.lambda_exact);
            f.min_lambda = f.first ? s.multiplier : std::min(f.min_lambda, s.multiplier);
            f.min_exact = f.first ? exact_lambda : std::min(f.min_exact, exact_lambda);
            f.lambda = s.multiplier, f.lambda_exact = exact_lambda, f.first = false;
          }
          if (f.next < f.levels.size() && s.level == f.levels[f.next]) {
            HorizonMeasures& cell = results[k][f.next++];
            cell.computed = true;
            cell.tv = f.tv, cell.tv_exact = f.tv_exact, cell.min_lambda = f.min_lambda;
            cell.min_lambda_exact = f.min_exact;
            cell.energy_ratio = s.energy / f.e0;
          }
        },
        keys, /*observer_reads_vectors=*/false);
    for (std::size_t k = 0; k < jobs.size(); ++k) {
      const std::vector<mrm::Index>& levels = follow[k].levels;
      if (follow[k].next != levels.size()) throw std::logic_error("baseline_regions: a horizon was not reached");
      for (std::size_t h = 0; h < levels.size(); ++h)
        results[k][h].errors =
            mrm::ErrorAccumulator::values(h + 1 < levels.size() ? measures[k].horizon_errors[h] : measures[k].errors);
    }
    const Study study{results};
    const auto cell = [&](std::size_t s, std::size_t a, std::size_t b, std::size_t h) -> const HorizonMeasures& {
      return study.cell(s, a, b, h);
    };
    const auto ratios = [&](std::size_t s, std::size_t a, std::size_t b, std::size_t h) {
      return study.ratios(s, a, b, h);
    };

    // 4. The data: one line per (N, Δt/h, horizon, scheme) computed.
    out << "# columns: elements courant periods scheme";
    for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name << "_ratio";
    out << " geometric_mean geometric_mean_error tv_ratio min_lambda min_lambda_exact energy_ratio\n";
    for (std::size_t a = 0; a < meshes.size(); ++a)
      for (std::size_t b = 0; b < courants.size(); ++b)
        for (std::size_t h = 0; h < horizons.size(); ++h)
          for (std::size_t s = 0; s < cases().size(); ++s) {
            const HorizonMeasures& c = cell(s, a, b, h);
            if (!c.computed) continue;
            out << meshes[a] << ' ' << cli::format_real(courants[b]) << ' ' << cli::format_real(horizons[h]) << ' '
                << cases()[s].id;
            for (double r : ratios(s, a, b, h)) out << ' ' << cli::format_real(r);
            out << ' ' << cli::format_real(geometric_mean(ratios(s, a, b, h))) << ' '
                << cli::format_real(geometric_mean(c.errors)) << ' ' << cli::format_real(c.tv / c.tv_exact) << ' '
                << cli::format_real(c.min_lambda) << ' ' << cli::format_real(c.min_lambda_exact) << ' '
                << cli::format_real(c.energy_ratio) << '\n';
          }

    std::ostream& defs = program.values();
    write_accuracy_table(defs, study);
    write_energy_table(defs, study);

    write_conclusion(defs, study);

    // 5. Commit.
    program.commit();
    return 0;
  });
}
