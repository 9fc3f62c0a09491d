// bar1d: one run of one configuration on the benchmark of mathematics.md §2.
//
// What it computes. The elastic bar (0, L), clamped at x = L and released at rest from
// u⁰(x) = a (L − x) against the rigid obstacle at x = 0, discretised with P1 elements and a
// Lagrange multiplier at the contact node, a mass matrix (consistent, or redistributed by Mod 1, 2
// or 3) and one time scheme (Crank–Nicolson, backward Euler or Paoli–Schatzman). It prints the
// relative errors of mathematics.md §5 against the exact solution, the energy range and the run's size
// and time, one `name = value` line each, and optionally writes the time series of the contact
// point (u(0,t), λ(t), the energy, and the exact values beside them). Its standard output is the
// same bytes for the same command except the wall time of the run (wall_seconds), which
// `--no-timing` leaves out.
//
// Sample runs:
//   bar1d --scheme cn --mass mod3 --elements 50 --courant 0.5 --final-time 12
//   bar1d --scheme ps --ps-form literal --mass mod2 --elements 100 --dt 0.004 --output ps.dat
//   bar1d --scheme be --mass consistent --elements 200 --courant 1
//
// Description. Steps: (1) read the options; (2) open the output file (so that a bad path fails
// before the run); (3) build the mesh, the mass and the scheme, Δt = C h unless --dt is given;
// (4) run to the final time, accumulating the errors and, if asked, the time series; (5) print the
// figures and commit the output.
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <sstream>
#include <string>

