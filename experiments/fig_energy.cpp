// fig_energy: the discrete energy of every scheme and mass choice against the exact energy 1/8.
//
// What it computes. On the benchmark of mathematics.md §2 and the mesh of the report's Figure 1
// (fig_contact_history; the paper gives no mesh for its own Figure 1), the discrete energy E_hⁿ of each scheme (Crank–Nicolson, backward Euler,
// Paoli–Schatzman (¼, 0)) with each mass choice (Mod 1, 2, 3) over several periods. The exact energy is
// E = 1/8 at all times. Crank–Nicolson conserves E_h exactly while the contact status does not change
// and jumps at impact and release; backward Euler dissipates; Paoli–Schatzman conserves its own
// three-level energy between status changes. It also measures the effect of the initial value of the
// massless contact node (mathematics.md §4): E_h(0) with u₀(0) solved from its algebraic row, and with the
// nodal interpolant of u⁰, and the errors of Crank–Nicolson with either choice.
//
// Sample runs:
//   fig_energy --output output/data/fig_energy.dat --tex output/data/fig_energy.tex
//   fig_energy --elements 40 --final-time 30 --output e.dat
//
// Description. Steps: (1) options and the limits of the run; (2) outputs; (3) every scheme × mass, one block each (t_energy
// energy_h), with the energy's range and its jumps; (4) the initial-datum comparison; (5) commit.
//
// Data file: block 3 s + m is scheme s ∈ (cn, be, ps), mass m ∈ (mod1, mod2, mod3); columns
// t_energy energy_h (Paoli–Schatzman's energy lives at t_{n+½}).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include "options.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "configurations.hpp"
#include "labels.hpp"
#include "figure_program.hpp"
#include "report_values.hpp"
#include "scheme_options.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_energy", [&] {
    // 1. Options and the limits of the run.
    mrm::repro::SchemeParameterOptions scheme_options;  // --ps-form
    mrm::repro::FigureProgram program(
        "fig_energy",
        "Writes the discrete energy history of every scheme (cn, be, ps) with every mass "
        "choice (mod1, mod2, mod3) on the benchmark; the exact energy is 1/8.",
        {"fig_energy --output output/data/fig_energy.dat --tex output/data/fig_energy.tex",
         "fig_energy --elements 40 --final-time 30 --output e.dat"});
    program.add_elements(20);
    program.add_courant(0.5);
    program.add_final_time(9.0);
    mrm::SchemeParameters literal_row;  // the figure's Paoli-Schatzman: the literal contact row by default
    literal_row.contact_row = mrm::ContactRow::literal;
    scheme_options.declare(program.parser, {mrm::SchemeParameter::contact_row}, literal_row);
    if (!program.parse(argc, argv)) return 0;
    const std::string ps_form = mrm::to_string(scheme_options.values().contact_row);
    const long elements = program.elements;
    const double courant = program.courant, final_time = program.final_time;
    program.steps(9);  // nine energy histories

    // 2. Outputs.
    program.open();
    const mrm::ExactSolution exact;
    std::ostream& out = program.header("discrete energy E_h(t) against the exact 1/8 (mathematics.md sec. 4-5)");
    program.write_step();
    mrm::repro::write_scheme_titles(out, ps_form);
    // The energy each scheme conserves: E_h, or Paoli–Schatzman's E_h^β for a scheme that takes β.
    for (const mrm::SchemeInfo& info : mrm::scheme_registry())
      out << "# energy " << info.id << " = "
          << (mrm::takes(info.scheme, mrm::SchemeParameter::beta) ? "E_h^beta" : "E_h") << '\n';
    out << "# exact_energy = " << cli::format_real(exact.energy())
        << "\n# blocks: 3 s + m: scheme s in (cn, be, ps), mass m in (mod1, mod2, mod3)\n";
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "energy:elements", std::to_string(elements));
    mrm::tex_define(defs, "energy:T", cli::format_real(final_time));

    // 3. Every scheme with every mass. The energy's largest jump in one step measures the jumps at impact
    // and release (between status changes Crank–Nicolson's energy does not move at all).
    int block = 0;
    for (const std::string& scheme : mrm::repro::scheme_names()) {
      for (const std::string& mass : mrm::repro::mass_names()) {
        std::cerr << "fig_energy: " << scheme << ' ' << mass << '\n';
        out << (block ? "\n\n" : "") << "# block " << block << ": scheme = " << scheme << ", mass = " << mass
            << "\n# columns: t_energy energy_h\n";
        ++block;
        double last = 0, largest_jump = 0;
        const mrm::repro::Measures measures = mrm::repro::run_configuration(
            mrm::repro::paper_configuration(scheme, ps_form, mass, elements, courant, final_time),
            [&](const mrm::Sample& s) {
              if (s.level == 0) last = s.energy;
              largest_jump = std::max(largest_jump, std::abs(s.energy - last));
              last = s.energy;
              out << cli::format_real(s.energy_time) << ' ' << cli::format_real(s.energy) << '\n';
            });
        const double initial = measures.energy_initial, lowest = measures.energy_min, highest = measures.energy_max;
        const std::string key = "energy:" + scheme + ":" + mass + ":";
        mrm::tex_define(defs, key + "initial", mrm::tex_number(initial, 4));
        mrm::tex_define(defs, key + "final", mrm::tex_number(last, 4));
        mrm::tex_define(defs, key + "min", mrm::tex_number(lowest, 4));
        mrm::tex_define(defs, key + "max", mrm::tex_number(highest, 4));
        mrm::tex_define(defs, key + "jump", mrm::tex_number(largest_jump, 2));
        mrm::tex_define(defs, key + "drift", mrm::tex_number((last - initial) / initial, 2));
      }
    }

    // 4. The initial value of the massless contact node (mathematics.md §4): solved from its algebraic row,
    // u₀(0) = max(0, u₁(0)), which gives E_h(0) = (1 − h)/8, or the interpolant u⁰(0) = ½, which gives
    // E_h(0) = 1/8 but is not a state of the reduced problem; Crank–Nicolson with Mod 3, errors of both.
    for (const std::string initial : {"consistent", "interpolant"}) {
      mrm::repro::Configuration configuration =
          mrm::repro::paper_configuration(mrm::Scheme::crank_nicolson, ps_form, "mod3", elements, courant, final_time);
      configuration.initial = mrm::initial_contact_node_by_name(initial);
      double first = 0, after_one_step = 0;
      const mrm::ErrorNorms e = mrm::repro::run_configuration(configuration, [&](const mrm::Sample& s) {
                                  if (s.level == 0) first = s.energy;
                                  if (s.level == 1) after_one_step = s.energy;
                                }).errors;
      const std::string key = "energy:initial:" + initial + ":";
      mrm::tex_define(defs, key + "E0", mrm::tex_number(first, 4));
      mrm::tex_define(defs, key + "E1", mrm::tex_number(after_one_step, 4));
      mrm::tex_define(defs, key + "err_u0_L2", mrm::tex_number(e.u0_L2, 3));
      mrm::tex_define(defs, key + "err_u_L2H1", mrm::tex_number(e.u_L2H1, 3));
      mrm::tex_define(defs, key + "err_v_L2L2", mrm::tex_number(e.v_L2L2, 3));
    }

    // 5. Commit.
    program.commit();
    return 0;
  });
}
