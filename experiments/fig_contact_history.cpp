// fig_contact_history: the paper's Figure 1, the history of the contact point.
//
// What it computes. The benchmark of mathematics.md §2 (bar released at rest from u⁰(x) = (1 − x)/2
// against the obstacle at x = 0) over several periods, with each of the paper's three schemes
// (Crank–Nicolson, backward Euler, Paoli–Schatzman (¼, 0)) and each of its three mass choices (Mod 1,
// Mod 2, Mod 3), on one coarse mesh: the displacement of the contact point u₀ⁿ ≈ u(0, tₙ) and the
// contact stress λⁿ ≈ λ(t) = u_x(0, t), beside the exact ones. The mesh is coarse on purpose: the three
// mass choices differ by O(h) near the contact node, so on a fine mesh their curves merge.
//
// Sample runs:
//   fig_contact_history --output output/data/fig_contact_history.dat --tex output/data/fig_contact_history.tex
//   fig_contact_history --elements 40 --courant 1 --final-time 6 --output h.dat
//
// Description. Steps: (1) read the options, check the limits of the run; (2) open the outputs; (3) write
// the exact history; (4) run every scheme × mass, writing one block each and accumulating the errors;
// (5) write the values the report quotes and commit.
//
// Data file: gnuplot blocks separated by two blank lines (select with `index`). Block 0 is the exact
// solution (t u0 lambda); block 1 + 3 s + m is scheme s ∈ (cn, be, ps), mass m ∈ (mod1, mod2, mod3),
// columns t u0_h t_lambda lambda_h (each quantity at the instant it approximates; lambda_h = n/a where
// a level has no multiplier).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "options.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "configurations.hpp"
#include "labels.hpp"
#include "figure_program.hpp"
#include "report_values.hpp"
#include "scheme_options.hpp"
#include "table.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_contact_history", [&] {
    // 1. Options.
    mrm::repro::SchemeParameterOptions scheme_options;  // --ps-form, algebraic by default
    mrm::repro::FigureProgram program(
        "fig_contact_history",
        "Writes the history of the contact point, u(0,t) and the contact stress lambda(t), of the "
        "exact solution and of every scheme (cn, be, ps) with every mass choice (mod1, mod2, mod3): "
        "the paper's Figure 1.",
        {"fig_contact_history --output output/data/fig_contact_history.dat "
         "--tex output/data/fig_contact_history.tex",
         "fig_contact_history --elements 40 --courant 1 --final-time 6 --output h.dat"});
    program.add_elements(20, "number of elements N (h = 1/N), in [2, 1e7]; coarse so that the masses differ");
    program.add_courant(0.5);
    program.add_final_time(9.0);
    scheme_options.declare(program.parser, {mrm::SchemeParameter::contact_row});
    program.add_exact_points(3600);
    if (!program.parse(argc, argv)) return 0;
    const std::string ps_form = mrm::to_string(scheme_options.values().contact_row);

    const long elements = program.elements, exact_points = program.exact_points;
    const double courant = program.courant, final_time = program.final_time, dt = program.dt();
    const mrm::UniformMesh mesh(1.0, elements);
    program.steps(10);  // ten contact histories

    // 2. Outputs, opened before the runs so that a bad path fails at once.
    program.open();
    const mrm::ExactSolution exact;
    std::ostream& out =
        program.header("u(0,t) and lambda(t), exact and computed (mathematics.md sec. 2; paper Figure 1)");
    program.write_step();
    mrm::repro::write_scheme_titles(out, ps_form);
    out << "# blocks: 0 exact (t u0 lambda); 1 + 3 s + m: scheme s in (cn, be, ps), mass m in (mod1, mod2, mod3);"
           "\n# 10: the baseline, Paoli-Schatzman with the consistent mass (literal contact row)"
           "\n# lambda_h = n/a where the level has no multiplier yet\n";

    // 3. The exact history on a fine, uniform grid of instants.
    out << "# block 0: exact\n# columns: t u0 lambda\n";
    for (long k = 0; k <= exact_points; ++k) {
      const double t = final_time * static_cast<double>(k) / static_cast<double>(exact_points);
      out << cli::format_real(t) << ' ' << cli::format_real(exact.contact_displacement(t)) << ' '
          << cli::format_real(exact.contact_multiplier(t)) << '\n';
    }

    // 4. Every scheme with every mass.
    {
      std::ostream& m = program.values();
      mrm::tex_define(m, "hist:elements", std::to_string(elements));
      mrm::tex_define(m, "hist:h", mrm::tex_number(mesh.h(), 3));
      mrm::tex_define(m, "hist:dt", mrm::tex_number(dt, 3));
      mrm::tex_define(m, "hist:courant", mrm::tex_number(courant, 3));
      mrm::tex_define(m, "hist:T", cli::format_real(final_time));
      mrm::tex_define(m, "hist:psform", ps_form);
      // The total mass 1ᵀM^mod1 of each choice on this mesh (paper §2: Mod 2 and Mod 3 preserve it).
      for (const std::string& mass : mrm::repro::mass_names())
        mrm::tex_define(m, "hist:totalmass:" + mass,
                        mrm::tex_number(mrm::total_mass(mesh, mrm::mass_redistribution_by_name(mass)), 6));
    }
    mrm::repro::Table table({"scheme", "mass", "$u(0,\\cdot)$, $L^2_t$", "$\\lambda$, $L^2_t$", "$u$, $L^2_t H^1$"});
    int block = 1;
    // Each run's u₀ⁿ and λⁿ (n/a levels skipped), kept to measure how far Paoli–Schatzman's row lies from
    // Crank–Nicolson's (the figure draws the paper's third row only if it differs).
    std::map<std::string, std::vector<std::pair<double, double>>> histories;
    // One run written as one block, its errors quoted by the report (\mrmdef hist:KEY:…) and its table row.
    const auto run_block = [&](const std::string& scheme, const std::string& form, const std::string& mass,
                               const std::string& key, const std::string& row_scheme, const std::string& row_mass) {
      std::cerr << "fig_contact_history: " << scheme << ' ' << mass << '\n';
      out << "\n\n# block " << block++ << ": scheme = " << scheme << ", mass = " << mass
          << "\n# columns: t u0_h t_lambda lambda_h\n";
      const mrm::repro::Configuration configuration =
          mrm::repro::paper_configuration(scheme, form, mass, elements, courant, final_time);
      std::vector<std::pair<double, double>>& history = histories[key];
      const mrm::ErrorNorms e = mrm::repro::run_configuration(configuration, [&](const mrm::Sample& s) {
                                  history.emplace_back((*s.displacement)[0], s.has_multiplier ? s.multiplier : 0.0);
                                  // A level without a multiplier (Paoli-Schatzman's first) says so: n/a, gnuplot's missing value.
                                  out << cli::format_real(s.time) << ' ' << cli::format_real((*s.displacement)[0])
                                      << ' ' << cli::format_real(s.multiplier_time) << ' '
                                      << (s.has_multiplier ? cli::format_real(s.multiplier) : std::string("n/a"))
                                      << '\n';
                                }).errors;
      // 5. The errors of the contact point, quoted by the report beside the figure.
      mrm::tex_define(program.values(), "hist:" + key + ":err_u0_L2", mrm::tex_number(e.u0_L2, 2));
      mrm::tex_define(program.values(), "hist:" + key + ":err_lambda_L2", mrm::tex_number(e.lambda_L2, 2));
      mrm::tex_define(program.values(), "hist:" + key + ":err_u_L2H1", mrm::tex_number(e.u_L2H1, 2));
      table.add_row({row_scheme, row_mass, mrm::tex_number(e.u0_L2, 2), mrm::tex_number(e.lambda_L2, 2),
                     mrm::tex_number(e.u_L2H1, 2)});
    };
    for (const std::string& scheme : mrm::repro::scheme_names()) {
      for (const std::string& mass : mrm::repro::mass_names())
        run_block(scheme, ps_form, mass, scheme + ":" + mass,
                  mass == "mod1" ? mrm::repro::scheme_row_label(scheme, ps_form) : std::string(),
                  std::string("Mod ") + mass.back());
      table.add_rule();
    }
    // The largest difference between Paoli–Schatzman (this form) and Crank–Nicolson, level by level, over
    // the three masses, in u(0, t) and λ: the report draws the two rows once when it is at round-off.
    double difference_u = 0, difference_lambda = 0;
    for (const std::string& mass : mrm::repro::mass_names()) {
      const auto& cn = histories.at("cn:" + mass);
      const auto& ps = histories.at("ps:" + mass);
      for (std::size_t n = 0; n < std::min(cn.size(), ps.size()); ++n) {
        difference_u = std::max(difference_u, std::abs(cn[n].first - ps[n].first));
        if (n > 0) difference_lambda = std::max(difference_lambda, std::abs(cn[n].second - ps[n].second));
      }
    }
    mrm::tex_define(program.values(), "hist:ps:cn:difference:u", mrm::tex_number(difference_u, 2));
    mrm::tex_define(program.values(), "hist:ps:cn:difference:lambda", mrm::tex_number(difference_lambda, 2));
    // 6. The baseline: Paoli–Schatzman (¼, 0) with the full consistent mass (its only contact row is the
    // literal one), stable and the method's natural point of comparison (block 10, last row of the table).
    const std::string ps = mrm::to_string(mrm::Scheme::paoli_schatzman);
    run_block(ps, "literal", "consistent", "ps:consistent", mrm::repro::scheme_row_label(ps, "literal"), "consistent");
    program.values() << "\\mrmdef{hist:table}{" << mrm::repro::latex_tabular(table, "llrrr") << "}\n";
    program.commit();
    return 0;
  });
}
