/// @file claims_phase.hpp
/// @brief The claims rows of the phase-matched interior mass: it lowers the long-time errors of CN + Mod 3
/// on the paper's benchmark (the sign derived and judged, the size a conjecture printed beside it) at the
/// smearing argument's asymptotic orders (judged within the fit's own uncertainty); and of the contact
/// stress: a window matched to the smearing width keeps its variation bounded.
#pragma once

#include <string>
#include <vector>

#include "claims.hpp"

namespace mrm::claims {

/// The study: CN + Mod 3 at Δt/h = ½ with the phase-matched interior mass A = ¼ on the meshes
/// coarsest·2^k ≤ finest and with A = 0 on `asymptotic_from`, over `final_time` (claims_phase.cpp (R), (O)).
struct PhaseMatchedSettings {
  Index coarsest = 50;          ///< the pre-asymptotic fit: coarsest … asymptotic_from (printed, not judged)
  Index asymptotic_from = 400;  ///< the judged fit: asymptotic_from … finest; the mesh of the ratios
  Index finest = 3200;          ///< the finest mesh of the judged fit
  double final_time = 30;       ///< ten periods
  double confidence = 0.95;     ///< the fitted order's confidence interval, the tolerance of the order rows
  /// The field's one-body benchmarks with jumps, each over its natural horizon (the registry's T), on one
  /// mesh of `field_elements` (a coarse one: pre-asymptotic, see claims_phase.cpp).
  std::vector<std::string> field_benchmarks{"bouncing", "impacting"};
  Index field_elements = 200;
};

/// Rows "7/phase-matched/ratio-u", ".../ratio-H1", ".../ratio-lambda": error(A = 0)/error(A = ¼) at
/// `asymptotic_from` at least 1, the smearing argument's size printed beside it; ".../order-u",
/// ".../order-H1", ".../order-lambda": the least-squares order over asymptotic_from … finest within its
/// confidence interval of 4/5 (u) or 2/5 (H¹, λ), the fit over coarsest … asymptotic_from printed; then for
/// each field benchmark B rows "7/phase-matched/B-u", "B-H1", "B-lambda": the blend lowers that error
/// (ratio at least 1), with the smearing argument's size printed beside it. The ratio and order rows carry
/// their numbers as report values (ClaimResult::values).
std::vector<ClaimResult> check_phase_matched(const PhaseMatchedSettings& settings, Judge& judge);

/// One case of the contact stress's claims: a benchmark over a horizon, and whether its exact λ jumps
/// (where the multiplier rattles) or is smooth.
struct StressCase {
  std::string benchmark;  ///< an id of lib/exact/benchmarks.hpp
  std::string key;        ///< in the row's name
  double final_time;      ///< in the benchmark's time unit
  bool jumps;             ///< the exact λ jumps: the "bounded" row; else the "smooth" row
};

/// The study of the contact stress (lib/measures/contact_stress.cpp): CN + Mod 3 at Δt/h = ½ on each case,
/// meshes coarsest·2^k ≤ finest, the default stress (bar1d's: the gated stress, contact_stress.cpp §6)
/// against the multiplier.
struct StressSettings {
  Index coarsest = 100;
  Index finest = 800;
  double ratio = 2.0;       ///< TV(stress)/TV(λ) at most this at every mesh (a convention)
  double slope = 1.0 / 12;  ///< the growth of the ratio in N at most this (contact_stress.cpp)
  /// The paper's benchmark over ten periods, the field's bouncing and impacting over their own horizons
  /// (lambda jumps); S1 over its own T = 2 and over 30, S2 over its own T = 2 (smooth).
  std::vector<StressCase> cases{{"paper", "paper", 30, true},           {"bouncing", "bouncing", -1, true},
                                {"impacting", "impacting", -1, true},   {"smooth-impact", "s1-T2", 2, false},
                                {"smooth-impact", "s1-T30", 30, false}, {"grazing", "s2", 2, false}};
};

/// Rows "7/stress/bounded/KEY" (a case whose λ jumps): TV(stress)/TV(λ) at most `ratio` on every mesh,
/// its log-slope in N at most `slope`, its L² error no larger than the multiplier's on every mesh; rows
/// "7/stress/smooth/KEY" (a smooth case): on every mesh the gate keeps the multiplier (its indicator G at
/// most gate_threshold), or the window it picks has an L² error no larger than the multiplier's and,
/// if it picks the window on any mesh, an L² order at least the multiplier's less twice the fits'
/// combined standard error. A final time below 0 is the benchmark's own horizon (the registry's T).
std::vector<ClaimResult> check_contact_stress(const StressSettings& settings, Judge& judge);

}  // namespace mrm::claims
