/// @file impact_reference.hpp
/// @brief The exact solution of a chain with a rigid obstacle as the reference of the error measures:
/// u, u_t, u_x, the contact point's u(0, t) and λ(t), and the conserved energy (derivation in
/// impact_reference.cpp).
#pragma once

#include <vector>

#include "exact/impact_chain.hpp"
#include "exact/reference_solution.hpp"

namespace mrm {

/// The exact solution of a chain with a rigid obstacle as the reference of the error measures
/// (errors.hpp): u, u_t, u_x = σ/E, the contact point's u(0, t) and λ(t) = σ(0, t) (the stress on the
/// obstacle, the multiplier of the finite element runs, whose contact row is S₀·U = F₀ − λ with the
/// stiffness E/h), and the energy. With a load the energy ½∫(ρu_t² + E u_x²) is not constant; energy()
/// is the conserved one, ½∫(ρu_t² + E u_x²) − ∫ f u (the contact does no work: u(0, ·) is constant
/// while λ ≠ 0), taken at t = 0. Throws InvalidParameter ("configuration") for a chain without an
/// obstacle (two-bars: its contact is between two bars).
class ImpactReference : public ReferenceSolution {
 public:
  /// The solution of ImpactSolution(configuration, data, final_time).
  ImpactReference(const ImpactConfiguration& configuration, const InitialData& data, double final_time);
  double length() const override { return solution_.configuration().length(); }
  double displacement(double x, double t) const override { return solution_.displacement(x, t); }
  double strain(double x, double t) const override;
  double velocity(double x, double t) const override { return solution_.velocity(x, t); }
  /// u(0, t): −g₀ exactly inside a contact window (the Skorokhod reflection holds z = 0 there), the
  /// waves' value outside.
  double contact_displacement(double t) const override;
  double contact_multiplier(double t) const override { return solution_.contact_stress(0, t); }
  double energy() const override { return energy_; }
  void displacement_at_points(double t, const double* x, long count, double* u) const override;
  void velocity_at_points(double t, const double* x, long count, double* v) const override;
  /// The contact windows with the obstacle over [0, T].
  const std::vector<ContactInterval>& contact_windows() const { return solution_.contact_windows(0); }
  const ImpactSolution& solution() const { return solution_; }  ///< the chain's solution

 private:
  ImpactSolution solution_;
  double energy_ = 0;
};
}  // namespace mrm
