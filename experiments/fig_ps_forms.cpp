// fig_ps_forms: Paoli–Schatzman with a massless contact node, literal against algebraic contact row.
//
// What it computes. Paoli–Schatzman (β, e) = (¼, 0) written on all unknowns has a contact row
//
//     M₀·(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹)/Δt² + S₀·(βUⁿ⁺¹ + (1−2β)Uⁿ + βUⁿ⁻¹) = F₀ⁿ − λⁿ.
//
// With a redistributed mass, M₀· = 0: applied literally, the row only asks the β-average of the defect
// dⁿ = S₀·Uⁿ − F₀ + λ over three levels to vanish, βdⁿ⁺¹ + (1−2β)dⁿ + βdⁿ⁻¹ = 0, whose solutions for
// β = ¼ are dⁿ = (p + qn)(−1)ⁿ: a sawtooth in u₀ that nothing damps once the contact opens (mathematics.md
// §4 predicts it; this program shows whether it appears). Imposing the algebraic row at every level
// removes it (and PS(¼, 0) then coincides with Crank–Nicolson). The consistent mass keeps the inertia of
// node 0, so its literal row is a true equation of motion: shown for contrast.
//
// It writes u₀ⁿ and the discrete energy of the three variants, and measures the sawtooth: the largest
// second difference |u₀ⁿ⁺¹ − 2u₀ⁿ + u₀ⁿ⁻¹| over the free flights of each period (the exact u(0,·) is
// piecewise linear, so away from the kinks at impact and release this is the scheme's oscillation).
//
// Sample runs:
//   fig_ps_forms --output output/data/fig_ps_forms.dat --tex output/data/fig_ps_forms.tex
//   fig_ps_forms --mass mod1 --elements 50 --final-time 30 --output ps.dat
//
// Description. Steps: (1) options and the limits of the run; (2) outputs; (3) the exact u(0,t); (4) the three variants, one block
// each, with the sawtooth per period; (5) commit.
//
// Data file: block 0 exact (t u0); blocks 1, 2, 3: algebraic row with the redistributed mass, literal row
// with the redistributed mass, literal row with the consistent mass; columns t u0_h t_energy energy_h.
#include <algorithm>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "configurations.hpp"
#include "figure_program.hpp"
#include "report_values.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_ps_forms", [&] {
    // 1. Options.
    std::string mass = "mod3";
    mrm::repro::FigureProgram program(
        "fig_ps_forms",
        "Writes u(0,t) and the energy of Paoli-Schatzman (1/4, 0) with a redistributed mass in its "
        "literal and algebraic contact-row forms, and with the consistent mass, and the amplitude of "
        "the sawtooth in u(0,t) per period.",
        {"fig_ps_forms --output output/data/fig_ps_forms.dat --tex output/data/fig_ps_forms.tex",
         "fig_ps_forms --mass mod1 --elements 50 --final-time 30 --output ps.dat"});
    program.add_elements(20);
    program.add_courant(0.5);
    program.add_final_time(15.0);
    program.parser.add_string("--mass", "-m", "M",
                              mrm::repro::mass_option_help("the redistributed mass (not consistent)"), &mass);
    program.add_exact_points(3000);
    if (!program.parse(argc, argv)) return 0;

    const long elements = program.elements, exact_points = program.exact_points;
    const double courant = program.courant, final_time = program.final_time, dt = program.dt();
    const mrm::UniformMesh mesh(1.0, elements);
    const mrm::MassRedistribution redistribution = mrm::repro::mass_from_option("--mass", mass, mesh, true);
    const mrm::ExactSolution exact;
    // Three histories, and one sawtooth value per period and variant.
    program.steps(3);
    if (!(final_time / exact.period() <= 1e6))
      throw cli::UsageError("--final-time: " + cli::format_real(final_time) + " spans " +
                            cli::format_real(std::ceil(final_time / exact.period())) +
                            " periods (allowed: at most 1e6 periods, each with its own values)");

    // 2. Outputs.
    program.open();
    std::ostream& out =
        program.header("Paoli-Schatzman (1/4, 0), literal and algebraic contact row (mathematics.md sec. 4)");
    program.write_step();
    out << "# total_mass = " << cli::format_real(mrm::total_mass(mesh, redistribution))
        << "\n# exact_energy = " << cli::format_real(exact.energy()) << "\n# blocks: 0 exact; 1 algebraic row, " << mass
        << "; 2 literal row, " << mass << "; 3 literal row, consistent mass\n";

    // 3. The exact contact displacement.
    out << "# block 0: exact\n# columns: t u0\n";
    for (long k = 0; k <= exact_points; ++k) {
      const double t = final_time * static_cast<double>(k) / static_cast<double>(exact_points);
      out << cli::format_real(t) << ' ' << cli::format_real(exact.contact_displacement(t)) << '\n';
    }

    // 4. The three variants. The sawtooth of a period is the largest |second difference of u₀| at the
    // levels whose three instants lie inside one of the period's two free flights, at least 2Δt away
    // from the kinks of the exact u(0,·) at the impact (t = 1 mod 3) and the release (t = 2 mod 3).
    struct Variant {
      std::string key, mass, form;
    };
    const std::vector<Variant> variants{
        {"algebraic", mass, "algebraic"}, {"literal", mass, "literal"}, {"consistent", "consistent", "literal"}};
    const long periods = static_cast<long>(std::ceil(final_time / exact.period() - 1e-9));
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "ps:elements", std::to_string(elements));
    mrm::tex_define(defs, "ps:dt", mrm::tex_number(dt, 3));
    mrm::tex_define(defs, "ps:T", mrm::tex_number(final_time, 3));
    mrm::tex_define(defs, "ps:mass", mrm::repro::mass_label(mass).abbreviation);
    mrm::tex_define(defs, "ps:periods", std::to_string(periods));
    int block = 1;
    for (const Variant& v : variants) {
      std::cerr << "fig_ps_forms: " << v.key << '\n';
      out << "\n\n# block " << block++ << ": form = " << v.form << ", mass = " << v.mass
          << "\n# columns: t u0_h t_energy energy_h\n";
      std::vector<double> sawtooth(static_cast<std::size_t>(periods), 0.0);
      double u_before = std::nan(""), u_prev = std::nan("");
      double energy_first = std::nan(""), energy_last = 0, energy_max = -1e300, energy_min = 1e300;
      const mrm::repro::Configuration configuration = mrm::repro::paper_configuration(
          mrm::to_string(mrm::Scheme::paoli_schatzman), v.form, v.mass, elements, courant, final_time);
      const mrm::ErrorNorms e =
          mrm::repro::run_configuration(configuration, [&](const mrm::Sample& s) {
            const double u0 = (*s.displacement)[0];
            if (s.level >= 2) {
              const double t_mid = s.time - dt, t_first = s.time - 2 * dt;
              const double period_start = exact.period() * std::floor(t_first / exact.period());
              const double a = t_first - period_start, b = s.time - period_start;  // the three instants, in [a, b]
              const double margin = 2 * dt;
              const bool free_flight = (b <= 1 - margin) || (a >= 2 + margin && b <= 3 - margin);
              const auto period = static_cast<std::size_t>(std::floor(t_mid / exact.period()));
              if (free_flight && a >= 0 && period < sawtooth.size())
                sawtooth[period] = std::max(sawtooth[period], std::abs(u0 - 2 * u_prev + u_before));
            }
            u_before = u_prev;
            u_prev = u0;
            // Paoli–Schatzman's three-level energy exists from level 2 on (levels 0, 1 carry the start's).
            if (s.level >= 2) {
              if (std::isnan(energy_first)) energy_first = s.energy;
              energy_last = s.energy;
              energy_max = std::max(energy_max, s.energy);
              energy_min = std::min(energy_min, s.energy);
            }
            out << cli::format_real(s.time) << ' ' << cli::format_real(u0) << ' ' << cli::format_real(s.energy_time)
                << ' ' << cli::format_real(s.energy) << '\n';
          }).errors;
      const std::string key = "ps:" + v.key + ":";
      mrm::tex_define(defs, key + "err_u0_L2", mrm::tex_number(e.u0_L2, 2));
      mrm::tex_define(defs, key + "err_u_L2H1", mrm::tex_number(e.u_L2H1, 2));
      mrm::tex_define(defs, key + "energy_first", mrm::tex_number(energy_first, 4));
      mrm::tex_define(defs, key + "energy_last", mrm::tex_number(energy_last, 4));
      mrm::tex_define(defs, key + "energy_max", mrm::tex_number(energy_max, 4));
      mrm::tex_define(defs, key + "energy_min", mrm::tex_number(energy_min, 4));
      for (std::size_t p = 0; p < sawtooth.size(); ++p)
        mrm::tex_define(defs, key + "sawtooth:" + std::to_string(p + 1), mrm::tex_number(sawtooth[p], 2));
      mrm::tex_define(defs, key + "sawtooth:last", mrm::tex_number(sawtooth.back(), 2));
      out << "# sawtooth per period (max |second difference of u0| in free flight):";
      for (double a : sawtooth) out << ' ' << cli::format_real(a);
      out << '\n';
    }

    // 5. Commit.
    program.commit();
    return 0;
  });
}
