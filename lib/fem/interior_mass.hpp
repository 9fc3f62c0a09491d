/// @file interior_mass.hpp
/// @brief The blended interior mass M^A = (1 − A) M + A M_L: the discrete dispersion of
/// Crank–Nicolson with it, the phase-matched blend A = ½ − (Δt/h)², and the names of the interior masses.
#pragma once

#include <string>

#include "fem/p1.hpp"

namespace mrm {

/// The relative phase-speed error ω̃/k − 1 of a Fourier mode e^{i(kx − ω̃t)} of Crank–Nicolson (the
/// trapezoidal rule, Newmark β = ¼, γ = ½; also EC and CN-switch away from status changes) with the
/// P1 stiffness and the blended mass M^A on a uniform mesh of a homogeneous bar with unit wave speed,
/// at ξ = kh ∈ (0, π] and Courant number c = Δt/h ≥ 0 (c = 0: the semi-discrete error). Throws
/// std::invalid_argument for ξ outside (0, π], c < 0 or not finite, A outside [0, 1].
double phase_speed_error(double xi, double courant, double blend);

/// The leading term of phase_speed_error, ((1 − 2A)/24 − c²/12) ξ² (interior_mass.cpp).
double phase_speed_error_leading(double xi, double courant, double blend);

/// The blend that cancels the ξ² term: 1 − 2A = 2c², A = ½ − c² (A = ¼ at c = ½, 0 at c = 1/√2). Its
/// phase error is −(1 − c⁴)ξ⁴/480 + O(ξ⁶). A value within 1e-12 below 0 (a Δt/h of 1/√2 given to 12
/// digits or more) is returned as 0. Throws std::invalid_argument, naming what is allowed, unless
/// 0 < c ≤ 1/√2 (c > 1/√2 would need A < 0, a mass that is not a blend of the two).
double phase_matched_blend(double courant);
/// The largest Courant number for which a phase-matched blend exists, 1/√2.
double largest_phase_matched_courant();

/// The interior mass of a command line: "consistent" (A = 0), "lumped" (A = 1) or "blend:A" with A a
/// decimal or a fraction p/q in [0, 1]. Throws std::invalid_argument naming the allowed forms otherwise.
/// (The strict number grammar is the harness's: repro/mass_spec.cpp parses the text and calls
/// interior_blend_from_value.)
double interior_blend_from_value(double value);
/// The spelling of a blend: "consistent" for 0, "lumped" for 1, "blend:A" (shortest decimal) otherwise.
std::string interior_mass_name(double blend);

}  // namespace mrm
