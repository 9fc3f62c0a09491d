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
// them), the reported contact stress's relative L²(0,T) error (err_stress_L2; err_lambda_L2 is the
// multiplier's) and oscillation (lambda_tv_ratio = TV(λ_h)/TV(λ_exact)), and the largest penetration
// (max_penetration). On the field's benchmarks (bouncing, impacting, gravity-paper, layered:
// doc/benchmarks.md) the run has the benchmark's load, gap, material and free far end, in its own units
// (the harness runs the dimensionless problem and scales back: repro/configurations.hpp, Scaling;
// Δt = C h/c with c the wave speed at the contact end), its reference is the chain's exact solution
// (lib/exact/impact_solution.hpp), and it also prints the exact contact windows over [0, T]
// (exact_contact_windows = [t1, t2] ...) and the run's (measured_contact_windows), in the benchmark's
// time unit. two-bars runs two meshes, N elements on each bar, coupled by one contact multiplier
// (lib/time/two_bodies.hpp; Crank-Nicolson only, a massless contact node on each bar); its errors are the
// larger of the two bars' (repro/configurations.hpp, run_configuration). --grading R runs the paper's
// benchmark, a smooth one or data of one's own on the mesh h_k = h0 R^k (finer toward the contact,
// dt = C h0), and on the paper's benchmark prints the period law's predictions for that mesh beside the
// measured drift (lib/fem/period_law.hpp: the eigenvalue law, and the first-order change against Mod 3). Its
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
#include <algorithm>
#include <chrono>
#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "options.hpp"
#include "peers.hpp"
#include "progress.hpp"
#include "output_file.hpp"
#include "configurations.hpp"
#include "figure_program.hpp"
#include "report_values.hpp"
#include "scheme_options.hpp"
#include "run_limits.hpp"
#include "initial_data_file.hpp"
#include "measures/errors.hpp"
#include "exact/benchmarks.hpp"
#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "fem/interior_mass.hpp"
#include "fem/p1.hpp"
#include "fem/period_law.hpp"
#include "classes/contact_classes.hpp"
#include "time/schemes.hpp"
#include "time/two_bodies.hpp"

namespace cli = mrm::cli;

