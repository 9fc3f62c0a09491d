// fig_convergence: convergence in space and time, every error measure against h.
//
// What it computes. The relative errors of mathematics.md §5 (u(0,·) and λ in L²(0,T); u in L∞(0,T;L²),
// L∞(0,T;H¹), L²(0,T;L²), L²(0,T;H¹); u_t in L∞(0,T;L²) and L²(0,T;L²)) against the exact solution of
// the benchmark, for every scheme (Crank–Nicolson, backward Euler, Paoli–Schatzman (¼, 0)) and every mass
// choice (Mod 1, 2, 3), on the meshes N = N₀, 2N₀, …, 2^{K−1}N₀ with Δt = h and Δt = h/2 (the paper's
// Section 2: the method converges as h, Δt → 0). The observed order of each measure is the slope of the
// least-squares line through (log h, log error) (mrm::fit_order, GSL). The final time is one period,
// T = 3: it covers the free flight, the impact at t = 1, the contact and the release at t = 2.
//
// The runs are independent; they are spread over --threads worker threads, and the results are
// written in a fixed order, so that the output does not depend on the number of threads.
//
// Sample runs:
//   fig_convergence --output output/data/fig_convergence.dat --tex output/data/fig_convergence.tex
//   fig_convergence --coarsest 16 --refinements 4 --threads 1 --output c.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the list of runs; (4) the runs, in parallel;
// (5) the data blocks; (6) the orders, the tables and the values the report quotes; (7) commit.
//
// Data file: block 2 (3 s + m) + c is scheme s ∈ (cn, be, ps), mass m ∈ (mod1, mod2, mod3), ratio
// c ∈ (Δt = h, Δt = h/2); columns N h dt and the eight errors.
#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "configurations.hpp"
#include "labels.hpp"
#include "figure_program.hpp"
#include "refinement.hpp"
#include "parallel.hpp"
#include "sweep.hpp"
#include "report_values.hpp"
#include "scheme_options.hpp"
#include "table.hpp"
#include "time/schemes.hpp"

namespace cli = mrm::cli;

