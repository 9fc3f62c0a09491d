/// @file configurations/configuration.hpp
/// @brief One run of the harness (a scheme, a mass, a mesh, the data of a benchmark or a file, the time step) and the paper's named configurations.
#pragma once

#include <array>
#include <functional>
#include <optional>

#include <memory>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

#include "labels.hpp"
#include "mass_spec.hpp"
#include "options.hpp"
#include "output_file.hpp"
#include "run_limits.hpp"

#include "exact/benchmarks.hpp"
#include "exact/characteristics.hpp"
#include "measures/contact_stress.hpp"
#include "measures/errors.hpp"
#include "exact/impact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "measures/phase.hpp"
#include "exact/reference_solution.hpp"
#include "time/schemes.hpp"

namespace mrm::repro {

/// The scheme's parameters; Paoli–Schatzman with β = ¼, e = 0 and the given contact row (a mass that
/// keeps the contact node's inertia always takes the literal row: it has no algebraic one). CN-switch's
/// θ keeps its default (1, backward Euler); a program that offers it sets SchemeParameters::switch_theta.
inline mrm::SchemeParameters scheme_parameters(mrm::Scheme scheme, const std::string& ps_form,
                                               const std::string& mass) {
  mrm::SchemeParameters p;
  p.scheme = scheme;
  if (p.scheme == mrm::Scheme::paoli_schatzman)
    p.contact_row = mass == "consistent" ? mrm::ContactRow::literal : mrm::contact_row_by_name(ps_form);
  return p;
}
/// The same, the scheme named by its id in the registry (mrm::scheme_by_name).
inline mrm::SchemeParameters scheme_parameters(const std::string& scheme, const std::string& ps_form,
                                               const std::string& mass) {
  return scheme_parameters(mrm::scheme_by_name(scheme), ps_form, mass);
}

/// The redistribution named by the value `spec` of the mass option `option`, checked on the mesh of the run
/// (mass_redistribution_from_spec, mass_spec.hpp); a bad value throws cli::UsageError "<option>: \"spec\": why
/// (allowed: ...)", so that the program exits with status 2 before any work. `massless` additionally refuses
/// the consistent mass (for a program that needs a massless contact node). `blend`: the interior mass
/// blend A the member is defined on (interior_blend_from_spec, mass_spec.hpp; 0 the paper's).
MassRedistribution mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                    bool massless = false, double blend = 0.0);
/// The same, with M^mod as the check assembled it on `mesh` (assembled_mass_from_spec): the one assembly of
/// a run that shares it (Configuration::assembled_mass).
AssembledMass assembled_mass_from_option(const std::string& option, const std::string& spec, const UniformMesh& mesh,
                                         bool massless = false, double blend = 0.0);

/// The velocity of a massless contact node in the velocity measures. `algebraic` (the default): the
/// library's own, defined from the algebraic contact row (mathematics.md §7; BarSimulation sets V₀ at
/// every level of a two-level scheme). `backward_difference`: (u₀ⁿ − u₀ⁿ⁻¹)/Δt at every level n ≥ 1,
/// as GetFEM's demo_dynamic_contact_1D.py does (mathematics.md §13), to compare with that code. A
/// contact node with inertia keeps the scheme's velocity either way.
enum class ContactVelocity { algebraic, backward_difference };
/// "algebraic" or "backward-difference"; throws std::invalid_argument otherwise.
ContactVelocity contact_velocity_by_name(const std::string& name);