namespace {

// The ranges below keep every quantity of the run (h, Δt², the matrices' entries, the energy a²L/2)
// far from overflow and underflow of a double (the energy and the errors are computed scale-free:
// errors.cpp, schemes.cpp), and the memory bounded: the peak memory of a run, measured at N = 1e6
// and 2e6, is 205 bytes per element (the scheme's vectors and factors, the error accumulator's
// interpolants and matrices); 256 with a margin, compared with what the process may use.
constexpr double largest_courant = cli::max_courant, bytes_per_element = 256;
// The grading ratio R of the mesh h_k = h0 R^k (lib/fem/p1.hpp graded_mesh): from 1 (uniform) to 1.1, a
// coarsest element 1.1^(N-1) h0 (Δt = C h0 sets the cost; the step count is checked with the step).
constexpr double largest_grading = 1.1;

// What the command line says, each value with its default.
struct Options {
  long elements = 100;
  double courant = 0.5, dt = 0.0, final_time = 6.0, length = 1.0, amplitude = 0.5, grading = 1.0;
  std::string peer = "none";
  std::string scheme = mrm::to_string(mrm::Scheme::crank_nicolson), mass = "mod3", initial = "consistent",
              contact_velocity = "algebraic", output;
  std::string benchmark = "paper", initial_data;
  std::string interior_mass = "consistent";
  // The contact stress whose oscillation bar1d reports (lib/measures/contact_stress.hpp; default: see the
  // --stress help and experiments/fig_stress.cpp's measurements).
  std::string stress = "gated";
  bool no_timing = false, phase_matched = false;
  // The scheme parameters (--beta, --restitution, --ps-form, --switch-theta, --newmark-beta, ...,
  // --lumping): each option, range and help from the registry (lib/time/scheme_registry.hpp).
  mrm::repro::SchemeParameterOptions scheme_options;
};

// What the run is, once the options are checked against each other and against the machine.
struct Run {
  mrm::repro::Configuration configuration;
  mrm::UniformMesh mesh{1.0, 2};
  const mrm::Benchmark* benchmark = nullptr;  // the registry's entry of --benchmark
  std::shared_ptr<const mrm::InitialData> data;
  mrm::Scheme scheme_id = mrm::Scheme::crank_nicolson;
  mrm::SchemeParameters scheme_parameters;
  bool own_data = false, field_benchmark = false, two_bodies = false, use_peer = false, massless = false;
  bool step_given = false;
  double blend = 0.0;  // the interior mass blend A (lib/fem/interior_mass.hpp)
  double transit = 0.0, step = 0.0;
  mrm::Index steps = 0;
  // M^mod on `mesh`, in the bar's units: the run's assembled mass (Configuration::assembled_mass), or
  // it times rho_c L when the run steps on the unit bar (Scaling::mass).
  std::shared_ptr<const mrm::AssembledMass> bar_mass;
  std::optional<mrm::BarSimulation>
      validated;  // one body: built before any work, so that the library checks every input; its matrices give the explicit limits' warning
  std::shared_ptr<const mrm::ReferenceSolution> reference;
  std::unique_ptr<cli::AtomicFile> series;
  std::unique_ptr<mrm::repro::PeerMeasures> peer_measures;
  mrm::repro::Measures measures;
  double wall = 0.0;
};

// 1. The options.
void declare_options(cli::Parser& parser, Options& o) {
  const cli::Check courant_range = [](std::string_view option, double value) {
    cli::require_positive(option, value);
    cli::require_in_closed_range(option, value, 0, largest_courant);
  };
  parser.add_integer("--elements", "-n", "N", "number of elements N of the mesh (h = L/N), an integer in [2, 1e7]",
                     &o.elements, cli::in_closed_range(2, cli::max_elements));
  parser.add_real("--courant", "-c", "C", "time step as a multiple of h: dt = C h (0 < C <= 1e6)", &o.courant,
                  courant_range);
  parser.add_real("--dt", "", "X", "time step (0 < dt <= 1e6 h); excludes --courant", &o.dt, cli::positive());
  parser.without_default("--dt");  // not given: dt = C h
  parser.add_real("--final-time", "-T", "T",
                  "final time (> 0): the run takes ceil(T/dt) steps of the step asked for and ends at the first "
                  "level at or after T (final_time_reached); the period of the paper's benchmark is 3L; default 6 "
                  "on the paper's benchmark and --initial-data, 2 on the smooth benchmarks, the benchmark's own "
                  "horizon (in its time unit) on the field's",
                  &o.final_time, cli::positive());
  parser.add_real("--grading", "", "R",
                  "grade the mesh toward the contact: element sizes h_k = h0 R^k, R in [1, 1.1] (1: uniform; "
                  "dt = C h0); the paper's benchmark, smooth-impact, grazing and --initial-data only",
                  &o.grading, cli::in_closed_range(1, largest_grading));
  parser.add_choice("--benchmark", "", "B",
                    mrm::repro::benchmark_help("the benchmark, each with its exact solution (S1, S2: mathematics.md "
                                               "sec. 11, L = 1; the field's ones with their own load, gap, "
                                               "material and units: doc/benchmarks.md)"),
                    mrm::repro::benchmark_names(), &o.benchmark);
  parser.add_input("--initial-data", "",
                   "read the initial data from FILE (columns x u0 v0, linearly interpolated, on [0, L] with L the "
                   "last x); excludes --benchmark",
                   &o.initial_data);
  parser.add_real("--length", "-L", "L", "length of the bar, in [1e-100, 1e100] (--benchmark paper only)", &o.length,
                  cli::in_closed_range(1e-100, 1e100));
  parser.add_real("--amplitude", "-a", "A",
                  "initial datum u0(x) = A (L - x), A in [1e-100, 1e100] (--benchmark paper only)", &o.amplitude,
                  cli::in_closed_range(1e-100, 1e100));
  parser.add_choice("--scheme", "-s", "S", mrm::repro::scheme_help("time scheme"), mrm::repro::scheme_ids(), &o.scheme);
  // The scheme parameters: each option, range and help from the registry (lib/time/scheme_registry.hpp),
  // declared where the help lists them.
  using P = mrm::SchemeParameter;
  o.scheme_options.declare(parser, {P::switch_theta});
  parser.add_string("--mass", "-m", "M", mrm::repro::mass_option_help("mass matrix"), &o.mass);
  o.scheme_options.declare(parser, {P::beta, P::restitution, P::newmark_beta, P::newmark_gamma, P::penalty,
                                    P::nitsche_theta, P::nitsche_gamma, P::moreau_theta});
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
      &o.peer);
  o.scheme_options.declare(parser, {P::contact_row, P::ps_start, P::mass_lumping});
  parser.add_choice("--initial-contact-node", "", "I",
                    "initial value of a massless contact node: solved from its algebraic row, or the interpolant",
                    {"consistent", "interpolant"}, &o.initial);
  parser.add_choice("--contact-velocity", "", "V",
                    "velocity of a massless contact node in the velocity measures: the library's, from the "
                    "algebraic row (mathematics.md sec. 7), or the backward difference (u0(t_n) - u0(t_n-1))/dt "
                    "as GetFEM's demo_dynamic_contact_1D.py",
                    {"algebraic", "backward-difference"}, &o.contact_velocity);
  parser.add_output("--output", "-o", "write the contact-point time series to FILE", &o.output);
  parser.add_flag("--no-timing", "",
                  "leave out the wall time of the run (wall_seconds, the one value that varies "
                  "from run to run)",
                  &o.no_timing);
  parser.add_string("--interior-mass", "", "I",
                    "interior mass the --mass member is defined on: " + mrm::repro::interior_mass_forms() +
                        "; the paper's is consistent",
                    &o.interior_mass);
  parser.add_flag("--phase-matched", "",
                  "interior mass blend:A with A = 1/2 - (c dt/h)^2 (c the wave speed at the contact end, 1 on "
                  "the paper's bar), which cancels Crank-Nicolson's leading phase error (needs c dt/h <= 1/sqrt(2))",
                  &o.phase_matched);
  {
    std::vector<std::string> stresses;
    for (const mrm::ContactStressEntry& e : mrm::contact_stress_registry()) stresses.push_back(e.name);
    parser.add_choice(
        "--stress", "", "S",
        "contact stress whose oscillation lambda_tv_ratio and error err_stress_L2 report: the multiplier, its "
        "box or B-spline window average over 8 smearing widths, the strain recovered over the first "
        "elements, or gated: the window where the multiplier's variation exceeds " +
            mrm::significant(mrm::gate_threshold) +
            " times the window's (it rattles), else the multiplier (lib/measures/contact_stress.hpp); default "
            "gated, multiplier on two-bars (its run keeps no stress history)",
        stresses, &o.stress);
  }
  parser.add_conflict("--dt", "--courant");
  parser.add_conflict("--interior-mass", "--phase-matched");
  parser.add_conflict("--initial-data", "--benchmark");
  // A peer runs its demo's problem (the paper's bar, L = 1, a = 1/2, a uniform mesh) and its measures are
  // the demo's against that problem's exact solution (repro/peers.hpp): an option that changes the problem
  // does not apply with a peer (its discretisation options do: --elements, --dt, --scheme, --mass, ...).
  for (const char* option : {"--benchmark", "--initial-data", "--length", "--amplitude", "--grading"})
    parser.add_not_applicable(option, "--peer",
                              "a peer runs its demo's problem, the paper's bar with L = 1 and a = 1/2 on a uniform "
                              "mesh; allowed: omit it, or --peer none",
                              [&o] { return o.peer != "none"; });
}

