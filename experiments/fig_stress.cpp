// fig_stress: a contact stress whose oscillation does not grow as the mesh is refined.
//
// What it computes. For each benchmark (the paper's, S1 = smooth-impact, bouncing), each variant of the
// scheme (CN + Mod 3 at Δt/h = ½ and 1 with the consistent interior mass, CN + Mod 3 with the
// phase-matched A = ¼ at Δt/h = ½, CN-switch (θ = 1 at status changes) with A = ¼ at ½ and A = 0 at 1,
// backward Euler at ½, whose windows are also measured at CN's width, the width before each scheme had
// its own: contact_stress.cpp §1b) (the last four on the paper's benchmark only) and each mesh
// N = N₀ 4^l, one run over T = 30 on the unit bar (ten periods of the paper's benchmark; the same T on
// S1) and T = 80/9 on bouncing (three of its contacts, which come every 8L/c = 8/3 from t = 1), and from
// that one run the stresses of lib/measures/contact_stress.hpp (multiplier, box, window, recovered, gated):
// TV(stress)/TV(λ_exact), the relative L² error, and the largest error away from the exact status
// changes (repro::stress_measures), with the slope of each against N (least squares over the meshes).
//
// Predictions (lib/measures/contact_stress.cpp, derived there before any measurement). The multiplier's ratio
// grows like N^{1/2} for every variant (the wake of the smeared fronts runs down to the grid scale);
// the box window of width 8W like N^{1/6} (μ = 2) or N^{3/10} (μ = 4); the recovered stress like the
// box; the B-spline window of width 8W stays bounded (slope 0); the gated stress is, run by run, the window
// or the multiplier (§6). The L² errors of the first four are O(W^{1/2}):
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
// max_error_away; then one block with the stresses and the exact λ over the last period of the
// paper's benchmark, CN + Mod 3, Δt/h = ½, on the middle mesh (the figure's bottom panel); then one block
// per (case, stress) of the default stress's region (below: columns N tv_ratio l2_error G).
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "exact/benchmarks.hpp"
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
  std::vector<mrm::repro::StressMeasures> measures;  // indexed by ContactStress
  mrm::repro::StressMeasures window_at_cn_width;     // backward Euler only
  std::vector<double> time, exact;
  std::vector<std::vector<double>> values;  // kept for the figure's history only, indexed by ContactStress
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
      << "\n# columns: t exact";
  for (const mrm::ContactStressEntry& e : stresses) out << ' ' << e.name;
  out << '\n';
  for (std::size_t i = 0; i < shown.time.size(); ++i) {
    out << cli::format_real(shown.time[i]) << ' ' << cli::format_real(shown.exact[i]);
    for (std::size_t s = 0; s < stresses.size(); ++s)
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

// ---------------------------------------------------------------------------------------------------
// The default stress over a region: the gate (contact_stress.cpp §6) against the multiplier and the
// window's width, for the default scheme (CN + Mod 3, Δt/h = ½, A = 0), on the meshes N_g 2^l.
//
// The cases: the three whose exact λ jumps (the paper's benchmark over T = 30, bouncing and impacting over
// their own horizons, the registry's T), where the multiplier rattles; the smooth S2 (grazing) and S1 at
// their own T = 2, where it does not; and S1 over T = 30, whose λ is smooth but whose fronts have had
// fifteen times longer to smear. The criteria, stated before the runs:
//   (a) every case, every mesh: L²(gated) ≤ L²(multiplier). A default that smooths must not be less
//       accurate than the multiplier it replaces. Where the gate keeps the multiplier the two are the same
//       numbers, so this judges the cases where it fires.
//   (b) the jump cases, every mesh: TV(gated)/TV(λ) ≤ 2, the stress study's bound.
//   (c) the smooth cases: the L² order fitted over the last four meshes at least the multiplier's minus
//       2σ, σ² = σ_g² + σ_m² the two fits' squared standard errors (OrderFit::order_std_error).
// The window's width: the B-spline window at 4W, 8W (the registry's) and 16W, measured without a verdict
// (the gate decides with the 8W window).
struct GateCase {
  const char* benchmark;  // Configuration::benchmark
  const char* key;
  double final_time;
  bool jumps;  // the exact λ jumps: criterion (b); else (c)
};
std::vector<GateCase> gate_cases() {
  return {{"paper", "paper", 30.0, true},
          {"bouncing", "bouncing", mrm::benchmark("bouncing").final_time, true},
          {"impacting", "impacting", mrm::benchmark("impacting").final_time, true},
          {"smooth-impact", "s1:T30", 30.0, false},
          {"smooth-impact", "s1:T2", 2.0, false},
          {"grazing", "s2", 2.0, false}};
}
std::string gate_case_label(const GateCase& c) {  // the horizon only where the benchmark is met twice
  const std::string key = c.key;
  if (key == "s1:T30" || key == "s1:T2") return "S1, $T = " + mrm::significant(c.final_time, 3) + "$";
  return key == "s2" ? "S2" : key;
}

// The stresses of the gate study, in the order of its tables.
enum GateStress { gate_multiplier, gate_window4, gate_window8, gate_window16, gate_gated, gate_stresses };
const char* const gate_stress_keys[gate_stresses] = {"multiplier", "window4", "window8", "window16", "gated"};
const char* const gate_stress_labels[gate_stresses] = {"multiplier", "window $4W$", "window $8W$", "window $16W$",
                                                       "gated"};

struct GateRun {
  std::size_t which, level;
  mrm::Index elements;
  std::array<mrm::repro::StressMeasures, gate_stresses> measures;
  double G = 0;  // TV(multiplier)/TV(window 8W), the gate's indicator
};

GateRun measure_gate_run(std::size_t which, std::size_t level, mrm::Index elements,
                         const mrm::repro::StressHistory& h) {
  GateRun r{which, level, elements, {}, 0};
  r.measures[gate_multiplier] = mrm::repro::stress_measures(h, mrm::ContactStress::multiplier);
  mrm::repro::StressHistory widths = h;
  for (const auto& [k, factor] : {std::pair{gate_window4, 4.0}, {gate_window8, 8.0}, {gate_window16, 16.0}}) {
    widths.width_factor = factor;
    r.measures[k] = mrm::repro::stress_measures(widths, mrm::ContactStress::window);
  }
  r.measures[gate_gated] = mrm::repro::stress_measures(h, mrm::ContactStress::gated);
  r.G = mrm::gate_indicator(h.multiplier, h.values(mrm::ContactStress::window));
  return r;
}

struct GateStudy {
  std::vector<GateCase> cases;
  std::vector<GateRun> runs;
  long coarsest, refinements;
  const GateRun& at(std::size_t c, std::size_t l) const {
    for (const GateRun& r : runs)
      if (r.which == c && r.level == l) return r;
    throw std::logic_error("fig_stress: no such gate run");
  }
  std::size_t levels() const { return static_cast<std::size_t>(refinements); }
  std::size_t fit_from() const { return levels() > 4 ? levels() - 4 : 0; }  // the last four meshes
};

// The blocks write_data writes: one per (benchmark, variant, stress), then the history.
std::size_t first_gate_block() {
  std::size_t blocks = 0;
  for (std::size_t b = 0; b < benchmarks.size(); ++b) blocks += variants_of(b) * mrm::contact_stress_registry().size();
  return blocks + 1;
}

// The data: one block per (case, stress) with the columns N tv_ratio l2_error G.
void write_gate_data(std::ostream& out, const GateStudy& study, std::size_t first_block) {
  std::size_t block = first_block;
  for (std::size_t c = 0; c < study.cases.size(); ++c)
    for (std::size_t s = 0; s < gate_stresses; ++s) {
      out << "\n\n# block " << block << ": the default stress's region, benchmark = " << study.cases[c].benchmark
          << ", T = " << cli::format_real(study.cases[c].final_time) << ", stress = " << gate_stress_keys[s]
          << "\n# block gate:" << study.cases[c].key << ':' << gate_stress_keys[s] << " = " << block
          << "\n# columns: N tv_ratio l2_error G\n";
      ++block;
      for (std::size_t l = 0; l < study.levels(); ++l) {
        const GateRun& r = study.at(c, l);
        out << r.elements << ' ' << cli::format_real(r.measures[s].tv_ratio) << ' '
            << cli::format_real(r.measures[s].l2_error) << ' ' << cli::format_real(r.G) << '\n';
      }
    }
}

// An order with its standard error in units of its last digit (three decimals), "0.321(2)": the error
// rounded up, at least 1.
std::string order_with_error(const mrm::OrderFit& fit) {
  char order[32];
  std::snprintf(order, sizeof order, "%.3f", fit.order);
  const double error = std::max(1.0, std::ceil(fit.order_std_error * 1000 - 1e-9));
  return std::string(order) + "(" + std::to_string(static_cast<long>(error)) + ")";
}

// The tables (TV ratios with the indicator G; L² errors with the orders and the verdict) and the values.
void write_gate_values(std::ostream& defs, const GateStudy& study) {
  const std::size_t k = study.levels(), from = study.fit_from();
  std::vector<double> steps;
  for (std::size_t l = 0; l < k; ++l) steps.push_back(1.0 / static_cast<double>(study.at(0, l).elements));
  const std::vector<double> fit_steps(steps.begin() + static_cast<std::ptrdiff_t>(from), steps.end());
  mrm::tex_define(defs, "st:gate:Nmin", std::to_string(study.at(0, 0).elements));
  mrm::tex_define(defs, "st:gate:Nmax", std::to_string(study.at(0, k - 1).elements));
  mrm::tex_define(defs, "st:gate:fit:Nmin", std::to_string(study.at(0, from).elements));
  mrm::tex_define(defs, "st:gate:threshold", mrm::tex_number(mrm::gate_threshold, 3));
  for (const GateCase& c : study.cases)  // each case's horizon, for the prose
    mrm::tex_define(defs, std::string("st:gate:T:") + c.key, mrm::significant(c.final_time, 3));
  std::vector<std::string> tv_headers{"case", "stress"}, l2_headers{"case", "stress"};
  for (std::size_t l = 0; l < k; ++l) {
    tv_headers.push_back("$\\mathrm{TV}_{" + std::to_string(study.at(0, l).elements) + "}$");
    l2_headers.push_back("$L^2_{" + std::to_string(study.at(0, l).elements) + "}$");
  }
  tv_headers.push_back("slope");
  l2_headers.push_back("order");
  l2_headers.push_back("verdict");
  mrm::repro::Table tv_table(tv_headers), l2_table(l2_headers);
  std::ostringstream summary;
  double fired_min = std::numeric_limits<double>::infinity(), kept_max = 0;
  bool all_met = true;
  for (std::size_t c = 0; c < study.cases.size(); ++c) {
    const GateCase& gc = study.cases[c];
    const std::string label = gate_case_label(gc);
    std::array<mrm::OrderFit, gate_stresses> fits;
    for (std::size_t s = 0; s < gate_stresses; ++s) {
      std::vector<double> tv, l2;
      for (std::size_t l = 0; l < k; ++l) {
        const mrm::repro::StressMeasures& m = study.at(c, l).measures[s];
        tv.push_back(m.tv_ratio), l2.push_back(m.l2_error);
        const std::string n =
            std::string(":") + gc.key + ":" + gate_stress_keys[s] + ":N" + std::to_string(study.at(c, l).elements);
        mrm::tex_define(defs, "st:gate:tv" + n, mrm::tex_number(m.tv_ratio, 3));
        mrm::tex_define(defs, "st:gate:l2" + n, mrm::tex_number(m.l2_error, 2));
        if (l + 1 == k) {  // the finest mesh, also under ":last"
          const std::string last = std::string(":") + gc.key + ":" + gate_stress_keys[s] + ":last";
          mrm::tex_define(defs, "st:gate:tv" + last, mrm::tex_number(m.tv_ratio, 3));
          mrm::tex_define(defs, "st:gate:l2" + last, mrm::tex_number(m.l2_error, 2));
        }
      }
      fits[s] =
          mrm::fit_order(fit_steps, std::vector<double>(l2.begin() + static_cast<std::ptrdiff_t>(from), l2.end()));
      const double slope = -mrm::fit_order(steps, tv).order;
      const std::string key = std::string(gc.key) + ":" + gate_stress_keys[s];
      mrm::tex_define(defs, "st:gate:order:" + key, mrm::tex_number(fits[s].order, 2));
      mrm::tex_define(defs, "st:gate:tvslope:" + key, mrm::tex_number(slope, 2));
      std::vector<std::string> tv_row{s == 0 ? label : "", gate_stress_labels[s]},
          l2_row{s == 0 ? label : "", gate_stress_labels[s]};
      for (double x : tv) tv_row.push_back(mrm::tex_number(x, 3));
      tv_row.push_back(mrm::tex_number(slope, 2));
      for (double x : l2) l2_row.push_back(mrm::tex_number(x, 2));
      l2_row.push_back(order_with_error(fits[s]));
      summary << "gate " << key << ": TV";
      for (double x : tv) summary << ' ' << x;
      summary << ", L2";
      for (double x : l2) summary << ' ' << x;
      summary << " (order " << fits[s].order << " +- " << fits[s].order_std_error
              << " over N >= " << study.at(c, from).elements << ")\n";
      if (s + 1 < gate_stresses) {
        l2_row.push_back("");
      } else {
        // The verdict of the default (criteria (a)-(c) above), with its margins.
        bool met = true;
        double worst_l2 = 0, worst_tv = 0;
        for (std::size_t l = 0; l < k; ++l) {
          const GateRun& r = study.at(c, l);
          const double ratio = r.measures[gate_gated].l2_error / r.measures[gate_multiplier].l2_error;
          worst_l2 = std::max(worst_l2, ratio);
          worst_tv = std::max(worst_tv, r.measures[gate_gated].tv_ratio);
          met = met && ratio <= 1.0;
          if (gc.jumps) met = met && r.measures[gate_gated].tv_ratio <= 2.0;
          if (r.G > mrm::gate_threshold)  // the gate's own rule (gated_stress): it fired
            fired_min = std::min(fired_min, r.G);
          else
            kept_max = std::max(kept_max, r.G);
        }
        const double sigma = std::hypot(fits[gate_gated].order_std_error, fits[gate_multiplier].order_std_error);
        const double order_margin = fits[gate_gated].order - (fits[gate_multiplier].order - 2 * sigma);
        if (!gc.jumps) met = met && order_margin >= 0;
        all_met = all_met && met;
        l2_row.push_back(met ? "met" : "not met");
        mrm::tex_define(defs, "st:gate:verdict:" + std::string(gc.key), met ? "met" : "not met");
        mrm::tex_define(defs, "st:gate:l2ratio:" + std::string(gc.key), mrm::tex_number(worst_l2, 3));
        mrm::tex_define(defs, "st:gate:worsttv:" + std::string(gc.key), mrm::tex_number(worst_tv, 3));
        mrm::tex_define(defs, "st:gate:ordermargin:" + std::string(gc.key), mrm::tex_number(order_margin, 2));
        summary << "gate verdict " << gc.key << ": " << (met ? "met" : "not met")
                << " (largest L2 ratio gated/multiplier " << worst_l2 << ", largest TV ratio " << worst_tv
                << ", order margin " << order_margin << ")\n";
      }
      tv_table.add_row(tv_row);
      l2_table.add_row(l2_row);
    }
    // The indicator G = TV(multiplier)/TV(window 8W) per mesh, under the case's TV rows.
    std::vector<std::string> g_row{"", "$G$"};
    std::vector<double> g;
    for (std::size_t l = 0; l < k; ++l) {
      g.push_back(study.at(c, l).G);
      g_row.push_back(mrm::tex_number(study.at(c, l).G, 3));
      mrm::tex_define(defs, "st:gate:G:" + std::string(gc.key) + ":N" + std::to_string(study.at(c, l).elements),
                      mrm::tex_number(study.at(c, l).G, 3));
      if (l + 1 == k)
        mrm::tex_define(defs, "st:gate:G:" + std::string(gc.key) + ":last", mrm::tex_number(study.at(c, l).G, 3));
    }
    g_row.push_back(mrm::tex_number(-mrm::fit_order(steps, g).order, 2));
    tv_table.add_row(g_row);
    if (c + 1 < study.cases.size()) tv_table.add_rule(), l2_table.add_rule();
  }
  // How well the threshold separates: the smallest G where the gate fired over τ, τ over the largest G
  // where it kept the multiplier.
  mrm::tex_define(defs, "st:gate:G:fired:min", mrm::tex_number(fired_min, 3));
  mrm::tex_define(defs, "st:gate:G:kept:max", mrm::tex_number(kept_max, 3));
  mrm::tex_define(defs, "st:gate:verdict", all_met ? "met" : "not met");
  summary << "gate: fired for G >= " << fired_min << ", kept the multiplier for G <= " << kept_max << " (threshold "
          << mrm::gate_threshold << "); every case " << (all_met ? "met" : "not met") << '\n';
  defs << "\\mrmdef{st:table:gate:tv}{" << mrm::repro::latex_tabular(tv_table, "ll" + std::string(k + 1, 'r')) << "}\n";
  defs << "\\mrmdef{st:table:gate:l2}{" << mrm::repro::latex_tabular(l2_table, "ll" + std::string(k + 1, 'r') + "l")
       << "}\n";
  std::cout << summary.str();
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_stress", [&] {
    // 1. Options.
    long coarsest = 100, refinements = 3, gate_coarsest = 100, gate_refinements = 6, threads = 2;
    mrm::repro::FigureProgram program(
        "fig_stress",
        "Writes the oscillation TV(stress)/TV(lambda_exact), the L2 error and the largest error away from the jumps "
        "of the contact stresses (the multiplier, box and B-spline windows of width 8W, the recovered strain, the "
        "gate) for "
        "CN + Mod 3, phase-matched CN and CN-switch on the paper's benchmark (ten periods), S1 and bouncing; then the "
        "default (gated) stress against the multiplier and the window at 4W, 8W, 16W over a region of six cases.",
        {"fig_stress --output output/data/fig_stress.dat --tex output/data/fig_stress.tex",
         "fig_stress --coarsest 50 --refinements 2 --output s.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0", "number of elements of the coarsest mesh, in [10, 1e4]",
                               &coarsest, cli::in_closed_range(10, 10000));
    program.parser.add_integer("--refinements", "-k", "K", "meshes N0, 4 N0, ..., 4^(K-1) N0, in [2, 5]", &refinements,
                               cli::in_closed_range(2, 5));
    program.parser.add_integer("--gate-coarsest", "", "NG",
                               "coarsest mesh of the default stress's region (meshes NG 2^l), in [10, 1e4]",
                               &gate_coarsest, cli::in_closed_range(10, 10000));
    program.parser.add_integer("--gate-refinements", "", "KG", "meshes NG, 2 NG, ..., 2^(KG-1) NG, in [2, 8]",
                               &gate_refinements, cli::in_closed_range(2, 8));
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the table and values the report quotes")) return 0;
    if (!(static_cast<double>(coarsest) * std::pow(4.0, static_cast<double>(refinements - 1)) <= 1e4))
      throw cli::UsageError("--coarsest: the finest mesh N0 4^(K-1) must be at most 1e4 elements");
    if (!(static_cast<double>(gate_coarsest) * std::pow(2.0, static_cast<double>(gate_refinements - 1)) <= 1e4))
      throw cli::UsageError("--gate-coarsest: the finest mesh NG 2^(KG-1) must be at most 1e4 elements");

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
    // The default stress's region: CN + Mod 3 at Δt/h = ½ on each case and mesh (after the study's runs).
    const std::vector<GateCase> cases = gate_cases();
    std::vector<std::pair<std::size_t, long>> gate_runs;  // (case, level)
    for (std::size_t g = 0; g < cases.size(); ++g)
      for (long l = 0; l < gate_refinements; ++l) {
        mrm::repro::Configuration c =
            mrm::repro::study_configuration(cases[g].benchmark, mrm::Scheme::crank_nicolson, mrm::mod3(),
                                            static_cast<mrm::Index>(gate_coarsest) << l, 0.5, cases[g].final_time);
        c.keep_stress_history = true;
        c.measure_errors = false;
        configurations.push_back(c);
        gate_runs.emplace_back(g, l);
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
      r.measures.resize(mrm::contact_stress_registry().size());
      r.values.resize(mrm::contact_stress_registry().size());
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
    GateStudy gate{cases, {}, gate_coarsest, gate_refinements};
    for (std::size_t k = 0; k < gate_runs.size(); ++k) {
      const mrm::repro::Configuration& c = configurations[runs.size() + k];
      gate.runs.push_back(measure_gate_run(gate_runs[k].first, static_cast<std::size_t>(gate_runs[k].second),
                                           c.elements, *measures[runs.size() + k].stress_history));
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "fig_stress: " << configurations.size() << " runs in " << wall << " s\n";
    const Study study{runs, coarsest, refinements, middle};

    // 4. The data.
    std::ostream& data = program.header("contact stresses: oscillation TV ratio, L2 error, error away from jumps");
    write_data(data, study);
    write_gate_data(data, gate, first_gate_block());

    // 5. The table, slopes, the target's verdict and the values.
    write_values(program.values(), study);
    write_gate_values(program.values(), gate);

    // 6. Commit.
    program.commit();
    return 0;
  });
}
