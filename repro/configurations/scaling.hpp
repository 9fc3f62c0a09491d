/// @file configurations/scaling.hpp
/// @brief The scaling law of the problem: a configuration at any length and amplitude is its unit configuration scaled back.
#pragma once

#include "configurations/configuration.hpp"

namespace mrm::repro {

/// The scaling law of the problem (configurations/scaling.cpp, mathematics.md §1): with x = Lξ, t = Lτ and
/// u = σL û, the problem on (0, L) is the one on (0, 1) with the data divided by σ, and
/// u_t = σ û_τ, λ = u_x(0, ·) = σ λ̂, E = σ²L Ê. The library runs the unit problem; the harness maps a
/// configuration to it and its outputs back. σ is a power of two (configuration_scaling), so that the
/// mapping is exact in floating point whenever L is one too.
///
/// A field benchmark (lib/exact/impact_solution.hpp) has its own units: a wave speed c and a modulus E at the
/// contact end (E = ρc²). With t = (L/c)τ, u = σL û, E = E_c Ê, ρ = ρ_c ρ̂ the equation
/// ρu_tt − (E u_x)_x = f becomes (E_c σ/L)(ρ̂û_ττ − (Êû_ξ)_ξ) = f, so the unit problem has the load
/// f̂ = f L/(E_c σ), the gaps ĝ = g/(σL), the material Ê, ρ̂ (1 at the contact end), and u_t = σc û_τ,
/// u_x = σ û_ξ, the stress E u_x = E_c σ σ̂ (λ), the energy E_c σ²L Ê. c = E_c = 1 is the law above.
struct Scaling {
  double length = 1.0;                                            ///< L
  double amplitude = 1.0;                                         ///< σ, a power of two
  double wave_speed = 1.0;                                        ///< c, the wave speed at the contact end
  double modulus = 1.0;                                           ///< E_c, the modulus at the contact end
  double time_scale() const { return length / wave_speed; }       ///< L/c
  double time(double unit) const { return time_scale() * unit; }  ///< t = (L/c)τ
  double displacement(double unit) const { return (amplitude * length) * unit; }  ///< u = σL û
  double velocity(double unit) const { return (amplitude * wave_speed) * unit; }  ///< u_t = σc û_τ
  double strain(double unit) const { return amplitude * unit; }                   ///< u_x = σ û_ξ
  double stress(double unit) const { return (modulus * amplitude) * unit; }       ///< E u_x = E_c σ σ̂, also λ
  double energy(double unit) const { return modulus * ((amplitude * amplitude * length) * unit); }  ///< E_c σ²L Ê
  /// m = ρ_c L m̂ with ρ_c = E_c/c²: a mass (an element's ρh, an entry of M^mod) in the bar's units.
  double mass(double unit) const { return (modulus / (wave_speed * wave_speed) * length) * unit; }
  /// Whether the unit bar's mesh is the bar's own mesh (L = 1, c = E = 1 at the contact end: the
  /// amplitude alone is scaled), so that a mass assembled on one is the other's.
  bool keeps_mesh() const { return length == 1.0 && wave_speed == 1.0 && modulus == 1.0; }
  /// Nothing to scale.
  bool identity() const { return length == 1.0 && amplitude == 1.0 && wave_speed == 1.0 && modulus == 1.0; }
};
/// The scaling of a configuration: L its bar's length, σ = 2^e for the amplitude a = m 2^e, m ∈ [½, 1),
/// of its data (the paper's a; for other data the largest of |u⁰|/L and |v⁰| at the breakpoints;
/// σ = 1 for data at rest). The paper's benchmark with L = 1, a = ½ has σ = 1: nothing to scale.
Scaling configuration_scaling(const Configuration& configuration);
/// The configuration on the unit bar that run_configuration runs: its data divided by `scaling`
/// (the paper's benchmark with amplitude a/σ, other data as unit InitialData), Δt, T and the horizons
/// divided by L.
Configuration unit_configuration(const Configuration& configuration, const Scaling& scaling);

/// The reference of the unit configuration up to `horizon` (the closed form, a field benchmark's
/// ImpactReference, or the characteristic solution of its data).
std::shared_ptr<const ReferenceSolution> unit_reference(const Configuration& unit, double horizon);
/// A unit reference seen at the scale of `scaling` (itself when nothing is scaled).
std::shared_ptr<const ReferenceSolution> to_unit(std::shared_ptr<const ReferenceSolution> reference,
                                                 const Scaling& scaling);

/// The instant up to which a reference must be known for a run of `steps` steps of size dt: the last
/// level plus one step (the schemes' staggered instants stay below it).
inline double reference_horizon(Index steps, double dt) { return static_cast<double>(steps + 1) * dt; }
/// A UsageError naming `option` unless the reference of a configuration (the characteristic solution
/// of data other than the paper's, up to `horizon`) fits in the memory the process may use
/// (cli::require_memory). Its memory grows with the coefficients of the data's pieces and the
/// periods of the horizon; measured on bar1d (peak resident size, 1e5 linear samples at T = 6 and 60,
/// S1 at T = 100 and 1000): below 400 + 128 T/L bytes per coefficient. The paper's closed form needs none.
void require_reference_memory(const Configuration& configuration, double horizon, std::string_view option);

}  // namespace mrm::repro
