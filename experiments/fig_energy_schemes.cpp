// fig_energy_schemes: Crank–Nicolson's energy and the two schemes that fix it (mathematics.md §12).
//
// What it computes. The discrete energy E_hⁿ of Crank–Nicolson (cn), energy-conserving Crank–Nicolson
// (ec), Crank–Nicolson with a θ-step at each change of the contact status (cn-switch, θ = --switch-theta,
// 1: backward Euler) and backward Euler (be) on the benchmark of mathematics.md §2, and what each costs
// in accuracy, in three views, one data file each (--view):
//   history   E_hⁿ/E_h(0) over 10 periods (T = 30) at Δt = h/2, h and 5h, on one mesh and mass
//             (--elements, --mass);
//   map       the largest E_hⁿ/E_h(0) over 100 periods (T = 300) against Δt/h = ¼ … 40 for N = 16, 32,
//             64, 128 (--mass), with the smallest and the final ratio and the largest one-step increase;
//             then the two long runs the report quotes, for Mod 1, 2 and 3: N = 16, Δt = 10h over 100
//             periods and N = 20, Δt = h over 1000 periods, where Crank–Nicolson gains most. The largest
//             one-step increase of CN-switch and backward Euler, whose exact energies never increase, is
//             measured against the round-off bound 16 N ε (1 + h/Δt) E₀ of energy_step.cpp §5 on every
//             run: the program fails if one is above it; and the drifting bar: EC with Mod 3 on the
//             layered bar (N = 50, 100, Δt = h/(2c)), which leaves the wall at t = 4.1 and flies off with
//             its free end, its energy's range up to t = 100, 300, 1000 against u(0, t)² (§5's model
//             assumes a clamped end);
//   measures  the eight relative errors of mathematics.md §5 of each scheme with Mod 1, 2 and 3 at
//             N = 100 and 400, Δt = h/2, T = 30, their ratios to Crank–Nicolson's, and the energy lost,
//             1 − E_h(T)/E_h(0) (in the data file; in per cent in the report's values), with the table of
//             each mesh in three parts (three, three and two measures, the energy lost with the last) so
//             that each fits the text width.
// Every run is repro/configurations' run_configuration, observed step by step for the energy, through the
// sweep layer (repro/sweep.hpp: runs of one mesh and scheme family in vector lanes, each bitwise its run
// alone, the batches shared among --threads workers; the observer reads the energy only, so the lanes are
// read in place): the output does not depend on the number of threads. EC needs a massless contact node:
// every mass here is Mod 1, 2 or 3.
//
// Sample runs:
//   fig_energy_schemes --view history --output output/data/fig_energy_schemes_history.dat
//   fig_energy_schemes --view map --threads 1 --output map.dat --tex map.tex
//
// Description. Steps: (1) options; (2) outputs; (3) the runs of the view through the sweep layer;
// (4) the data blocks; (5) the values and tables the report quotes; (6) commit.
//
// Data files. history: block 4 c + s is ratio c ∈ (1/2, 1, 5), scheme s ∈ (cn, ec, cn-switch, be),
// columns t_energy energy_ratio. map: block 4 s + k is scheme s, mesh k ∈ (16, 32, 64, 128), columns
// dt_over_h largest smallest final largest_increase increase_bound; block 16 the long runs, columns run
// scheme mass N dt_over_h periods drift largest_increase largest final increase_bound; block 17 the
// drifting bar, columns N T u0 energy_range model_scale range_over_scale (model_scale = ε N u0²/(L E₀)). measures: block k is N ∈ (100, 400), columns
// scheme mass, the eight measures, the eight ratios to Crank–Nicolson's (same mass), energy_lost.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "batched/batched_step.hpp"
#include "configurations.hpp"
#include "figure_program.hpp"
#include "steps/energy_step.hpp"
#include "options.hpp"
#include "report_values.hpp"
#include "scheme_options.hpp"
#include "time/schemes.hpp"
#include "sweep.hpp"
#include "table.hpp"

namespace cli = mrm::cli;