/// One run: the bar (0, L) released from the initial data of a benchmark (the paper's u⁰(x) = a (L − x)
/// by default) or of a file, a scheme, a mass, a mesh of N elements and Δt (given, or C h), to the first
/// level t_n ≥ T (or for a given number of steps).
struct Configuration {
  SchemeParameters scheme;
  MassRedistribution mass = mod3();
  /// `mass` assembled once on the mesh the run steps on (assembled_mass_from_option; null by default),
  /// which the run reads instead of assembling M^mod again: the unit bar's,
  /// configuration_mesh(unit_configuration(*this, configuration_scaling(*this))) (of two bodies, body
  /// 0's), the configuration's own mesh when the scaling keeps it (Scaling::keeps_mesh). Whoever
  /// changes `mass` or the mesh resets it.
  std::shared_ptr<const AssembledMass> assembled_mass;
  /// Two bodies: `mass` assembled once on body 1's unit mesh (configuration_mesh(unit, 1), unit as
  /// above; null by default), which their run reads like `assembled_mass` on body 0's.
  std::shared_ptr<const AssembledMass> assembled_mass_body1;
  Index elements = 100;
  double courant = 0.5;  ///< Δt = C h, unless dt > 0
  double dt = 0.0;       ///< the time step if > 0
  double final_time = 3.0;
  Index steps = -1;  ///< the number of steps if ≥ 0 (final_time is then unused)
  double length = 1.0;
  double amplitude = 0.5;
  InitialContactNode initial = InitialContactNode::consistent;
  /// Horizons T_k (increasing, each ≤ final_time) at which the errors over [0, T_k] are also measured,
  /// from the same run: a prefix of the run is the run to T_k.
  std::vector<double> horizons;
  /// The id of an entry of the registry of benchmarks (mrm::benchmarks(), lib/exact/benchmarks.hpp);
  /// `length` and `amplitude` apply to the one that takes them (Benchmark::takes_length: the paper's).
  /// Ignored when `data` is set. A field benchmark (Benchmark::field: bouncing, impacting, gravity-paper,
  /// two-bars, layered) runs its chain of lib/exact/impact_solution.hpp: its load, gap, material and far
  /// end, in its own units, with the exact ImpactSolution as the reference.
  std::string benchmark = "paper";
  /// The field benchmark's chain and data when they are not the registry's: set by unit_configuration
  /// to the dimensionless ones (empty: the registry's entry named `benchmark`).
  std::shared_ptr<const ImpactBenchmark> field;
  /// Initial data of one's own (bar1d --initial-data), L = their last x; the reference is then the
  /// characteristic solution.
  std::shared_ptr<const InitialData> data;
  /// The contact node's velocity in the velocity measures (the library's by default).
  ContactVelocity contact_velocity = ContactVelocity::algebraic;
  /// The mesh's grading ratio r: element sizes h_k = h₀ r^k, k = 0..N−1, finer toward the contact for
  /// r > 1 (graded_mesh, lib/fem/p1.hpp); 1, the uniform mesh, by default. Not on a field benchmark
  /// (configuration_mesh refuses it: their interfaces and Δt = C h/c are set on the uniform mesh).
  double grading = 1.0;
  /// The contact stress whose oscillation Measures::lambda_tv_ratio reports (lib/measures/contact_stress.hpp; the
  /// scheme's multiplier by default).
  ContactStress stress = ContactStress::multiplier;
  /// Whether Measures::stress_history keeps the histories every stress is computed from (fig_stress).
  /// A stress other than the multiplier keeps the histories it needs (the multiplier and the exact λ,
  /// 24 bytes per step; the recovered strain 24 more): a run's memory then grows with its steps.
  bool keep_stress_history = false;
  /// Whether the run measures the eight errors (Measures::errors and horizon_errors; false: they stay
  /// 0, for a study of the stresses only, which then costs the steps alone).
  bool measure_errors = true;

  /// The length of the bar: L of the data, of a field benchmark's chain, of the smooth benchmarks (1), or
  /// `length`.
  double bar_length() const;
  /// Δt: dt if given, otherwise C h/c with c the wave speed at the contact end (1 but on a field
  /// benchmark: C is the Courant number of the contact element), h the contact element's size: L/N, h₀
  /// on a graded mesh, ℓ/N on two bodies (N elements on each body, ℓ the left body's length).
  double step() const;
};

/// The registry's entry of a configuration's benchmark (mrm::benchmark); throws InvalidParameter
/// ("benchmark") for an unknown id.
const Benchmark& configuration_benchmark(const Configuration& configuration);

/// Whether the configuration runs the paper's benchmark (not data of one's own), whose exact solution is
/// the closed form of mathematics.md §2.
bool has_closed_form(const Configuration& configuration);