// The values the options leave open (a peer's defaults, a benchmark's horizon) and the combinations
// that cannot run, refused before any work.
void resolve_options(const cli::Parser& parser, Options& o, Run& r) {
  r.blend = 0.0;  // the interior mass blend A (lib/fem/interior_mass.hpp)
  try {
    r.blend = mrm::repro::interior_blend_from_spec(o.interior_mass);
  } catch (const std::invalid_argument& e) {
    throw cli::UsageError(std::string("--interior-mass: ") + e.what());
  }
  r.own_data = parser.given("--initial-data");
  r.benchmark = &mrm::benchmark(o.benchmark);
  for (const char* option : {"--length", "--amplitude"})
    if (parser.given(option) && (r.own_data || !r.benchmark->takes_length()))
      throw cli::UsageError(std::string(option) + ": only with --benchmark paper (the smooth benchmarks have L = 1, " +
                            "and --initial-data gives L as its last x)");
  if (r.own_data) r.data = std::make_shared<const mrm::InitialData>(mrm::repro::read_initial_data(o.initial_data));
  r.field_benchmark = !r.own_data && r.benchmark->field != nullptr;
  if (!parser.given("--final-time") && !r.own_data) o.final_time = r.benchmark->final_time;
  // A peer's defaults (repro/peers.cpp): every parameter the command line does not give.
  r.use_peer = o.peer != "none";
  r.step_given = parser.given("--dt");
  if (r.use_peer) {
    const mrm::repro::PeerPreset& preset = mrm::repro::peer_preset(o.peer);
    const auto set = [&](const char* option, auto& variable, const auto& value) {
      if (!parser.given(option)) variable = value;
    };
    set("--elements", o.elements, preset.elements);
    if (!parser.given("--dt") && !parser.given("--courant")) {
      o.dt = preset.dt;
      r.step_given = true;
    }
    set("--final-time", o.final_time, preset.final_time);
    set("--scheme", o.scheme, mrm::to_string(preset.scheme.scheme));
    set("--mass", o.mass, preset.mass);
    set("--initial-contact-node", o.initial, preset.initial);
    set("--contact-velocity", o.contact_velocity, preset.contact_velocity);
  }
  r.scheme_id = mrm::scheme_by_name(o.scheme);
  // Each parameter the scheme takes: given, or else the peer's, or else the library's default.
  r.scheme_parameters = o.scheme_options.parameters(
      parser, r.scheme_id, r.use_peer ? mrm::repro::peer_preset(o.peer).scheme : mrm::SchemeParameters{});
  // GetFEM's demo starts Paoli-Schatzman (getfem-v1) by its own Newmark (beta, 1/2) step: the explicit step
  // at beta = 0 (the preset's --ps-start explicit) and the trapezoidal one, Crank-Nicolson's, at beta = 1/4
  // (the demo's implicit Newmark with the impulse is, V eliminated, the three-level scheme with the same
  // beta; doc/peer.md). A --beta given with the peer takes the start that is the demo's; for another beta
  // no start of this library is the demo's, and --ps-start must say which to take.
  if (r.use_peer && parser.given("--beta") && !parser.given("--ps-start") &&
      mrm::repro::peer_preset(o.peer).scheme.scheme == mrm::Scheme::paoli_schatzman &&
      r.scheme_id == mrm::Scheme::paoli_schatzman) {
    if (r.scheme_parameters.beta != 0.0 && r.scheme_parameters.beta != 0.25)
      throw cli::UsageError("--beta: " + cli::format_real(r.scheme_parameters.beta) + " with --peer " + o.peer +
                            ", whose demo starts by its Newmark (beta, 1/2) step, which this library has for beta = 0 "
                            "(explicit) and 1/4 (cn) only (allowed: 0 or 0.25, or choose the start with --ps-start)");
    r.scheme_parameters.ps_explicit_start = r.scheme_parameters.beta == 0.0;
  }
  // Two bodies (two-bars, lib/time/two_bodies.hpp): Crank-Nicolson with a massless contact node on each bar,
  // measured by run_configuration; the options of one body's run do not apply.
  r.two_bodies = r.field_benchmark && r.benchmark->two_bodies();
  if (r.two_bodies) {
    if (r.scheme_id != mrm::Scheme::crank_nicolson)
      throw cli::UsageError("--scheme: " + o.scheme + ": --benchmark " + o.benchmark +
                            " (two bodies coupled by one contact multiplier) runs with cn only (allowed: cn)");
    // The stresses other than the multiplier are computed from one body's history, which the two bodies'
    // run does not keep (repro/configurations/two_bodies.cpp, run_two_bodies): the multiplier is its stress.
    if (parser.given("--stress") && o.stress != "multiplier")
      throw cli::UsageError("--stress: " + o.stress + " with --benchmark " + o.benchmark +
                            " (the two bodies' run keeps no stress history; allowed: multiplier)");
    o.stress = "multiplier";
  }
  if (o.grading != 1.0 && r.field_benchmark)
    throw cli::UsageError("--grading: " + cli::format_real(o.grading) + " with --benchmark " + o.benchmark +
                          " (allowed: 1 on the field's benchmarks; in [1, 1.1] on paper, smooth-impact, grazing "
                          "and --initial-data)");
  // The coarsest element R^(N-1) h0: at most 1e6 h0 (beyond, h0 = L(R - 1)/(R^N - 1) underflows toward 0
  // long before; the number of steps T/(C h0) is checked with the step below).
  if (o.grading != 1.0 && (static_cast<double>(o.elements) - 1) * std::log(o.grading) > std::log(1e6))
    throw cli::UsageError("--grading: " + cli::format_real(o.grading) +
                          "^(N - 1) with N = " + std::to_string(o.elements) +
                          " is more than 1e6 (allowed: R^(N - 1) <= 1e6, the coarsest element at most 1e6 h0)");
  if (o.grading != 1.0 && o.phase_matched)
    throw cli::UsageError("--phase-matched: its blend is derived on the uniform mesh (allowed: --grading 1)");
  // One blend matches one Courant number c Δt/h: a bar whose layers have different wave speeds (layered)
  // has one per layer, and no A cancels the phase error in both.
  if (o.phase_matched && r.field_benchmark) {
    const auto& segments = r.benchmark->field->configuration.segments;
    for (const auto& segment : segments)
      if (segment.modulus * segments.front().density != segments.front().modulus * segment.density)
        throw cli::UsageError("--phase-matched: --benchmark " + o.benchmark +
                              " has layers of different wave speeds, and one blend matches one Courant number "
                              "(allowed: --interior-mass blend:A)");
  }
}