namespace {

// The schemes compared, in the order of every block and table (labelled by their abbreviations in the
// tables: the captions say CN for Crank–Nicolson and BE for backward Euler).
const std::string cn = mrm::to_string(mrm::Scheme::crank_nicolson), be = mrm::to_string(mrm::Scheme::backward_euler),
                  switching = mrm::to_string(mrm::Scheme::switching);
const std::array<std::string, 4> schemes{cn, mrm::to_string(mrm::Scheme::energy_conserving), switching, be};

// A header cell on two lines (a one-column tabular inside the cell), to keep a table within the width.
std::string stacked(const std::string& top, const std::string& bottom) {
  return "\\begin{tabular}[b]{@{}c@{}}" + top + "\\\\ " + bottom + "\\end{tabular}";
}

// One run and what the views read from it.
struct Run {
  std::string scheme, mass;
  mrm::Index elements = 0;
  double courant = 0, final_time = 0;
  bool history = false;  // keep (t, Eⁿ/E⁰) at every level
  mrm::repro::Measures measures;
  double largest_increase = 0;  // max over the steps of (Eⁿ⁺¹ − Eⁿ)/E⁰
  std::vector<std::pair<double, double>> energy;
};

Run make_run(const std::string& scheme, const std::string& mass, mrm::Index elements, double courant, double final_time,
             bool history = false) {
  Run r;
  r.scheme = scheme, r.mass = mass, r.elements = elements, r.courant = courant, r.final_time = final_time;
  r.history = history;
  return r;
}

// Run k's configuration, and what its observer keeps of level n (the energy only).
mrm::repro::Configuration configuration_of(const Run& r, double switch_theta) {
  mrm::repro::Configuration c =
      mrm::repro::paper_configuration(r.scheme, "algebraic", r.mass, r.elements, r.courant, r.final_time);
  c.scheme.switch_theta = switch_theta;
  return c;
}
struct EnergyFollow {
  double initial = 0, previous = 0;
  void add(Run& r, const mrm::Sample& s) {
    if (s.level == 0) {
      initial = previous = s.energy;
      r.largest_increase = -std::numeric_limits<double>::infinity();
    } else {
      r.largest_increase = std::max(r.largest_increase, (s.energy - previous) / initial);
    }
    previous = s.energy;
    if (r.history) r.energy.emplace_back(s.energy_time, s.energy / initial);
  }
};

double ratio(const Run& r, double energy) { return energy / r.measures.energy_initial; }
// max over the run of |Eⁿ − E⁰|/E⁰
double drift(const Run& r) {
  return std::max(ratio(r, r.measures.energy_max) - 1, 1 - ratio(r, r.measures.energy_min));
}

// A step as a multiple of h, for the prose (math mode): "h/2", "h", "5h".
std::string step_text(double courant) {
  if (courant == 1) return "h";
  return courant < 1 ? "h/" + cli::format_real(1 / courant) : cli::format_real(courant) + "h";
}

// The grid of each view: the history's ratios Δt/h, the map's ratios and meshes, the measures' meshes
// and ratio, the masses, the long runs (coarse: N = 16, Δt = 10h, 100 periods; long: N = 20, Δt = h,
// 1000 periods), the period and the measures' horizon in periods.
const std::vector<double> history_ratios{0.5, 1.0, 5.0};
const std::vector<double> map_ratios{0.25, 0.5, 1, 2, 5, 10, 20, 40};
const std::vector<mrm::Index> map_meshes{16, 32, 64, 128}, measure_meshes{100, 400};
const double measure_courant = 0.5;
const std::vector<std::string> masses{"mod1", "mod2", "mod3"};
struct LongRun {
  const char* key;
  mrm::Index elements;
  double courant, periods;
};
const std::array<LongRun, 2> long_runs{LongRun{"coarse", 16, 10.0, 100}, LongRun{"long", 20, 1.0, 1000}};
const double period = 3.0, measure_periods = 10;
// The drifting bar: EC + Mod 3 on the layered bar (released at 4.1, then flying off with its free far
// end), N elements, observed up to each horizon.
const std::vector<mrm::Index> drift_meshes{50, 100};
const std::vector<double> drift_horizons{100, 300, 1000};

// What the drifting bar's run keeps at each horizon: the range (max − min)/E₀ of its energy so far and
// u(0, t), and the round-off model's scale ε N u(0, t)²/(L E₀) (energy_step.cpp §5).
struct DriftRun {
  mrm::Index elements = 0;
  std::vector<double> range, u0, scale;
};

// Steps 4 and 5 of a view: its blocks in the data file and its values, the runs taken in the order they
// were made.
struct ViewWriter {
  std::ostream& out;
  std::ostream& defs;
  const std::vector<Run>& runs;
  std::size_t next = 0, block = 0;
  // CN-switch and backward Euler: every one-step increase within the round-off bound (energy_step.cpp §5).
  double largest_bound_fraction = -std::numeric_limits<double>::infinity();
  void start_block(const std::string& title, const std::string& columns) {
    out << (block ? "\n\n" : "") << "# block " << block << ": " << title << "\n# columns: " << columns << '\n';
    ++block;
  }
  void check_increase(const Run& r) {
    if (r.scheme != switching && r.scheme != be) return;
    const double bound = mrm::energy_round_off_per_step(r.elements, r.courant);
    largest_bound_fraction = std::max(largest_bound_fraction, r.largest_increase / bound);
    if (!(r.largest_increase <= bound))
      throw std::runtime_error(r.scheme + " " + r.mass + " N = " + std::to_string(r.elements) +
                               " dt/h = " + cli::format_real(r.courant) + ": a one-step energy increase of " +
                               cli::format_real(r.largest_increase) + " E0, above the round-off bound " +
                               cli::format_real(bound) + " E0");
  }
};

// The history view: E_h(t)/E_h(0) of every scheme at three ratios Δt/h on one mesh.
void write_history(ViewWriter& w, const std::string& mass, mrm::Index elements) {
  w.out << "# mass = " << mass << "\n# N = " << elements << "\n# T = " << cli::format_real(10 * period) << '\n';
  mrm::tex_define(w.defs, "ecs:hist:N", std::to_string(elements));
  mrm::tex_define(w.defs, "ecs:hist:mass", mrm::repro::mass_label(mass).latex);
  mrm::tex_define(w.defs, "ecs:hist:T", mrm::tex_number(10 * period, 2));
  for (std::size_t j = 0; j < history_ratios.size(); ++j)
    mrm::tex_define(w.defs, "ecs:hist:dt:" + std::to_string(j), step_text(history_ratios[j]));
  for (double c : history_ratios)
    for (const std::string& s : schemes) {
      const Run& r = w.runs[w.next++];
      w.check_increase(r);
      w.start_block(std::string("scheme = ") + s + ", dt/h = " + cli::format_real(c), "t_energy energy_ratio");
      for (const auto& [t, e] : r.energy) w.out << cli::format_real(t) << ' ' << cli::format_real(e) << '\n';
      const std::string key = std::string("ecs:hist:") + s + ":" + cli::format_real(c);
      mrm::tex_define(w.defs, key + ":final", mrm::tex_number(ratio(r, r.measures.energy_final), 4));
      mrm::tex_define(w.defs, key + ":largest", mrm::tex_number(ratio(r, r.measures.energy_max), 4));
    }
}

// The map view: the largest E_h/E_h(0) of every scheme over meshes and ratios, and the long runs.
void write_map(ViewWriter& w, const std::string& mass) {
  w.out << "# mass = " << mass << "\n# T = " << cli::format_real(100 * period) << '\n';
  mrm::tex_define(w.defs, "ecs:map:mass", mrm::repro::mass_label(mass).latex);
  mrm::tex_define(w.defs, "ecs:map:T", mrm::tex_number(100 * period, 2));
  mrm::tex_define(w.defs, "ecs:map:Nmin", std::to_string(map_meshes.front()));
  mrm::tex_define(w.defs, "ecs:map:Nmax", std::to_string(map_meshes.back()));
  mrm::tex_define(w.defs, "ecs:map:ratiomin", mrm::tex_number(map_ratios.front(), 2));
  mrm::tex_define(w.defs, "ecs:map:ratiomax", mrm::tex_number(map_ratios.back(), 2));
  w.out << "# increase_bound = 16 N eps (1 + h/dt): the largest one-step increase (E^{n+1} - E^n)/E^0 that "
           "round-off explains where the exact energy does not increase (cn-switch, be; energy_step.cpp sec. 5)\n";
  for (const std::string& s : schemes) {
    double largest = 0, largest_drift = 0, largest_increase = -std::numeric_limits<double>::infinity();
    for (mrm::Index n : map_meshes) {
      w.start_block(std::string("scheme = ") + s + ", N = " + std::to_string(n),
                    "dt_over_h largest smallest final largest_increase increase_bound");
      for (double c : map_ratios) {
        const Run& r = w.runs[w.next++];
        w.out << cli::format_real(c) << ' ' << cli::format_real(ratio(r, r.measures.energy_max)) << ' '
              << cli::format_real(ratio(r, r.measures.energy_min)) << ' '
              << cli::format_real(ratio(r, r.measures.energy_final)) << ' ' << cli::format_real(r.largest_increase)
              << ' ' << cli::format_real(mrm::energy_round_off_per_step(n, c)) << '\n';
        w.check_increase(r);
        largest = std::max(largest, ratio(r, r.measures.energy_max));
        largest_drift = std::max(largest_drift, drift(r));
        largest_increase = std::max(largest_increase, r.largest_increase);
        if (s == cn)
          mrm::tex_define(w.defs, "ecs:map:cn:" + std::to_string(n) + ":" + cli::format_real(c),
                          mrm::tex_magnitude(ratio(r, r.measures.energy_max)));
      }
    }
    const std::string key = std::string("ecs:map:") + s;
    mrm::tex_define(w.defs, key + ":largest", mrm::tex_magnitude(largest));
    mrm::tex_define(w.defs, key + ":drift", mrm::tex_number(largest_drift, 2));
    mrm::tex_define(w.defs, key + ":increase", mrm::tex_number(largest_increase, 2));
  }
  // The long runs: a block and a table (run, scheme, mass: drift, largest increase, largest, final).
  w.start_block("the long runs",
                "run scheme mass N dt_over_h periods drift largest_increase largest final increase_bound");
  mrm::repro::Table table({stacked("$N$, $\\Delta t$,", "periods"), "scheme", "mass",
                           stacked("$\\max_n |E_h^n - E_h(0)|$", "$/E_h(0)$"),
                           stacked("$\\max_n (E_h^{n+1} - E_h^n)$", "$/E_h(0)$"),
                           stacked("$\\max_n E_h^n$", "$/E_h(0)$"), stacked("$E_h(T)$", "$/E_h(0)$")});
  for (const LongRun& l : long_runs) {
    const std::string run_label =
        std::to_string(l.elements) + ", $" + step_text(l.courant) + "$, " + cli::format_real(l.periods);
    mrm::tex_define(w.defs, std::string("ecs:long:") + l.key + ":N", std::to_string(l.elements));
    mrm::tex_define(w.defs, std::string("ecs:long:") + l.key + ":courant", cli::format_real(l.courant));
    mrm::tex_define(w.defs, std::string("ecs:long:") + l.key + ":dt", step_text(l.courant));
    mrm::tex_define(w.defs, std::string("ecs:long:") + l.key + ":periods", cli::format_real(l.periods));
    const double bound = mrm::energy_round_off_per_step(l.elements, l.courant);
    mrm::tex_define(w.defs, std::string("ecs:long:") + l.key + ":bound", mrm::tex_number(bound, 2));
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      for (const std::string& m : masses) {
        const Run& r = w.runs[w.next++];
        w.out << l.key << ' ' << schemes[s] << ' ' << m << ' ' << l.elements << ' ' << cli::format_real(l.courant)
              << ' ' << cli::format_real(l.periods) << ' ' << cli::format_real(drift(r)) << ' '
              << cli::format_real(r.largest_increase) << ' ' << cli::format_real(ratio(r, r.measures.energy_max)) << ' '
              << cli::format_real(ratio(r, r.measures.energy_final)) << ' ' << cli::format_real(bound) << '\n';
        w.check_increase(r);
        const std::string key = std::string("ecs:long:") + l.key + ":" + schemes[s] + ":" + m;
        mrm::tex_define(w.defs, key + ":drift", mrm::tex_number(drift(r), 2));
        mrm::tex_define(w.defs, key + ":increase", mrm::tex_number(r.largest_increase, 2));
        mrm::tex_define(w.defs, key + ":largest", mrm::tex_magnitude(ratio(r, r.measures.energy_max)));
        mrm::tex_define(w.defs, key + ":final", mrm::tex_number(ratio(r, r.measures.energy_final), 3));
        table.add_row({s == 0 && m == masses.front() ? run_label : std::string(),
                       m == masses.front() ? mrm::repro::scheme_label(schemes[s]).abbreviation : std::string(),
                       mrm::repro::mass_label(m).latex, mrm::tex_number(drift(r), 2),
                       mrm::tex_number(r.largest_increase, 2),
                       "$" + mrm::tex_magnitude(ratio(r, r.measures.energy_max)) + "$",
                       mrm::tex_number(ratio(r, r.measures.energy_final), 3)});
      }
      table.add_rule();
    }
  }
  mrm::tex_define(w.defs, "ecs:long:table", mrm::repro::latex_tabular(table, "lllrrrr"));
  // The largest one-step increase of CN-switch and backward Euler over every run above, as a fraction
  // of its round-off bound.
  mrm::tex_define(w.defs, "ecs:increase:bound_fraction", mrm::tex_number(w.largest_bound_fraction, 2));
  w.out << "# largest_bound_fraction = " << cli::format_real(w.largest_bound_fraction)
        << " (max over the cn-switch and be runs of largest_increase / increase_bound)\n";
}

