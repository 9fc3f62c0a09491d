// bar1d: one run of one configuration on a benchmark or on initial data of one's own.
//
// What it computes. The elastic bar (0, L), clamped at x = L, released against the rigid obstacle at
// x = 0 from the initial data of a benchmark — the paper's u⁰(x) = a (L − x), v⁰ = 0 with its closed-form
// solution (mathematics.md §2, the default), or the smooth S1 (smooth-impact) and S2 (grazing) of
// mathematics.md §11 — or from samples x, u⁰, v⁰ read from a file (--initial-data), discretised with P1
// elements and a Lagrange multiplier at the contact node, a mass matrix (consistent, or redistributed by
// Mod 1, 2 or 3 or another member of the weighted family of mathematics.md §3: node1:X, spread:K,
// beta:B) and one time scheme (Crank–Nicolson, backward Euler, Paoli–Schatzman, or the
// energy-conserving Crank–Nicolson and Crank–Nicolson with a θ-step at each status change of
// mathematics.md §12). It prints the relative errors of mathematics.md §5 against the exact solution (the
// closed form for the paper's benchmark, the characteristic solution of mathematics.md §10 for any other
// data), the energy range, the run's size and time, and its phase (mathematics.md §8: the number of
// impacts, impacts_compared = how many were paired with exact impacts (mutual nearest neighbours no
// farther apart than half the exact inter-impact time: a run's extra contacts stay unpaired, and a run
// whose first impact has no partner gets no phase, mathematics.md §8), first_impact_error = the error of
// the first impact time, phase_drift_per_period = the least-squares drift of the impact times per
// period, negative when the impacts come early, and phase_period = the period it is counted in: 3L on
// the paper's benchmark, the mean interval between the exact impacts for other data; on the paper's
// benchmark the period law's predictions beside them), one `name = value` line each, and optionally
// writes the time series of the contact point (u(0,t), λ(t), the energy, and the exact values beside
// them), and the contact stress's oscillation (lambda_tv_ratio = TV(λ_h)/TV(λ_exact)) and the largest
// penetration (max_penetration). On the field's benchmarks (bouncing, impacting, gravity-paper, layered:
// field.md sec. 1) the run has the benchmark's load, gap, material and free far end, in its own units
// (the harness runs the dimensionless problem and scales back: repro/configurations.hpp, Scaling;
// Δt = C h/c with c the wave speed at the contact end), its reference is the chain's exact solution
// (lib/exact/impact_solution.hpp), and it also prints the exact contact windows over [0, T]
// (exact_contact_windows = [t1, t2] ...) and the run's (measured_contact_windows), in the benchmark's
// time unit. two-bars runs two meshes, N elements on each bar, coupled by one contact multiplier
// (lib/time/two_bodies.hpp; Crank-Nicolson only, a massless contact node on each bar); its errors are the
// larger of the two bars' (repro/configurations.hpp, run_configuration). --grading R runs the paper's
// benchmark, a smooth one or data of one's own on the mesh h_k = h0 R^k (finer toward the contact,
// dt = C h0), and on the paper's benchmark prints the period law's predictions for that mesh beside the
// measured drift (lib/measures/period_law.hpp: the eigenvalue law, and the first-order change against Mod 3). Its
// standard output is the same bytes for the same command except the wall time of the run
// (wall_seconds), which `--no-timing` leaves out.
//
// Sample runs:
//   bar1d --scheme cn --mass mod3 --elements 50 --courant 0.5 --final-time 12
//   bar1d --scheme ps --ps-form literal --mass mod2 --elements 100 --dt 0.004 --output ps.dat
//   bar1d --benchmark grazing --scheme cn --mass mod1 --elements 400
//   bar1d --initial-data tests/data/initial_data/left_going_wave.dat --elements 200 --final-time 4
//   bar1d --benchmark bouncing --scheme cn --mass mod3 --elements 300
//   bar1d --benchmark two-bars --scheme cn --mass mod3 --elements 100
//   bar1d --grading 1.005 --mass mod1 --elements 200 --final-time 30
//   bar1d --scheme be --mass consistent --elements 200 --courant 1
//   bar1d --scheme ec --mass mod3 --elements 16 --courant 10 --final-time 300
//   bar1d --scheme cn-switch --switch-theta 1 --mass mod1 --elements 400
//   bar1d --mass node1:7/6 --initial-contact-node interpolant --contact-velocity backward-difference
//         --elements 20 --dt 0.005 --final-time 12      (GetFEM's demo_dynamic_contact_1D.py, CN)
//
// Description. Steps: (1) read the options and the initial-data file (so that bad values fail before
// any work); (2) open the output file (so that a bad path fails before the run); (3) build the mesh,
// the mass, the scheme and the reference, Δt = C h unless --dt is given; (4) run to the final time,
// accumulating the errors and, if asked, the time series; (5) print the figures and commit the output.
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "options.hpp"
#include "peers.hpp"
#include "output_file.hpp"
#include "configurations.hpp"
#include "figure_program.hpp"
#include "run_limits.hpp"
#include "initial_data_file.hpp"
#include "measures/errors.hpp"
#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "fem/interior_mass.hpp"
#include "fem/period_law.hpp"
#include "classes/contact_classes.hpp"
#include "time/schemes.hpp"
#include "time/two_bodies.hpp"

namespace cli = mrm::cli;

