/// @file two_bodies.hpp
/// @brief Two bars in unilateral contact with each other (doc/benchmarks.md §6, two-bars): two P1 meshes coupled by
/// one contact multiplier, each contact node massless under redistribution, stepped by Crank–Nicolson
/// (derivation in two_bodies.cpp), and the exact chain solution seen from each body.
#pragma once

#include <array>
#include <memory>

#include <Eigen/Core>

#include "exact/impact_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "exact/reference_solution.hpp"

namespace mrm {

/// One of the two bodies, in its own frame: ξ ∈ (0, ℓ) from its contact end (ξ = 0) to its far end, the
/// displacement w counted positive along ξ (for the left body ξ = ℓ − x and w = −u; for the right one
/// ξ = x − ℓ_left and w = u). In this frame each body is the paper's bar with its contact node 0.
struct TwoBodyPart {
  UniformMesh mesh{1.0, 2};           ///< its mesh (material, far end), contact node 0
  MassRedistribution redistribution;  ///< its mass; the contact node must be massless
  Eigen::VectorXd displacement;       ///< w⁰ on its unknowns (the contact node's value is recomputed)
  Eigen::VectorXd velocity;           ///< ẇ⁰ on its unknowns (the contact node's likewise)
  /// `redistribution` already assembled on `mesh` (assemble_mass), which the run then reads instead of
  /// assembling M^mod again; null: assembled by the run.
  std::shared_ptr<const AssembledMass> assembled;
};

/// Crank–Nicolson for two bodies coupled by one contact multiplier λ ≤ 0 (the contact stress, the same
/// on both sides), the gap z = w₀ᴬ + w₀ᴮ + g₀ ≥ 0, λz = 0 at every level. Throws InvalidParameter
/// ("mass") unless both contact nodes are massless, ("dt") for Δt not positive and finite, ("gap") for
/// g₀ < 0 or data that violate the contact, std::invalid_argument for vectors of the wrong size.
class TwoBodySimulation {
 public:
  /// Body 0 (the left one) and body 1 in their own frames, the initial gap g₀ between them and Δt; the
  /// contact nodes' values are set from their rows (w₀ = w₁ − cₖλ⁰, λ⁰ = min(0, s⁰)/c).
  TwoBodySimulation(std::array<TwoBodyPart, 2> parts, double gap, double dt);
  /// Advances one step.
  void step();
  Index level() const { return level_; }                                   ///< n
  double time() const { return static_cast<double>(level_) * dt_; }        ///< t_n
  double dt() const { return dt_; }                                        ///< Δt
  const UniformMesh& mesh(int k) const { return body_[k].mesh; }           ///< body k's mesh
  const Eigen::VectorXd& displacement(int k) const { return body_[k].w; }  ///< Wₖⁿ (own frame)
  const Eigen::VectorXd& velocity(int k) const { return body_[k].v; }      ///< Vₖⁿ (own frame)
  double multiplier() const { return lambda_; }                            ///< λⁿ ≤ 0
  /// zⁿ = w₀ᴬ + w₀ᴮ + g₀, 0 up to round-off while the contact holds.
  double gap() const;
  /// sⁿ = w₁ᴬ + w₁ᴮ + g₀: the contact indicator (the gap the bodies would have with no force: > 0 open,
  /// ≤ 0 closed; λ = min(0, s)/c with c the sum of the two contact compliances).
  double indicator() const;
  /// The discrete energy Σₖ ½VₖᵀM̄ₖVₖ + ½WₖᵀSₖWₖ (on all nodes, the contact nodes included).
  double energy() const;
  /// The momentum in the global frame, 1ᵀM̄ᴮVᴮ − 1ᵀM̄ᴬVᴬ (the left body's frame points the other way).
  double momentum() const;

 private:
  struct Body {
    UniformMesh mesh{1.0, 2};
    Tridiagonal mass, stiffness;     // M̄ and S on the unknowns (own frame)
    Tridiagonal interior_mass;       // M̄_II: M̄ on nodes 1..
    Tridiagonal interior_stiffness;  // S̃: S on nodes 1.. with S̃₁₁ = S₁₁ + S₁₀ (u₀ eliminated)
    Eigen::VectorXd w, v;            // Wⁿ, Vⁿ on the unknowns
    Eigen::VectorXd response;        // y = A⁻¹e₁ on nodes 1..
    Eigen::VectorXd l, d;            // A = M̄_II + (Δt²/4)S̃ = L D Lᵀ (tridiagonal)
    double compliance = 0;           // c_k = h₀/E₀
  };
  Eigen::VectorXd solve(const Body& body, Eigen::VectorXd rhs) const;
  void set_contact_nodes();
  std::array<Body, 2> body_;
  double gap_, dt_, lambda_ = 0;
  Index level_ = 0;
};

/// The exact solution of a two-body chain (ImpactSolution: two segments, one contact junction, no
/// obstacle) seen from body k in its own frame, as the reference of that body's error measures: w, w_ξ
/// = u_x, ẇ, the contact node's w(0, t) (its own side of the junction) and λ(t) the junction's stress.
/// energy() is the body's energy at t = 0.
class TwoBodyReference : public ReferenceSolution {
 public:
  /// The chain's solution (shared) seen from body 0 (left) or 1 (right); std::invalid_argument otherwise.
  TwoBodyReference(std::shared_ptr<const ImpactSolution> chain, int body);
  double length() const override;
  double displacement(double xi, double t) const override;
  double strain(double xi, double t) const override;
  double velocity(double xi, double t) const override;
  double contact_displacement(double t) const override;
  double contact_multiplier(double t) const override { return chain_->contact_stress(0, t); }
  double energy() const override { return energy_; }
  void displacement_at_points(double t, const double* xi, long count, double* w) const override;
  void velocity_at_points(double t, const double* xi, long count, double* v) const override;

 private:
  double global(double xi) const;  // x of the point ξ (the right body's ξ = 0: just right of the junction)
  std::shared_ptr<const ImpactSolution> chain_;
  int body_;
  double junction_, sign_, energy_ = 0;
};

}  // namespace mrm
