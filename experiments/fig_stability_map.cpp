// fig_stability_map: where Crank–Nicolson with a massless contact node stays bounded (claim 1 over a
// region; mathematics.md §12).
//
// What it computes. Crank–Nicolson's energy balance with a massless contact node: a step that keeps
// the contact status conserves E_h, an impact loses energy and a release gains some, at most c²h v²/8
// per switch (c = Δt/h). For c ≲ 1 the two nearly cancel; for c ≫ 1 the gains win. This program
// measures the largest E_hⁿ/E_h(0) over 100 periods of the benchmark for Δt/h from ¼ to 40 (a geometric
// grid, ratio √2, and 40) on N = 16, 32, 64, 128 with Mod 3, and over 1000 periods at Δt = h with
// Mod 1, 2, 3 on the same meshes.
//
// Sample runs:
//   fig_stability_map --output output/data/fig_stability_map.dat --tex output/data/fig_stability_map.tex
//   fig_stability_map --periods 10 --long-periods 100 --output s.dat
//
// Description. Steps: (1) options; (2) outputs; (3) all runs at once (threads); (4) the blocks and the
// values; (5) commit.
//
// Data file: block k (k = 0 … 3 for N = 16, 32, 64, 128): columns courant largest_energy_ratio; block 4:
// columns mass_index (1, 2, 3) elements largest_energy_ratio (the long runs at Δt = h).
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "figure_program.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "report_values.hpp"

namespace cli = mrm::cli;
namespace repro = mrm::repro;

int main(int argc, char** argv) {
  return cli::guarded_main("fig_stability_map", [&] {
    // 1. Options.
    double periods = 100, long_periods = 1000;
    mrm::repro::FigureProgram program(
        "fig_stability_map",
        "Writes Crank-Nicolson's largest energy relative to E_h(0) over 100 periods for dt/h from 1/4 "
        "to 40 on N = 16, 32, 64, 128 (Mod 3), and over 1000 periods at dt = h (Mod 1, 2, 3).",
        {"fig_stability_map --output output/data/fig_stability_map.dat",
         "fig_stability_map --periods 10 --long-periods 100 --output s.dat"});
    program.parser.add_real("--periods", "-p", "P", "periods of the large-step runs, in [1, 1000]", &periods,
                            cli::in_closed_range(1, 1000));
    program.parser.add_real("--long-periods", "", "P", "periods of the long runs at dt = h, in [1, 10000]",
                            &long_periods, cli::in_closed_range(1, 10000));
    if (!program.parse(argc, argv)) return 0;

    // 2. Outputs.
    program.open();
    const std::vector<mrm::Index> meshes = {16, 32, 64, 128};
    std::vector<double> courants;
    for (int k = 0; k <= 14; ++k) courants.push_back(0.25 * std::pow(2.0, 0.5 * k));  // ¼ … 32
    courants.push_back(40);
    std::ostream& out = program.header("Crank-Nicolson's largest E_h/E_h(0) (claim 1, mathematics.md sec. 12)");
    out << "# blocks 0-3: N = 16, 32, 64, 128, Mod 3, " << cli::format_real(periods)
        << " periods (courant largest); block 4: dt = h, " << cli::format_real(long_periods)
        << " periods (mass_index elements largest)\n";
    // The long runs' step, Δt = h.
    const double long_courant = 1.0;
    // "Bounded": the largest energy at most twice the initial one on every mesh.
    const double threshold = 2;
    out << "# threshold = " << cli::format_real(threshold) << "\n# long_courant = " << cli::format_real(long_courant)
        << '\n';

    // 3. All runs.
    std::vector<repro::Configuration> configurations;
    for (mrm::Index n : meshes)
      for (double c : courants)
        configurations.push_back(
            repro::paper_configuration(mrm::Scheme::crank_nicolson, "algebraic", "mod3", n, c, 3 * periods));
    for (const std::string& mass : repro::mass_names())
      for (mrm::Index n : meshes)
        configurations.push_back(repro::paper_configuration(mrm::Scheme::crank_nicolson, "algebraic", mass, n,
                                                            long_courant, 3 * long_periods));
    std::cerr << "fig_stability_map: " << configurations.size() << " runs\n";
    const std::vector<repro::Measures> m = repro::run_configurations(configurations);

    // 4. The blocks and the values.
    std::ostream& defs = program.values();
    std::size_t k = 0;
    double bounded_up_to = 0;
    bool bounded = true;
    std::vector<double> worst(courants.size(), 0.0);
    for (std::size_t b = 0; b < meshes.size(); ++b) {
      out << (b ? "\n\n" : "") << "# block " << b << ": N = " << meshes[b] << "\n# columns: courant largest\n";
      for (std::size_t j = 0; j < courants.size(); ++j, ++k) {
        const double ratio = m[k].energy_max / m[k].energy_initial;
        worst[j] = std::max(worst[j], ratio);
        out << cli::format_real(courants[j]) << ' ' << cli::format_real(ratio) << '\n';
      }
    }
    for (std::size_t j = 0; j < courants.size(); ++j) {
      bounded = bounded && worst[j] <= threshold;
      if (bounded) bounded_up_to = courants[j];
    }
    mrm::tex_define(defs, "stab:bounded", cli::format_real(bounded_up_to));
    mrm::tex_define(defs, "stab:threshold", cli::format_real(threshold));
    mrm::tex_define(defs, "stab:periods", cli::format_real(periods));
    mrm::tex_define(defs, "stab:longperiods", cli::format_real(long_periods));
    // The grid, for the prose: the meshes, the coarsest one and the range of Δt/h.
    std::string mesh_list;
    for (mrm::Index n : meshes) mesh_list += (mesh_list.empty() ? "" : ", ") + std::to_string(n);
    mrm::tex_define(defs, "stab:meshes", mesh_list);
    mrm::tex_define(defs, "stab:coarse", std::to_string(meshes.front()));
    mrm::tex_define(defs, "stab:ratiomin", cli::format_real(courants.front()));
    mrm::tex_define(defs, "stab:ratiomax", cli::format_real(courants.back()));
    mrm::tex_define(defs, "stab:long:dt", long_courant == 1 ? "h" : cli::format_real(long_courant) + "h");
    out << "\n\n# block 4: dt = h\n# columns: mass_index elements largest\n";
    for (std::size_t mass = 0; mass < repro::mass_names().size(); ++mass)
      for (mrm::Index n : meshes) {
        const double ratio = m[k].energy_max / m[k].energy_initial;
        ++k;
        out << mass + 1 << ' ' << n << ' ' << cli::format_real(ratio) << '\n';
        mrm::tex_define(defs, "stab:long:" + repro::mass_names()[mass] + ":" + std::to_string(n),
                        mrm::tex_magnitude(ratio));
        if (n == meshes.front())  // the coarsest mesh under a name of its own, for the prose
          mrm::tex_define(defs, "stab:long:" + repro::mass_names()[mass] + ":coarse", mrm::tex_magnitude(ratio));
      }

    // 5. Commit.
    program.commit();
    return 0;
  });
}
