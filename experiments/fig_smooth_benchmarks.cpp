// fig_smooth_benchmarks: the smooth benchmarks S1 and S2 at the contact point, exact against Mod 1/2/3.
//
// What it computes. For S1 (generic impact) and S2 (grazing contact) of mathematics.md §11, the contact
// point's displacement u(0, t) and the contact stress λ(t) of Crank–Nicolson with Mod 1, 2 and 3 on a
// coarse mesh (N = 40, Δt = h/2 by default), beside the exact values of the characteristic solution
// (mathematics.md §10), on [0, T], T = 2. The report also quotes the benchmarks' computed constants (K,
// t*, t_r), the largest error of u(0, ·) of each mass, and a check of the characteristic solution itself:
// its largest difference from the closed form of the paper's benchmark (mathematics.md §2) over 10
// periods, in u, u_x, u_t, u(0, ·) and λ, for two bars (L, a) (characteristics.hpp's
// closed_form_difference), each checked against the round-off bound derived there: the program fails
// if one is above it.
//
// Sample runs:
//   fig_smooth_benchmarks --output output/data/fig_smooth_benchmarks.dat --tex output/data/fig_smooth_benchmarks.tex
//   fig_smooth_benchmarks --elements 20 --output s.dat
//
// Description. Steps: (1) options; (2) outputs; (3) the closed-form check; (4) for each benchmark, the
// three runs and the exact values at their levels, one data block, and the values the report quotes;
// (5) commit.
//
// Data file: block b ∈ (S1, S2); columns t u0_exact lambda_exact, then u0_h and lambda_h for Mod 1, 2, 3.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <iostream>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "exact/characteristics.hpp"
#include "configurations.hpp"
#include "figure_program.hpp"
#include "options.hpp"
#include "report_values.hpp"
#include "exact/smooth_benchmarks.hpp"

namespace cli = mrm::cli;