#include "options.hpp"
#include "output_file.hpp"
#include "configurations.hpp"
#include "errors.hpp"
#include "exact_solution.hpp"
#include "schemes.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("bar1d", [&] {
    // 1. Options.
    long elements = 100;
    double courant = 0.5, dt = 0.0, final_time = 6.0, length = 1.0, amplitude = 0.5, beta = 0.25, restitution = 0.0;
    std::string scheme = "cn", mass = "mod3", ps_form = "algebraic", initial = "consistent", contact_velocity = "scheme",
                output;
    bool no_timing = false;
    // The ranges below keep every quantity of the run (h, Δt², the matrices' entries, the energy a²L/2)
    // far from overflow and underflow of a double, and the memory (≈ 250 bytes per element) bounded.
    constexpr double largest_courant = 1e6, largest_steps = 1e12;
    const cli::Check courant_range = [&](std::string_view option, double value) {
      cli::require_positive(option, value);
      cli::require_in_closed_range(option, value, 0, largest_courant);
    };
    cli::Parser parser("bar1d",
                       "Runs one scheme with one mass matrix on the bar hitting an obstacle (the benchmark with "
                       "a closed-form solution) and prints the relative errors against the exact solution, "
                       "the energy range, the number of steps and the run time, one `name = value` line each.",
                       {"bar1d --scheme cn --mass mod3 --elements 50 --courant 0.5 --final-time 12",
                        "bar1d --scheme ps --ps-form literal --mass mod2 --elements 100 --dt 0.004 --output ps.dat"});
    parser.add_integer("--elements", "-n", "N", "number of elements N of the mesh (h = L/N), an integer in [2, 1e7]",
                       &elements, cli::in_closed_range(2, 1e7));
    parser.add_real("--courant", "-c", "C", "time step as a multiple of h: dt = C h (0 < C <= 1e6)", &courant,
                    courant_range);
    parser.add_real("--dt", "", "X", "time step (0 < dt <= 1e6 h); excludes --courant", &dt, cli::positive());
    parser.add_real("--final-time", "-T", "T", "final time (> 0); the period of the benchmark is 3L", &final_time,
                    cli::positive());
    parser.add_real("--length", "-L", "L", "length of the bar, in [1e-100, 1e100]", &length,
                    cli::in_closed_range(1e-100, 1e100));
    parser.add_real("--amplitude", "-a", "A", "initial datum u0(x) = A (L - x), A in [1e-100, 1e100]", &amplitude,
                    cli::in_closed_range(1e-100, 1e100));
    parser.add_choice("--scheme", "-s", "S", "time scheme: Crank-Nicolson, backward Euler, Paoli-Schatzman",
                      {"cn", "be", "ps"}, &scheme);
    parser.add_string("--mass", "-m", "M", mrm::repro::mass_option_help("mass matrix"), &mass);
    parser.add_real("--beta", "-b", "B", "Paoli-Schatzman's beta, in [0, 1e6]", &beta, cli::in_closed_range(0, 1e6));
    parser.add_real("--restitution", "-e", "E", "Paoli-Schatzman's restitution coefficient e in [0, 1]",
                    &restitution, cli::in_closed_range(0, 1));
    parser.add_choice("--ps-form", "", "F",
                      "Paoli-Schatzman's contact row: algebraic at every level, or the literal three-level formula "
                      "(the consistent mass needs literal, which is then the default)",
                      {"algebraic", "literal"}, &ps_form);
    parser.add_choice("--initial-contact-node", "", "I",
                      "initial value of a massless contact node: solved from its algebraic row, or the interpolant",
                      {"consistent", "interpolant"}, &initial);
    parser.add_choice("--contact-velocity", "", "V",
                      "velocity of a massless contact node in the velocity measures: the scheme's own, or the "
                      "backward difference (u0(t_n) - u0(t_n-1))/dt as GetFEM's demo_dynamic_contact_1D.py",
                      {"scheme", "backward-difference"}, &contact_velocity);
    parser.add_string("--output", "-o", "FILE", "write the contact-point time series to FILE", &output);
    parser.add_flag("--no-timing", "", "leave out the wall time of the run (wall_seconds, the one value that varies "
                    "from run to run)", &no_timing);
    parser.add_conflict("--dt", "--courant");
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    if (mass == "consistent" && !parser.given("--ps-form")) ps_form = "literal";
    if (mass == "consistent" && scheme == "ps" && ps_form == "algebraic")
      throw cli::UsageError("--ps-form: algebraic needs a massless contact node (any --mass but consistent); "
                            "with --mass consistent use --ps-form literal");
    if (scheme == "ps" && ps_form == "literal" && beta == 0.0 && mass != "consistent")
      throw cli::UsageError("--beta: 0 is not allowed with --ps-form literal and a massless contact node "
                            "(the step matrix is singular); use --beta > 0 or --ps-form algebraic");

    // The mass is checked on the mesh of the run (a spread over more nodes than the mesh has, a matrix
    // that is not positive definite): a bad value fails here, before any file is touched.
    const mrm::UniformMesh mesh(length, elements);
    const mrm::MassRedistribution redistribution = mrm::repro::mass_from_option("--mass", mass, mesh);

    // 2. The output, opened now so that an unwritable path fails before the run.
    std::unique_ptr<cli::AtomicFile> series;
    if (parser.given("--output")) series = std::make_unique<cli::AtomicFile>(output, "--output");

    // 3. Mesh, mass, scheme; Δt derived from h in this one place.
    const double step = parser.given("--dt") ? dt : courant * mesh.h();
    if (!(step <= largest_courant * mesh.h()))
      throw cli::UsageError("--dt: " + cli::format_real(step) + " is more than 1e6 h = " +
                            cli::format_real(largest_courant * mesh.h()) + " (allowed: 0 < dt <= 1e6 h, h = L/N)");
    if (!(final_time / step <= largest_steps))
      throw cli::UsageError("--final-time: " + cli::format_real(final_time) + " needs " +
                            cli::format_real(std::ceil(final_time / step)) + " steps of " + cli::format_real(step) +
                            " (allowed: at most 1e12 steps; lower --final-time or raise --dt or --courant)");
    dt = step;  // the header echoes the effective step
    mrm::repro::Configuration configuration;
    configuration.scheme.scheme = mrm::scheme_by_name(scheme);
    configuration.scheme.beta = beta;
    configuration.scheme.restitution = restitution;
    configuration.scheme.contact_row = mrm::contact_row_by_name(ps_form);
    configuration.mass = redistribution;
    configuration.elements = elements;
    configuration.dt = step;
    configuration.final_time = final_time;
    configuration.length = length;
    configuration.amplitude = amplitude;
    configuration.initial = mrm::initial_contact_node_by_name(initial);
    configuration.contact_velocity = mrm::repro::contact_velocity_by_name(contact_velocity);
    const mrm::Index steps = mrm::steps_to_reach(final_time, step);
    const mrm::ExactSolution exact(length, amplitude);
    const bool massless = mrm::contact_node_is_massless(mrm::modified_mass(mesh, configuration.mass));

    if (series) {
      std::ostream& out = series->stream();
      out << "# bar1d: time series at the contact point x = 0 (problem.md §2 benchmark)\n";
      parser.echo(out);
      out << "# h = " << cli::format_real(mesh.h()) << "\n# steps = " << steps << "\n# total_mass = " << cli::format_real(mrm::total_mass(mesh, configuration.mass))
          << "\n# massless_contact_node = " << (massless ? "true" : "false")
          << "\n# exact_energy = " << cli::format_real(exact.energy()) << '\n'
          << "# Each quantity is given at the instant it approximates: t for u0, t_lambda for lambda,\n"
          << "# t_energy for the energy (Paoli-Schatzman: lambda at t_n or t_{n+1}, energy at t_{n+1/2}).\n"
          << "# lambda_h = nan where the level has no multiplier yet.\n"
          << "# columns: t u0_h u0_exact t_lambda lambda_h lambda_exact t_energy energy_h energy_exact\n";
    }

    // 4. The run (repro/configurations: the errors and the energy range), writing the series if asked.
    const auto start = std::chrono::steady_clock::now();
    const mrm::repro::Measures measures = mrm::repro::run_configuration(configuration, [&](const mrm::Sample& s) {
      if (series) {
        std::ostream& out = series->stream();
        const double nan = std::numeric_limits<double>::quiet_NaN();
        out << cli::format_real(s.time) << ' ' << cli::format_real((*s.displacement)[0]) << ' '
            << cli::format_real(exact.contact_displacement(s.time)) << ' ' << cli::format_real(s.multiplier_time)
            << ' ' << cli::format_real(s.has_multiplier ? s.multiplier : nan) << ' '
            << cli::format_real(exact.contact_multiplier(s.multiplier_time)) << ' '
            << cli::format_real(s.energy_time) << ' ' << cli::format_real(s.energy) << ' '
            << cli::format_real(exact.energy()) << '\n';
      }
    });
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

    // 5. The figures, then the output file.
    const auto values = mrm::ErrorAccumulator::values(measures.errors);
    for (std::size_t k = 0; k < values.size(); ++k)
      std::cout << mrm::ErrorAccumulator::names[k] << " = " << cli::format_real(values[k]) << '\n';
    std::cout << "energy_initial = " << cli::format_real(measures.energy_initial) << '\n'
              << "energy_final = " << cli::format_real(measures.energy_final) << '\n'
              << "energy_min = " << cli::format_real(measures.energy_min) << '\n'
              << "energy_max = " << cli::format_real(measures.energy_max) << '\n'
              << "steps = " << measures.steps << '\n';
    if (!no_timing) std::cout << "wall_seconds = " << cli::format_real(std::round(wall * 1e4) / 1e4) << '\n';
    if (series) series->commit();
    return 0;
  });
}
