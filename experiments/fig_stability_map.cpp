// fig_stability_map: where Crank–Nicolson with a massless contact node stays bounded (claim 1 over a
// region; mathematics.md §12).
//
// What it computes. Crank–Nicolson's energy balance with a massless contact node: a step that keeps
// the contact status conserves E_h, an impact loses energy and a release gains some, at most c²h v²/8
// per switch (c = Δt/h). For c ≲ 1 the two nearly cancel; for c ≫ 1 the gains win. This program
// measures the largest E_hⁿ/E_h(0) over 100 periods of the benchmark for Δt/h from ¼ to 40 (a geometric
// grid, ratio √2, and 40) on N = 16, 32, 64, 128 with Mod 3, over 1000 periods at Δt = h with
// Mod 1, 2, 3 on the same meshes, and every N from 4 to 40 at Δt/h ≤ 2 (how far down in N the bound
// holds). The grid is repro::StabilityGrid, the one the claims check judges.
//
// Sample runs:
//   fig_stability_map --output output/data/fig_stability_map.dat --tex output/data/fig_stability_map.tex
//   fig_stability_map --periods 10 --long-periods 100 --output s.dat
//
// Description. Steps: (1) options; (2) outputs; (3) all runs at once (threads); (4) the blocks and the
// values; (5) commit.
//
// Data file: block k (k = 0 … 3 for N = 16, 32, 64, 128): columns courant largest_energy_ratio; block 4:
// columns mass_index (1, 2, 3) elements largest_energy_ratio (the long runs at Δt = h); block 5: columns
// elements largest_energy_ratio (the scan, the largest over Δt/h ≤ 2).
#include <algorithm>
#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include "configurations.hpp"
#include "regions.hpp"
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

    // 2. Outputs. The grid is the claims' (repro::StabilityGrid), with the periods given.
    program.open();
    repro::StabilityGrid grid;
    grid.periods = periods;
    grid.long_periods = long_periods;
    std::ostream& out = program.header("Crank-Nicolson's largest E_h/E_h(0) (claim 1, mathematics.md sec. 12)");
    out << "# blocks 0-" << grid.meshes.size() - 1 << ": N = ";
    for (std::size_t b = 0; b < grid.meshes.size(); ++b) out << (b ? ", " : "") << grid.meshes[b];
    out << ", Mod 3, " << cli::format_real(periods) << " periods (courant largest); block " << grid.meshes.size()
        << ": dt = h, " << cli::format_real(long_periods) << " periods (mass_index elements largest); block "
        << grid.meshes.size() + 1
        << ": every N of the scan, the largest over dt/h <= " << cli::format_real(grid.scan_up_to)
        << " (elements largest)\n";
    out << "# threshold = " << cli::format_real(grid.threshold)
        << "\n# long_courant = " << cli::format_real(grid.long_courant) << '\n';

    // 3. All runs.
    std::cerr << "fig_stability_map: running the grid\n";
    const repro::StabilityRegion region = repro::run_stability_region(grid);

    // 4. The blocks and the values.
    std::ostream& defs = program.values();
    for (std::size_t b = 0; b < grid.meshes.size(); ++b) {
      out << (b ? "\n\n" : "") << "# block " << b << ": N = " << grid.meshes[b] << "\n# columns: courant largest\n";
      for (const repro::StabilityCell& cell : region.large)
        if (cell.elements == grid.meshes[b])
          out << cli::format_real(cell.courant) << ' ' << cli::format_real(cell.largest) << '\n';
    }
    mrm::tex_define(defs, "stab:bounded", cli::format_real(region.bounded_up_to()));
    mrm::tex_define(defs, "stab:threshold", cli::format_real(grid.threshold));
    mrm::tex_define(defs, "stab:periods", cli::format_real(periods));
    mrm::tex_define(defs, "stab:longperiods", cli::format_real(long_periods));
    // The grid, for the prose: the meshes, the coarsest one and the range of Δt/h.
    std::string mesh_list;
    for (mrm::Index n : grid.meshes) mesh_list += (mesh_list.empty() ? "" : ", ") + std::to_string(n);
    mrm::tex_define(defs, "stab:meshes", mesh_list);
    mrm::tex_define(defs, "stab:coarse", std::to_string(grid.meshes.front()));
    mrm::tex_define(defs, "stab:ratiomin", cli::format_real(grid.courants.front()));
    mrm::tex_define(defs, "stab:ratiomax", cli::format_real(grid.courants.back()));
    mrm::tex_define(defs, "stab:long:dt", grid.long_courant == 1 ? "h" : cli::format_real(grid.long_courant) + "h");
    out << "\n\n# block " << grid.meshes.size() << ": dt = h\n# columns: mass_index elements largest\n";
    const std::vector<std::string> masses = repro::mass_names();
    for (const repro::StabilityCell& cell : region.long_runs) {
      const std::size_t mass =
          static_cast<std::size_t>(std::find(masses.begin(), masses.end(), cell.mass) - masses.begin());
      out << mass + 1 << ' ' << cell.elements << ' ' << cli::format_real(cell.largest) << '\n';
      mrm::tex_define(defs, "stab:long:" + cell.mass + ":" + std::to_string(cell.elements),
                      mrm::tex_magnitude(cell.largest));
      if (cell.elements == grid.meshes.front())  // the coarsest mesh under a name of its own, for the prose
        mrm::tex_define(defs, "stab:long:" + cell.mass + ":coarse", mrm::tex_magnitude(cell.largest));
    }
    // The scan: how far down in N the bound holds at Δt/h ≤ scan_up_to.
    out << "\n\n# block " << grid.meshes.size() + 1 << ": scan, dt/h <= " << cli::format_real(grid.scan_up_to)
        << "\n# columns: elements largest\n";
    for (mrm::Index n : grid.scan) {
      double worst = 0;
      for (const repro::StabilityCell& cell : region.scan)
        if (cell.elements == n) worst = std::max(worst, cell.largest);
      out << n << ' ' << cli::format_real(worst) << '\n';
    }
    std::string failures;
    for (const auto& [n, largest] : region.scan_failures())
      failures += (failures.empty() ? "" : ", ") + std::to_string(n) + " (" + mrm::tex_magnitude(largest) + ")";
    mrm::tex_define(defs, "stab:scan:upto", cli::format_real(grid.scan_up_to));
    mrm::tex_define(defs, "stab:scan:first", std::to_string(grid.scan.front()));
    mrm::tex_define(defs, "stab:scan:last", std::to_string(grid.scan.back()));
    mrm::tex_define(defs, "stab:scan:from", std::to_string(region.bounded_from()));
    mrm::tex_define(defs, "stab:scan:failures", failures.empty() ? "none" : failures);

    // 5. Commit.
    program.commit();
    return 0;
  });
}