/// The problem of a configuration: its benchmark's (Benchmark::problem; the field chain's load and gap),
/// or its data of one's own with f = 0. Throws InvalidParameter ("benchmark") for an unknown id and for
/// two-bars (two bodies have no one-body problem: run_configuration runs them).
Problem configuration_problem(const Configuration& configuration);

/// The field benchmark of a configuration (its `field`, or the registry's entry named `benchmark`), or
/// null for the paper's, the smooth ones and data of one's own.
const ImpactBenchmark* configuration_field(const Configuration& configuration);

/// The mesh of a configuration: its benchmark's (Benchmark::mesh: N elements on (0, L) graded by
/// Configuration::grading; on a field benchmark its material per element and its far end, mrm::chain_mesh),
/// or N elements on the length of its data of one's own. Throws InvalidParameter ("elements") when an
/// interface between two materials is not a node (the allowed N named), InvalidParameter ("grading") for
/// a grading on a field benchmark. On two bodies (two-bars: is_two_body_chain), the mesh of body k (0 the
/// left one) in its own frame (lib/time/two_bodies.hpp: ξ from its contact end): N elements on its length,
/// its material, its far end; both bodies have N elements.
UniformMesh configuration_mesh(const Configuration& configuration, int body = 0);
/// Whether the configuration is a field benchmark of two bodies in contact (two-bars), which
/// run_configuration runs with lib/time/two_bodies.hpp (Crank–Nicolson only).
bool is_two_body_configuration(const Configuration& configuration);

/// The initial data of a configuration as piecewise polynomials (the paper's, a smooth benchmark's or
/// the file's).
InitialData configuration_data(const Configuration& configuration);

/// The exact solution a configuration's errors are measured against: the closed form for the paper's
/// benchmark (has_closed_form, mathematics.md §2), a field benchmark's ImpactReference, otherwise the
/// characteristic solution of its data (mathematics.md §10) up to
/// `horizon`, tabulated on the lattice of h and Δt when one of them is a whole multiple of the other.
/// At the configuration's own scale (the characteristic solution is computed for the unit
/// configuration and scaled back).
std::shared_ptr<const ReferenceSolution> configuration_reference(const Configuration& configuration, double horizon);

/// The exact solution's contact windows over [0, T] of a configuration's contact point, in the
/// configuration's own units: for a field benchmark (Benchmark::field) its chain and data, for the
/// others (paper, smooth ones, data of one's own) the clamped homogeneous bar of unit wave speed with
/// configuration_data. Computed by mrm::ImpactSolution (lib/exact/impact_solution.cpp), in the data's units
/// (SI for impacting: the exact solution needs no scaling). Throws mrm::InvalidParameter ("final_time")
/// when the horizon needs more wave fronts than the solver keeps.
std::vector<ContactInterval> configuration_contact_windows(const Configuration& configuration, double final_time);

/// A configuration named as the paper names it: a scheme of the registry (mrm::scheme_registry; Paoli–
/// Schatzman is (¼, 0) with the contact row `ps_form`), a mass spec of mass_redistribution_from_spec in
/// mass_spec.hpp ("mod1", "mod2", "mod3", "consistent", "node1:7/6", ...), N, Δt = C h, T.
Configuration paper_configuration(Scheme scheme, const std::string& ps_form, const std::string& mass, Index elements,
                                  double courant, double final_time);
/// The same, the scheme named by its id in the registry (mrm::scheme_by_name).
Configuration paper_configuration(const std::string& scheme, const std::string& ps_form, const std::string& mass,
                                  Index elements, double courant, double final_time);

/// One run of a study over benchmarks and variants (fig_stress, fig_phase_matched; fig_classes may use
/// it too): `scheme` with its registry defaults, the contact mass `mass`, N elements, Δt = C h (c the
/// wave speed at the contact end on a field benchmark), to T on `benchmark` (an id of mrm::benchmarks()).
/// Every other field keeps Configuration's default.
Configuration study_configuration(const std::string& benchmark, Scheme scheme, const MassRedistribution& mass,
                                  Index elements, double courant, double final_time);
/// The work of a run, elements × steps (the cost a study's costliest_first schedules by); throws
/// std::invalid_argument where Configuration::step() or mrm::steps_to_reach does.
double run_cost(const Configuration& c);

}  // namespace mrm::repro
