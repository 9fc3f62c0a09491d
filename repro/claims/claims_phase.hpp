/// @file claims_phase.hpp
/// @brief The claims rows of the phase-matched interior mass: it lowers the long-time errors of CN + Mod 3
/// on the paper's benchmark (predictions with targets fixed before the measurement, checked with their
/// margins); and of the contact stress: a window matched to the smearing width keeps its variation bounded.
#pragma once

#include <string>
#include <vector>

#include "claims.hpp"

namespace mrm::claims {

/// The study: CN + Mod 3 at Δt/h = ½ with the interior mass A = 0 and the phase-matched A = ¼, on the
/// meshes coarsest·2^k ≤ finest, over `final_time`.
struct PhaseMatchedSettings {
  Index coarsest = 50;
  Index finest = 400;
  double final_time = 30;        ///< ten periods
  double ratio_u = 2.5;          ///< the target: the u error (L²L²) at least this much lower with A = ¼
  double ratio_h1_lambda = 1.6;  ///< the same for u in L²H¹ and λ in L²
  double order_u = 0.85;         ///< the fitted order of u at A = ¼ at least this
  double order_h1_lambda = 0.4;  ///< the same for u in L²H¹ and λ
  /// The field's one-body benchmarks with jumps, each over its natural horizon (the registry's T), on one
  /// mesh of `field_elements` (a coarse one: pre-asymptotic, see claims_phase.cpp).
  std::vector<std::string> field_benchmarks{"bouncing", "impacting"};
  Index field_elements = 200;
};

/// Rows "7/phase-matched/ratio-u", ".../ratio-H1", ".../ratio-lambda", ".../order-u", ".../order-H1",
/// ".../order-lambda": each measured value against its target with its margin; then for each
/// field benchmark B rows "7/phase-matched/B-u", "B-H1", "B-lambda": the blend lowers that error
/// (ratio at least 1), with the smearing argument's predicted ratio printed beside it.
std::vector<ClaimResult> check_phase_matched(const PhaseMatchedSettings& settings, Judge& judge);

/// The study of the contact stress (lib/measures/contact_stress.cpp): CN + Mod 3 at Δt/h = ½ on the paper's
/// benchmark over ten periods, meshes coarsest·2^k ≤ finest, the stress `stress` against the multiplier.
struct StressSettings {
  Index coarsest = 100;
  Index finest = 400;
  double final_time = 30;         ///< ten periods
  std::string stress = "window";  ///< a name of contact_stress_registry()
  double ratio = 2.0;             ///< the target: TV(stress)/TV(λ) at most this at every mesh
  double slope = 1.0 / 12;        ///< the growth of the ratio in N at most this (contact_stress.cpp)
};

/// Row "7/stress/bounded": TV(stress)/TV(λ) at most `ratio` on every mesh, its log-slope in N at most
/// `slope`, and its L² error no larger than the multiplier's on every mesh.
ClaimResult check_bounded_stress(const StressSettings& settings, Judge& judge);

}  // namespace mrm::claims
