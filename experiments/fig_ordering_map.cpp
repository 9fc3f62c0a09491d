// fig_ordering_map: where the paper's ranking Mod 3 < Mod 2 < Mod 1 holds (claim 3 over a region).
//
// What it computes. From the sweep of check_claims (repro/regions.cpp: Crank–Nicolson, backward Euler and
// Paoli–Schatzman with the algebraic row, Mod 1/2/3, Δt/h ∈ {¼, ½, ¾, 1}, N = 25 … 800, horizons of
// 1, 4, 10 and 30 periods, and Paoli–Schatzman with the consistent mass as a baseline), per cell
// (scheme, Δt/h, N, horizon): how many of the measures the scheme is judged in rank the masses as the
// paper says (repro::ordering_cells; Paoli–Schatzman's displacements and λ are Crank–Nicolson's, so only
// its velocity counts), per (scheme, Δt/h, N) and measure the horizon from which the ranking holds at
// every longer horizon, and per cell how many of the eight measures Crank–Nicolson with Mod 3 has
// smaller than the baseline.
//
// Sample runs:
//   fig_ordering_map --sweep output/data/sweep.dat --output output/data/fig_ordering_map.dat --tex output/data/fig_ordering_map.tex
//
// Description. Steps: (1) options; (2) outputs; (3) read the sweep; (4) the cells, block by block;
// (5) the values; (6) commit.
//
// Data file: block 4s + j (scheme s ∈ (cn, be, ps), ratio j) has columns elements horizon ranked judged
// cn_mod3_beats_baseline; block 12 + 4s + j has columns elements and, per measure, the first horizon (in
// periods) from which it is ranked at every longer horizon (0: not at the longest).
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
  return cli::guarded_main("fig_ordering_map", [&] {
    // 1. Options.
    std::string sweep_file = "output/data/sweep.dat";
    mrm::repro::FigureProgram program(
        "fig_ordering_map",
        "Reads the sweep written by check_claims --sweep and writes, per cell (scheme, dt/h, N, "
        "horizon), how many measures rank the masses Mod 3 < Mod 2 < Mod 1, and from which horizon.",
        {"fig_ordering_map --sweep output/data/sweep.dat --output output/data/fig_ordering_map.dat"});
    program.parser.add_input("--sweep", "-i", "the sweep to read (check_claims --sweep FILE)", &sweep_file);
    if (!program.parse(argc, argv)) return 0;

    // 2. Outputs, opened first so that a bad output path fails before anything is read.
    program.open();

    // 3. The sweep.
    const repro::Sweep sweep = repro::read_sweep_file(sweep_file, "--sweep");
    const repro::SweepGrid& g = sweep.grid;

    std::ostream& out =
        program.header("the ranking Mod 3 < Mod 2 < Mod 1 per cell (claim 3, mathematics.md sec. 6, 8)");
    // The title of a scheme's panels: its name, or for a scheme judged in its velocity only (Paoli–Schatzman,
    // repro::judged_measures) its name without its parameters, and "velocity".
    for (const std::string& s : g.schemes) {
      const std::string& name = repro::scheme_label(s).plain;
      const bool velocity_only = repro::judged_measures(s) == std::vector<std::size_t>{4, 7};
      out << "# title " << s << " = " << (velocity_only ? name.substr(0, name.find(" (")) + ", velocity" : name)
          << '\n';
    }
    out << "# blocks 4 s + j: scheme s in (cn, be, ps), ratio j in (";
    for (double c : g.courants) out << ' ' << cli::format_real(c);
    out << " ); columns: elements horizon ranked judged cn_mod3_beats_baseline\n"
        << "# blocks 12 + 4 s + j: columns elements and, per measure, the first horizon from which it is ranked (0: "
           "never)\n";

    // 4. The cells.
    const std::vector<repro::OrderingCell> cells = repro::ordering_cells(sweep, g.masses);
    const auto cell = [&](const std::string& s, double c, mrm::Index n, std::size_t k) -> const repro::OrderingCell& {
      for (const repro::OrderingCell& x : cells)
        if (x.scheme == s && x.courant == c && x.elements == n && x.horizon == k) return x;
      throw std::logic_error("fig_ordering_map: missing cell");
    };
    int block = 0;
    for (const std::string& s : g.schemes) {
      const std::vector<std::size_t> judged = repro::judged_measures(s);
      for (double c : g.courants) {
        out << (block ? "\n\n" : "") << "# block " << block << ": scheme = " << s << ", dt/h = " << cli::format_real(c)
            << "\n";
        ++block;
        for (mrm::Index n : g.elements)
          for (std::size_t k = 0; k < g.horizons.size(); ++k) {
            int beats = 0;
            if (g.baseline) {
              const auto& mine = sweep.find(mrm::to_string(mrm::Scheme::crank_nicolson), "mod3", c, n).errors[k];
              const auto& base = sweep.find("ps-consistent", "consistent", c, n).errors[k];
              for (std::size_t q = 0; q < 8; ++q) beats += mine[q] < base[q];
            }
            out << n << ' ' << cli::format_real(g.horizons[k]) << ' ' << cell(s, c, n, k).count(judged) << ' '
                << judged.size() << ' ' << beats << '\n';
          }
      }
    }
    for (const std::string& s : g.schemes)
      for (double c : g.courants) {
        out << "\n\n# block " << block << ": scheme = " << s << ", dt/h = " << cli::format_real(c)
            << "\n# columns: elements";
        ++block;
        for (const char* name : mrm::ErrorAccumulator::names) out << ' ' << name;
        out << '\n';
        for (mrm::Index n : g.elements) {
          out << n;
          for (std::size_t q = 0; q < 8; ++q) {
            double from = 0;
            for (std::size_t k = g.horizons.size(); k-- > 0;) {
              if (!cell(s, c, n, k).ordered[q]) break;
              from = g.horizons[k];
            }
            out << ' ' << cli::format_real(from);
          }
          out << '\n';
        }
      }

    // 5. The values: cells ranked in every judged measure, per scheme and horizon.
    std::ostream& defs = program.values();
    // The same counts as one list per scheme ("0, 4, 7, 17"), in the order of the horizons, and the grid
    // itself, for the prose: the ratios, the horizons and the meshes, as the sweep ran them.
    const auto list = [](const auto& values, const auto& text) {
      std::string joined;
      for (const auto& v : values) joined += (joined.empty() ? "" : ", ") + text(v);
      return joined;
    };
    for (const std::string& s : g.schemes) {
      const std::vector<std::size_t> judged = repro::judged_measures(s);
      std::vector<int> counts;
      for (std::size_t k = 0; k < g.horizons.size(); ++k) {
        int ranked = 0;
        for (double c : g.courants)
          for (mrm::Index n : g.elements) ranked += cell(s, c, n, k).count(judged) == static_cast<int>(judged.size());
        mrm::tex_define(defs, "ordermap:" + s + ":" + cli::format_real(g.horizons[k]), std::to_string(ranked));
        counts.push_back(ranked);
      }
      mrm::tex_define(defs, "ordermap:" + s + ":ranked", list(counts, [](int n) { return std::to_string(n); }));
    }
    mrm::tex_define(defs, "ordermap:cells", std::to_string(g.courants.size() * g.elements.size()));
    mrm::tex_define(defs, "ordermap:Nmin", std::to_string(g.elements.front()));
    mrm::tex_define(defs, "ordermap:Nmax", std::to_string(g.elements.back()));
    mrm::tex_define(defs, "ordermap:meshes", list(g.elements, [](mrm::Index n) { return std::to_string(n); }));
    mrm::tex_define(defs, "ordermap:ratios", list(g.courants, [](double c) { return cli::format_real(c); }));
    mrm::tex_define(defs, "ordermap:horizons", list(g.horizons, [](double k) { return cli::format_real(k); }));

    // 6. Commit.
    program.commit();
    return 0;
  });
}