namespace {

// The bars of the closed-form check: (L, a), compared over 10 periods (T = 30 L).
constexpr std::array<std::pair<double, double>, 2> closed_form_bars{{{1.0, 0.5}, {2.5, 1e-3}}};
constexpr double closed_form_periods = 10;

// The characteristic solution against the closed form over 10 periods (a check of the reference,
// mathematics.md §2 against §10), for two bars; every difference must be within the round-off bound
// derived in characteristics.cpp. Writes the differences to the data file's header and the report's values.
void check_closed_form(std::ostream& out, std::ostream& defs) {
  const double bound = mrm::closed_form_round_off_bound(closed_form_periods);
  out << "# closed_form_periods = " << cli::format_real(closed_form_periods)
      << "\n# closed_form_bound = " << cli::format_real(bound)
      << " (eps (W (W + 1)/2 + 8 (W + 1)), W = 3 x periods: the number of windows of length L)\n"
      << "# closed_form_k_*: bar k, the largest |difference| of u and u0 = u(0,t) relative to aL, of u_x, u_t and "
         "lambda relative to a\n";
  mrm::tex_define(defs, "smoothbench:closedform:periods", cli::format_real(closed_form_periods));
  mrm::tex_define(defs, "smoothbench:closedform:bound", mrm::tex_number(bound, 2));
  for (std::size_t k = 0; k < closed_form_bars.size(); ++k) {
    const auto [length, amplitude] = closed_form_bars[k];
    const mrm::ClosedFormDifference d = mrm::closed_form_difference(length, amplitude, closed_form_periods);
    const std::string key = "smoothbench:closedform:" + std::to_string(k + 1);
    const std::pair<const char*, double> entries[] = {{"u", d.displacement},
                                                      {"u_x", d.strain},
                                                      {"u_t", d.velocity},
                                                      {"u0", d.contact_displacement},
                                                      {"lambda", d.contact_multiplier}};
    const std::string prefix = "# closed_form_" + std::to_string(k + 1) + "_";
    out << prefix << "L = " << cli::format_real(length) << '\n'
        << prefix << "a = " << cli::format_real(amplitude) << '\n';
    for (const auto& [name, value] : entries) out << prefix << name << " = " << cli::format_real(value) << '\n';
    mrm::tex_define(defs, key + ":L", cli::format_real(length));
    mrm::tex_define(defs, key + ":a", cli::format_real(amplitude));
    for (const auto& [name, value] : entries) {
      if (!(value <= bound))
        throw std::runtime_error(std::string("the characteristic solution differs from the closed form in ") + name +
                                 " by " + cli::format_real(value) + " (L = " + cli::format_real(length) +
                                 ", a = " + cli::format_real(amplitude) + "), above the round-off bound " +
                                 cli::format_real(bound));
      mrm::tex_define(defs, key + ":" + name, mrm::tex_number(value, 2));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("fig_smooth_benchmarks", [&] {
    // 1. Options.
    mrm::repro::FigureProgram program(
        "fig_smooth_benchmarks",
        "Writes u(0,t) and lambda(t) of the smooth benchmarks S1 and S2 (mathematics.md sec. 11): "
        "Crank-Nicolson with mod1, mod2, mod3 on a coarse mesh beside the characteristic solution.",
        {"fig_smooth_benchmarks --output output/data/fig_smooth_benchmarks.dat --tex "
         "output/data/fig_smooth_benchmarks.tex",
         "fig_smooth_benchmarks --elements 20 --output s.dat"});
    program.add_elements(40, "number of elements of the mesh, in [2, 1e5]", cli::in_closed_range(2, 1e5));
    program.add_courant(0.5, "time step dt = C h, C in (0, 100]", [](std::string_view option, double value) {
      cli::require_positive(option, value);
      cli::require_in_closed_range(option, value, 0, 100);
    });
    if (!program.parse(argc, argv, "also write the values the report quotes")) return 0;
    const long elements = program.elements;
    const double courant = program.courant;

    // 2. Outputs.
    program.open();
    std::ostream& out =
        program.header("u(0,t) and lambda(t) of the smooth benchmarks (mathematics.md sec. 11), Crank-Nicolson");
    std::ostream& defs = program.values();
    const auto& masses = mrm::repro::mass_names();

    // 3. The characteristic solution against the closed form (a check of the reference).
    check_closed_form(out, defs);
    out << "# lambda_h = n/a at a level without a multiplier\n";

    // 4. One block per benchmark: the three runs sampled at their levels, the exact values beside them.
    const std::array<mrm::SmoothBenchmark, 2> which{mrm::SmoothBenchmark::generic_impact,
                                                    mrm::SmoothBenchmark::grazing};
    const std::array<const char*, 2> names{"smooth-impact", "grazing"}, keys{"s1", "s2"};
    for (std::size_t b = 0; b < which.size(); ++b) {
      const mrm::SmoothBenchmarkData benchmark = mrm::smooth_benchmark(which[b]);
      std::vector<std::vector<double>> columns(2 + 2 * masses.size());
      std::vector<std::vector<bool>> absent(columns.size());  // a level without a multiplier: written n/a
      std::vector<double> times;
      std::shared_ptr<const mrm::ReferenceSolution> reference;
      std::vector<double> first_impact_error(masses.size());
      for (std::size_t m = 0; m < masses.size(); ++m) {
        mrm::repro::Configuration c = mrm::repro::paper_configuration(
            mrm::Scheme::crank_nicolson, "algebraic", masses[m], elements, courant, benchmark.final_time);
        c.benchmark = names[b];
        if (!reference) {
          const double dt = c.step();
          reference = mrm::repro::configuration_reference(
              c, mrm::repro::reference_horizon(mrm::steps_to_reach(c.final_time, dt), dt));
        }
        std::size_t level = 0;
        const mrm::repro::Measures measures = mrm::repro::run_configuration(
            c,
            [&](const mrm::Sample& s) {
              if (m == 0) {
                times.push_back(s.time);
                columns[0].push_back(reference->contact_displacement(s.time));
                columns[1].push_back(reference->contact_multiplier(s.multiplier_time));
              } else if (level >= times.size() || times[level] != s.time) {
                throw std::logic_error("the three runs of a benchmark must share their levels");
              }
              columns[2 + 2 * m].push_back((*s.displacement)[0]);
              columns[3 + 2 * m].push_back(s.has_multiplier ? s.multiplier : 0.0);
              absent[3 + 2 * m].resize(columns[3 + 2 * m].size());
              absent[3 + 2 * m].back() = !s.has_multiplier;
              ++level;
            },
            reference.get());
        // The phase against the characteristic solution's impacts (mathematics.md §8): the error of the
        // first impact, in units of h.
        // A step too long to resolve the contact (dt = C h of the order of the contact interval) may give
        // a run without an impact to pair with the exact one: its first impact error is then absent, and
        // the data say so in words.
        if (!measures.phase) {
          first_impact_error[m] = std::numeric_limits<double>::quiet_NaN();
          continue;
        }
        first_impact_error[m] = measures.phase->first_impact_error * elements;
      }
      out << (b ? "\n\n" : "") << "# block " << b << ": benchmark = " << names[b]
          << "\n# K = " << cli::format_real(benchmark.scale)
          << "\n# touch_time = " << cli::format_real(benchmark.touch_time) << "\n# release_time = "
          << (std::isfinite(benchmark.release_time) ? cli::format_real(benchmark.release_time)
                                                    : std::string("none before T (held until the reflected wave)"))
          << "\n# exact_energy = " << cli::format_real(reference->energy());
      for (std::size_t m = 0; m < masses.size(); ++m)
        out << "\n# first_impact_error_over_h_" << masses[m] << " = "
            << (std::isfinite(first_impact_error[m])
                    ? cli::format_real(first_impact_error[m])
                    : std::string("n/a: no impact of the run paired with an exact one"));
      out << "\n# columns: t u0_exact lambda_exact u0_mod1 lambda_mod1 u0_mod2 lambda_mod2 u0_mod3 lambda_mod3\n";
      for (std::size_t n = 0; n < times.size(); ++n) {
        out << cli::format_real(times[n]);
        for (std::size_t k = 0; k < columns.size(); ++k)
          out << ' ' << (n < absent[k].size() && absent[k][n] ? std::string("n/a") : cli::format_real(columns[k][n]));
        out << '\n';
      }
      mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":K", mrm::tex_number(benchmark.scale, 4));
      mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":touch", mrm::tex_number(benchmark.touch_time, 4));
      if (std::isfinite(benchmark.release_time))
        mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":release",
                        mrm::tex_number(benchmark.release_time, 4));
      mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":energy", mrm::tex_number(reference->energy(), 4));
      for (std::size_t m = 0; m < masses.size(); ++m) {
        double largest = 0;
        for (std::size_t n = 0; n < times.size(); ++n)
          largest = std::max(largest, std::abs(columns[2 + 2 * m][n] - columns[0][n]));
        mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":" + masses[m] + ":u0error",
                        mrm::tex_number(largest, 2));
        mrm::tex_define(defs, std::string("smoothbench:") + keys[b] + ":" + masses[m] + ":firstimpact",
                        std::isfinite(first_impact_error[m]) ? mrm::tex_number(first_impact_error[m], 2)
                                                             : std::string("n/a (no impact)"));
      }
    }
    mrm::tex_define(defs, "smoothbench:N", std::to_string(elements));
    mrm::tex_define(defs, "smoothbench:courant", mrm::tex_number(courant, 3));

    // 5. Commit.
    program.commit();
    return 0;
  });
}
