// fig_phase: the mechanism of the paper's ranking made visible — errors against time and the drift of
// the impact times (mathematics.md §8).
//
// What it computes. One scheme (Crank–Nicolson by default) with Mod 1, Mod 2 and Mod 3 on one mesh over
// many periods (30 by default) of the benchmark of mathematics.md §2: (a) the error of the contact
// point |u₀ⁿ − u(0, tₙ)| and the L² error of u at every level (absolute: the exact u vanishes at the
// instants of impact and release), against time; (b) the impact
// times read off the contact indicator (lib/measures/phase.cpp) and their errors eₖ = t̂ₖ − tₖ against the
// exact impacts tₖ = L + 3Lk, beside the period law's prediction e₀ + k ΔP with ΔP = 2ℓ_f + ℓ_c − 3L
// from the first eigenvalues of the reduced pencils (lib/fem/period_law.cpp: −4h/3, −h/3, 0 + O(h²)).
// The measured drift per period (least squares, time units per period, early < 0) and the law's are
// written for the report.
//
// Sample runs:
//   fig_phase --output output/data/fig_phase.dat --tex output/data/fig_phase.tex
//   fig_phase --elements 50 --courant 1 --periods 10 --output p.dat
//
// Description. Steps: (1) options; (2) outputs; (3) one run per mass, writing the error history
// (every `stride`-th level) and collecting the impacts; (4) the impact blocks and the values; (5) commit.
//
// Data file: block m (m = 0, 1, 2 for Mod 1, 2, 3) is the error history, columns t err_u0 err_u_L2 (absolute);
// block 3 + m the impacts, columns k t_exact error law (law = e₀ + k ΔP_law).
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "report_values.hpp"
#include "exact/exact_solution.hpp"
#include "fem/p1.hpp"
#include "fem/period_law.hpp"
#include "measures/phase.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_phase", [&] {
    // 1. Options.
    long stride = 8;
    double periods = 30;
    std::string scheme = mrm::to_string(mrm::Scheme::crank_nicolson);
    mrm::repro::FigureProgram program(
        "fig_phase",
        "Writes the errors against time of one scheme with Mod 1, Mod 2 and Mod 3 over many periods, "
        "and the errors of the impact times beside the period law's prediction (-4h/3, -h/3, 0 per "
        "period).",
        {"fig_phase --output output/data/fig_phase.dat --tex output/data/fig_phase.tex",
         "fig_phase --elements 50 --courant 1 --periods 10 --output p.dat"});
    program.add_elements(100, "number of elements N (h = 1/N), in [3, 1e5]", cli::in_closed_range(3, 1e5));
    program.add_courant(0.5, "time step dt = C h, C in (0, 10]", [](std::string_view o, double v) {
      cli::require_positive(o, v);
      cli::require_in_closed_range(o, v, 0, 10);
    });
    program.parser.add_real("--periods", "-p", "P", "number of periods (3L each), in [2, 1000]", &periods,
                            cli::in_closed_range(2, 1000));
    program.parser.add_integer("--stride", "", "K",
                               "keep every K-th level of the error history in the data file (K >= 1)", &stride,
                               cli::at_least(1));
    program.parser.add_choice("--scheme", "-s", "S", "time scheme (Paoli-Schatzman with the algebraic row)",
                              mrm::repro::scheme_names(), &scheme);
    if (!program.parse(argc, argv)) return 0;

    const long elements = program.elements;
    const double courant = program.courant;
    // The run's steps, checked before any work (run_limits.hpp): a step that underflows to 0 or needs
    // more than 1e12 steps is refused.
    cli::checked_steps("--periods", 3 * periods, program.dt(), "--courant");
    cli::require_mesh_memory("--elements", static_cast<double>(elements), mrm::repro::bytes_per_element);

    // 2. Outputs.
    program.open();
    const mrm::UniformMesh mesh(1.0, elements);
    const double h = mesh.h();
    const mrm::ExactSolution exact;
    std::ostream& out = program.header("errors against time and the drift of the impact times (mathematics.md sec. 8)");
    out << "# h = " << cli::format_real(h) << "\n# dt = " << cli::format_real(program.dt())
        << "\n# blocks 0-2: error history of mod1, mod2, mod3 (t err_u0 err_u_L2); blocks 3-5: impacts "
           "(k t_exact error law)\n";
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "phase:elements", std::to_string(elements));
    mrm::tex_define(defs, "phase:courant", cli::format_real(courant));
    mrm::tex_define(defs, "phase:periods", cli::format_real(periods));
    mrm::tex_define(defs, "phase:scheme", scheme);

    // 3. One run per mass: the error history and the impacts (run_configuration's phase measures).
    const mrm::Tridiagonal mass_matrix = mrm::p1_mass(mesh);
    std::vector<mrm::repro::Measures> measures;
    int block = 0;
    for (const std::string& mass : mrm::repro::mass_names()) {
      std::cerr << "fig_phase: " << scheme << ' ' << mass << '\n';
      const mrm::repro::Configuration c =
          mrm::repro::paper_configuration(scheme, "algebraic", mass, elements, courant, 3 * periods);
      out << (block ? "\n\n" : "") << "# block " << block << ": error history, mass = " << mass
          << "\n# columns: t err_u0 err_u_L2\n";
      ++block;
      Eigen::VectorXd interpolant(mesh.unknowns()), difference(mesh.unknowns());
      measures.push_back(mrm::repro::run_configuration(c, [&](const mrm::Sample& s) {
        if (s.level % stride != 0) return;
        for (mrm::Index i = 0; i < mesh.unknowns(); ++i) interpolant[i] = exact.displacement(mesh.x(i), s.time);
        difference = *s.displacement - interpolant;
        out << cli::format_real(s.time) << ' '
            << cli::format_real(std::abs((*s.displacement)[0] - exact.contact_displacement(s.time))) << ' '
            << cli::format_real(std::sqrt(mass_matrix.bilinear(difference, difference))) << '\n';
      }));
    }

    // 4. The impacts against the law, and the values.
    for (std::size_t m = 0; m < measures.size(); ++m) {
      const std::string& mass = mrm::repro::mass_names()[m];
      const mrm::repro::Measures& r = measures[m];
      if (!r.phase || !r.phase->drift_per_period || r.phase->matched != r.impacts.size())
        throw std::runtime_error("fig_phase: the " + mass +
                                 " run has fewer than two impacts, or one farther than 3L/2 from its exact partner");
      const mrm::PeriodPrediction law = mrm::predict_period(mesh, mrm::mass_redistribution_by_name(mass));
      const std::vector<double> t = mrm::benchmark_impact_times(exact, r.impacts.size());
      out << "\n\n# block " << block << ": impacts, mass = " << mass << "\n# columns: k t_exact error law\n";
      ++block;
      for (std::size_t k = 0; k < r.impacts.size(); ++k)
        out << k << ' ' << cli::format_real(t[k]) << ' ' << cli::format_real(r.impacts[k] - t[k]) << ' '
            << cli::format_real(law.first_impact_error + static_cast<double>(k) * law.period_error) << '\n';
      const std::string key = "phase:" + mass + ":";
      mrm::tex_define(defs, key + "drift", mrm::tex_number(*r.phase->drift_per_period / h, 3));
      mrm::tex_define(defs, key + "law", mrm::tex_number(law.period_error / h, 3));
      mrm::tex_define(defs, key + "first", mrm::tex_number(r.phase->first_impact_error / h, 3));
      mrm::tex_define(defs, key + "firstlaw", mrm::tex_number(law.first_impact_error / h, 3));
      mrm::tex_define(defs, key + "err_u0_L2", mrm::tex_number(r.errors.u0_L2, 3));
    }

    // 5. Commit.
    program.commit();
    return 0;
  });
}