// 3. Mesh, mass, scheme; Δt derived from h in this one place.
void build_run(const cli::Parser& parser, Options& o, Run& r) {
  r.configuration.benchmark = o.benchmark;
  r.configuration.data = r.data;
  r.configuration.length = o.length;
  r.configuration.amplitude = o.amplitude;
  r.configuration.elements = o.elements;
  r.configuration.grading = o.grading;
  // The mesh (on a field benchmark with its material and far end; an interface must be a node, and
  // two-bars has no finite element run: refused here, naming the option) and h/c, the transit time of
  // one element at the contact end (h on the paper's bar): Δt = C h/c.
  cli::require_mesh_memory("--elements", static_cast<double>(o.elements) * (r.two_bodies ? 2 : 1),  // two-bars: 2 N
                           bytes_per_element);
  mrm::UniformMesh mesh(1.0, 2);
  mrm::repro::as_usage_error({{"elements", "--elements"}, {"benchmark", "--benchmark"}, {"grading", "--grading"}},
                             [&] { r.mesh = mrm::repro::configuration_mesh(r.configuration); });
  r.configuration.courant = 1.0;
  r.transit = r.configuration.step();
  r.step = r.step_given ? o.dt : o.courant * r.transit;
  if (!(r.step <= largest_courant * r.transit))
    throw cli::UsageError("--dt: " + cli::format_real(r.step) +
                          " is more than 1e6 h/c = " + cli::format_real(largest_courant * r.transit) +
                          " (allowed: 0 < dt <= 1e6 h/c, h = L/N, c the wave speed at the contact end)");
  r.steps = cli::checked_steps("--final-time", o.final_time, r.step, "--dt or --courant");
  // One rule for the final time in every program (mrm::steps_to_reach, which the studies and the claims
  // use): the step is the one asked for, constant over the run, and the run takes ⌈T/Δt⌉ steps, so that
  // it ends at the first level at or after T (final_time_reached, less than T + Δt). A last short step
  // would need a second factorisation and would break the three-level schemes' uniform levels; a step
  // shrunk to land on T would not be the Δt = C h that a study's row states.
  // The exact solution of data other than the paper's grows with the horizon: checked before anything
  // is built from the data.
  mrm::repro::require_reference_memory(r.configuration, mrm::repro::reference_horizon(r.steps, r.step),
                                       r.own_data ? "--initial-data" : "--final-time");
  if (parser.given("--output"))
    cli::require_rows("--final-time", static_cast<double>(r.steps) + 1,
                      cli::format_real(static_cast<double>(r.steps)) + " steps");
  // The mass, checked on the mesh of the run (a spread over more nodes than the mesh has, a matrix
  // that is not positive definite) once the mesh is known to fit in memory, before the run: a bad
  // value exits 2 and leaves no output behind.
  if (o.phase_matched) try {
      r.blend = mrm::phase_matched_blend(r.step / r.transit);  // the Courant number c Δt/h (c = 1 on the paper's bar)
    } catch (const std::invalid_argument& e) {
      throw cli::UsageError(std::string("--phase-matched: ") + e.what());
    }
  // The mass spec parsed once and M^mod assembled once per body, on the mesh the run steps on
  // (Configuration::assembled_mass): the unit bar (the bar's own mesh unless the scaling changes L, c or
  // E at the contact end; of two bodies, body 0's). The run reads it; the checks on the
  // bar's mesh (the simulation built below, the total mass, the period law) read it in the bar's units,
  // M = rho_c L M^ (Scaling::mass: every element's rho h is rho_c L times its unit one), a matrix
  // the run does not step with.
  const mrm::repro::Scaling scaling = mrm::repro::configuration_scaling(r.configuration);
  const bool unit_bar = !scaling.keeps_mesh();
  const mrm::repro::Configuration unit = mrm::repro::unit_configuration(r.configuration, scaling);
  const mrm::UniformMesh run_mesh = unit_bar ? mrm::repro::configuration_mesh(unit) : r.mesh;
  r.configuration.assembled_mass = std::make_shared<const mrm::AssembledMass>(
      mrm::repro::assembled_mass_from_option("--mass", o.mass, run_mesh, r.two_bodies, r.blend));
  r.configuration.mass = r.configuration.assembled_mass->redistribution;
  r.bar_mass = r.configuration.assembled_mass;
  if (unit_bar) {
    mrm::AssembledMass bar = *r.configuration.assembled_mass;
    bar.all_nodes = bar.all_nodes.scaled(scaling.mass(1.0));
    bar.matrix = bar.matrix.scaled(scaling.mass(1.0));
    r.bar_mass = std::make_shared<const mrm::AssembledMass>(std::move(bar));
  }
  if (r.two_bodies)  // the options of one body's run (after the checks of the values the run takes)
    for (const char* option :
         {"--output", "--peer", "--initial-contact-node", "--contact-velocity", "--interior-mass", "--phase-matched"})
      if (parser.given(option))
        throw cli::UsageError(std::string(option) + ": not with --benchmark " + o.benchmark +
                              " (two bodies: the run has no one-body contact point; allowed: --scheme cn, --mass, "
                              "--elements, --courant or --dt, --final-time, --no-timing)");
  r.massless = r.configuration.assembled_mass->massless;
  // A massless contact node's options do not apply to a node with inertia (its value and velocity are
  // its own unknowns); the literal row is the only Paoli-Schatzman row of such a node.
  if (!r.massless)
    for (const char* option : {"--initial-contact-node", "--contact-velocity"})
      if (parser.given(option))
        throw cli::UsageError(std::string(option) + ": the mass " + o.mass +
                              " keeps the inertia of the contact node (allowed: omit it, or a mass with a "
                              "massless contact node: mod1, mod2, mod3, ...)");
  if (!r.massless && !parser.given("--ps-form") && mrm::takes(r.scheme_id, mrm::SchemeParameter::contact_row))
    r.scheme_parameters.contact_row = mrm::ContactRow::literal;
  o.dt = r.step;  // the header echoes the effective step
  r.configuration.scheme = r.scheme_parameters;
  r.configuration.elements = o.elements;
  r.configuration.dt = r.step;
  r.configuration.final_time = o.final_time;
  r.configuration.initial = mrm::initial_contact_node_by_name(o.initial);
  r.configuration.contact_velocity = mrm::repro::contact_velocity_by_name(o.contact_velocity);
  r.configuration.stress = mrm::contact_stress_by_name(o.stress);
  // A stress other than the multiplier is computed from the run's history (repro/configurations.hpp):
  // 24 bytes per step, 48 for the recovered strain.
  if (r.configuration.stress != mrm::ContactStress::multiplier)
    cli::require_memory("--stress", (static_cast<double>(r.steps) + 1) * (o.stress == "recovered" ? 48.0 : 24.0),
                        "the history of the " + o.stress + " stress over " + std::to_string(r.steps) +
                            " steps (allowed without it: --stress multiplier)");
  // The simulation, built once before any work: the library refuses a combination that cannot run (the
  // algebraic row or ec with a contact node that has inertia, a literal row with beta < 1/4 and a massless
  // node) and names the parameter, worded here as the option that sets it.
  // An explicit scheme's stability limit names the option that set the step.
  // Two bodies: both meshes with the mass on each (their Crank-Nicolson step needs nothing else); the left
  // body's is the run's mesh, checked with the mass above; the right body's assembled here, once, on the
  // unit bar too.
  if (r.two_bodies)
    r.configuration.assembled_mass_body1 = std::make_shared<const mrm::AssembledMass>(
        mrm::assemble_mass(mrm::repro::configuration_mesh(unit, 1), r.configuration.mass));
  std::vector<std::pair<std::string, std::string>> option_names = o.scheme_options.option_names();
  option_names.insert(option_names.begin(), {"dt", parser.given("--dt") ? "--dt" : "--courant"});
  for (const auto& name : std::vector<std::pair<std::string, std::string>>{
           {"mass", "--mass"}, {"gap", "--scheme"}, {"scheme", "--scheme"}})
    option_names.push_back(name);
  mrm::repro::as_usage_error(option_names, [&] {
    if (r.two_bodies) return;
    r.validated.emplace(mrm::repro::configuration_problem(r.configuration), r.mesh, *r.bar_mass, r.configuration.scheme,
                        r.step, r.configuration.initial);
  });
}

