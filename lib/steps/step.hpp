/// @file step.hpp
/// @brief One step of a time scheme as a run holds it: the state it advances (StepState), what it is
/// built from (StepContext), the step itself (Step), and a scheme's registry entry (SchemeInfo), which
/// checks a run's inputs and builds its step. The families of schemes implement Step and register their
/// entries: the paper's one-step form (one_step_form.hpp), central differences (explicit_schemes.hpp),
/// the contact classes (classes/contact_classes.hpp); time/scheme_registry.hpp gathers them.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "core/problem.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "steps/scheme_parameters.hpp"

namespace mrm {

/// The state of a run between two steps, owned by the run (BarSimulation) and advanced by its Step, which
/// reads and writes nothing else of the run.
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

/// What a scheme's checks and its step are built from: one run's mesh, mass and parameters, after the
/// run's own checks (Δt, the parameters' ranges, the problem's data). References into the run, valid
/// during the call only.
struct StepContext {
  const UniformMesh& mesh;                   ///< the mesh
  const MassRedistribution& redistribution;  ///< the mass redistribution the run was given
  const Tridiagonal& mass;                   ///< M (or M^mod) on the unknowns, assembled from it
  const Tridiagonal& stiffness;              ///< S on the unknowns
  const SchemeParameters& parameters;        ///< the scheme and its parameters
  double dt;                                 ///< Δt
  double gap;                                ///< the initial gap g₀ ≥ 0 (the obstacle at −g₀)
  bool has_load;                             ///< whether the problem has a load f
  bool massless;                             ///< whether the contact node is massless (row 0 of M vanishes)
  /// The run's mass as it was assembled once (M^mod on every node too, which a step that lumps its rows
  /// reads): a step reads it rather than assembling M^mod again.
  const AssembledMass& assembled;
};

/// One step of a scheme, built once per run by its registry entry (SchemeInfo::make_step).
class Step {
 public:
  virtual ~Step() = default;
  /// Sets what the scheme defines at the initial level, once, after the run has filled U⁰, V⁰ (in w) and,
  /// for a massless contact node, λ⁰ and the status: the contact classes' own λ⁰, status and energy.
  /// The schemes of the paper's form keep the run's.
  virtual void start(StepState& state) { (void)state; }
  /// Advances `state` from level `level` to level + 1 (Fⁿ⁺¹ already in f_next when `has_load`).
  virtual void advance(StepState& state, Index level, bool has_load) = 0;
  /// The mass the step runs with when it is not the run's assembled one (the explicit schemes' row-sum
  /// lumped mass); null otherwise.
  virtual const Tridiagonal* own_mass() const { return nullptr; }
};

/// One entry of the registry of schemes: everything the library and the programs name or decide about a
/// scheme, spelled once: its id and summary (help texts, choice lists, data headers, claims rows, as
/// MFEM's ODESolver::Types or PETSc's -ts_type list), the parameters it takes, its own checks of a run's
/// inputs and the builder of its step (as MFEM's ODESolver::Select), the family of its batched kernel,
/// and its labels in plain text, LaTeX and short form (figures and tables). Each family of schemes
/// defines its entries in its own file.
struct SchemeInfo {
  Scheme scheme;                            ///< the scheme
  std::string id;                           ///< its name on command lines and in data files ("cn")
  std::string summary;                      ///< one line for help texts and reports
  std::vector<SchemeParameter> parameters;  ///< the parameters it takes beyond Δt (the others keep their defaults)
  /// Its own checks of a run, before any work (the mass its step needs, the parameters' combinations, a
  /// step limit); throws InvalidParameter naming the parameter at fault.
  void (*validate)(const StepContext&);
  /// Builds the step of a run that passed `validate`.
  std::unique_ptr<Step> (*make_step)(const StepContext&);
  /// Its batched kernel's family: 0 the two-level steps of (★) (Crank–Nicolson and backward Euler), 1
  /// Paoli–Schatzman, 2 EC, 3 CN-switch, 4 the Newmark-type classes, 5 Moreau–Jean, 6 DKE, 7 the central
  /// differences (batched_step.hpp, batch_family).
  int batch_family;
  std::string plain;         ///< its label in plain text (figure keys, data headers)
  std::string latex;         ///< its label in LaTeX (the report's tables)
  std::string abbreviation;  ///< its short ASCII label (narrow table columns)

  /// Whether the scheme takes `parameter` (its entry lists it).
  bool takes(SchemeParameter parameter) const;
};

/// The entry of `scheme` among `entries` (a family's), or null.
const SchemeInfo* find_entry(const std::vector<SchemeInfo>& entries, Scheme scheme);

}  // namespace mrm