// The drifting bar's block and values: the energy's range against u(0, t)² (energy_step.cpp §5).
void write_drift(ViewWriter& w, const std::vector<DriftRun>& drifting) {
  w.start_block("the drifting bar: ec, mod3, layered, dt = h/(2c)", "N T u0 energy_range model_scale range_over_scale");
  double smallest = HUGE_VAL, largest = 0;
  for (const DriftRun& d : drifting)
    for (std::size_t k = 0; k < drift_horizons.size(); ++k) {
      const double constant = d.range[k] / d.scale[k];
      smallest = std::min(smallest, constant), largest = std::max(largest, constant);
      w.out << d.elements << ' ' << cli::format_real(drift_horizons[k]) << ' ' << cli::format_real(d.u0[k]) << ' '
            << cli::format_real(d.range[k]) << ' ' << cli::format_real(d.scale[k]) << ' ' << cli::format_real(constant)
            << '\n';
      const std::string key = "ecs:drift:" + std::to_string(d.elements) + ":" + cli::format_real(drift_horizons[k]);
      mrm::tex_define(w.defs, key + ":range", mrm::tex_number(d.range[k], 2));
      mrm::tex_define(w.defs, key + ":u0", mrm::tex_number(d.u0[k], 3));
    }
  mrm::tex_define(w.defs, "ecs:drift:constant:min", mrm::tex_number(smallest, 2));
  mrm::tex_define(w.defs, "ecs:drift:constant:max", mrm::tex_number(largest, 2));
  std::string horizons;
  for (std::size_t k = 0; k < drift_horizons.size(); ++k)
    horizons += (k == 0 ? "" : k + 1 == drift_horizons.size() ? " and " : ", ") + cli::format_real(drift_horizons[k]);
  mrm::tex_define(w.defs, "ecs:drift:horizons", horizons);
  mrm::tex_define(w.defs, "ecs:drift:Ncoarse", std::to_string(drift_meshes.front()));
  mrm::tex_define(w.defs, "ecs:drift:Nfine", std::to_string(drift_meshes.back()));
}

