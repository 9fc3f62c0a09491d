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
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "steps/contact.hpp"
#include "steps/step.hpp"
#include "time/scheme_registry.hpp"

namespace mrm {

class FastStep;
class ContactClassStep;
class ExplicitStep;
class OneStepFormStep;

/// One run of one scheme on one mesh with one mass: the state, the initial level, and the step its
/// registry entry builds (SchemeInfo::make_step: the paper's form (★), central differences or a contact
/// class). Memory is O(N): no history is kept. The formulas hold for any L,
/// but the numbers are sized for the dimensionless problem, L = 1 and data of order one (the energy's
/// quadratic forms are taken as they are): the harness maps any length and amplitude to it by the
/// scaling law (mathematics.md §1, repro/configurations/scaling.cpp).
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
  /// The same with the mass the run assembled once on `mesh` (assemble_mass): M^mod is not formed again.
  BarSimulation(const Problem& problem, const UniformMesh& mesh, const AssembledMass& mass,
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

  /// The state and the pieces of the step of this run, for a step taken outside BarSimulation::step (the
  /// batched step, batched_step.hpp, which advances the state in vector lanes and then calls
  /// finish_step): pointers into this simulation, valid while it is neither moved nor destroyed.
  struct StepParts {
    StepState* state;                   ///< the current level's state, advanced by the step
    const ContactSolver* solver;        ///< A of the step (★), factorised (null for the other families)
    const FastStep* fast;               ///< the fast kernel (null for the reference step and the other families)
    ContactClassStep* class_step;       ///< a contact class's step (null for the other schemes)
    const ExplicitStep* explicit_step;  ///< an explicit class's step (null for the other schemes)
    bool has_load;                      ///< whether the problem has a load
    bool steady_load;                   ///< whether that load is steady: Fⁿ = F⁰ at every level (Problem)
    bool three_level;                   ///< Paoli–Schatzman's three levels (W' = Uⁿ − Uⁿ⁻¹)
    bool algebraic_row;                 ///< whether row 0 is algebraic (a massless contact node)
    bool starting;                      ///< whether Paoli–Schatzman's Crank–Nicolson first step is pending
  };
  /// This run's StepParts.
  StepParts step_parts();
  /// CN-switch's θ-step from the current state, replacing a Crank–Nicolson step at a change of the contact
  /// status (`has_load`: the problem has a load and Fⁿ⁺¹ has been filled in); finish_step follows.
  void switch_step(bool has_load);
  /// The bookkeeping after the state has been advanced by one step: the massless node's velocity, the
  /// instants of λ and of the energy, the level.
  void finish_step();

 private:
  void load_at(double t, Eigen::VectorXd& f) const;
  double energy_two_level() const;
  double contact_load(double t) const;
  double contact_load_rate(double t) const;
  double massless_node_velocity(double t) const;

  Problem problem_;
  UniformMesh mesh_;
  SchemeParameters parameters_;
  double dt_;
  bool massless_, algebraic_row_, three_level_;
  Tridiagonal mass_, stiffness_;
  // The step, built by the scheme's registry entry; one_step_form_ is the same step seen as (★)'s (for
  // CN-switch's θ-step and the batched step's parts), class_step_ and explicit_step_ as a contact class's
  // and an explicit class's (the batched step's parts), each null for the other families: cast once here,
  // not at each step.
  std::unique_ptr<Step> step_;
  OneStepFormStep* one_step_form_ = nullptr;
  ContactClassStep* class_step_ = nullptr;
  const ExplicitStep* explicit_step_ = nullptr;

  Index level_ = 0;
  StepState state_;
  double lambda_time_ = 0.0, energy_time_ = 0.0;
  bool has_lambda_ = true;
  std::unique_ptr<BarSimulation> start_;  // the Crank–Nicolson first step of Paoli–Schatzman
  bool explicit_start_ = false;           // Paoli–Schatzman's first step is the explicit Newmark one (pending)
  void explicit_first_step();
  // Problem::steady_load: Fⁿ = F⁰ in state_.f_now and state_.f_next at every level, F₀ kept here.
  bool steady_load_ = false;
  double steady_contact_load_ = 0.0;
};

/// The number of steps of size dt that reach the final time T (the last level is the first t_n ≥ T
/// up to round-off): ceil(T/dt − 1e-9).
Index steps_to_reach(double final_time, double dt);

/// Runs from the current level for `steps` steps, calling `observe` on the current sample first and
/// after every step.
void run(BarSimulation& simulation, Index steps, const std::function<void(const Sample&)>& observe);

/// How Crank–Nicolson's step is solved: for the increment ΔU = Uⁿ⁺¹ − Uⁿ (the library's step), or for
/// Uⁿ⁺¹ with the velocity recovered from the difference 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ (kept only for the round-off
/// benchmark of the time study and its doctest, which compare the two).
enum class StepForm { increment, for_u };
/// The benchmark's first impact time by Crank–Nicolson with `mass` (massless contact node) on N
/// elements at step dt: the zero of the contact indicator u₁ (f = 0), linear between the two levels
/// around it. Throws std::invalid_argument for a mass with inertia at the contact node and
/// std::runtime_error if no impact occurs before t = 3L.
double first_impact_time(Index elements, const MassRedistribution& mass, double dt, StepForm form);

}  // namespace mrm