int main(int argc, char** argv) {
  return cli::guarded_main("bar1d", [&] {
    // 1. Options.
    long elements = 100;
    double courant = 0.5, dt = 0.0, final_time = 6.0, length = 1.0, amplitude = 0.5, beta = 0.25, restitution = 0.0,
           switch_theta = 1.0;
    // The contact classes' parameters (lib/classes/contact_classes.cpp), their defaults the library's.
    const mrm::SchemeParameters class_defaults;
    double newmark_beta = class_defaults.newmark_beta, newmark_gamma = class_defaults.newmark_gamma,
           penalty = class_defaults.penalty, nitsche_theta = class_defaults.nitsche_theta,
           nitsche_gamma = class_defaults.nitsche_gamma, moreau_theta = class_defaults.moreau_theta;
    std::string peer = "none", ps_start = "cn";
    std::string scheme = mrm::to_string(mrm::Scheme::crank_nicolson), mass = "mod3", ps_form = "algebraic",
                initial = "consistent", contact_velocity = "algebraic", output, lumping = "row-sum";
    std::string benchmark = "paper", initial_data;
    bool no_timing = false, phase_matched = false;
    // The grading ratio R of the mesh h_k = h0 R^k (lib/fem/p1.hpp graded_mesh): from 1 (uniform) to 1.1, a
    // coarsest element 1.1^(N-1) h0 (Δt = C h0 sets the cost; the step count is checked below).
    double grading = 1.0;
    constexpr double largest_grading = 1.1;
    std::string interior_mass = "consistent";
    // The contact stress whose oscillation bar1d reports (lib/measures/contact_stress.hpp; default: see the
    // --stress help and experiments/fig_stress.cpp's measurements).
    std::string stress = "window";
    // The ranges below keep every quantity of the run (h, Δt², the matrices' entries, the energy a²L/2)
    // far from overflow and underflow of a double (the energy and the errors are computed scale-free:
    // errors.cpp, schemes.cpp), and the memory bounded: the peak memory of a run, measured at N = 1e6
    // and 2e6, is 205 bytes per element (the scheme's vectors and factors, the error accumulator's
    // interpolants and matrices); 256 with a margin, compared with what the process may use.
    constexpr double largest_courant = cli::max_courant, bytes_per_element = 256;
    const cli::Check courant_range = [&](std::string_view option, double value) {
      cli::require_positive(option, value);
      cli::require_in_closed_range(option, value, 0, largest_courant);
    };
    cli::Parser parser(
        "bar1d",
        "Runs one scheme with one mass matrix on a bar hitting an obstacle (the paper's benchmark "
        "with a closed-form solution, a smooth benchmark, one of the field's benchmarks, or initial data "
        "from a file) or on two bars hitting each other (two-bars), and prints the "
        "relative errors against the exact solution, the energy range, the number of steps and the "
        "run time, one `name = value` line each.",
        {"bar1d --scheme cn --mass mod3 --elements 50 --courant 0.5 --final-time 12",
         "bar1d --scheme ps --ps-form literal --mass mod2 --elements 100 --dt 0.004 --output ps.dat",
         "bar1d --benchmark grazing --scheme cn --mass mod1 --elements 400",
         "bar1d --initial-data tests/data/initial_data/left_going_wave.dat --elements 200 --final-time 4"});
    parser.add_integer("--elements", "-n", "N", "number of elements N of the mesh (h = L/N), an integer in [2, 1e7]",
                       &elements, cli::in_closed_range(2, cli::max_elements));
    parser.add_real("--courant", "-c", "C", "time step as a multiple of h: dt = C h (0 < C <= 1e6)", &courant,
                    courant_range);
    parser.add_real("--dt", "", "X", "time step (0 < dt <= 1e6 h); excludes --courant", &dt, cli::positive());
    parser.add_real("--final-time", "-T", "T",
                    "final time (> 0); the period of the paper's benchmark is 3L; default 6 on the paper's "
                    "benchmark and --initial-data, 2 on the smooth benchmarks, the benchmark's own horizon (in "
                    "its time unit) on the field's",
                    &final_time, cli::positive());
    parser.add_real("--grading", "", "R",
                    "grade the mesh toward the contact: element sizes h_k = h0 R^k, R in [1, 1.1] (1: uniform; "
                    "dt = C h0); the paper's benchmark, smooth-impact, grazing and --initial-data only",
                    &grading, cli::in_closed_range(1, largest_grading));
    parser.add_choice("--benchmark", "", "B",
                      mrm::repro::benchmark_help("the benchmark, each with its exact solution (S1, S2: mathematics.md "
                                                 "sec. 11, L = 1; the field's ones with their own load, gap, "
                                                 "material and units: field.md sec. 1)"),
                      mrm::repro::benchmark_names(), &benchmark);
    parser.add_input("--initial-data", "",
                     "read the initial data from FILE (columns x u0 v0, linearly interpolated, on [0, L] with L the "
                     "last x); excludes --benchmark",
                     &initial_data);
    parser.add_real("--length", "-L", "L", "length of the bar, in [1e-100, 1e100] (--benchmark paper only)", &length,
                    cli::in_closed_range(1e-100, 1e100));
    parser.add_real("--amplitude", "-a", "A",
                    "initial datum u0(x) = A (L - x), A in [1e-100, 1e100] (--benchmark paper only)", &amplitude,
                    cli::in_closed_range(1e-100, 1e100));
    parser.add_choice("--scheme", "-s", "S", mrm::repro::scheme_help("time scheme"), mrm::repro::scheme_ids(), &scheme);
    parser.add_real("--switch-theta", "", "TH",
                    "cn-switch: theta of the step that replaces a Crank-Nicolson step across a change of the "
                    "contact status; only 1 (backward Euler), the one theta whose energy identity proves that "
                    "no step gains energy (below 1 a release may gain: lib/time/schemes.hpp)",
                    &switch_theta, cli::in_closed_range(mrm::switch_theta_without_gain, 1));
    parser.add_string("--mass", "-m", "M", mrm::repro::mass_option_help("mass matrix"), &mass);
    parser.add_real("--beta", "-b", "B",
                    "Paoli-Schatzman's beta, in [0, 1e6]; at least 1/4 with --ps-form literal and a massless "
                    "contact node",
                    &beta, cli::in_closed_range(0, 1e6));
    parser.add_real("--restitution", "-e", "E",
                    "restitution coefficient e in [0, 1] of the schemes with an impact law (ps: the constraint on "
                    "(u0^{n+1} + e u0^{n-1})/(1 + e); moreau-jean: v+ = -e v-)",
                    &restitution, cli::in_closed_range(0, 1));
    parser.add_real("--newmark-beta", "", "B",
                    "Newmark's beta of newmark, penalty, nitsche, in [0, 1e6] (0: explicit, the step solves with "
                    "the mass; 1/4 with gamma 1/2 is Crank-Nicolson)",
                    &newmark_beta, cli::in_closed_range(0, 1e6));
    parser.add_real("--newmark-gamma", "", "G",
                    "Newmark's gamma of newmark, penalty, nitsche, in [0.5, 1e6] (below 1/2 Newmark amplifies)",
                    &newmark_gamma, cli::in_closed_range(0.5, 1e6));
    parser.add_real("--penalty", "", "G0",
                    "penalty: the parameter gamma0 of the contact force (gamma0/h) min(0, u0), in (0, 1e12]", &penalty,
                    [](std::string_view option, double value) {
                      cli::require_positive(option, value);
                      cli::require_in_closed_range(option, value, 0, 1e12);
                    });
    parser.add_real("--nitsche-theta", "", "TH",
                    "nitsche: the symmetry parameter theta in [-1, 1] (1 symmetric, 0 skew-free, -1 "
                    "skew-symmetric), below --nitsche-gamma",
                    &nitsche_theta, cli::in_closed_range(-1, 1));
    parser.add_real("--nitsche-gamma", "", "G0", "nitsche: the parameter gamma0 (gamma = gamma0/h), in (0, 1e12]",
                    &nitsche_gamma, [](std::string_view option, double value) {
                      cli::require_positive(option, value);
                      cli::require_in_closed_range(option, value, 0, 1e12);
                    });
    parser.add_real("--moreau-theta", "", "TH",
                    "moreau-jean: theta of the theta-method, in [0.5, 1] (below 1/2 the method amplifies)",
                    &moreau_theta, cli::in_closed_range(0.5, 1));
    parser.add_choice(
        "--peer", "", "P",
        "set every parameter to a peer's defaults (the options given override them): GetFEM's "
        "demo_dynamic_contact_1D.py, version K, standard mass, NX 20, dt 0.002, T 12, Newmark "
        "(0, 1/2) (repro/peers.cpp); none: no preset",
        [] {
          std::vector<std::string> names{"none"};
          for (const std::string& name : mrm::repro::peer_names()) names.push_back(name);
          return names;
        }(),
        &peer);
    parser.add_choice("--ps-form", "", "F",
                      "Paoli-Schatzman's contact row: algebraic at every level, or the literal three-level formula "
                      "(the consistent mass needs literal, which is then the default)",
                      {"algebraic", "literal"}, &ps_form);
    parser.add_choice("--ps-start", "", "S",
                      "Paoli-Schatzman's first step: cn (one Crank-Nicolson step) or explicit (the explicit Newmark "
                      "step of GetFEM's demo; a contact node with inertia)",
                      {"cn", "explicit"}, &ps_start);
    parser.add_choice("--lumping", "", "K",
                      "taylor-flanagan's mass: row-sum lumped (the default; dt <= h), or none, the consistent mass "
                      "solved at every step as GetFEM's demo (dt <= h/sqrt(3))",
                      {"row-sum", "none"}, &lumping);
    parser.add_choice("--initial-contact-node", "", "I",
                      "initial value of a massless contact node: solved from its algebraic row, or the interpolant",
                      {"consistent", "interpolant"}, &initial);
    parser.add_choice("--contact-velocity", "", "V",
                      "velocity of a massless contact node in the velocity measures: the library's, from the "
                      "algebraic row (mathematics.md sec. 7), or the backward difference (u0(t_n) - u0(t_n-1))/dt "
                      "as GetFEM's demo_dynamic_contact_1D.py",
                      {"algebraic", "backward-difference"}, &contact_velocity);
    parser.add_output("--output", "-o", "write the contact-point time series to FILE", &output);
    parser.add_flag("--no-timing", "",
                    "leave out the wall time of the run (wall_seconds, the one value that varies "
                    "from run to run)",
                    &no_timing);
    parser.add_string("--interior-mass", "", "I",
                      "interior mass the --mass member is defined on (issue 26): " + mrm::repro::interior_mass_forms() +
                          "; the paper's is consistent",
                      &interior_mass);
    parser.add_flag("--phase-matched", "",
                    "interior mass blend:A with A = 1/2 - (c dt/h)^2 (c the wave speed at the contact end, 1 on "
                    "the paper's bar), which cancels Crank-Nicolson's leading phase error (needs c dt/h <= 1/sqrt(2))",
                    &phase_matched);
    {
      std::vector<std::string> stresses;
      for (const mrm::ContactStressEntry& e : mrm::contact_stress_registry()) stresses.push_back(e.name);
      parser.add_choice(
          "--stress", "", "S",
          "contact stress whose oscillation lambda_tv_ratio reports (issue 26): the multiplier, its box "
          "or B-spline window average over 8 smearing widths, or the strain recovered over the first "
          "elements (lib/measures/contact_stress.hpp); default window, multiplier on two-bars (its run keeps no "
          "stress history)",
          stresses, &stress);
    }
    parser.add_conflict("--dt", "--courant");
    parser.add_conflict("--interior-mass", "--phase-matched");
    parser.add_conflict("--initial-data", "--benchmark");
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    double blend = 0.0;  // the interior mass blend A (lib/fem/interior_mass.hpp)
    try {
      blend = mrm::repro::interior_blend_from_spec(interior_mass);
    } catch (const std::invalid_argument& e) {
      throw cli::UsageError(std::string("--interior-mass: ") + e.what());
    }
    const bool own_data = parser.given("--initial-data");
    for (const char* option : {"--length", "--amplitude"})
      if (parser.given(option) && (own_data || benchmark != "paper"))
        throw cli::UsageError(std::string(option) +
                              ": only with --benchmark paper (the smooth benchmarks have L = 1, " +
                              "and --initial-data gives L as its last x)");
    std::shared_ptr<const mrm::InitialData> data;
    if (own_data) data = std::make_shared<const mrm::InitialData>(mrm::repro::read_initial_data(initial_data));
    const bool field_benchmark = !own_data && mrm::repro::is_impact_benchmark(benchmark);
    if (!parser.given("--final-time") && !own_data && benchmark != "paper")
      final_time = field_benchmark ? mrm::impact_benchmark(benchmark).final_time : 2.0;
    // A peer's defaults (repro/peers.cpp): every parameter the command line does not give.
    const bool use_peer = peer != "none";
    bool step_given = parser.given("--dt");
    if (use_peer) {
      const mrm::repro::PeerPreset& preset = mrm::repro::peer_preset(peer);
      const auto set = [&](const char* option, auto& variable, const auto& value) {
        if (!parser.given(option)) variable = value;
      };
      set("--elements", elements, preset.elements);
      if (!parser.given("--dt") && !parser.given("--courant")) {
        dt = preset.dt;
        step_given = true;
      }
      set("--final-time", final_time, preset.final_time);
      set("--scheme", scheme, mrm::to_string(preset.scheme.scheme));
      set("--mass", mass, preset.mass);
      set("--initial-contact-node", initial, preset.initial);
      set("--contact-velocity", contact_velocity, preset.contact_velocity);
      const mrm::Scheme s = mrm::scheme_by_name(scheme);
      const auto set_taken = [&](const char* option, mrm::SchemeParameter parameter, double& variable, double value) {
        if (mrm::takes(s, parameter)) set(option, variable, value);
      };
      set_taken("--beta", mrm::SchemeParameter::beta, beta, preset.scheme.beta);
      set_taken("--restitution", mrm::SchemeParameter::restitution, restitution, preset.scheme.restitution);
      if (mrm::takes(s, mrm::SchemeParameter::contact_row) && !parser.given("--ps-form"))
        ps_form = mrm::to_string(preset.scheme.contact_row);
      if (mrm::takes(s, mrm::SchemeParameter::ps_start) && !parser.given("--ps-start"))
        ps_start = preset.scheme.ps_explicit_start ? "explicit" : "cn";
      set_taken("--newmark-beta", mrm::SchemeParameter::newmark_beta, newmark_beta, preset.scheme.newmark_beta);
      set_taken("--newmark-gamma", mrm::SchemeParameter::newmark_gamma, newmark_gamma, preset.scheme.newmark_gamma);
      set_taken("--penalty", mrm::SchemeParameter::penalty, penalty, preset.scheme.penalty);
      set_taken("--nitsche-theta", mrm::SchemeParameter::nitsche_theta, nitsche_theta, preset.scheme.nitsche_theta);
      set_taken("--nitsche-gamma", mrm::SchemeParameter::nitsche_gamma, nitsche_gamma, preset.scheme.nitsche_gamma);
      if (mrm::takes(s, mrm::SchemeParameter::mass_lumping) && !parser.given("--lumping"))
        lumping = mrm::to_string(preset.scheme.lumping);
    }
    const mrm::Scheme scheme_id = mrm::scheme_by_name(scheme);
    // Two bodies (two-bars, lib/time/two_bodies.hpp): Crank-Nicolson with a massless contact node on each bar,
    // measured by run_configuration; the options of one body's run do not apply.
    const bool two_bodies = field_benchmark && mrm::is_two_body_chain(mrm::impact_benchmark(benchmark).configuration);
    if (two_bodies) {
      if (scheme_id != mrm::Scheme::crank_nicolson)
        throw cli::UsageError("--scheme: " + scheme + ": --benchmark " + benchmark +
                              " (two bodies coupled by one contact multiplier) runs with cn only (allowed: cn)");
      // The stresses other than the multiplier are computed from one body's history, which the two bodies'
      // run does not keep (repro/configurations.cpp, run_two_bodies): the multiplier is its stress.
      if (parser.given("--stress") && stress != "multiplier")
        throw cli::UsageError("--stress: " + stress + " with --benchmark " + benchmark +
                              " (the two bodies' run keeps no stress history; allowed: multiplier)");
      stress = "multiplier";
    }
    if (grading != 1.0 && field_benchmark)
      throw cli::UsageError("--grading: " + cli::format_real(grading) + " with --benchmark " + benchmark +
                            " (allowed: 1 on the field's benchmarks; in [1, 1.1] on paper, smooth-impact, grazing "
                            "and --initial-data)");
    // The coarsest element R^(N-1) h0: at most 1e6 h0 (beyond, h0 = L(R - 1)/(R^N - 1) underflows toward 0
    // long before; the number of steps T/(C h0) is checked with the step below).
    if (grading != 1.0 && (static_cast<double>(elements) - 1) * std::log(grading) > std::log(1e6))
      throw cli::UsageError("--grading: " + cli::format_real(grading) +
                            "^(N - 1) with N = " + std::to_string(elements) +
                            " is more than 1e6 (allowed: R^(N - 1) <= 1e6, the coarsest element at most 1e6 h0)");
    if (grading != 1.0 && phase_matched)
      throw cli::UsageError("--phase-matched: its blend is derived on the uniform mesh (allowed: --grading 1)");
    // One blend matches one Courant number c Δt/h: a bar whose layers have different wave speeds (layered)
    // has one per layer, and no A cancels the phase error in both.
    if (phase_matched && field_benchmark) {
      const auto& segments = mrm::impact_benchmark(benchmark).configuration.segments;
      for (const auto& segment : segments)
        if (segment.modulus * segments.front().density != segments.front().modulus * segment.density)
          throw cli::UsageError("--phase-matched: --benchmark " + benchmark +
                                " has layers of different wave speeds, and one blend matches one Courant number "
                                "(allowed: --interior-mass blend:A)");
    }
    mrm::repro::refuse_untaken(parser, scheme_id,
                               {{"--beta", mrm::SchemeParameter::beta},
                                {"--restitution", mrm::SchemeParameter::restitution},
                                {"--ps-form", mrm::SchemeParameter::contact_row},
                                {"--ps-start", mrm::SchemeParameter::ps_start},
                                {"--switch-theta", mrm::SchemeParameter::switch_theta},
                                {"--newmark-beta", mrm::SchemeParameter::newmark_beta},
                                {"--newmark-gamma", mrm::SchemeParameter::newmark_gamma},
                                {"--penalty", mrm::SchemeParameter::penalty},
                                {"--nitsche-theta", mrm::SchemeParameter::nitsche_theta},
                                {"--nitsche-gamma", mrm::SchemeParameter::nitsche_gamma},
                                {"--moreau-theta", mrm::SchemeParameter::moreau_theta},
                                {"--lumping", mrm::SchemeParameter::mass_lumping}});

    // 2. The output, opened now so that an unwritable path fails before the run.
    std::unique_ptr<cli::AtomicFile> series;
    if (parser.given("--output")) series = std::make_unique<cli::AtomicFile>(output, "--output");

    // 3. Mesh, mass, scheme; Δt derived from h in this one place.
    mrm::repro::Configuration configuration;
    configuration.benchmark = benchmark;
    configuration.data = data;
    configuration.length = length;
    configuration.amplitude = amplitude;
    configuration.elements = elements;
    configuration.grading = grading;
    // The mesh (on a field benchmark with its material and far end; an interface must be a node, and
    // two-bars has no finite element run: refused here, naming the option) and h/c, the transit time of
    // one element at the contact end (h on the paper's bar): Δt = C h/c.
    cli::require_mesh_memory("--elements", static_cast<double>(elements) * (two_bodies ? 2 : 1),  // two-bars: 2 N
                             bytes_per_element);
    mrm::UniformMesh mesh(1.0, 2);
    mrm::repro::as_usage_error({{"elements", "--elements"}, {"benchmark", "--benchmark"}, {"grading", "--grading"}},
                               [&] { mesh = mrm::repro::configuration_mesh(configuration); });
    configuration.courant = 1.0;
    const double transit = configuration.step();
    const double step_request = step_given ? dt : courant * transit;
    if (!(step_request <= largest_courant * transit))
      throw cli::UsageError("--dt: " + cli::format_real(step_request) +
                            " is more than 1e6 h/c = " + cli::format_real(largest_courant * transit) +
                            " (allowed: 0 < dt <= 1e6 h/c, h = L/N, c the wave speed at the contact end)");
    const mrm::Index steps = cli::checked_steps("--final-time", final_time, step_request, "--dt or --courant");
    // The run ends exactly at T: Δt = T/⌈T/Δt_requested⌉, at most the requested step, constant over the
    // run (a last short step would need a second factorisation and would break the three-level
    // scheme's uniform levels; the changed Δt differs from the requested one by less than Δt/steps).
    const double step = final_time / static_cast<double>(steps);
    // The exact solution of data other than the paper's grows with the horizon: checked before anything
    // is built from the data.
    mrm::repro::require_reference_memory(configuration, mrm::repro::reference_horizon(steps, step),
                                         own_data ? "--initial-data" : "--final-time");
    if (parser.given("--output"))
      cli::require_rows("--final-time", static_cast<double>(steps) + 1,
                        cli::format_real(static_cast<double>(steps)) + " steps");
    // The mass, checked on the mesh of the run (a spread over more nodes than the mesh has, a matrix
    // that is not positive definite) once the mesh is known to fit in memory, before the run: a bad
    // value exits 2 and leaves no output behind.
    if (phase_matched) try {
        blend = mrm::phase_matched_blend(step / transit);  // the Courant number c Δt/h (c = 1 on the paper's bar)
      } catch (const std::invalid_argument& e) {
        throw cli::UsageError(std::string("--phase-matched: ") + e.what());
      }
    configuration.mass = mrm::repro::mass_from_option("--mass", mass, mesh, two_bodies, blend);
    if (two_bodies)  // the options of one body's run (after the checks of the values the run takes)
      for (const char* option :
           {"--output", "--peer", "--initial-contact-node", "--contact-velocity", "--interior-mass", "--phase-matched"})
        if (parser.given(option))
          throw cli::UsageError(std::string(option) + ": not with --benchmark " + benchmark +
                                " (two bodies: the run has no one-body contact point; allowed: --scheme cn, --mass, "
                                "--elements, --courant or --dt, --final-time, --no-timing)");
    const bool massless = mrm::contact_node_is_massless(mrm::modified_mass(mesh, configuration.mass));
    if (!massless && !parser.given("--ps-form")) ps_form = "literal";  // the only row of a node with inertia
    dt = step;                                                         // the header echoes the effective step
    configuration.scheme.scheme = scheme_id;
    configuration.scheme.beta = beta;
    configuration.scheme.restitution = restitution;
    if (mrm::takes(configuration.scheme.scheme, mrm::SchemeParameter::contact_row))
      configuration.scheme.contact_row = mrm::contact_row_by_name(ps_form);
    configuration.scheme.switch_theta = switch_theta;
    configuration.scheme.ps_explicit_start = ps_start == "explicit";
    if (mrm::is_contact_class(scheme_id)) {
      configuration.scheme.newmark_beta = newmark_beta;
      configuration.scheme.newmark_gamma = newmark_gamma;
      configuration.scheme.penalty = penalty;
      configuration.scheme.nitsche_theta = nitsche_theta;
      configuration.scheme.nitsche_gamma = nitsche_gamma;
      configuration.scheme.moreau_theta = moreau_theta;
    }
    configuration.scheme.lumping = mrm::mass_lumping_by_name(lumping);
    configuration.elements = elements;
    configuration.dt = step;
    configuration.final_time = final_time;
    configuration.initial = mrm::initial_contact_node_by_name(initial);
    configuration.contact_velocity = mrm::repro::contact_velocity_by_name(contact_velocity);
    configuration.stress = mrm::contact_stress_by_name(stress);
    // A stress other than the multiplier is computed from the run's history (repro/configurations.hpp):
    // 24 bytes per step, 48 for the recovered strain.
    if (configuration.stress != mrm::ContactStress::multiplier)
      cli::require_memory("--stress", (static_cast<double>(steps) + 1) * (stress == "recovered" ? 48.0 : 24.0),
                          "the history of the " + stress + " stress over " + std::to_string(steps) +
                              " steps (allowed without it: --stress multiplier)");
    // The simulation, built once before any work: the library refuses a combination that cannot run (the
    // algebraic row or ec with a contact node that has inertia, a literal row with beta < 1/4 and a massless
    // node) and names the parameter, worded here as the option that sets it.
    // An explicit scheme's stability limit names the option that set the step.
    // Two bodies: both meshes with the mass on each (their Crank-Nicolson step needs nothing else).
    if (two_bodies)
      for (int k = 0; k < 2; ++k)
        mrm::modified_mass(mrm::repro::configuration_mesh(configuration, k), configuration.mass);
    std::optional<mrm::BarSimulation> checked;  // one body: kept for the explicit limits' warning below
    mrm::repro::as_usage_error({{"dt", parser.given("--dt") ? "--dt" : "--courant"},
                                {"mass_lumping", "--lumping"},
                                {"beta", "--beta"},
                                {"restitution", "--restitution"},
                                {"contact_row", "--ps-form"},
                                {"ps_start", "--ps-start"},
                                {"switch_theta", "--switch-theta"},
                                {"newmark_beta", "--newmark-beta"},
                                {"newmark_gamma", "--newmark-gamma"},
                                {"penalty", "--penalty"},
                                {"nitsche_theta", "--nitsche-theta"},
                                {"nitsche_gamma", "--nitsche-gamma"},
                                {"moreau_theta", "--moreau-theta"},
                                {"mass", "--mass"},
                                {"gap", "--scheme"},
                                {"scheme", "--scheme"}},
                               [&] {
                                 if (two_bodies) return;
                                 checked.emplace(mrm::repro::configuration_problem(configuration), mesh,
                                                 configuration.mass, configuration.scheme, step, configuration.initial);
                               });
    // Explicit penalty and explicit Nitsche (Newmark beta < gamma/2): the linear step limit checked above is
    // necessary, not sufficient (lib/classes/contact_classes.cpp, "Central differences with a penalty" and "... with
    // Nitsche's terms"); a run outside the measured region where the energy stayed below 2 E0 (fig_classes
    // blocks 5 and 6, per horizon) gets one warning line, labelled as measured, not derived.
    const bool stiff_law = scheme_id == mrm::Scheme::penalty || scheme_id == mrm::Scheme::nitsche;
    if (!two_bodies && stiff_law && configuration.scheme.newmark_beta < 0.5 * configuration.scheme.newmark_gamma) {
      const double fraction = step / mrm::newmark_stability_limit(checked->mass(), checked->stiffness(),
                                                                  configuration.scheme, mesh.contact_compliance());
      const double periods = final_time / (3 * mesh.length);
      const bool penalty = scheme_id == mrm::Scheme::penalty;
      const double safe =
          penalty ? mrm::penalty_measured_safe_fraction(periods) : mrm::nitsche_measured_safe_fraction(periods);
      if (fraction > safe)
        std::cerr << "bar1d: warning: dt = " << cli::format_real(std::round(fraction * 1000) / 1000)
                  << " dt_max of explicit " << mrm::to_string(scheme_id)
                  << " lies outside the measured region where E_max <= 2 E0 over " << cli::format_real(periods)
                  << " periods of 3L ("
                  << (safe > 0          ? "dt <= " + cli::format_real(safe) + " dt_max"
                      : periods <= 1000 ? std::string("not even at 0.3 dt_max, the grid's smallest")
                                        : std::string("none measured beyond 1000 periods"))
                  << "; fig_classes block " << (penalty ? "5" : "6")
                  << ", consistent mass, paper's benchmark; measured, not derived): the linear limit is necessary, "
                     "not sufficient\n";
    }
    std::shared_ptr<const mrm::ReferenceSolution> reference;
    mrm::repro::as_usage_error({{"final_time", "--final-time"}, {"configuration", "--final-time"}}, [&] {
      if (two_bodies) {  // the chain's exact solution, built by the run (its horizon checked here)
        mrm::repro::configuration_contact_windows(configuration, mrm::repro::reference_horizon(steps, step));
        return;
      }
      reference = mrm::repro::configuration_reference(configuration, mrm::repro::reference_horizon(steps, step));
    });

    if (series) {
      std::ostream& out = series->stream();
      out << "# bar1d: time series at the contact point x = 0 ("
          << (own_data ? std::string("initial data from a file") : benchmark + " benchmark") << "; exact values: "
          << (field_benchmark                    ? "the chain's exact solution, lib/exact/impact_solution.hpp"
              : own_data || benchmark != "paper" ? "characteristic solution, mathematics.md sec. 10"
                                                 : "closed form, mathematics.md sec. 2")
          << ")\n";
      parser.echo(out);
      out << "# h = " << cli::format_real(mesh.h(0)) << (grading != 1.0 ? " (h0, the contact element)" : "")
          << "\n# steps = " << steps
          << "\n# total_mass = " << cli::format_real(mrm::total_mass(mesh, configuration.mass))
          << "\n# massless_contact_node = " << (massless ? "true" : "false")
          << "\n# exact_energy = " << cli::format_real(reference->energy()) << '\n'
          << "# Each quantity is given at the instant it approximates: t for u0, t_lambda for lambda,\n"
          << "# t_energy for the energy (Paoli-Schatzman: lambda at t_n or t_{n+1}, energy at t_{n+1/2}).\n"
          << "# lambda_h = n/a where the level has no multiplier yet.\n"
          << "# columns: t u0_h u0_exact t_lambda lambda_h lambda_exact t_energy energy_h energy_exact\n";
    }

    // 4. The run (repro/configurations: the errors and the energy range), writing the series if asked;
    // with a peer, its own measures beside (repro/peers.hpp).
    std::unique_ptr<mrm::repro::PeerMeasures> peer_measures;
    if (use_peer)
      peer_measures = std::make_unique<mrm::repro::PeerMeasures>(
          mesh, *reference, mrm::contact_node_is_massless(mrm::modified_mass(mesh, configuration.mass)));
    const auto start = std::chrono::steady_clock::now();
    const mrm::repro::Measures measures =
        two_bodies ? mrm::repro::run_configuration(configuration)
                   : mrm::repro::run_configuration(
                         configuration,
                         [&](const mrm::Sample& s) {
                           if (peer_measures) peer_measures->add(s);
                           if (series) {
                             const mrm::ReferenceSolution& exact = *reference;
                             std::ostream& out = series->stream();
                             out << cli::format_real(s.time) << ' ' << cli::format_real((*s.displacement)[0]) << ' '
                                 << cli::format_real(exact.contact_displacement(s.time)) << ' '
                                 << cli::format_real(s.multiplier_time) << ' '
                                 << (s.has_multiplier ? cli::format_real(s.multiplier) : "n/a") << ' '
                                 << cli::format_real(exact.contact_multiplier(s.multiplier_time)) << ' '
                                 << cli::format_real(s.energy_time) << ' ' << cli::format_real(s.energy) << ' '
                                 << cli::format_real(exact.energy()) << '\n';
                           }
                         },
                         reference.get());
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
    // The interior mass, printed when it is not the paper's consistent one (issue 26).
    if (blend != 0.0) std::cout << "interior_mass = " << mrm::interior_mass_name(blend) << '\n';
    std::cout << "final_time_reached = " << cli::format_real(static_cast<double>(measures.steps) * step) << '\n';
    // The contact stress's oscillation, TV(λ_h)/TV(λ_exact) over the run's multiplier samples ("n/a" when
    // the exact λ does not vary: no contact), and the largest penetration of the contact node.
    std::cout << "stress = " << mrm::to_string(measures.stress) << '\n';
    std::cout << "lambda_tv_ratio = "
              << (measures.lambda_tv_ratio ? cli::format_real(*measures.lambda_tv_ratio)
                                           : std::string("n/a: the exact stress does not vary over the run"))
              << '\n'
              << "max_penetration = " << cli::format_real(measures.max_penetration) << '\n';
    // The phase (mathematics.md §8): the impacts found, the error of the first one and the drift of
    // the impact times per period (time units per period, early = negative) with that period, each
    // printed only when it can be computed (an impact in the run and in the exact solution; two of
    // each), against the exact impacts of the reference: L + 3Lk for the paper's benchmark, the
    // characteristic solution's for any other data. The period law's predictions (ℓ_f and 2ℓ_f + ℓ_c)
    // are derived for the paper's benchmark and printed for it alone.
    if (peer_measures) {  // the peer's definitions of the displacement measures (repro/peers.hpp)
      const auto peer_values = peer_measures->values();
      for (std::size_t k = 0; k < peer_values.size(); ++k)
        std::cout << "peer_" << mrm::repro::PeerMeasures::names[k] << " = " << cli::format_real(peer_values[k]) << '\n';
      std::cout << "peer_formulation = " << mrm::repro::peer_preset(peer).formulation << '\n';
    }
    std::cout << "impacts = " << measures.impacts.size() << '\n';
    if (!measures.impacts.empty() && !measures.phase)
      std::cout << "impacts_compared = 0\n"
                << "first_impact_error = n/a: no impact of the run lies within half the exact inter-impact time of "
                   "the first exact impact (a pair farther apart would compare unrelated events)\n";
    if (measures.phase) {
      std::cout << "impacts_compared = " << measures.phase->matched << '\n';
      std::cout << "first_impact_error = " << cli::format_real(measures.phase->first_impact_error) << '\n';
      if (measures.phase->drift_per_period)
        std::cout << "phase_drift_per_period = " << cli::format_real(*measures.phase->drift_per_period) << '\n'
                  << "phase_period = " << cli::format_real(measures.phase->period) << '\n';
    }
    if (elements >= 3 && !configuration.data && configuration.benchmark == "paper") {
      const mrm::PeriodPrediction law = mrm::predict_period(mesh, configuration.mass);
      std::cout << "period_law_first_impact_error = " << cli::format_real(law.first_impact_error) << '\n'
                << "period_law_drift_per_period = " << cli::format_real(law.period_error) << '\n';
      // On a graded mesh (issue 22): h0 and the coarsest element, and the first-order law's change of the
      // drift against Mod 3's on the same mesh, Σ δm_i κ(x_i) (period_law.cpp, "unequal elements").
      if (grading != 1.0)
        std::cout << "grading = " << cli::format_real(grading) << '\n'
                  << "h0 = " << cli::format_real(mesh.h(0)) << '\n'
                  << "h_max = " << cli::format_real(mesh.h(elements - 1)) << '\n'
                  << "period_law_first_order_drift_change_vs_mod3 = "
                  << cli::format_real(mrm::first_order_period_change(mesh, configuration.mass)) << '\n';
    }
    // On a field benchmark: the exact contact windows over [0, T] (lib/exact/impact_solution.hpp, computed in the
    // benchmark's own units) and the run's (the crossings of the contact indicator, phase.hpp), in the
    // benchmark's time unit.
    if (field_benchmark) {
      std::vector<mrm::ContactInterval> windows;
      mrm::repro::as_usage_error({{"final_time", "--final-time"}, {"configuration", "--final-time"}}, [&] {
        windows = mrm::repro::configuration_contact_windows(configuration, final_time);
      });
      const auto print = [](const char* name, const std::vector<mrm::ContactInterval>& list) {
        std::cout << name << " =";
        for (const mrm::ContactInterval& w : list)
          std::cout << " [" << cli::format_real(w.start) << ", " << cli::format_real(w.end) << "]";
        std::cout << (list.empty() ? " none" : "") << '\n';
      };
      if (!mrm::impact_benchmark(benchmark).time_unit.empty())
        std::cout << "time_unit = " << mrm::impact_benchmark(benchmark).time_unit << '\n';
      print("exact_contact_windows", windows);
      print("measured_contact_windows", measures.contact_windows);
      std::cout << "exact_contact_held_at_final_time = " << (!windows.empty() && windows.back().open ? "true" : "false")
                << '\n'
                << "measured_contact_held_at_final_time = "
                << (!measures.contact_windows.empty() && measures.contact_windows.back().open ? "true" : "false")
                << '\n';
    }
    if (!no_timing) std::cout << "wall_seconds = " << cli::format_real(std::round(wall * 1e4) / 1e4) << '\n';
    if (series) series->commit();
    return 0;
  });
}
