/// @file contact_stress.hpp
/// @brief The contact stresses a run can report: the scheme's multiplier λ_h and
/// post-processings of one run that keep its oscillation bounded as the mesh is refined; their registry,
/// the smearing width they are matched to, and the measures of a stress history.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "fem/p1.hpp"
#include "time/schemes.hpp"

namespace mrm {

/// The contact stresses, named once (contact_stress_registry).
enum class ContactStress {
  multiplier,  ///< λ_h, the scheme's multiplier at its own instants
  box,         ///< λ_h averaged over a centred box window of width δ = 8W (W the smearing width)
  window,      ///< λ_h averaged with the cubic B-spline window of width δ = 8W
  recovered,   ///< the strain at x = 0 of the least-squares quadratic through the first k ≈ 4W/h elements
  gated,       ///< the window where the multiplier rattles (gated_stress), the multiplier where it does not
};
/// One entry of the registry of contact stresses.
struct ContactStressEntry {
  ContactStress stress;     ///< the stress
  const char* name;         ///< the command-line name
  const char* description;  ///< one line
};
/// The registry: every stress with its name and a one-line description, in the order above.
const std::vector<ContactStressEntry>& contact_stress_registry();
/// The stress of a name; throws std::invalid_argument naming the allowed names otherwise.
ContactStress contact_stress_by_name(const std::string& name);
/// The names joined by '|', for messages and help texts.
std::string contact_stress_names();
/// The name of a stress (its registry entry's).
const char* to_string(ContactStress stress);

/// The leading relative phase-speed error of CN with the blended mass as C ξ^μ: μ = 2 and
/// C = |(1 − 2A)/24 − c²/12| (interior_mass.cpp), or μ = 4 and C = (1 − c⁴)/480 where that vanishes
/// (the phase-matched blend, |C₂| below 1e-12).
struct PhaseOrder {
  int mu;              ///< μ, the power of ξ
  double coefficient;  ///< C > 0
};
/// The phase order of CN with the blend A at the Courant number c = Δt/h (the rule above).
PhaseOrder crank_nicolson_phase_order(double courant, double blend);
/// The smearing order of a scheme's interior step (contact_stress.cpp §1b), W = (C h^μ t)^{1/(μ+1)}:
/// CN, EC and CN-switch: crank_nicolson_phase_order; Paoli–Schatzman (β): μ = 2,
/// C = |(1 − 2A) − (12β − 1)c²|/24 (β = ¼ is CN's), or CN's μ = 4 rule where that vanishes at β = ¼;
/// backward Euler: μ = 1, C = c/2 (a damping, not a dispersion); Newmark(β, ½) of the classes as
/// Paoli–Schatzman with Newmark's β; every other scheme: CN's (not derived for it).
PhaseOrder interior_phase_order(const SchemeParameters& scheme, double courant, double blend);

/// The smearing width of a jump carried for a time t by a scheme of phase error C ξ^μ on a mesh of size
/// h (contact_stress.cpp, §1): W = (C h^μ t)^{1/(μ+1)}. Throws std::invalid_argument unless h > 0,
/// t ≥ 0, C > 0.
double smearing_width(double h, double t, const PhaseOrder& order);
/// factor · W(h, t) at each instant t ≥ 0 of `times`, with one power per instant: factor (C h^μ)^{1/(μ+1)}
/// times t^{1/(μ+1)}, the same number as factor · smearing_width(h, t) up to a few roundings. Throws
/// std::invalid_argument as smearing_width does, and for factor ≤ 0.
std::vector<double> smearing_widths(double h, std::vector<double> times, const PhaseOrder& order, double factor);

/// The window kernels: the box (transfer sinc(kδ/2), decay order p = 1) and the cubic B-spline of
/// support δ (four boxes of width δ/4: transfer sinc⁴(kδ/8), p = 4).
enum class WindowKernel { box, spline };

/// The window average of uniformly spaced samples v_n at t_n = t₀ + nτ: at every n,
/// ṽ_n = Σ_m K((t_m − t_n)/δ_n) v_m / Σ_m K((t_m − t_n)/δ_n), the samples extended by their first and last
/// values beyond the ends, with δ_n = width[n] (a width below the spacing leaves the sample as it is).
/// Summed from running moments of the kernel's polynomial pieces (contact_stress.cpp §5): O(1) per
/// sample where the widths change slowly, within 4096 ε max|v| of the direct sum.
/// Throws std::invalid_argument if the sizes differ, or a width is negative, not finite or more than
/// 2e12 spacings.
std::vector<double> window_average(const std::vector<double>& values, double spacing, const std::vector<double>& width,
                                   WindowKernel kernel);

/// The strain at x = 0 of the least-squares quadratic through (ih, u_i), i = 0..k (k ≥ 2): exact for a
/// quadratic u (a linear strain). u holds at least k + 1 values. Throws std::invalid_argument for k < 2
/// or h ≤ 0.
double recovered_strain(const double* u, Index k, double h);
/// The same with u_i at u[i·stride] (stride ≥ 1: a run's displacement in the interleaved vector lanes of
/// a batch, LaneVectors): the same operations in the same order, so the same bits as the contiguous
/// values. Throws std::invalid_argument for k < 2, h ≤ 0 or stride 0.
double recovered_strain(const double* u, std::size_t stride, Index k, double h);

/// The number of elements of the recovered stress: k = max(2, round(4W/h)), so that the spatial fit
/// spans the time window 2kh ≈ 8W of the window stress (contact_stress.cpp, §4).
Index recovered_elements(double smearing, double h);

/// The total variation Σ |v_{n+1} − v_n|.
double total_variation(const std::vector<double>& values);

/// The gate's threshold τ (contact_stress.cpp §6): the multiplier rattles when its variation exceeds τ
/// times the variation of its window average.
inline constexpr double gate_threshold = 1.5;
/// The gate's indicator G = TV(multiplier)/TV(window) (contact_stress.cpp §6): it grows like N^{1/2}
/// where the multiplier rattles and tends to a constant near 1 where it does not.
double gate_indicator(const std::vector<double>& multiplier, const std::vector<double>& window);
/// The gated stress (contact_stress.cpp §6): `window` (the multiplier's window average) if
/// gate_indicator(multiplier, window) > gate_threshold, else `multiplier`. Throws std::invalid_argument if
/// the sizes differ.
std::vector<double> gated_stress(const std::vector<double>& multiplier, std::vector<double> window);

}  // namespace mrm
