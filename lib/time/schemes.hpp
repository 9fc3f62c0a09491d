/// @file schemes.hpp
/// @brief The time schemes of the paper (Crank–Nicolson, backward Euler, Paoli–Schatzman) for the
/// P1 bar with a redistributed or consistent mass (mathematics.md §4).
#pragma once

#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "core/problem.hpp"
#include "time/contact.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"

namespace mrm {

/// The time schemes of the paper (mathematics.md §4).
enum class Scheme {
  crank_nicolson,     ///< Crank–Nicolson (trapezoidal rule), two levels
  backward_euler,     ///< backward Euler, two levels
  paoli_schatzman,    ///< Paoli–Schatzman (β, e), three levels
  energy_conserving,  ///< EC: Crank–Nicolson with the discrete gradient of the contact energy (mathematics.md §12)
  switching,          ///< CN-switch: Crank–Nicolson, a θ-step where the contact status changes (mathematics.md §12)
  // The field's contact treatments (Doyen–Ern–Piperno's classes, field.md §2; lib/classes/contact_classes.cpp):
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

/// One entry of the registry of schemes: what the programs' help texts, choice lists, data headers
/// and claims rows name a scheme by, as MFEM's ODESolver::Types or PETSc's -ts_type list do.
struct SchemeInfo {
  Scheme scheme;                            ///< the scheme
  std::string id;                           ///< its name on command lines and in data files ("cn")
  std::string summary;                      ///< one line for help texts and reports
  std::vector<SchemeParameter> parameters;  ///< the parameters it takes beyond Δt (the others keep their defaults)
};
/// Every scheme of the library, in the order of the enum. Adding a scheme is: its code, its doctests,
/// one entry here (schemes.cpp).
const std::vector<SchemeInfo>& scheme_registry();
/// The registry entry of a scheme.
const SchemeInfo& scheme_info(Scheme);
/// Whether `scheme` takes `parameter` (its registry entry lists it).
bool takes(Scheme scheme, SchemeParameter parameter);

std::string to_string(Scheme);                         ///< the registry's id: "cn", "be", "ps", "ec", "cn-switch"
std::string to_string(SchemeParameter);                ///< "beta", "restitution", "contact_row", "switch_theta"
std::string to_string(ContactRow);                     ///< "algebraic", "literal"
std::string to_string(InitialContactNode);             ///< "consistent", "interpolant"
std::string to_string(StepKernel);                     ///< "reference", "fast"
std::string to_string(MassLumping);                    ///< "row-sum", "none"
MassLumping mass_lumping_by_name(const std::string&);  ///< row-sum, none; std::invalid_argument otherwise
/// Parsers of the names above; throw std::invalid_argument listing the allowed names.
Scheme scheme_by_name(const std::string&);                            ///< an id of the registry
ContactRow contact_row_by_name(const std::string&);                   ///< algebraic, literal
InitialContactNode initial_contact_node_by_name(const std::string&);  ///< consistent, interpolant

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

/// The matrices and scalars of one step (★) of schemes.cpp,
/// A Uⁿ⁺¹ = B₁ Uⁿ + B₂ W + G − κ λ e₀, 0 ≤ u₀ⁿ⁺¹ − g ⊥ λ ≤ 0, for one scheme, mass and Δt: the one
/// builder of the step's coefficients, used by the reference step, the fast kernel's set-up,
/// CN-switch's θ-step and the harness's checks of the contact step (repro/claims.cpp).
struct StepMatrices {
  Tridiagonal a;   ///< A, the step matrix (row 0 the algebraic contact row S₀· when `algebraic_row`)
  Tridiagonal b1;  ///< B₁, applied to Uⁿ (row 0 zero with the algebraic row)
  Tridiagonal b2;  ///< B₂, applied to W = Vⁿ (two levels) or Uⁿ⁻¹ (three levels) (row 0 zero likewise)
  /// The increment form the steps solve (schemes.cpp, "the increment form"): A ΔU = C₁ Uⁿ + C₂ W' + G
  /// − κλe₀ for ΔU = Uⁿ⁺¹ − Uⁿ, with C₁ = B₁ − A = −θΔt²S (two levels) or B₁ + B₂ − A = −Δt²S (three),
  /// row 0 −S₀· with the algebraic row, built as multiples of S (no difference of matrices is rounded).
  Tridiagonal c1;
  /// C₂ = B₂ applied to W' = Vⁿ (two levels), or −B₂ = A applied to W' = Uⁿ − Uⁿ⁻¹ (three levels);
  /// row 0 zero with the algebraic row.
  Tridiagonal c2;
  double kappa = 0;  ///< κ: the weight of λⁿ⁺¹ (or λⁿ for Paoli–Schatzman) in row 0; 1 with the algebraic row
  double load_now = 0;   ///< G = load_now Fⁿ + load_next Fⁿ⁺¹ on the rows of inertia
  double load_next = 0;  ///< see load_now (with the algebraic row, G₀ = F₀ⁿ⁺¹)
  double lambda_in_rhs = 0;  ///< the weight of −λⁿ in row 0 (Crank–Nicolson-type steps with an inertial contact node)
  double velocity_rate = 0;  ///< two levels: Vⁿ⁺¹ = rate (Uⁿ⁺¹ − Uⁿ) − memory Vⁿ; three levels: X = rate (Uⁿ⁺¹ − Uⁿ)
  double velocity_memory = 0;  ///< see velocity_rate
  bool algebraic_row = false;  ///< whether row 0 is the algebraic contact row S₀·U = F₀ − λ (massless contact node)
  /// The part of the obstacle g that the gap sets: −gap, or −(1 + e) gap for Paoli–Schatzman's
  /// averaged constraint (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ≥ −gap; 0 without a gap (set by BarSimulation).
  double obstacle_offset = 0;
};
/// The step of `parameters.scheme` (CN-switch's and EC's is Crank–Nicolson's) on the unknowns 0..N−1
/// with mass M and stiffness S (schemes.cpp, mathematics.md §4). Does not check the parameters
/// (BarSimulation does).
StepMatrices step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, const SchemeParameters& parameters,
                           double dt);
/// The step of the θ-rule, θ ∈ [½, 1] (θ = ½ is Crank–Nicolson, θ = 1 backward Euler; CN-switch's
/// θ-step), with the algebraic contact row when the contact node is massless.
StepMatrices theta_step_matrices(const Tridiagonal& mass, const Tridiagonal& stiffness, double theta, double dt);
/// The right-hand side of (★) before the contact force: b = B₁ Uⁿ + B₂ W + G − lambda_in_rhs λⁿ e₀,
/// row 0 replaced by F₀ⁿ⁺¹ with the algebraic row. `load_now` and `load_next` are Fⁿ and Fⁿ⁺¹, or
/// null for f = 0.
Eigen::VectorXd step_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                     double lambda, const Eigen::VectorXd* load_now = nullptr,
                                     const Eigen::VectorXd* load_next = nullptr);
