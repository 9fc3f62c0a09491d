/// @file claims_classes.hpp
/// @brief The verdicts of the contact classes: where mass redistribution (Mod 3 with CN, EC, CN-switch) is
/// better than, equal to or worse than each other contact class of the registry, with the mechanism and the
/// criterion derived before the numbers (claims_classes.cpp). Registered in check_all (claims.cpp).
#pragma once

#include <vector>

#include "claims.hpp"

namespace mrm::claims {

/// The region of the comparison.
struct ClassesSettings {
  std::vector<Index> meshes{50, 100, 200};
  std::vector<double> courants{0.5, 0.5773502691896257};  ///< ½ and 1/√3 (every class runs both)
  double band = 0.1;     ///< "equal" within ±10 %: the band of baseline_regions' verdicts
  Index long_mesh = 25;  ///< the long runs: the paper's benchmark, 10³ impacts
  double long_periods = 1000;
};

/// Rows "classes/oscillation/<benchmark>/<class>" on paper, smooth-impact and the field's impacting,
/// layered, bouncing and two-bars (TV(λ)/TV(λ_exact) of every redistributed pair below the class's by
/// more than the band, in every cell of the region; on two-bars cn + Mod 3 on the two bodies against each
/// class on the one-bar problem of the symmetry) and "classes/energy/<class>" (after 10³ impacts, EC + Mod 3
/// keeps E(0) to 1e-6 while the class loses or gains more than the band; dke's energy also never grows).
/// The classes: cn, ps, cn-switch, taylor-flanagan, dke and moreau-jean (θ = ½, e = 0) with the standard
/// mass, and (oscillation only) the penalty (γ₀ = 1) and Nitsche (θ = 0, γ₀ = 5) with the standard mass.
std::vector<ClaimResult> check_classes(const ClassesSettings& settings, Judge& judge);

}  // namespace mrm::claims