// The measures view: the eight errors of every scheme and mass, relative to Crank–Nicolson's.
void write_measures(ViewWriter& w) {
  w.out << "# dt/h = " << cli::format_real(measure_courant) << "\n# T = " << cli::format_real(measure_periods * period)
        << '\n';
  mrm::tex_define(w.defs, "ecs:meas:T", mrm::tex_number(measure_periods * period, 2));
  mrm::tex_define(w.defs, "ecs:meas:periods", cli::format_real(measure_periods));
  mrm::tex_define(w.defs, "ecs:meas:dt", step_text(measure_courant));
  mrm::tex_define(w.defs, "ecs:meas:coarse", std::to_string(measure_meshes[0]));
  mrm::tex_define(w.defs, "ecs:meas:fine", std::to_string(measure_meshes[1]));
  std::vector<double> switch_lost;  // CN-switch with Mod 3, per mesh: the loss is O(h) per event
  for (mrm::Index n : measure_meshes) {
    w.start_block("N = " + std::to_string(n),
                  "scheme mass (8 measures) (8 ratios to cn) energy_lost; measures in the order of mathematics.md "
                  "sec. 5: u0_L2 lambda_L2 u_LinfL2 u_LinfH1 v_LinfL2 u_L2L2 u_L2H1 v_L2L2");
    // The table in three parts, measures 0–2, 3–5 and 6–7 with the energy lost, each within the text
    // width.
    constexpr std::size_t per_part = 3;
    std::array<std::vector<std::string>, 3> headers;
    for (auto& h : headers) h = {"scheme", "mass"};
    for (std::size_t k = 0; k < mrm::repro::measure_labels().size(); ++k)
      headers[k / per_part].push_back(mrm::repro::measure_labels()[k].latex);
    headers.back().push_back("energy lost, \\%");
    std::array<mrm::repro::Table, 3> tables{mrm::repro::Table(headers[0]), mrm::repro::Table(headers[1]),
                                            mrm::repro::Table(headers[2])};
    const std::size_t first = w.next;  // Crank–Nicolson's runs come first, one per mass
    for (std::size_t s = 0; s < schemes.size(); ++s) {
      double largest_ratio = 0, largest_deviation = 0;  // over the measures and the masses
      for (std::size_t m = 0; m < masses.size(); ++m) {
        const Run& r = w.runs[w.next++];
        const auto errors = mrm::ErrorAccumulator::values(r.measures.errors);
        const auto reference = mrm::ErrorAccumulator::values(w.runs[first + m].measures.errors);
        const double lost = 1 - ratio(r, r.measures.energy_final);
        w.out << schemes[s] << ' ' << masses[m];
        for (double e : errors) w.out << ' ' << cli::format_real(e);
        for (std::size_t k = 0; k < errors.size(); ++k) w.out << ' ' << cli::format_real(errors[k] / reference[k]);
        w.out << ' ' << cli::format_real(lost) << '\n';
        std::array<std::vector<std::string>, 3> rows;
        for (auto& row : rows)
          row = {m == 0 ? mrm::repro::scheme_label(schemes[s]).abbreviation : std::string(),
                 mrm::repro::mass_label(masses[m]).latex};
        const std::string key = "ecs:meas:" + std::to_string(n) + ":" + schemes[s] + ":" + masses[m];
        for (std::size_t k = 0; k < errors.size(); ++k) {
          const std::string value = mrm::tex_number(errors[k], 3);
          // Beside Crank–Nicolson's row, each other scheme's error relative to it, in per cent.
          const std::string relative = mrm::tex_number(100 * (errors[k] / reference[k] - 1), 2);
          rows[k / per_part].push_back(
              s == 0 ? value : value + " (" + (errors[k] >= reference[k] ? "+" : "") + relative + "\\%)");
          mrm::tex_define(w.defs, key + ":" + mrm::ErrorAccumulator::names[k], value);
          mrm::tex_define(w.defs, key + ":" + mrm::ErrorAccumulator::names[k] + ":vs_cn", relative);
          largest_ratio = std::max(largest_ratio, errors[k] / reference[k]);
          largest_deviation = std::max(largest_deviation, std::abs(errors[k] / reference[k] - 1));
        }
        if (schemes[s] == switching && masses[m] == "mod3") switch_lost.push_back(lost);
        rows.back().push_back(mrm::tex_number(100 * lost, 2));
        mrm::tex_define(w.defs, key + ":lost", mrm::tex_number(100 * lost, 2));
        for (std::size_t t = 0; t < tables.size(); ++t) tables[t].add_row(rows[t]);
      }
      for (auto& table : tables) table.add_rule();
      const std::string key = "ecs:meas:" + std::to_string(n) + ":" + schemes[s];
      mrm::tex_define(w.defs, key + ":largest_ratio", mrm::tex_number(largest_ratio, 2));
      mrm::tex_define(w.defs, key + ":largest_deviation", mrm::tex_number(100 * largest_deviation, 2));
    }
    for (std::size_t t = 0; t < tables.size(); ++t)
      mrm::tex_define(w.defs, "ecs:meas:table:" + std::to_string(n) + ":" + std::to_string(t + 1),
                      mrm::repro::latex_tabular(tables[t], "ll" + std::string(tables[t].columns() - 2, 'r')));
  }
  mrm::tex_define(w.defs, "ecs:meas:cn-switch:mod3:lost_ratio", mrm::tex_number(switch_lost[0] / switch_lost[1], 2));
  mrm::tex_define(w.defs, "ecs:meas:mesh_ratio", std::to_string(measure_meshes[1] / measure_meshes[0]));
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_energy_schemes", [&] {
    // 1. Options.
    long threads = 2;
    mrm::repro::SchemeParameterOptions scheme_options;  // --switch-theta
    std::string view = "history", mass = "mod3";
    mrm::repro::FigureProgram program(
        "fig_energy_schemes",
        "Writes the energy of Crank-Nicolson, energy-conserving Crank-Nicolson (ec), Crank-Nicolson "
        "with a theta-step at each status change (cn-switch) and backward Euler on the benchmark: "
        "their histories, the largest energy against dt/h, or their errors against Crank-Nicolson's.",
        {"fig_energy_schemes --view history --output output/data/fig_energy_schemes_history.dat",
         "fig_energy_schemes --view map --threads 1 --output map.dat --tex map.tex"});
    program.parser.add_choice(
        "--view", "", "V",
        "history: E/E0 over 10 periods at dt = h/2, h, 5h; map: the largest E/E0 over 100 periods "
        "against dt/h, and the long runs; measures: the errors at N = 100 and 400",
        {"history", "map", "measures"}, &view);
    program.add_elements(20, "history: number of elements N (h = 1/N), in [2, 1e5]", cli::in_closed_range(2, 1e5));
    program.parser.add_choice("--mass", "-m", "M",
                              "history and map: the mass (a massless contact node, which ec needs)",
                              {"mod1", "mod2", "mod3"}, &mass);
    scheme_options.declare(program.parser, {mrm::SchemeParameter::switch_theta});
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the values and tables the report quotes, as \\mrmdef lines")) return 0;
    const long elements = program.elements;
    const double switch_theta = scheme_options.values().switch_theta;
    if (view != "history" && program.parser.given("--elements"))
      throw cli::UsageError("--elements: only with --view history (the other views fix their meshes)");
    if (view == "measures" && program.parser.given("--mass"))
      throw cli::UsageError("--mass: not with --view measures (it runs Mod 1, 2 and 3)");

    // 2. Outputs.
    program.open();
    std::ostream& out = program.header("the energy of cn, ec, cn-switch and be (mathematics.md sec. 12), view " + view);
    // One colour per scheme, the same in the three views, none of them a mass's (figures/style.gp:
    // scheme_colour reads these lines).
    const std::array<std::pair<mrm::Scheme, const char*>, 4> colours{{{mrm::Scheme::crank_nicolson, "#ff7f0e"},
                                                                      {mrm::Scheme::energy_conserving, "black"},
                                                                      {mrm::Scheme::switching, "#17becf"},
                                                                      {mrm::Scheme::backward_euler, "#8c564b"}}};
    for (const auto& [scheme, colour] : colours)
      out << "# colour " << mrm::to_string(scheme) << " = " << colour << '\n';
    // EC, which conserves the energy, is drawn dashed and thicker in the history, so that the curves it covers
    // stay visible.
    out << "# conserving = " << mrm::to_string(mrm::Scheme::energy_conserving) << '\n';
    std::ostream& defs = program.values();
    const std::string theta_text = mrm::tex_number(switch_theta, 3);
    mrm::tex_define(defs, "ecs:theta", theta_text);

    // 3. The runs of the view.
    std::vector<Run> runs;
    if (view == "history") {
      for (double c : history_ratios)
        for (const std::string& s : schemes) runs.push_back(make_run(s, mass, elements, c, 10 * period, true));
    } else if (view == "map") {
      for (const std::string& s : schemes)
        for (mrm::Index n : map_meshes)
          for (double c : map_ratios) runs.push_back(make_run(s, mass, n, c, 100 * period));
      for (const LongRun& l : long_runs)
        for (const std::string& s : schemes)
          for (const std::string& m : masses) runs.push_back(make_run(s, m, l.elements, l.courant, l.periods * period));
    } else {
      for (mrm::Index n : measure_meshes)
        for (const std::string& s : schemes)
          for (const std::string& m : masses)
            runs.push_back(make_run(s, m, n, measure_courant, measure_periods * period));
    }
    std::vector<mrm::repro::Configuration> configurations;
    for (const Run& r : runs) configurations.push_back(configuration_of(r, switch_theta));
    std::vector<EnergyFollow> follow(runs.size());
    mrm::repro::SweepSettings settings;
    settings.threads = static_cast<unsigned>(threads);
    // The batches: the runs of one mesh and scheme family, given as the caller's keys, so that each run
    // steps at its own rate (Δt/h = ¼ … 40 in one batch of the map, every Δt a whole multiple of the
    // smallest, one horizon: repro/sweep.hpp, own_rates). With the default keys every lane of a batch
    // steps as often as its finest run: the map view then takes 3.8 times the CPU time of run_configuration
    // alone (3.62–3.95, 3 pairs); with these keys 0.77 (0.70–0.90), the measures view 0.41 (0.38–0.47)
    // (5 pairs, --threads 1).
    std::vector<mrm::repro::BatchKey> keys;
    for (const mrm::repro::Configuration& c : configurations)
      keys.emplace_back(c.elements, mrm::batch_family(c.scheme.scheme));
    const std::vector<mrm::repro::Measures> measures = mrm::repro::run_batched(
        configurations, settings, [&](std::size_t k, const mrm::Sample& s) { follow[k].add(runs[k], s); }, keys,
        /*observer_reads_vectors=*/false);
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].measures = measures[k];

    // The drifting bar (map view): one run per mesh, observed at every level (its displacement too), so
    // run alone, without the error measures it does not report; each horizon is read at the first level at
    // or after it.
    std::vector<DriftRun> drifting;
    if (view == "map")
      for (const mrm::Index n : drift_meshes) {
        mrm::repro::Configuration c = mrm::repro::study_configuration("layered", mrm::Scheme::energy_conserving,
                                                                      mrm::repro::mass_redistribution_from_spec("mod3"),
                                                                      n, 0.5, drift_horizons.back());
        c.measure_errors = false;
        DriftRun d{n, {}, {}, {}};
        double initial = 0, lowest = 0, highest = 0;
        const double length = c.bar_length();
        mrm::repro::run_configuration(c, [&](const mrm::Sample& s) {
          if (s.level == 0) initial = lowest = highest = s.energy;
          lowest = std::min(lowest, s.energy), highest = std::max(highest, s.energy);
          if (d.range.size() < drift_horizons.size() && s.time >= drift_horizons[d.range.size()]) {
            const double u0 = (*s.displacement)[0];
            d.range.push_back((highest - lowest) / initial);
            d.u0.push_back(u0);
            d.scale.push_back(std::numeric_limits<double>::epsilon() * static_cast<double>(n) * u0 * u0 /
                              (length * initial));
          }
        });
        if (d.range.size() != drift_horizons.size())
          throw std::logic_error("fig_energy_schemes: the drifting bar's run ended before its last horizon");
        drifting.push_back(d);
      }

    // 4 and 5. The blocks, the values and the tables, view by view (runs in the order they were made).
    ViewWriter w{out, defs, runs};
    if (view == "history")
      write_history(w, mass, elements);
    else if (view == "map") {
      write_map(w, mass);
      write_drift(w, drifting);
    } else
      write_measures(w);

    // 6. Commit.
    program.commit();
    return 0;
  });
}
