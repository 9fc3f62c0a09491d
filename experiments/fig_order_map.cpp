// fig_order_map: the observed orders of convergence in h against the predicted ones, over horizons
// (claim 4 over a region; mathematics.md §9).
//
// What it computes. From the sweep of check_claims (repro/regions.cpp), per (scheme, mass, Δt/h,
// horizon) the least-squares order in h over N = 25 … 800 of each of the eight measures
// (repro::order_cells), beside the predicted orders: Crank–Nicolson 2/3 for the displacement measures and
// 1/3 for the energy-type ones and λ, backward Euler 1/2 and 1/4 (the regularity limit of the benchmark),
// and, for a mass whose period is off by O(h) (Mod 1, Mod 2), the orders 1 and 1/2 of its phase error.
//
// Sample runs:
//   fig_order_map --sweep output/data/sweep.dat --output output/data/fig_order_map.dat --tex output/data/fig_order_map.tex
//
// Description. Steps: (1) options; (2) outputs; (3) read the sweep; (4) one block per (scheme, mass,
// Δt/h): a line per horizon; (5) the values; (6) commit.
//
// Data file: block b = (s · M + m) · J + j for scheme s ∈ (cn, be, ps, ps-consistent), mass m, ratio j;
// columns horizon, the eight orders, the predicted displacement and energy-type orders, the lower and
// upper ends of the allowed interval of a displacement and of an energy-type measure.
#include <iostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "labels.hpp"
#include "measures/errors.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "regions.hpp"
#include "report_values.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_order_map", [&] {
    // 1. Options.
    std::string sweep_file = "output/data/sweep.dat";
    mrm::repro::FigureProgram program(
        "fig_order_map",
        "Reads the sweep written by check_claims --sweep and writes the least-squares orders in h of "
        "every measure per (scheme, mass, dt/h, horizon) beside the predicted orders.",
        {"fig_order_map --sweep output/data/sweep.dat --output output/data/fig_order_map.dat"});
    program.parser.add_input("--sweep", "-i", "the sweep to read (check_claims --sweep FILE)", &sweep_file);
    if (!program.parse(argc, argv)) return 0;

    // 2. Outputs, opened first so that a bad output path fails before anything is read.
    program.open();

    // 3. The sweep.
    const repro::Sweep sweep = repro::read_sweep_file(sweep_file, "--sweep");
    const repro::SweepGrid& g = sweep.grid;

    std::ostream& out =
        program.header("least-squares orders in h per (scheme, mass, dt/h, horizon) (claim 4, mathematics.md sec. 9)");
    // The figure's rows: Crank–Nicolson (with the baseline beside it) and backward Euler; the baseline's title.
    out << "# panels = " << mrm::to_string(mrm::Scheme::crank_nicolson) << ' '
        << mrm::to_string(mrm::Scheme::backward_euler) << '\n'
        << "# baseline_with = " << mrm::to_string(mrm::Scheme::crank_nicolson) << '\n'
        << "# title ps-consistent = " << repro::scheme_label(mrm::Scheme::paoli_schatzman).plain << ", "
        << repro::mass_label("consistent").plain << '\n';
    std::vector<std::pair<std::string, std::string>> pairs;
    for (const std::string& s : g.schemes)
      for (const std::string& m : g.masses) pairs.emplace_back(s, m);
    if (g.baseline)
      for (std::size_t m = 0; m < g.masses.size(); ++m) pairs.emplace_back("ps-consistent", "consistent");
    out << "# blocks (s M + m) J + j: scheme s, mass m, ratio j (the baseline repeated M times to keep the indexing)\n"
        << "# columns: horizon";
    for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
    out << " predicted_u predicted_energy u_low u_high energy_low energy_high\n";

    // 4. The blocks.
    const std::vector<repro::OrderCell> cells = repro::order_cells(sweep);
    std::ostream& defs = program.values();
    int block = 0;
    for (const auto& [s, m] : pairs) {
      const repro::PredictedOrders p = repro::predicted_orders(s);
      const std::pair<double, double> du = repro::allowed_order(s, m, 0), de = repro::allowed_order(s, m, 3);
      for (double c : g.courants) {
        out << (block ? "\n\n" : "") << "# block " << block << ": scheme = " << s << ", mass = " << m
            << ", dt/h = " << cli::format_real(c) << '\n';
        ++block;
        for (const repro::OrderCell& cell : cells) {
          if (cell.scheme != s || cell.mass != m || cell.courant != c) continue;
          out << cli::format_real(g.horizons[cell.horizon]);
          for (double o : cell.order) out << ' ' << cli::format_real(o);
          out << ' ' << cli::format_real(p.displacement) << ' ' << cli::format_real(p.energy) << ' '
              << cli::format_real(du.first) << ' ' << cli::format_real(du.second) << ' ' << cli::format_real(de.first)
              << ' ' << cli::format_real(de.second) << '\n';
          // 5. The values: the orders of u(0,·) and u L∞(H¹) at Δt = h/2 for every horizon.
          if (c == 0.5 && s != "ps-consistent")
            for (const std::size_t q : {std::size_t{0}, std::size_t{3}, std::size_t{7}})
              mrm::tex_define(defs,
                              "orders:" + s + ":" + m + ":" + cli::format_real(g.horizons[cell.horizon]) + ":" +
                                  mrm::ErrorAccumulator::names[q],
                              mrm::tex_number(cell.order[q], 2));
        }
      }
    }

    // 6. Commit.
    program.commit();
    return 0;
  });
}