/// The right-hand side of the increment form before the contact force: c = C₁ Uⁿ + C₂ W' + G −
/// lambda_in_rhs λⁿ e₀, row 0 −S₀·Uⁿ + F₀ⁿ⁺¹ with the algebraic row; W' = Vⁿ or Uⁿ − Uⁿ⁻¹.
Eigen::VectorXd increment_right_hand_side(const StepMatrices& step, const Eigen::VectorXd& u, const Eigen::VectorXd& w,
                                          double lambda, const Eigen::VectorXd* load_now = nullptr,
                                          const Eigen::VectorXd* load_next = nullptr);

/// The state of a run between two steps, owned by BarSimulation and advanced by its step kernels (the
/// reference step of schemes.cpp and the fast kernel of fast_step.cpp), which read and write nothing else.
struct StepState {
  Eigen::VectorXd u;       ///< Uⁿ
  Eigen::VectorXd u_new;   ///< the scratch of the sweeps, then Uⁿ⁺¹ (swapped into u)
  Eigen::VectorXd w;       ///< W': Vⁿ (the two-level schemes' velocity) or Uⁿ − Uⁿ⁻¹ (Paoli–Schatzman)
  Eigen::VectorXd x;       ///< X = (Uⁿ − Uⁿ⁻¹)/Δt, Paoli–Schatzman's velocity (empty for two levels)
  Eigen::VectorXd f_now;   ///< Fⁿ (empty without a load)
  Eigen::VectorXd f_next;  ///< Fⁿ⁺¹ (empty without a load)
  double lambda = 0.0;     ///< λ at the current level
  double energy = 0.0;     ///< the discrete energy at the current level
  bool active = false;     ///< the contact status: λ < 0, or s = u₁ + hF₀ < 0 for a massless node
};