// Explicit penalty and explicit Nitsche (Newmark beta < gamma/2): the linear step limit checked when the
// run was built is necessary, not sufficient (lib/classes/contact_classes.cpp, "Central differences with a
// penalty" and "... with Nitsche's terms"); a run outside the measured region where the energy stayed
// below 2 E0 (fig_classes blocks 5 and 6, per horizon) gets one warning line, labelled as measured, not
// derived.
void warn_outside_measured_region(const Options& o, const Run& r) {
  const bool stiff_law = r.scheme_id == mrm::Scheme::penalty || r.scheme_id == mrm::Scheme::nitsche;
  if (!r.two_bodies && stiff_law && r.configuration.scheme.newmark_beta < 0.5 * r.configuration.scheme.newmark_gamma) {
    const double fraction = r.step / mrm::newmark_stability_limit(r.validated->mass(), r.validated->stiffness(),
                                                                  r.configuration.scheme, r.mesh.contact_compliance());
    const double periods = o.final_time / (3 * r.mesh.length);
    const bool penalty = r.scheme_id == mrm::Scheme::penalty;
    const double safe =
        penalty ? mrm::penalty_measured_safe_fraction(periods) : mrm::nitsche_measured_safe_fraction(periods);
    if (fraction > safe)
      std::cerr << "bar1d: warning: dt = " << cli::format_real(std::round(fraction * 1000) / 1000)
                << " dt_max of explicit " << mrm::to_string(r.scheme_id)
                << " lies outside the measured region where E_max <= 2 E0 over " << cli::format_real(periods)
                << " periods of 3L ("
                << (safe > 0          ? "dt <= " + cli::format_real(safe) + " dt_max"
                    : periods <= 1000 ? std::string("not even at 0.3 dt_max, the grid's smallest")
                                      : std::string("none measured beyond 1000 periods"))
                << "; fig_classes block " << (penalty ? "5" : "6")
                << ", consistent mass, paper's benchmark; measured, not derived): the linear limit is necessary, "
                   "not sufficient\n";
  }
}

