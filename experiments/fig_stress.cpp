// fig_stress: a contact stress whose oscillation does not grow as the mesh is refined.
//
// What it computes. For each benchmark (the paper's, S1 = smooth-impact, bouncing), each variant of the
// scheme (CN + Mod 3 at Δt/h = ½ and 1 with the consistent interior mass, CN + Mod 3 with the
// phase-matched A = ¼ at Δt/h = ½, CN-switch (θ = 1 at status changes) with A = ¼ at ½ and A = 0 at 1,
// backward Euler at ½, whose windows are also measured at CN's width, the width before each scheme had
// its own: contact_stress.cpp §1b) (the last four on the paper's benchmark only) and each mesh
// N = N₀ 4^l, one run over T = 30 on the unit bar (ten periods of the paper's benchmark; the same T on
// S1) and T = 80/9 on bouncing (three of its contacts, which come every 8L/c = 8/3 from t = 1), and from
// that one run the four stresses of lib/measures/contact_stress.hpp (multiplier, box, window, recovered):
// TV(stress)/TV(λ_exact), the relative L² error, and the largest error away from the exact status
// changes (repro::stress_measures), with the slope of each against N (least squares over the meshes).
//
// Predictions (lib/measures/contact_stress.cpp, derived there before any measurement). The multiplier's ratio
// grows like N^{1/2} for every variant (the wake of the smeared fronts runs down to the grid scale);
// the box window of width 8W like N^{1/6} (μ = 2) or N^{3/10} (μ = 4); the recovered stress like the
// box; the B-spline window of width 8W stays bounded (slope 0). The L² errors of all four are O(W^{1/2}):
// slope −1/3 (μ = 2), −2/5 (μ = 4). The target: a ratio at most 2 at every N with an L²
// error no larger than CN + Mod 3's multiplier at the same N, Δt/h and benchmark.
//
// Cost: one run per (benchmark, variant, mesh), all through the sweep layer (repro::run_batched: the
// runs of the same mesh and scheme family stepped together in the vector lanes of one register, each
// lane bitwise its run stepped alone, so the output does not depend on the batching or the threads);
// the stresses are post-processing of the returned histories. The finest mesh dominates (steps ∝ N²,
// T/Δt); the wall time goes to standard error.
//
// Sample runs:
//   fig_stress --output output/data/fig_stress.dat --tex output/data/fig_stress.tex
//   fig_stress --coarsest 50 --refinements 2 --output s.dat
//
// Data file: one block per (benchmark, variant, stress) with the columns N tv_ratio l2_error
// max_error_away; then one block with the four stresses and the exact λ over the last period of the
// paper's benchmark, CN + Mod 3, Δt/h = ½, on the middle mesh (the figure's bottom panel).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "measures/contact_stress.hpp"
#include "studies/convergence.hpp"
#include "figure_program.hpp"
#include "fem/interior_mass.hpp"
#include "options.hpp"
#include "report_values.hpp"
#include "sweep.hpp"
#include "table.hpp"

namespace cli = mrm::cli;