class FastStep;
class ContactClassStep;
class ExplicitStep;

/// One run of one scheme on one mesh with one mass: the state, the constant step matrix factorised
/// once, and the step (the reference step of schemes.cpp or the fast kernel of fast_step.cpp, as
/// SchemeParameters::kernel says). Memory is O(N): no history is kept. The formulas hold for any L,
/// but the numbers are sized for the dimensionless problem, L = 1 and data of order one (the energy's
/// quadratic forms are taken as they are): the harness maps any length and amplitude to it by the
/// scaling law (mathematics.md §1, repro/configurations.cpp).
class BarSimulation {
 public:
  /// Checks every input before any work and throws InvalidParameter (a std::invalid_argument) naming
  /// the parameter at fault: Δt not positive and finite; β < 0; e ∉ [0, 1]; CN-switch's θ ∉ [½, 1];
  /// a parameter the scheme does not take (scheme_registry) with another value than its default; the
  /// algebraic Paoli–Schatzman row with a contact node that has inertia; the literal Paoli–Schatzman
  /// row with a massless contact node and β = 0 (singular) or 0 < β < ¼ (u₀ − u₁ grows geometrically in
  /// free flight); EC with a contact node that has inertia (it needs the condensed row); a problem
  /// without u⁰, with data that are not finite, or on a bar of another length than the mesh's.
  BarSimulation(const Problem& problem, const UniformMesh& mesh, const MassRedistribution& mass,
                const SchemeParameters& parameters, double dt,
                InitialContactNode initial = InitialContactNode::consistent);

  /// Advances one time level.
  void step();
  /// Defined out of line, where FastStep is complete; a simulation moves but is not copied.
  ~BarSimulation();
  BarSimulation(BarSimulation&&);             ///< moves the state and the factors
  BarSimulation& operator=(BarSimulation&&);  ///< moves the state and the factors
  /// The current level's sample (valid until the next step).
  Sample sample() const;

  Index level() const { return level_; }                              ///< the current level n
  double time() const { return static_cast<double>(level_) * dt_; }   ///< t_n = n Δt
  double dt() const { return dt_; }                                   ///< Δt
  const UniformMesh& mesh() const { return mesh_; }                   ///< the mesh
  const Tridiagonal& mass() const { return mass_; }                   ///< M (or M^mod) on the unknowns
  const Tridiagonal& stiffness() const { return stiffness_; }         ///< S on the unknowns
  bool massless_contact_node() const { return massless_; }            ///< whether row 0 of M vanishes
  const SchemeParameters& parameters() const { return parameters_; }  ///< the scheme and its parameters

 private:
  void load_at(double t, Eigen::VectorXd& f) const;
  double energy_two_level() const;
  double contact_load(double t) const;
  double contact_load_rate(double t) const;
  double massless_node_velocity(double t) const;
  void reference_step(bool has_load);
  void switch_step(bool has_load);  // CN-switch's θ-step, replacing a Crank–Nicolson step
  void finish_step();               // the bookkeeping after the state has been advanced
  friend class BatchedSimulation;   // advances many runs' states together (batched_step.hpp)