// The time series' header: what the columns are and the run that made them.
void write_series_header(const cli::Parser& parser, const Options& o, const Run& r) {
  if (r.series) {
    std::ostream& out = r.series->stream();
    out << "# bar1d: time series at the contact point x = 0 ("
        << (r.own_data ? std::string("initial data from a file") : o.benchmark + " benchmark") << "; exact values: "
        << (r.field_benchmark ? "the chain's exact solution, lib/exact/impact_solution.hpp"
            : !mrm::repro::has_closed_form(r.configuration) ? "characteristic solution, mathematics.md sec. 10"
                                                            : "closed form, mathematics.md sec. 2")
        << ")\n";
    parser.echo(out);
    out << "# h = " << cli::format_real(r.mesh.h(0)) << (o.grading != 1.0 ? " (h0, the contact element)" : "")
        << "\n# steps = " << r.steps << "\n# total_mass = " << cli::format_real(r.bar_mass->total())
        << "\n# massless_contact_node = " << (r.massless ? "true" : "false")
        << "\n# exact_energy = " << cli::format_real(r.reference->energy()) << '\n'
        << "# Each quantity is given at the instant it approximates: t for u0, t_lambda for lambda,\n"
        << "# t_energy for the energy (Paoli-Schatzman: lambda at t_n or t_{n+1}, energy at t_{n+1/2}).\n"
        << "# lambda_h = n/a where the level has no multiplier yet.\n"
        << "# columns: t u0_h u0_exact t_lambda lambda_h lambda_exact t_energy energy_h energy_exact\n";
  }
}

// The configuration, first on standard output, as `# key = value` lines (the values the run took: a
// peer's or a benchmark's defaults, the effective step), so that the output is a record of what ran:
// the scheme, the mass, N, Δt, T, the benchmark (or the file of initial data), the contact stress, and
// each parameter the scheme takes.
std::string configuration_text(const Options& o, const Run& r) {
  std::ostringstream text;
  text << "# scheme = " << mrm::to_string(r.scheme_id) << "\n# mass = " << o.mass << "\n# elements = " << o.elements
       << "\n# dt = " << cli::format_real(r.step) << "\n# final_time = " << cli::format_real(o.final_time)
       << "\n# benchmark = " << (r.own_data ? "initial-data" : o.benchmark) << '\n';
  if (r.own_data) text << "# initial_data = " << cli::json_string(o.initial_data) << '\n';
  text << "# stress = " << o.stress << '\n';
  for (const mrm::SchemeParameter parameter : mrm::scheme_info(r.scheme_id).parameters)
    text << "# " << mrm::to_string(parameter) << " = "
         << (mrm::parameter_spec(parameter).choices.empty()
                 ? cli::format_real(mrm::number(r.scheme_parameters, parameter))
                 : mrm::choice(r.scheme_parameters, parameter))
         << '\n';
  return text.str();
}

// Under a load (the field's benchmarks with gravity), the energy E_h = ½VᵀMV + ½UᵀSU alone is not
// conserved: the load does work on the bar. The total energy adds the load's potential −F(t)·U, with F
// the load vector of p1_load at the instant of the energy (Paoli–Schatzman's energy is at t_{n+1/2}: U
// there is the mean of two levels): for a steady load, Crank–Nicolson's and EC's steps change E_h by
// F·(Uⁿ⁺¹ − Uⁿ) between contact events, and EC's total is conserved through them as well. Its largest
// change is relative to the larger of |total(0)| and the largest E_h of the run, the scale of the
// energies the load exchanges (the total itself may start near 0: a bar at rest, its potential's zero
// at the undeformed position).
struct TotalEnergy {
  mrm::Problem problem;
  Eigen::VectorXd load, previous, at_energy;
  double initial = 0, final = 0, min = HUGE_VAL, max = -HUGE_VAL, largest_energy = 0, largest_change = 0;
  bool active = false;

  void observe(const mrm::UniformMesh& mesh, const mrm::Sample& s) {
    const Eigen::VectorXd& u = *s.displacement;
    if (s.energy_time != s.time && s.level > 0) {
      at_energy = 0.5 * (previous + u);
    } else {
      at_energy = u;
    }
    previous = u;
    if (!problem.steady_load || load.size() == 0)
      mrm::p1_load(
          mesh, [&](double x) { return problem.load(x, s.energy_time); }, load);
    const double total = s.energy - load.dot(at_energy);
    if (s.level == 0) initial = total;
    final = total;
    min = std::min(min, total);
    max = std::max(max, total);
    largest_energy = std::max(largest_energy, s.energy);
    largest_change = std::max(largest_change, std::abs(total - initial));
  }
  void print() const {
    if (!active) return;
    const double scale = std::max(std::abs(initial), largest_energy);
    std::cout << "energy_total_initial = " << cli::format_real(initial)
              << "\nenergy_total_final = " << cli::format_real(final)
              << "\nenergy_total_min = " << cli::format_real(min) << "\nenergy_total_max = " << cli::format_real(max)
              << "\nenergy_total_max_drift = "
              << (scale > 0 ? cli::format_real(largest_change / scale) : std::string("n/a: no energy in the run"))
              << '\n';
  }
};

