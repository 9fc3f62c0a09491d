/// @file configurations/stress.hpp
/// @brief The histories of one run that the contact stresses are computed from, and what a study reports of a stress.
#pragma once

#include "configurations/configuration.hpp"

namespace mrm::repro {

/// The histories of one run that every contact stress of lib/measures/contact_stress.hpp is computed from, at the
/// unit scale of the run (unit_configuration: a ratio or a relative error does not depend on it): the
/// multiplier λ_h at its instants, the recovered strain at the levels (k = recovered_elements(W(t), h)),
/// the exact λ at the multiplier's instants, h, the spacing Δt, the smearing order of the run's interior
/// step (interior_phase_order of the scheme, Δt/h and the blend: each scheme's own symbol, derived in
/// contact_stress.cpp §1b).
struct StressHistory {
  std::vector<double> time, multiplier, recovered_time, recovered, exact, exact_at_levels;
  double h = 0, spacing = 0;
  PhaseOrder order{2, 1.0 / 48};
  /// The windows' width in units of the smearing width W(h, t): 8 is the width of the registry's box,
  /// window and gated stresses (contact_stress.cpp §2); fig_stress also measures 4 and 16.
  double width_factor = 8;
  /// The stress's values: the multiplier, its box or spline window average of width width_factor ·
  /// W(h, t), the gate between the multiplier and that window (contact_stress.cpp §6), or the recovered
  /// strain projected onto λ ≤ 0 (contact_stress.cpp §2–§4).
  std::vector<double> values(ContactStress stress) const;
  /// The instants of values(stress) and the exact λ there.
  const std::vector<double>& instants(ContactStress stress) const;
  const std::vector<double>& exact_values(ContactStress stress) const;
};
/// What fig_stress and bar1d report of a stress: TV(stress)/TV(λ_exact) over the same instants, the
/// relative L²(0,T) error (trapezoidal, as ErrorAccumulator's λ error), and the largest error away from
/// the exact status changes, relative to max|λ_exact|: over the instants at a distance of at least
/// ε = ¼ of the shortest exact contact window from every start and end of one (a distance fixed in the
/// problem's units, so that it measures pointwise convergence; 0 when no instant qualifies). The exact
/// contact windows are read off the exact λ at the instants: the maximal runs where λ < 0.
struct StressMeasures {
  double tv_ratio = 0, l2_error = 0, max_error_away = 0;
};
StressMeasures stress_measures(const StressHistory& history, ContactStress stress);

}  // namespace mrm::repro