  Problem problem_;
  UniformMesh mesh_;
  SchemeParameters parameters_;
  double dt_;
  bool massless_, algebraic_row_, three_level_;
  Tridiagonal mass_, stiffness_;
  // One step is (★) with the matrices and scalars of step_ (step_matrices), A factorised in solver_.
  // B₁ and B₂ are kept for the reference step only; the fast kernel keeps its rows of B₁, B₂, M and S
  // in fast_ (null for the reference step).
  StepMatrices step_;
  ContactSolver solver_;
  std::unique_ptr<const FastStep> fast_;
  // CN-switch: the θ-step's matrices and scalars (theta_step_matrices) and its factorisation.
  struct SwitchStep {
    StepMatrices matrices;
    ContactSolver solver;
  };
  std::unique_ptr<const SwitchStep> switch_;
  // The explicit schemes' step (explicit_schemes.cpp), null for the others; it replaces (★) and both kernels.
  std::unique_ptr<const ExplicitStep> explicit_;
  bool energy_conserving_ = false;

  Index level_ = 0;
  StepState state_;
  double lambda_time_ = 0.0, energy_time_ = 0.0;
  bool has_lambda_ = true;
  std::unique_ptr<BarSimulation> start_;  // the Crank–Nicolson first step of Paoli–Schatzman
  bool explicit_start_ = false;           // Paoli–Schatzman's first step is the explicit Newmark one (pending)
  void explicit_first_step();
  // The step of a contact class (newmark, penalty, nitsche, moreau-jean: lib/classes/contact_classes.cpp),
  // which replaces (★) and its kernels; null for the schemes of this file.
  std::unique_ptr<ContactClassStep> class_step_;
  // Problem::steady_load: Fⁿ = F⁰ in state_.f_now and state_.f_next at every level, F₀ kept here.
  bool steady_load_ = false;
  double steady_contact_load_ = 0.0;
};

/// The θ of CN-switch's step for which the θ-step's energy identity proves that no step gains energy
/// (energy_step.cpp §4): Eⁿ⁺¹ − Eⁿ ≤ −(θ − ½)‖ΔV‖²_M̄ + ρ_θ(a, b), and at a release (a < 0 ≤ b, s = u₁ + hF₀
/// before and after) ρ_θ = ((1 − θ)|ab| − (θ − ½)a²)/h, positive as soon as |b|/|a| > (θ − ½)/(1 − θ).
/// A release falls anywhere inside its step, so |b|/|a| takes every value in (0, ∞): for every θ < 1
/// some release gains energy (measured: θ = 0.6 gains, θ = 0.51 blows up; issue 21), and only θ = 1
/// (backward Euler, ρ₁ ≤ 0 in every case) is proved. The programs accept this value only; the library
/// keeps θ ∈ [½, 1] for the checks of the θ-step itself.
constexpr double switch_theta_without_gain = 1.0;

/// The number of steps of size dt that reach the final time T (the last level is the first t_n ≥ T
/// up to round-off): ceil(T/dt − 1e-9).
Index steps_to_reach(double final_time, double dt);

/// Runs from the current level for `steps` steps, calling `observe` on the current sample first and
/// after every step.
void run(BarSimulation& simulation, Index steps, const std::function<void(const Sample&)>& observe);

/// How Crank–Nicolson's step is solved: for the increment ΔU = Uⁿ⁺¹ − Uⁿ (the library's step), or for
/// Uⁿ⁺¹ with the velocity recovered from the difference 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ (the form before issue 21,
/// kept only for the round-off benchmark of the time study and its doctest).
enum class StepForm { increment, for_u };
/// The benchmark's first impact time by Crank–Nicolson with `mass` (massless contact node) on N
/// elements at step dt: the zero of the contact indicator u₁ (f = 0), linear between the two levels
/// around it. Throws std::invalid_argument for a mass with inertia at the contact node and
/// std::runtime_error if no impact occurs before t = 3L.
double first_impact_time(Index elements, const MassRedistribution& mass, double dt, StepForm form);

}  // namespace mrm
