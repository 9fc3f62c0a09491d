/// @file energy_step.hpp
/// @brief The scalar pieces of the energy-conserving Crank–Nicolson step (EC) and of Crank–Nicolson
/// with a θ-step at each change of contact status (CN-switch): the condensed contact energy ψ, its
/// discrete gradient, the closed-form root of the monotone scalar equation of an EC step, and the
/// energy a θ-step creates through the contact (mathematics.md §12).
///
/// Everything here is written in the variable s = u₁ + hF₀ of the condensed contact row (u₀ = max(0, s),
/// mathematics.md §3), so that ψ(s) = max(0, s)²/(2h).
#pragma once

namespace mrm {

/// ψ(s) = max(0, s)²/(2h): the part of the stiffness energy that the massless contact node removes
/// when it is free (mathematics.md §12).
double contact_energy(double s, double h);
/// ψ'(s) = max(0, s)/h, which is u₀/h.
double contact_energy_derivative(double s, double h);

/// χ(a, b) = 2h (ψ(b) − ψ(a))/(b − a), and 2hψ'(a) = 2 max(0, a) when b = a: twice h times the discrete
/// gradient of ψ (independent of h). Evaluated case by case by the sign of a and b, without a
/// division by b − a when a and b lie on the same side of 0 (then χ = max(0, a) + max(0, b), bitwise
/// Crank–Nicolson's trapezoidal value).
double contact_secant(double a, double b);
/// φ(a, b) = χ(a, b)/(2h), the discrete gradient of ψ.
double contact_discrete_gradient(double a, double b, double h);

/// The contact node's status at a level: active (u₀ = 0 held by a compressive λ < 0) when s < 0.
inline bool contact_is_active(double s) { return s < 0; }

/// The energy that a θ-step (θ ∈ [½, 1]) gains through the contact force over a step from s = a to
/// s = b, beyond its linear part: κ_θ(a, b) = (b − a)((1 − θ)ψ'(a) + θψ'(b)) − (ψ(b) − ψ(a)).
/// θ = ½ is Crank–Nicolson's trapezoidal rule: 0 without a status change, ab/(2h) at an impact,
/// −ab/(2h) at a release.
double contact_energy_defect(double a, double b, double h, double theta);
/// ρ_θ(a, b) = κ_θ(a, b) − (θ − ½)(b − a)²/h: the bound on the energy change of a θ-step beyond its
/// kinetic dissipation −(θ − ½)‖Vⁿ⁺¹ − Vⁿ‖²_M̄ (mathematics.md §12). Closed form, case by case.
double contact_energy_bound(double a, double b, double h, double theta);

/// The largest one-step increase of the computed energy, relative to E₀, that round-off explains for a
/// step whose exact discrete energy does not increase (a Crank–Nicolson step without a status change,
/// a backward-Euler step; so every step of CN-switch): 16 N ε (1 + h/Δt) on a mesh of N elements, with
/// ε the machine epsilon (derived in energy_step.cpp, §5). Throws std::invalid_argument unless N ≥ 1
/// and Δt/h > 0 is finite.
double energy_round_off_per_step(long elements, double dt_over_h);

/// The root s of the scalar equation of an energy-conserving step, s = c + μ χ(α, s), for α (the
/// previous level's s), c (where s would go without the contact force) and μ ∈ [0, 1). The root
/// exists and is unique (the left side minus the right is increasing with slope ≥ 1 − μ); it is
/// computed in closed form. Throws std::invalid_argument unless α, c are finite and 0 ≤ μ < 1.
double energy_conserving_contact_root(double alpha, double c, double mu);
/// The same equation with Crank–Nicolson's trapezoidal force, s = c + μ (max(0, α) + max(0, s)).
double crank_nicolson_contact_root(double alpha, double c, double mu);

/// The contact of one EC step, decided on row 1 of the Crank–Nicolson system after the sweep down
/// (energy_step.cpp, "In the library's step").
struct EnergyConservingContact {
  double s;              ///< sⁿ⁺¹ = u₁ⁿ⁺¹ + hF₀ⁿ⁺¹ + g₀
  double u0;             ///< the contact node's value at the new level, max(0, sⁿ⁺¹) − g₀
  double recurrence_u0;  ///< the value of u₀ the sweep up starts from: χ(sⁿ, sⁿ⁺¹) − 2g₀ − u₀ⁿ
  double multiplier;     ///< λⁿ⁺¹ = min(0, sⁿ⁺¹)/h, the condensed row's multiplier at the new level
  bool active;           ///< sⁿ⁺¹ < 0
};
/// Given z₁ (node 1's value if the contact node stayed at u₀ = 0 for the sweep up), μ = θ(Ā⁻¹)₁₁/h,
/// the contact node's current value u₀ⁿ, u₁ⁿ + hF₀ⁿ (`s_now`, without the gap), h, F₀ⁿ⁺¹ and the initial
/// gap g₀ ≥ 0 (energy_step.cpp, "With a gap": s is then u₁ + hF₀ + g₀, u₀ = max(0, s) − g₀).
EnergyConservingContact energy_conserving_contact(double z1, double mu, double u0_now, double s_now, double h,
                                                  double load0_next, double gap = 0.0);

}  // namespace mrm