namespace {

struct Variant {
  const char* key;    // in the value names
  const char* label;  // in the tables
  mrm::Scheme scheme;
  double courant, blend;
};
const std::vector<Variant> variants{
    {"cn:c12", "CN, $c = 1/2$", mrm::Scheme::crank_nicolson, 0.5, 0.0},
    {"cn:c1", "CN, $c = 1$", mrm::Scheme::crank_nicolson, 1.0, 0.0},
    {"pm:c12", "CN, $c = 1/2$, $A = 1/4$", mrm::Scheme::crank_nicolson, 0.5, 0.25},
    {"sw:c12", "CN-switch, $c = 1/2$, $A = 1/4$", mrm::Scheme::switching, 0.5, 0.25},
    {"sw:c1", "CN-switch, $c = 1$", mrm::Scheme::switching, 1.0, 0.0},
    {"be:c12", "BE, $c = 1/2$", mrm::Scheme::backward_euler, 0.5, 0.0},
};
// The variant whose windows are also measured at CN's width (the width every scheme used before
// contact_stress.cpp §1b): backward Euler, the one scheme whose own W differs in kind (a damping).
constexpr std::size_t be_variant = 5;

struct Benchmark {
  const char* name;  // Configuration::benchmark
  const char* key;
  double final_time;  // in the benchmark's own unit (above)
};
// bouncing: T = 80/9 holds its first three contacts, [1, 5/3], [11/3, 13/3], [19/3, 7] (every 8L/c with L = 10 m,
// c = 30 m/s: lib/exact/impact_closed_forms.cpp).
const std::vector<Benchmark> benchmarks{
    {"paper", "paper", 30.0}, {"smooth-impact", "s1", 30.0}, {"bouncing", "bouncing", 80.0 / 9}};

// The variants run on a benchmark: all five on the paper's, CN + Mod 3 at Δt/h = ½ and 1 (the
// study's own) on the others, which keeps the program's cost down (the steps of the finest mesh are its cost).
constexpr std::size_t cn_variants = 2;
std::size_t variants_of(std::size_t benchmark) { return benchmark == 0 ? variants.size() : cn_variants; }

struct Run {
  std::size_t benchmark, variant, level;
  mrm::Index elements;
  std::array<mrm::repro::StressMeasures, 4> measures;
  mrm::repro::StressMeasures window_at_cn_width;  // backward Euler only
  std::vector<double> time, exact;
  std::array<std::vector<double>, 4> values;  // kept for the figure's history only
};

// The runs of the study and the meshes N0 4^l, l < K (`middle` the figure's).
struct Study {
  const std::vector<Run>& runs;
  long coarsest, refinements;
  std::size_t middle;
  const Run& at(std::size_t b, std::size_t v, std::size_t l) const {
    for (const Run& r : runs)
      if (r.benchmark == b && r.variant == v && r.level == l) return r;
    throw std::logic_error("fig_stress: no such run");
  }
};

// Step 4: the blocks of every benchmark, variant and stress (one line per mesh), then the history of
// the figure over the last period.
void write_data(std::ostream& out, const Study& study) {
  const auto& stresses = mrm::contact_stress_registry();
  out << "# st_N0 = " << study.coarsest << "\n# st_Nmax = " << (study.coarsest << (2 * (study.refinements - 1)))
      << '\n';
  std::size_t block = 0;
  for (std::size_t b = 0; b < benchmarks.size(); ++b)
    for (std::size_t v = 0; v < variants_of(b); ++v)
      for (const mrm::ContactStressEntry& e : stresses) {
        out << (block == 0 ? "" : "\n\n") << "# block " << block << ": benchmark = " << benchmarks[b].name
            << ", variant = " << variants[v].key << ", stress = " << e.name << "\n# block " << benchmarks[b].key << ':'
            << variants[v].key << ':' << e.name << " = " << block
            << "\n# columns: N tv_ratio l2_error max_error_away\n";
        ++block;
        for (std::size_t l = 0; l < static_cast<std::size_t>(study.refinements); ++l) {
          const mrm::repro::StressMeasures& s = study.at(b, v, l).measures[static_cast<std::size_t>(e.stress)];
          out << study.at(b, v, l).elements << ' ' << cli::format_real(s.tv_ratio) << ' '
              << cli::format_real(s.l2_error) << ' ' << cli::format_real(s.max_error_away) << '\n';
        }
      }
  const Run& shown = study.at(0, 0, study.middle);
  out << "\n\n# block " << block << ": history over the last period, paper, cn:c12, N = " << shown.elements
      << "\n# block history = " << block << "\n# history_N = " << shown.elements
      << "\n# tv_multiplier_N0 = " << cli::format_real(study.at(0, 0, 0).measures[0].tv_ratio)
      << "\n# columns: t exact multiplier box window recovered\n";
  for (std::size_t i = 0; i < shown.time.size(); ++i) {
    out << cli::format_real(shown.time[i]) << ' ' << cli::format_real(shown.exact[i]);
    for (std::size_t s = 0; s < 4; ++s)
      out << ' ' << (i < shown.values[s].size() ? cli::format_real(shown.values[s][i]) : std::string("?"));
    out << '\n';
  }
}

// Step 5: the table of the stresses with their slopes and the target's verdict, the wake of the matched
// mass's window, backward Euler's window at CN's width, and the values of the prose.
void write_values(std::ostream& defs, const Study& study) {
  const auto& stresses = mrm::contact_stress_registry();
  const Run& shown = study.at(0, 0, study.middle);
  mrm::tex_define(defs, "st:Nmin", std::to_string(study.coarsest));
  for (const Benchmark& b : benchmarks)  // each benchmark's horizon, for the captions
    mrm::tex_define(defs, std::string("st:T:") + b.key, mrm::significant(b.final_time, 3));
  mrm::tex_define(defs, "st:Nmax",
                  std::to_string(study.at(0, 0, static_cast<std::size_t>(study.refinements - 1)).elements));
  mrm::tex_define(defs, "st:Nshown", std::to_string(shown.elements));
  std::vector<std::string> headers{"data", "variant", "stress"};
  for (long l = 0; l < study.refinements; ++l)
    headers.push_back("$\\mathrm{TV}_{" + std::to_string(study.coarsest << (2 * l)) + "}$");
  headers.push_back("slope");
  for (long l = 0; l < study.refinements; ++l)
    headers.push_back("$L^2_{" + std::to_string(study.coarsest << (2 * l)) + "}$");
  headers.push_back("away");
  headers.push_back("target");
  mrm::repro::Table table(headers);
  std::ostringstream summary;
  std::vector<double> steps;
  for (long l = 0; l < study.refinements; ++l) steps.push_back(1.0 / static_cast<double>(study.coarsest << (2 * l)));
  for (std::size_t b = 0; b < benchmarks.size(); ++b) {
    for (std::size_t v = 0; v < variants_of(b); ++v)
      for (const mrm::ContactStressEntry& e : stresses) {
        const std::size_t s = static_cast<std::size_t>(e.stress);
        const std::string key = std::string(benchmarks[b].key) + ":" + variants[v].key + ":" + e.name;
        std::vector<std::string> row{benchmarks[b].key, variants[v].label, e.name};
        std::vector<double> tv, l2;
        bool met = true;
        double worst = 0;  // the largest ratio over the meshes
        for (std::size_t l = 0; l < static_cast<std::size_t>(study.refinements); ++l) {
          const mrm::repro::StressMeasures& m = study.at(b, v, l).measures[s];
          // The reference of the L² condition: CN + Mod 3's multiplier at the same Δt/h.
          const std::size_t reference = variants[v].courant == 1.0 ? 1 : 0;
          const double l2_reference = study.at(b, reference, l).measures[0].l2_error;
          met = met && m.tv_ratio <= 2.0 && m.l2_error <= l2_reference;
          worst = std::max(worst, m.tv_ratio);
          tv.push_back(m.tv_ratio), l2.push_back(m.l2_error);
          row.push_back(mrm::tex_number(m.tv_ratio, 3));
          const std::string n = ":N" + std::to_string(study.at(b, v, l).elements);
          mrm::tex_define(defs, "st:tv:" + key + n, mrm::tex_number(m.tv_ratio, 3));
          mrm::tex_define(defs, "st:l2:" + key + n, mrm::tex_number(m.l2_error, 2));
          mrm::tex_define(defs, "st:away:" + key + n, mrm::tex_number(m.max_error_away, 2));
          if (l == 0 || l + 1 == static_cast<std::size_t>(study.refinements)) {  // the first and the last mesh
            const std::string which = l == 0 ? ":first" : ":last";
            mrm::tex_define(defs, "st:tv:" + key + which, mrm::tex_number(m.tv_ratio, 3));
            mrm::tex_define(defs, "st:l2:" + key + which, mrm::tex_number(m.l2_error, 2));
            mrm::tex_define(defs, "st:away:" + key + which, mrm::tex_number(m.max_error_away, 2));
          }
        }
        // The slope of TV against N (the order of growth, −fit over h).
        const double slope = -mrm::fit_order(steps, tv).order;
        const double l2_slope = mrm::fit_order(steps, l2).order;
        row.push_back(mrm::tex_number(slope, 2));
        for (double x : l2) row.push_back(mrm::tex_number(x, 2));
        row.push_back(mrm::tex_number(
            study.at(b, v, static_cast<std::size_t>(study.refinements - 1)).measures[s].max_error_away, 2));
        row.push_back(met ? "met" : "not met");
        mrm::tex_define(defs, "st:tvslope:" + key, mrm::tex_number(slope, 2));
        mrm::tex_define(defs, "st:l2order:" + key, mrm::tex_number(l2_slope, 2));
        mrm::tex_define(defs, "st:target:" + key, met ? "met" : "not met");
        mrm::tex_define(defs, "st:worst:" + key, mrm::tex_number(worst, 3));
        table.add_row(row);
        summary << key << ": TV ratio";
        for (double x : tv) summary << ' ' << x;
        summary << " (slope " << slope << "), L2";
        for (double x : l2) summary << ' ' << x;
        summary << " (order " << l2_slope << "), away "
                << study.at(b, v, static_cast<std::size_t>(study.refinements - 1)).measures[s].max_error_away
                << ", target " << (met ? "met" : "not met") << '\n';
      }
    if (b + 1 < benchmarks.size()) table.add_rule();
  }
  // The keys of mesh l: ":N<n>", and ":first", ":mid" (the middle mesh), ":last" where it is one of those.
  auto position_keys = [&](std::size_t l) {
    std::vector<std::string> keys{":N" + std::to_string(study.at(0, 0, l).elements)};
    if (l == 0) keys.push_back(":first");
    if (l == study.middle) keys.push_back(":mid");
    if (l + 1 == static_cast<std::size_t>(study.refinements)) keys.push_back(":last");
    return keys;
  };
  // The level of the B-spline window's ratio with the matched mass (contact_stress.cpp §2b): the wake
  // left after the window has TV ∝ J (μ(μ + 1))^{1/2}/(p − (μ + 1)/2), whatever C, t and h, so the
  // excess of the ratio over 1 with μ = 4 is predicted at (√20/1.5)/(√6/2.5) = 3.04 times CN's (μ = 2),
  // each at its own width 8W; a prediction from CN's measured excess, not a fit.
  {
    const double p = 4;
    auto wake = [&](double mu) { return std::sqrt(mu * (mu + 1)) / (p - (mu + 1) / 2); };
    const double factor = wake(4) / wake(2);
    mrm::tex_define(defs, "st:wake:factor", mrm::tex_number(factor, 3));
    summary << "window level with the matched mass: predicted 1 + " << factor << " (CN's ratio - 1):";
    for (std::size_t l = 0; l < static_cast<std::size_t>(study.refinements); ++l) {
      const double cn = study.at(0, 0, l).measures[static_cast<std::size_t>(mrm::ContactStress::window)].tv_ratio;
      const double pm = study.at(0, 2, l).measures[static_cast<std::size_t>(mrm::ContactStress::window)].tv_ratio;
      for (const std::string& n : position_keys(l)) {
        mrm::tex_define(defs, "st:wake:predicted" + n, mrm::tex_number(1 + factor * (cn - 1), 3));
        mrm::tex_define(defs, "st:wake:measured" + n, mrm::tex_number(pm, 3));
        mrm::tex_define(defs, "st:wake:measured-factor" + n, mrm::tex_number((pm - 1) / (cn - 1), 3));
      }
      summary << " N = " << study.at(0, 0, l).elements << ": " << 1 + factor * (cn - 1) << " (measured " << pm
              << ", excess ratio " << (pm - 1) / (cn - 1) << ")";
    }
    summary << '\n';
  }
  // Backward Euler's window at CN's width (the width before §1b), beside its own.
  summary << "paper:be:c12:window at CN's width: TV ratio";
  for (std::size_t l = 0; l < static_cast<std::size_t>(study.refinements); ++l) {
    const mrm::repro::StressMeasures& m = study.at(0, be_variant, l).window_at_cn_width;
    for (const std::string& n : position_keys(l)) {
      mrm::tex_define(defs, "st:tv:paper:be:c12:window-cn" + n, mrm::tex_number(m.tv_ratio, 3));
      mrm::tex_define(defs, "st:l2:paper:be:c12:window-cn" + n, mrm::tex_number(m.l2_error, 2));
    }
    summary << ' ' << m.tv_ratio;
  }
  summary << ", L2";
  for (std::size_t l = 0; l < static_cast<std::size_t>(study.refinements); ++l)
    summary << ' ' << study.at(0, be_variant, l).window_at_cn_width.l2_error;
  summary << '\n';
  // In two halves at the text size: the ratios with their slope and the verdict, then the errors.
  const std::size_t k = static_cast<std::size_t>(study.refinements);
  std::vector<std::size_t> first{0, 1, 2}, second{0, 1, 2};
  for (std::size_t l = 0; l <= k; ++l) first.push_back(3 + l);       // the ratios and the slope
  first.push_back(5 + 2 * k);                                        // the verdict
  for (std::size_t l = 0; l <= k; ++l) second.push_back(4 + k + l);  // the L² errors and the error away
  defs << "\\mrmdef{st:table:tv}{"
       << mrm::repro::latex_tabular(table.columns_subset(first), "lll" + std::string(k + 1, 'r') + "l") << "}\n";
  defs << "\\mrmdef{st:table:errors}{"
       << mrm::repro::latex_tabular(table.columns_subset(second), "lll" + std::string(k + 1, 'r')) << "}\n";
  std::cout << summary.str();
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_stress", [&] {
    // 1. Options.
    long coarsest = 100, refinements = 3, threads = 2;
    mrm::repro::FigureProgram program(
        "fig_stress",
        "Writes the oscillation TV(stress)/TV(lambda_exact), the L2 error and the largest error away from the jumps "
        "of four contact stresses (the multiplier, box and B-spline windows of width 8W, the recovered strain) for "
        "CN + Mod 3, phase-matched CN and CN-switch on the paper's benchmark, S1 and bouncing over ten periods.",
        {"fig_stress --output output/data/fig_stress.dat --tex output/data/fig_stress.tex",
         "fig_stress --coarsest 50 --refinements 2 --output s.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0", "number of elements of the coarsest mesh, in [10, 1e4]",
                               &coarsest, cli::in_closed_range(10, 10000));
    program.parser.add_integer("--refinements", "-k", "K", "meshes N0, 4 N0, ..., 4^(K-1) N0, in [2, 5]", &refinements,
                               cli::in_closed_range(2, 5));
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the table and values the report quotes")) return 0;
    if (!(static_cast<double>(coarsest) * std::pow(4.0, static_cast<double>(refinements - 1)) <= 1e4))
      throw cli::UsageError("--coarsest: the finest mesh N0 4^(K-1) must be at most 1e4 elements");

    // 2. Outputs.
    program.open();

    // 3. The runs; the stresses of each from its histories.
    const std::size_t middle = static_cast<std::size_t>(refinements - 1) / 2;
    std::vector<Run> runs;
    for (std::size_t b = 0; b < benchmarks.size(); ++b)
      for (std::size_t v = 0; v < variants_of(b); ++v)
        for (long l = 0; l < refinements; ++l)
          runs.push_back(
              {b, v, static_cast<std::size_t>(l), static_cast<mrm::Index>(coarsest) << (2 * l), {}, {}, {}, {}, {}});
    auto configuration = [&](const Run& r) {
      const Variant& variant = variants[r.variant];
      return mrm::repro::study_configuration(benchmarks[r.benchmark].name, variant.scheme, mrm::mod3(variant.blend),
                                             r.elements, variant.courant, benchmarks[r.benchmark].final_time);
    };
    std::vector<mrm::repro::Configuration> configurations;
    for (const Run& r : runs) {
      mrm::repro::Configuration c = configuration(r);
      c.keep_stress_history = true;
      c.measure_errors = false;  // the stresses only
      configurations.push_back(c);
    }
    const auto start = std::chrono::steady_clock::now();
    mrm::repro::SweepSettings settings;
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::require_batched_memory("--coarsest", configurations, settings);  // before any run
    const std::vector<mrm::repro::Measures> measures = mrm::repro::run_batched(configurations, settings);
    for (std::size_t k = 0; k < runs.size(); ++k) {
      Run& r = runs[k];
      const mrm::repro::Configuration& c = configurations[k];
      const mrm::repro::StressHistory& h = *measures[k].stress_history;
      for (const mrm::ContactStressEntry& e : mrm::contact_stress_registry())
        r.measures[static_cast<std::size_t>(e.stress)] = mrm::repro::stress_measures(h, e.stress);
      if (r.variant == be_variant) {  // the same history, the window at CN's width
        mrm::repro::StressHistory at_cn = h;
        at_cn.order = mrm::crank_nicolson_phase_order(variants[r.variant].courant, variants[r.variant].blend);
        r.window_at_cn_width = mrm::repro::stress_measures(at_cn, mrm::ContactStress::window);
      }
      if (r.benchmark == 0 && r.variant == 0 && r.level == middle) {  // the figure's history, last period
        for (const mrm::ContactStressEntry& e : mrm::contact_stress_registry()) {
          const std::vector<double> values = h.values(e.stress);
          const std::vector<double>& t = h.instants(e.stress);
          for (std::size_t i = 0; i < t.size(); ++i)
            if (t[i] >= c.final_time - 3.0) r.values[static_cast<std::size_t>(e.stress)].push_back(values[i]);
        }
        for (std::size_t i = 0; i < h.time.size(); ++i)
          if (h.time[i] >= c.final_time - 3.0) r.time.push_back(h.time[i]), r.exact.push_back(h.exact[i]);
      }
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "fig_stress: " << runs.size() << " runs in " << wall << " s\n";
    const Study study{runs, coarsest, refinements, middle};

    // 4. The data.
    write_data(program.header("contact stresses: oscillation TV ratio, L2 error, error away from jumps"), study);

    // 5. The table, slopes, the target's verdict and the values.
    write_values(program.values(), study);

    // 6. Commit.
    program.commit();
    return 0;
  });
}