// 4. The run (repro/configurations: the errors and the energy range), writing the series if asked;
// with a peer, its own measures beside (repro/peers.hpp).
void run(Run& r, TotalEnergy& total, mrm::repro::ProgressLine& progress) {
  // The peer's norms take the consistent mass on the bar's mesh: the run's own when the run takes it on
  // that mesh (the demo's standard mass), otherwise assembled for them.
  if (r.use_peer) {
    const mrm::AssembledMass& run = *r.bar_mass;
    const bool consistent = run.redistribution.name == mrm::consistent_mass().name &&
                            run.redistribution.interior_blend == 0.0 && r.bar_mass == r.configuration.assembled_mass;
    r.peer_measures = consistent ? std::make_unique<mrm::repro::PeerMeasures>(r.mesh, *r.reference, run, r.massless)
                                 : std::make_unique<mrm::repro::PeerMeasures>(r.mesh, *r.reference, r.massless);
  }
  const auto start = std::chrono::steady_clock::now();
  r.measures = r.two_bodies ? mrm::repro::run_configuration(r.configuration)
                            : mrm::repro::run_configuration(
                                  r.configuration,
                                  [&](const mrm::Sample& s) {
                                    progress.update(s.time);
                                    if (total.active) total.observe(r.mesh, s);
                                    if (r.peer_measures) r.peer_measures->add(s);
                                    if (r.series) {
                                      const mrm::ReferenceSolution& exact = *r.reference;
                                      std::ostream& out = r.series->stream();
                                      out << cli::format_real(s.time) << ' ' << cli::format_real((*s.displacement)[0])
                                          << ' ' << cli::format_real(exact.contact_displacement(s.time)) << ' '
                                          << cli::format_real(s.multiplier_time) << ' '
                                          << (s.has_multiplier ? cli::format_real(s.multiplier) : "n/a") << ' '
                                          << cli::format_real(exact.contact_multiplier(s.multiplier_time)) << ' '
                                          << cli::format_real(s.energy_time) << ' ' << cli::format_real(s.energy) << ' '
                                          << cli::format_real(exact.energy()) << '\n';
                                    }
                                  },
                                  r.reference.get());
  r.wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// 5. The figures.
void print_results(const Options& o, const Run& r, const TotalEnergy& total) {
  const auto values = mrm::ErrorAccumulator::values(r.measures.errors);
  for (std::size_t k = 0; k < values.size(); ++k)
    std::cout << mrm::ErrorAccumulator::names[k] << " = " << cli::format_real(values[k]) << '\n';
  std::cout << "energy_initial = " << cli::format_real(r.measures.energy_initial) << '\n'
            << "energy_final = " << cli::format_real(r.measures.energy_final) << '\n'
            << "energy_min = " << cli::format_real(r.measures.energy_min) << '\n'
            << "energy_max = " << cli::format_real(r.measures.energy_max) << '\n';
  total.print();
  std::cout << "steps = " << r.measures.steps << '\n';
  // The interior mass, printed when it is not the paper's consistent one.
  if (r.blend != 0.0) std::cout << "interior_mass = " << mrm::interior_mass_name(r.blend) << '\n';
  std::cout << "final_time_reached = " << cli::format_real(static_cast<double>(r.measures.steps) * r.step) << '\n';
  // The contact stress's oscillation, TV(λ_h)/TV(λ_exact) over the run's multiplier samples ("n/a" when
  // the exact λ does not vary: no contact), and the largest penetration of the contact node.
  std::cout << "stress = " << mrm::to_string(r.measures.stress) << '\n';
  // The relative L²(0,T) error of that stress (err_lambda_L2 is the multiplier's, whatever the stress).
  std::cout << "err_stress_L2 = "
            << (r.measures.stress_l2_error ? cli::format_real(*r.measures.stress_l2_error)
                                           : std::string("n/a: the exact stress does not vary over the run"))
            << '\n';
  std::cout << "lambda_tv_ratio = "
            << (r.measures.lambda_tv_ratio ? cli::format_real(*r.measures.lambda_tv_ratio)
                                           : std::string("n/a: the exact stress does not vary over the run"))
            << '\n'
            << "max_penetration = " << cli::format_real(r.measures.max_penetration) << '\n';
  // The phase (mathematics.md §8): the impacts found, the error of the first one and the drift of
  // the impact times per period (time units per period, early = negative) with that period, each
  // printed only when it can be computed (an impact in the run and in the exact solution; two of
  // each), against the exact impacts of the reference: L + 3Lk for the paper's benchmark, the
  // characteristic solution's for any other data. The period law's predictions (ℓ_f and 2ℓ_f + ℓ_c)
  // are derived for the paper's benchmark and printed for it alone.
  if (r.peer_measures) {  // the peer's definitions of the displacement measures (repro/peers.hpp)
    const auto peer_values = r.peer_measures->values();
    for (std::size_t k = 0; k < peer_values.size(); ++k)
      std::cout << "peer_" << mrm::repro::PeerMeasures::names[k] << " = " << cli::format_real(peer_values[k]) << '\n';
    // The preset's formulation, or, for getfem-v1 with a --beta of its own, the same words with that beta
    // and the start it takes (resolve_options).
    const mrm::repro::PeerPreset& preset = mrm::repro::peer_preset(o.peer);
    const mrm::SchemeParameters& p = r.configuration.scheme;
    const bool own_beta = preset.scheme.scheme == mrm::Scheme::paoli_schatzman &&
                          p.scheme == mrm::Scheme::paoli_schatzman && p.beta != preset.scheme.beta;
    std::cout << "peer_formulation = "
              << (own_beta ? "ps: three-level Paoli-Schatzman (beta = " + cli::format_real(p.beta) +
                                 "), the literal contact row, e = e_PS, started by " +
                                 (p.ps_explicit_start ? "the explicit Newmark step"
                                                      : "one Crank-Nicolson step (the demo's Newmark (1/4, 1/2) step)")
                           : preset.formulation)
              << '\n';
  }
  std::cout << "impacts = " << r.measures.impacts.size() << '\n';
  if (!r.measures.impacts.empty() && !r.measures.phase)
    std::cout << "impacts_compared = 0\n"
              << "first_impact_error = n/a: no impact of the run lies within half the exact inter-impact time of "
                 "the first exact impact (a pair farther apart would compare unrelated events)\n";
  if (r.measures.phase) {
    std::cout << "impacts_compared = " << r.measures.phase->matched << '\n';
    std::cout << "first_impact_error = " << cli::format_real(r.measures.phase->first_impact_error) << '\n';
    if (r.measures.phase->drift_per_period)
      std::cout << "phase_drift_per_period = " << cli::format_real(*r.measures.phase->drift_per_period) << '\n'
                << "phase_period = " << cli::format_real(r.measures.phase->period) << '\n';
  }
  if (o.elements >= 3 && mrm::repro::has_closed_form(r.configuration)) {
    const mrm::PeriodPrediction law = mrm::predict_period(r.mesh, r.bar_mass->matrix);
    std::cout << "period_law_first_impact_error = " << cli::format_real(law.first_impact_error) << '\n'
              << "period_law_drift_per_period = " << cli::format_real(law.period_error) << '\n';
    // On a graded mesh: h0 and the coarsest element, and the first-order law's change of the
    // drift against Mod 3's on the same mesh, Σ δm_i κ(x_i) (period_law.cpp, "unequal elements").
    // The first-order law compares redistributions (a massless contact node): for a mass that keeps the
    // node's inertia the value is n/a with the reason, not an error after the results.
    if (o.grading != 1.0)
      std::cout << "grading = " << cli::format_real(o.grading) << '\n'
                << "h0 = " << cli::format_real(r.mesh.h(0)) << '\n'
                << "h_max = " << cli::format_real(r.mesh.h(o.elements - 1)) << '\n'
                << "period_law_first_order_drift_change_vs_mod3 = "
                << (r.massless ? cli::format_real(mrm::first_order_period_change(r.mesh, r.configuration.mass))
                               : "n/a: the mass " + o.mass +
                                     " keeps the inertia of the contact node (the law compares redistributions)")
                << '\n';
  }
  // On a field benchmark: the exact contact windows over [0, T] (lib/exact/impact_solution.hpp, computed in the
  // benchmark's own units) and the run's (the crossings of the contact indicator, phase.hpp), in the
  // benchmark's time unit.
  if (r.field_benchmark) {
    std::vector<mrm::ContactInterval> windows;
    mrm::repro::as_usage_error({{"final_time", "--final-time"}, {"configuration", "--final-time"}}, [&] {
      windows = mrm::repro::configuration_contact_windows(r.configuration, o.final_time);
    });
    const auto print = [](const char* name, const std::vector<mrm::ContactInterval>& list) {
      std::cout << name << " =";
      for (const mrm::ContactInterval& w : list)
        std::cout << " [" << cli::format_real(w.start) << ", " << cli::format_real(w.end) << "]";
      std::cout << (list.empty() ? " none" : "") << '\n';
    };
    if (!r.benchmark->time_unit.empty()) std::cout << "time_unit = " << r.benchmark->time_unit << '\n';
    print("exact_contact_windows", windows);
    print("measured_contact_windows", r.measures.contact_windows);
    std::cout << "exact_contact_held_at_final_time = " << (!windows.empty() && windows.back().open ? "true" : "false")
              << '\n'
              << "measured_contact_held_at_final_time = "
              << (!r.measures.contact_windows.empty() && r.measures.contact_windows.back().open ? "true" : "false")
              << '\n';
  }
  if (!o.no_timing) std::cout << "wall_seconds = " << cli::format_real(std::round(r.wall * 1e4) / 1e4) << '\n';
}

}  // namespace

