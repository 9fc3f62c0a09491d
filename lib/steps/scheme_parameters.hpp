/// @file scheme_parameters.hpp
/// @brief The time schemes' names and parameters: the Scheme enum, SchemeParameters, and one spec per
/// parameter (its option, range, default and help), spelled once. Which scheme takes which parameter, and
/// how its step is built, is its registry entry's (step.hpp, SchemeInfo; time/scheme_registry.hpp).
#pragma once

#include <string>
#include <vector>

namespace mrm {

/// The time schemes of the paper (mathematics.md §4).
enum class Scheme {
  crank_nicolson,     ///< Crank–Nicolson (trapezoidal rule), two levels
  backward_euler,     ///< backward Euler, two levels
  paoli_schatzman,    ///< Paoli–Schatzman (β, e), three levels
  energy_conserving,  ///< EC: Crank–Nicolson with the discrete gradient of the contact energy (mathematics.md §12)
  switching,          ///< CN-switch: Crank–Nicolson, a θ-step where the contact status changes (mathematics.md §12)
  // The field's contact treatments (Doyen–Ern–Piperno's classes, doc/contact_treatments.md; lib/classes/):
  newmark,           ///< Newmark(β, γ) with exact (Signorini) enforcement by a multiplier at the new level
  penalty,           ///< Newmark(β, γ) with the penalty force (γ₀/h) min(0, u₀)
  nitsche,           ///< Newmark(β, γ) with Nitsche's boundary terms (θ, γ₀), GetFEM's formulation
  moreau_jean,       ///< Moreau–Jean (θ, e): the θ-method with a velocity-level impact law (inertial contact node)
  taylor_flanagan,   ///< central differences, contact by Taylor–Flanagan's velocity correction (explicit_schemes.cpp)
  explicit_central,  ///< central differences with a massless contact node on its algebraic row (explicit_schemes.cpp)
  dke  ///< Deuflhard–Krause–Ertel's contact-stabilised Newmark (¼, ½): the predictor projected in the mass norm
};

/// The mass an explicit scheme uses (explicit_schemes.cpp): `row_sum` lumps the run's mass by row sums
/// (the default), `none` keeps the consistent mass and solves with it at every step (GetFEM's demo with
/// lump_mass_matrix = 0; taylor-flanagan with the consistent mass only).
enum class MassLumping { row_sum, none };

/// How the Paoli–Schatzman scheme treats the contact row when the contact node is massless:
/// `literal` applies the three-level formula to every row, the contact row included;
/// `algebraic` imposes the contact row S₀·U = F₀ − λ at every new level, as the other schemes do.
enum class ContactRow { algebraic, literal };

/// The initial value of a massless contact node: `consistent` solves its algebraic row,
/// u₀(0) = max(0, u₁(0) + hF₀); `interpolant` keeps the nodal value of u⁰.
enum class InitialContactNode { consistent, interpolant };

/// Which implementation of one step a BarSimulation runs (mathematics.md §4). Both compute the step
/// (★) of schemes.cpp and give the same samples up to round-off (doctest "the fast step and the
/// reference step agree to round-off"):
/// `reference` is the step written as its derivation (schemes.cpp: the assembled matrices A, B₁, B₂,
/// one tridiagonal solve with the closed-form contact step, the velocity and the energy from their
/// definitions); `fast` is the fused two-chain kernel of fast_step.cpp, the default, used by every
/// program of this project (bench_step times both). The contact classes (contact_classes.hpp) read it
/// too: `reference` their step written as its derivation, `fast` the same operations fused node by node,
/// the same bits.
enum class StepKernel { reference, fast };

/// A parameter of SchemeParameters that only some schemes take (the registry says which).
enum class SchemeParameter {
  beta,           ///< Paoli–Schatzman's β
  restitution,    ///< Paoli–Schatzman's restitution coefficient e
  contact_row,    ///< Paoli–Schatzman's contact-row form (algebraic or literal)
  switch_theta,   ///< CN-switch's θ of the step taken at a change of the contact status
  newmark_beta,   ///< Newmark's β of the contact classes (newmark, penalty, nitsche)
  newmark_gamma,  ///< Newmark's γ of the contact classes
  penalty,        ///< the penalty parameter γ₀ (stiffness γ₀/h)
  nitsche_theta,  ///< Nitsche's symmetry parameter θ ∈ [−1, 1]
  nitsche_gamma,  ///< Nitsche's γ₀ (γ = γ₀/h)
  moreau_theta,   ///< Moreau–Jean's θ ∈ [½, 1]
  ps_start,       ///< Paoli–Schatzman's first step (Crank–Nicolson, or GetFEM's explicit Newmark step)
  mass_lumping    ///< the explicit schemes' mass lumping (row-sum or none)
};

/// A time scheme with its parameters.
struct SchemeParameters {
  Scheme scheme = Scheme::crank_nicolson;          ///< the scheme
  double beta = 0.25;                              ///< Paoli–Schatzman's β ≥ 0
  double restitution = 0.0;                        ///< Paoli–Schatzman's e ∈ [0, 1]
  ContactRow contact_row = ContactRow::algebraic;  ///< Paoli–Schatzman's contact row (massless node)
  StepKernel kernel = StepKernel::fast;            ///< the implementation of the step (same results to round-off)
  /// CN-switch's θ ∈ [½, 1] of the step that replaces a Crank–Nicolson step across which the contact
  /// status changes: 1 is backward Euler, the only value for which the energy provably never increases.
  double switch_theta = 1.0;
  // The contact classes (lib/classes/contact_classes.cpp). The defaults of γ₀ and θ are GetFEM's demo's
  // (demo_dynamic_contact_1D.py: γ₀_P = 1, γ₀_N = 5, θ_N = 0); Newmark's default is (¼, ½), Crank–Nicolson.
  double newmark_beta = 0.25;  ///< Newmark's β ≥ 0 (0: explicit, the step solves with the mass)
  double newmark_gamma = 0.5;  ///< Newmark's γ ≥ ½
  double penalty = 1.0;        ///< the penalty's γ₀ > 0: the contact force (γ₀/h) min(0, u₀)
  double nitsche_theta = 0.0;  ///< Nitsche's θ ∈ [−1, 1] (1 symmetric, 0 skew-free, −1 skew-symmetric)
  double nitsche_gamma = 5.0;  ///< Nitsche's γ₀ > 0 (and > θ): γ = γ₀/h
  double moreau_theta = 0.5;   ///< Moreau–Jean's θ ∈ [½, 1]
  /// Paoli–Schatzman's first step: false, one Crank–Nicolson step (the library's); true, the explicit
  /// Newmark step U¹ = U⁰ + ΔtV⁰ + ½Δt² M⁻¹(F⁰ − SU⁰) of GetFEM's demo (a contact node with inertia only).
  bool ps_explicit_start = false;
  MassLumping lumping = MassLumping::row_sum;  ///< the explicit schemes' mass (explicit_schemes.hpp)
};

/// `scheme` with every parameter at its default, the contact row and the step's kernel as given.
SchemeParameters parameters_of(Scheme scheme, ContactRow row = ContactRow::algebraic,
                               StepKernel kernel = StepKernel::fast);

/// The θ of CN-switch's step for which the θ-step's energy identity proves that no step gains energy
/// (energy_step.cpp §4): Eⁿ⁺¹ − Eⁿ ≤ −(θ − ½)‖ΔV‖²_M̄ + ρ_θ(a, b), and at a release (a < 0 ≤ b, s = u₁ + hF₀
/// before and after) ρ_θ = ((1 − θ)|ab| − (θ − ½)a²)/h, positive as soon as |b|/|a| > (θ − ½)/(1 − θ).
/// A release falls anywhere inside its step, so |b|/|a| takes every value in (0, ∞): for every θ < 1
/// some release gains energy (θ = 0.6 gains energy on the benchmark, θ = 0.51 blows up), and only θ = 1
/// (backward Euler, ρ₁ ≤ 0 in every case) is proved. The programs accept this value only; the library
/// keeps θ ∈ [½, 1] for the checks of the θ-step itself.
constexpr double switch_theta_without_gain = 1.0;

/// One parameter of SchemeParameters that only some schemes take: what a program needs to offer it as
/// an option (its name, its option, its allowed values, its default, its help), spelled once here, as
/// PETSc's TS types own their -ts_* options. A real parameter has the closed range [lowest, highest]
/// (lowest excluded when `lowest_excluded`); a named one, its `choices`.
struct ParameterSpec {
  SchemeParameter parameter;         ///< which member of SchemeParameters
  std::string name;                  ///< its name in messages ("newmark_beta"): to_string(parameter)
  std::string option;                ///< its command-line option ("--newmark-beta")
  std::string short_option;          ///< a one-letter option ("-b"), or empty
  std::string placeholder;           ///< the value's name in help texts ("B")
  std::string help;                  ///< one sentence: what it is, which schemes take it, its range
  std::vector<std::string> choices;  ///< a named parameter's values; empty for a real one
  double lowest = 0;                 ///< a real parameter's smallest value a program accepts
  double highest = 0;                ///< its largest
  bool lowest_excluded = false;      ///< whether `lowest` itself is refused (a positive parameter)
};
/// The specs of every SchemeParameter, in the order of the enum (doctest: one per member, each named
/// as to_string says).
const std::vector<ParameterSpec>& scheme_parameter_specs();
/// The spec of one parameter.
const ParameterSpec& parameter_spec(SchemeParameter parameter);
/// A real parameter's value in `parameters` (the default of every parameter is its value in
/// SchemeParameters{}); std::invalid_argument for a named one.
double number(const SchemeParameters& parameters, SchemeParameter parameter);
/// The choice a named parameter has in `parameters` ("algebraic", "cn", "row-sum"); std::invalid_argument
/// for a real one.
std::string choice(const SchemeParameters& parameters, SchemeParameter parameter);
/// Sets a real parameter (no check of the value: BarSimulation checks it); std::invalid_argument for a
/// named one.
void set_number(SchemeParameters& parameters, SchemeParameter parameter, double value);
/// Sets a named parameter from one of its choices; std::invalid_argument listing the choices otherwise.
void set_choice(SchemeParameters& parameters, SchemeParameter parameter, const std::string& value);
/// Whether a parameter keeps its default value in `parameters`.
bool is_default(const SchemeParameters& parameters, SchemeParameter parameter);

std::string to_string(SchemeParameter);                ///< its spec's name: "beta", "restitution", ...
std::string to_string(ContactRow);                     ///< "algebraic", "literal"
std::string to_string(InitialContactNode);             ///< "consistent", "interpolant"
std::string to_string(StepKernel);                     ///< "reference", "fast"
std::string to_string(MassLumping);                    ///< "row-sum", "none"
MassLumping mass_lumping_by_name(const std::string&);  ///< row-sum, none; std::invalid_argument otherwise
/// Parsers of the names above; throw std::invalid_argument listing the allowed names.
ContactRow contact_row_by_name(const std::string&);                   ///< algebraic, literal
InitialContactNode initial_contact_node_by_name(const std::string&);  ///< consistent, interpolant

}  // namespace mrm