namespace {

// The two ratios Δt/h of mathematics.md §5, with the short names used in keys and their labels.
const std::array<double, 2> courants{1.0, 0.5};
const std::array<const char*, 2> courant_keys{"dth", "dth2"};
const std::array<const char*, 2> courant_labels{"$\\Delta t = h$", "$\\Delta t = h/2$"};

struct Run {
  std::size_t scheme, mass, courant, level;
  mrm::Index elements;
  double cost;  // steps × unknowns, to start the longest runs first
  std::array<double, 8> errors{};
};

// The runs of the study in the order of the data blocks (scheme, mass, ratio, mesh).
struct Study {
  const std::vector<Run>& runs;
  std::size_t masses, levels;
  const Run& at(std::size_t s, std::size_t m, std::size_t c, std::size_t l) const {
    return runs[((s * masses + m) * courants.size() + c) * levels + l];
  }
};

// Step 6: the orders (fit over all meshes), the tables of orders and of the errors on the finest mesh,
// the ranking of the three masses, and the values quoted in the prose.
void write_orders(std::ostream& defs, const Study& study, const mrm::repro::MeshRefinement& meshes,
                  const std::vector<std::string>& schemes, const std::vector<std::string>& masses,
                  const std::string& ps_form, double final_time) {
  const mrm::Index finest = meshes.finest();
  const mrm::Index coarsest = meshes.coarsest();
  const std::size_t levels = meshes.levels();
  auto at = [&](std::size_t s, std::size_t m, std::size_t c, std::size_t l) -> const Run& {
    return study.at(s, m, c, l);
  };
  mrm::tex_define(defs, "conv:Nmin", std::to_string(coarsest));
  mrm::tex_define(defs, "conv:Nmax", std::to_string(finest));
  mrm::tex_define(defs, "conv:meshes", std::to_string(levels));
  mrm::tex_define(defs, "conv:T", cli::format_real(final_time));
  mrm::tex_define(defs, "conv:psform", ps_form);
  // The two steps of the study, for the prose ("\mrm{conv:dt:dth2}" prints "$\Delta t = h/2$").
  for (std::size_t c = 0; c < courants.size(); ++c)
    mrm::tex_define(defs, std::string("conv:dt:") + courant_keys[c], courant_labels[c]);
  std::vector<std::string> headers{"scheme", "mass", "$\\Delta t$"}, ranking_headers{"scheme", "$\\Delta t$"};
  for (const mrm::repro::Label& label : mrm::repro::measure_labels()) {
    headers.push_back("\\rotatebox{70}{" + label.latex + "}");
    ranking_headers.push_back(headers.back());
  }
  mrm::repro::Table orders_table(headers), errors_table(headers), ranking_table(ranking_headers);

  for (std::size_t s = 0; s < schemes.size(); ++s) {
    long ordered = 0, cases = 0;
    for (std::size_t m = 0; m < masses.size(); ++m)
      for (std::size_t c = 0; c < courants.size(); ++c) {
        std::vector<std::string> orders_row{
            m == 0 && c == 0 ? mrm::repro::scheme_row_label(schemes[s], ps_form) : std::string(),
            c == 0 ? mrm::repro::mass_label(masses[m]).abbreviation : std::string(), courant_labels[c]};
        std::vector<std::string> errors_row = orders_row;
        for (std::size_t k = 0; k < 8; ++k) {
          std::vector<double> errors(levels);
          for (std::size_t l = 0; l < levels; ++l) errors[l] = at(s, m, c, l).errors[k];
          const std::string key =
              schemes[s] + ":" + masses[m] + ":" + courant_keys[c] + ":" + mrm::ErrorAccumulator::names[k];
          const bool fittable =
              std::all_of(errors.begin(), errors.end(), [](double e) { return e > 0 && std::isfinite(e); });
          if (fittable) {
            const mrm::OrderFit fit = meshes.fit(errors);
            orders_row.push_back(mrm::tex_number(fit.order, 2));
            mrm::tex_define(defs, "conv:order:" + key, mrm::tex_number(fit.order, 2));
            mrm::tex_define(defs, "conv:stderr:" + key, mrm::tex_number(fit.order_std_error, 1));
          } else {
            orders_row.push_back("n/a");
            mrm::tex_define(defs, "conv:order:" + key, "n/a");
            mrm::tex_define(defs, "conv:stderr:" + key, "n/a");
          }
          errors_row.push_back(mrm::tex_number(errors.back(), 2));
          mrm::tex_define(defs, "conv:err:" + key, mrm::tex_number(errors.back(), 2));
          mrm::tex_define(defs, "conv:errcoarse:" + key, mrm::tex_number(errors.front(), 2));
        }
        orders_table.add_row(orders_row);
        errors_table.add_row(errors_row);
      }
    // The paper's claim 3: Mod 3 < Mod 2 < Mod 1 in error. Counted over every measure, mesh and ratio.
    for (std::size_t c = 0; c < courants.size(); ++c) {
      std::vector<std::string> ranking_row{c == 0 ? mrm::repro::scheme_row_label(schemes[s], ps_form) : std::string(),
                                           courant_labels[c]};
      for (std::size_t k = 0; k < 8; ++k) {
        for (std::size_t l = 0; l < levels; ++l) {
          const double e1 = at(s, 0, c, l).errors[k], e2 = at(s, 1, c, l).errors[k], e3 = at(s, 2, c, l).errors[k];
          ordered += (e3 < e2 && e2 < e1);
          ++cases;
        }
        // The ranking on the finest mesh, best first: "3 2 1" is the paper's order.
        std::array<std::size_t, 3> rank{0, 1, 2};
        std::stable_sort(rank.begin(), rank.end(), [&](std::size_t a, std::size_t b) {
          return at(s, a, c, levels - 1).errors[k] < at(s, b, c, levels - 1).errors[k];
        });
        const bool paper = rank[0] == 2 && rank[1] == 1 && rank[2] == 0;
        const std::string ranking =
            std::to_string(rank[0] + 1) + std::to_string(rank[1] + 1) + std::to_string(rank[2] + 1);
        ranking_row.push_back(paper ? "\\textbf{" + ranking + "}" : ranking);
      }
      ranking_table.add_row(ranking_row);
    }
    for (mrm::repro::Table* table : {&orders_table, &errors_table, &ranking_table}) table->add_rule();
    mrm::tex_define(defs, "conv:ordered:" + schemes[s], std::to_string(ordered));
    mrm::tex_define(defs, "conv:cases:" + schemes[s], std::to_string(cases));
  }
  // Each table in two halves at the text size (measures 1-4, then 5-8 of mathematics.md §5), not shrunk.
  const auto halves = [&](const std::string& key, const mrm::repro::Table& table, std::size_t lead, char align) {
    for (std::size_t half = 0; half < 2; ++half) {
      std::vector<std::size_t> keep;
      for (std::size_t c = 0; c < lead; ++c) keep.push_back(c);
      for (std::size_t k = 4 * half; k < 4 * half + 4; ++k) keep.push_back(lead + k);
      defs << "\\mrmdef{" << key << (half == 0 ? ":a" : ":b") << "}{"
           << mrm::repro::latex_tabular(table.columns_subset(keep), std::string(lead, 'l') + std::string(4, align))
           << "}\n";
    }
  };
  halves("conv:table:orders", orders_table, 3, 'r');
  halves("conv:table:errors", errors_table, 3, 'r');
  halves("conv:table:ranking", ranking_table, 2, 'c');
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_convergence", [&] {
    // 1. Options.
    long coarsest = 128, refinements = 6, threads = 2;
    mrm::repro::SchemeParameterOptions scheme_options;  // --ps-form
    mrm::repro::FigureProgram program(
        "fig_convergence",
        "Writes every relative error of mathematics.md §5 against h, with dt = h and dt = h/2, for "
        "every scheme (cn, be, ps) and mass choice (mod1, mod2, mod3), and the observed orders "
        "(least-squares fit of log error against log h).",
        {"fig_convergence --output output/data/fig_convergence.dat --tex output/data/fig_convergence.tex",
         "fig_convergence --coarsest 16 --refinements 4 --threads 1 --output c.dat"});
    program.parser.add_integer("--coarsest", "-n", "N0", "number of elements of the coarsest mesh, in [2, 1e7]",
                               &coarsest, mrm::repro::elements_range());
    program.parser.add_integer(
        "--refinements", "-k", "K",
        "number of meshes N0, 2 N0, ..., 2^(K-1) N0, in [2, 20]; the finest has at most 1e7 elements", &refinements,
        cli::in_closed_range(2, 20));
    program.add_final_time(3.0, "final time (> 0); one period is 3");
    mrm::SchemeParameters literal_row;  // the figure's Paoli-Schatzman: the literal contact row by default
    literal_row.contact_row = mrm::ContactRow::literal;
    scheme_options.declare(program.parser, {mrm::SchemeParameter::contact_row}, literal_row);
    cli::add_threads_option(program.parser, &threads);
    if (!program.parse(argc, argv, "also write the tables and values the report quotes")) return 0;
    const std::string ps_form = mrm::to_string(scheme_options.values().contact_row);
    const double final_time = program.final_time;
    // The finest mesh (K ≤ 20 and N0 ≤ 1e7: the product is exact in a double), its steps at Δt = h/2 and the
    // coarsest run's at Δt = h (at least one); the memory of the runs that may run at once (the batches of
    // the 18 finest, on up to `threads` workers) is checked before the runs (require_batched_memory).
    const double finest_elements = std::ldexp(static_cast<double>(coarsest), static_cast<int>(refinements) - 1);
    if (!(finest_elements <= cli::max_elements))
      throw cli::UsageError("--refinements: " + std::to_string(refinements) + " meshes from N0 = " +
                            std::to_string(coarsest) + " end at " + cli::format_real(finest_elements) +
                            " elements (allowed: at most 1e7; lower --coarsest or --refinements)");
    cli::checked_steps("--final-time", final_time, 0.5 / finest_elements,
                       "the finest mesh size (lower --coarsest or --refinements)");
    cli::checked_steps("--final-time", final_time, 1.0 / static_cast<double>(coarsest), "--coarsest");

    // 2. Outputs.
    program.open();
    const auto& schemes = mrm::repro::scheme_names();
    const auto& masses = mrm::repro::mass_names();

    // 3. The runs, longest first.
    const mrm::repro::MeshRefinement meshes(static_cast<mrm::Index>(coarsest), static_cast<std::size_t>(refinements));
    std::vector<Run> runs;
    for (std::size_t s = 0; s < schemes.size(); ++s)
      for (std::size_t m = 0; m < masses.size(); ++m)
        for (std::size_t c = 0; c < courants.size(); ++c)
          for (std::size_t l = 0; l < meshes.levels(); ++l) {
            const mrm::Index n = meshes.elements(l);
            const double h = meshes.mesh_sizes()[l];
            runs.push_back(
                {s, m, c, l, n, static_cast<double>(mrm::steps_to_reach(final_time, courants[c] * h)) * n, {}});
          }

    // 4. The runs through the sweep layer (repro/sweep.hpp: batched in vector lanes on `threads` workers;
    // each run's measures are its own, bit for bit, in the order of `runs`).
    std::vector<mrm::repro::Configuration> configurations;
    for (const Run& r : runs)
      configurations.push_back(mrm::repro::paper_configuration(schemes[r.scheme], ps_form, masses[r.mass], r.elements,
                                                               courants[r.courant], final_time));
    mrm::repro::SweepSettings settings = mrm::repro::sweep_settings();
    settings.threads = static_cast<unsigned>(threads);
    mrm::repro::require_batched_memory("--coarsest", configurations, settings);  // before any run
    const std::vector<mrm::repro::Measures> measures = mrm::repro::run_batched(configurations, settings);
    for (std::size_t k = 0; k < runs.size(); ++k) runs[k].errors = mrm::ErrorAccumulator::values(measures[k].errors);
    std::cerr << "fig_convergence: " << runs.size() << " runs done\n";

    // 5. The data blocks, in the fixed order of `runs` (scheme, mass, ratio, mesh).
    std::ostream& out = program.header("relative errors against h (mathematics.md sec. 5)");
    mrm::repro::write_scheme_titles(out, ps_form);
    out << "# blocks: 2 (3 s + m) + c: scheme s in (cn, be, ps), mass m in (mod1, mod2, mod3), c in (dt = h, dt = "
           "h/2)\n";
    const Study study{runs, masses.size(), meshes.levels()};
    const std::size_t levels = meshes.levels();
    auto at = [&](std::size_t s, std::size_t m, std::size_t c, std::size_t l) -> const Run& {
      return study.at(s, m, c, l);
    };
    for (std::size_t s = 0; s < schemes.size(); ++s)
      for (std::size_t m = 0; m < masses.size(); ++m)
        for (std::size_t c = 0; c < courants.size(); ++c) {
          out << (s + m + c ? "\n\n" : "") << "# block " << (s * masses.size() + m) * courants.size() + c
              << ": scheme = " << schemes[s] << ", mass = " << masses[m] << ", dt/h = " << cli::format_real(courants[c])
              << '\n';
          std::vector<mrm::repro::ErrorRow> rows;
          for (std::size_t l = 0; l < levels; ++l) rows.push_back({at(s, m, c, l).elements, at(s, m, c, l).errors});
          mrm::repro::write_error_rows(out, 1.0, courants[c], rows);
        }

    // 6. Orders (fit over all meshes), the tables of orders and of the errors on the finest mesh, the
    // ranking of the three masses, and the values quoted in the prose.
    write_orders(program.values(), study, meshes, schemes, masses, ps_form, final_time);

    // 7. Commit.
    program.commit();
    return 0;
  });
}
