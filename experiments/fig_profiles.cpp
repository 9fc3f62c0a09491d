// fig_profiles: the displacement along the bar at a few instants of each phase.
//
// What it computes. The profiles x ↦ u(x, t) of the benchmark of mathematics.md §2 at instants of the free
// flight towards the obstacle (t < 1), of the contact (1 < t < 2) and of the release (2 < t < 3): the
// exact solution (a broken line: the rigid motion behind an unloading wave, the tent of the contact
// phase) and the nodal values of one scheme with Mod 1, Mod 2 and Mod 3 on the coarse mesh of the
// report's Figure 1 (the paper gives no mesh). The mass choices differ near the contact node; the profiles show where along the
// bar the differences are and how the wave fronts are smeared.
//
// Sample runs:
//   fig_profiles --output output/data/fig_profiles.dat --tex output/data/fig_profiles.tex
//   fig_profiles --scheme be --instants 0.5,1.5,2.5 --output p.dat
//
// Description. Steps: (1) options; (2) the instants, rounded to time levels, the limits of the run and
// the outputs; (3) one run per mass, keeping the profiles at those levels; (4) the blocks: exact and
// computed per instant; (5) commit.
//
// Data file: for instant k (in the order given), block 2k is the exact profile (x u) on a fine grid and
// block 2k+1 the nodal values (x u_mod1 u_mod2 u_mod3), node N (clamped, u = 0) included.
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
#include "scheme_options.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_profiles", [&] {
    // 1. Options.
    mrm::repro::SchemeParameterOptions scheme_options;  // --ps-form, --switch-theta
    std::string scheme = mrm::to_string(mrm::Scheme::crank_nicolson), instants_text = "0.5,1.5,2.5,6.5,7.5,8.5";
    mrm::repro::FigureProgram program(
        "fig_profiles",
        "Writes the displacement along the bar at a few instants (free flight, contact, release): "
        "exact, and one scheme with Mod 1, Mod 2 and Mod 3.",
        {"fig_profiles --output output/data/fig_profiles.dat --tex output/data/fig_profiles.tex",
         "fig_profiles --scheme be --instants 0.5,1.5,2.5 --output p.dat"});
    program.add_elements(20);
    program.add_courant(0.5);
    program.parser.add_choice("--scheme", "-s", "S",
                              "time scheme (ec: energy-conserving Crank-Nicolson; cn-switch: "
                              "Crank-Nicolson with a theta-step at each change of the contact status)",
                              mrm::repro::scheme_ids(), &scheme);
    mrm::SchemeParameters literal_row;  // the figure's Paoli-Schatzman: the literal contact row by default
    literal_row.contact_row = mrm::ContactRow::literal;
    // In the order the series header echoes them: --switch-theta, then --ps-form.
    scheme_options.declare(program.parser, {mrm::SchemeParameter::switch_theta});
    scheme_options.declare(program.parser, {mrm::SchemeParameter::contact_row}, literal_row);
    program.parser.add_string("--instants", "-t", "LIST",
                              "comma-separated instants t >= 0, each rounded to a time level (at most 1e12 steps away)",
                              &instants_text);
    program.add_exact_points(400, "number of intervals of each exact profile, in [10, 1e6]");
    if (!program.parse(argc, argv)) return 0;
    const long exact_points = program.exact_points;
    scheme_options.parameters(program.parser, mrm::scheme_by_name(scheme));  // refuses an option it does not take
    const std::string ps_form = mrm::to_string(scheme_options.values().contact_row);
    const double switch_theta = scheme_options.values().switch_theta;
    std::vector<double> instants;
    for (const double t : cli::parse_real_list("--instants", instants_text)) {
      cli::require_at_least("--instants", t, 0.0);
      instants.push_back(t);
    }

    // 2. The instants, rounded to the nearest time level; the limits; the program.
    const long elements = program.elements;
    const double courant = program.courant, dt = program.dt();
    const mrm::UniformMesh mesh(1.0, elements);
    const mrm::ExactSolution exact;
    std::vector<mrm::Index> levels;
    mrm::Index last_level = 0;
    for (double t : instants) {
      levels.push_back(cli::checked_level("--instants", t, dt, "--courant"));
      last_level = std::max(last_level, levels.back());
    }
    const double count = static_cast<double>(instants.size());
    cli::require_rows("--instants", count * (static_cast<double>(exact_points) + static_cast<double>(elements) + 2),
                      cli::format_real(count) + " instants of " + cli::format_real(static_cast<double>(exact_points)) +
                          " exact points and " + cli::format_real(static_cast<double>(elements)) + " nodes");
    // A run at a time, and the profiles kept: three masses times the instants, 8 bytes a node each.
    cli::require_mesh_memory("--elements", static_cast<double>(elements), mrm::repro::bytes_per_element + 24 * count);
    program.open();

    // 3. One run per mass, keeping Uⁿ at the chosen levels.
    const auto& masses = mrm::repro::mass_names();
    std::vector<std::vector<Eigen::VectorXd>> profiles(masses.size(), std::vector<Eigen::VectorXd>(levels.size()));
    for (std::size_t m = 0; m < masses.size(); ++m) {
      std::cerr << "fig_profiles: " << scheme << ' ' << masses[m] << '\n';
      mrm::repro::Configuration configuration = mrm::repro::paper_configuration(
          scheme, ps_form, masses[m], elements, courant, static_cast<double>(last_level) * dt);
      configuration.scheme.switch_theta = switch_theta;
      configuration.steps = last_level;  // exactly the last chosen level (it may be level 0)
      mrm::repro::run_configuration(configuration, [&](const mrm::Sample& s) {
        for (std::size_t k = 0; k < levels.size(); ++k)
          if (levels[k] == s.level) profiles[m][k] = *s.displacement;
      });
    }

    // 4. The blocks.
    std::ostream& out = program.header("u(x,t) at a few instants, exact and computed (mathematics.md sec. 2)");
    out << "# h = " << cli::format_real(mesh.h()) << "\n# dt = " << cli::format_real(dt)
        << "\n# blocks: 2k exact profile at instant k (x u); 2k+1 nodal values (x u_mod1 u_mod2 u_mod3)\n";
    std::ostream& defs = program.values();
    mrm::tex_define(defs, "prof:elements", std::to_string(elements));
    mrm::tex_define(defs, "prof:dt", mrm::tex_number(dt, 3));
    mrm::tex_define(defs, "prof:scheme", mrm::repro::scheme_label(scheme).latex);
    for (std::size_t k = 0; k < levels.size(); ++k) {
      const double t = static_cast<double>(levels[k]) * dt;
      mrm::tex_define(defs, "prof:t:" + std::to_string(k + 1), mrm::tex_number(t, 3));
      out << (k ? "\n\n" : "") << "# block " << 2 * k << ": exact, t = " << cli::format_real(t) << "\n# columns: x u\n";
      for (long j = 0; j <= exact_points; ++j) {
        const double x = static_cast<double>(j) / static_cast<double>(exact_points);
        out << cli::format_real(x) << ' ' << cli::format_real(exact.displacement(x, t)) << '\n';
      }
      out << "\n\n# block " << 2 * k + 1 << ": " << scheme << ", t = " << cli::format_real(t)
          << "\n# columns: x u_mod1 u_mod2 u_mod3\n";
      for (mrm::Index i = 0; i <= mesh.elements; ++i) {
        out << cli::format_real(mesh.x(i));
        for (std::size_t m = 0; m < masses.size(); ++m)
          out << ' ' << cli::format_real(i < mesh.elements ? profiles[m][k][i] : 0.0);
        out << '\n';
      }
      // The largest nodal error of each mass at this instant, for the caption.
      for (std::size_t m = 0; m < masses.size(); ++m) {
        double largest = 0;
        for (mrm::Index i = 0; i < mesh.elements; ++i)
          largest = std::max(largest, std::abs(profiles[m][k][i] - exact.displacement(mesh.x(i), t)));
        mrm::tex_define(defs, "prof:maxerr:" + std::to_string(k + 1) + ":" + masses[m], mrm::tex_number(largest, 2));
      }
    }

    // 5. Commit.
    program.commit();
    return 0;
  });
}