int main(int argc, char** argv) {
  return cli::guarded_main("bar1d", [&] {
    Options o;
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
    declare_options(parser, o);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    Run r;
    resolve_options(parser, o, r);
    // 2. The output, opened now so that an unwritable path fails before the run.
    if (parser.given("--output")) r.series = std::make_unique<cli::AtomicFile>(o.output, "--output");
    build_run(parser, o, r);
    warn_outside_measured_region(o, r);
    mrm::repro::as_usage_error({{"final_time", "--final-time"}, {"configuration", "--final-time"}}, [&] {
      if (r.two_bodies) {  // the chain's exact solution, built by the run (its horizon checked here)
        mrm::repro::configuration_contact_windows(r.configuration, mrm::repro::reference_horizon(r.steps, r.step));
        return;
      }
      r.reference =
          mrm::repro::configuration_reference(r.configuration, mrm::repro::reference_horizon(r.steps, r.step));
    });
    if (r.series) write_series_header(parser, o, r);
    // The configuration first: at once on a terminal (a person sees what runs while it runs), otherwise
    // with the results, so that a run that fails leaves nothing on standard output.
    const std::string configuration = configuration_text(o, r);
    const bool terminal = ::isatty(STDOUT_FILENO) == 1;
    if (terminal) std::cout << configuration << std::flush;
    TotalEnergy total;
    if (!r.two_bodies) {
      total.problem = mrm::repro::configuration_problem(r.configuration);
      total.active = static_cast<bool>(total.problem.load);
    }
    {
      // A person at a terminal sees how far a long run is (standard error, after 2 s); erased before
      // the results are printed.
      mrm::repro::ProgressLine progress("bar1d", o.final_time);
      run(r, total, progress);
    }
    if (!terminal) std::cout << configuration;
    print_results(o, r, total);
    if (r.series) r.series->commit();
    return 0;
  });
}
