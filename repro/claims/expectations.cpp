/// @file claims/expectations.cpp
/// @brief The expectation table: the rows of the claims that do not reproduce, with the numbers that showed it.
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

#include "batched/batched_step.hpp"
#include "claims.hpp"
#include "claims/wording.hpp"
#include "configurations.hpp"
#include "exact/exact_solution.hpp"
#include "labels.hpp"
#include "fem/period_law.hpp"
#include "regions.hpp"
#include "report_values.hpp"
#include "studies/convergence.hpp"
#include "sweep.hpp"
#include "table.hpp"
#include "steps/contact.hpp"
#include "time_family.hpp"

namespace mrm::claims {

// ---------------------------------------------------------------------------------------------------
// The expectation table: the rows that do not reproduce, with the numbers that showed it.
//
// Each entry's comment quotes the numbers that show the row does not reproduce (the rows print the
// current numbers). Nothing here changes a criterion: an entry only turns a FAILED row into a "not
// reproduced" row with its reason.
const Expectations& paper_expectations() {
  // Reasons shared by several rows.
  const std::string sawtooth =
      "the literal Paoli-Schatzman contact row lets a sawtooth in u₀ grow after each release (mathematics.md §4), "
      "which dominates the H¹ and velocity errors";
  const std::string be_ranking =
      "backward Euler's dissipation smears the fronts over (Δt t)^{1/2}, far more than the drift of the impact times "
      "(mathematics.md §8); the mass changes its errors by a few percent and ranks them in 0 to 6 of 8 measures, in no "
      "systematic order";
  const std::string late_release =
      "at Δt ≥ ¾h Crank-Nicolson's own release is late (a drift of +0.1h to +0.2h per period, the same for every "
      "mass) and partly compensates Mod 2's drift of −h/3: Mod 2 and Mod 3 swap in some energy-type measures on "
      "the finer meshes, while Mod 1 stays the worst";
  const std::string cn_mod3_half =
      "Crank-Nicolson with Mod 3 at Δt = h/2 falls just outside the bands: u_t in L²(L²) at 0.16 over 1 and 4 periods, "
      "u(0,·) and u at 0.45-0.5 over 10 and 30 periods. Its impact times drift by −0.04h to −0.16h per period with a "
      "coefficient that grows with N (mechanism row), an error of the scheme that the smearing prediction leaves "
      "out; every other (mass, Δt/h) cell is in its band";
  const std::string phase_matched_orders =
      "over N = 400 ... 3200 the H¹ and λ orders with the matched mass (0.375, 0.373) lie below 2/5 by more than "
      "their fits' 95 % intervals (0.009, 0.010), and their local orders fall with refinement (0.382 to 0.369, "
      "0.382 to 0.368) instead of approaching 2/5, while with A = 0 they rise towards 1/3 (0.31 to 0.33): a part "
      "of the error that the matched mass does not remove and that converges more slowly than the smeared "
      "fronts (conjecture: the contact's own error; not derived). The u order holds";
  static const Expectations table = {
      // Claim 1. ps-literal, N = 200, Δt = h/2, T = 300: ½UⁿᵀSUⁿ/E_h(0) first above 1.01 soon after the first
      // release at t = 2, and up to about 100 E_h(0) over the run (the row prints the current numbers).
      {"1/ps-literal", sawtooth +
                           ": the strain energy of the iterate leaves the bound soon after the first release and "
                           "keeps growing, while the scheme's own β-energy, blind to the sawtooth, stays bounded"},
      // cn, mod3, N = 16 … 128, 100 periods, largest E/E(0) per Δt/h: 1 (¼), 1.01 (½), 1.02 (1), 1.16 (2),
      // 23.4 (5), 1.1e7 (10), 3.1e11 (20), 3.8e12 (40).
      {"1/cn/large-steps",
       "Crank-Nicolson with a massless contact node gains energy at every release, up to c²h v²/8 (mathematics.md "
       "§12): for Δt/h ≥ 5 the gains outweigh the losses at impacts and the energy grows by orders of magnitude"},
      // cn, Δt = h, 1000 periods (repro::StabilityGrid): mod1 4.83 (N = 16), 2.27 (32), 1.14 (64); mod2 7.48,
      // 2.59, 1.39; mod3 2.53, 1.38, 1.02.
      {"1/cn/1000-periods",
       "the same gains at releases accumulate over 1000 periods on the coarse meshes N = 16 and 32 (up to several "
       "times E_h(0)); on N = 64 and 128 they stay below 1.4 E_h(0): the jumps are O(h)"},

      // Claim 3, sweep N = 25 … 800, 30 periods. cn Δt = ¾h: 8 8 8 8 7 7 measures; Δt = h: 8 7 5 5 5 3.
      {"3/cn/dt=0.75h", late_release},
      {"3/cn/dt=1h", late_release},
      // be, 30 periods: Δt = ¼h: 6 5 5 5 3 1; ½h: 1 3 2 1 1 1; ¾h: 0 0 1 1 1 1; h: 0 0 0 1 1 1.
      {"3/be/dt=0.25h", be_ranking},
      {"3/be/dt=0.5h", be_ranking},
      {"3/be/dt=0.75h", be_ranking},
      {"3/be/dt=1h", be_ranking},
      // ps velocity, 30 periods, Δt = h: 2 2 1 1 1 0 of 2.
      {"3/ps/dt=1h",
       "Paoli-Schatzman's velocity, a difference quotient at the half step, is an energy-type "
       "measure: at Δt = h it sees the swap of Mod 2 and Mod 3 that Crank-Nicolson's late release "
       "causes (see 3/cn/dt=1h)"},

      // Claim 4 in h, sweep N = 25 … 800. cn: every (mass, Δt/h) cell in its band except mod3 at Δt = h/2:
      // u_t L²(L²) 0.16 (1 and 4 periods), u(0,·) and u 0.45–0.49 (10 and 30 periods); its drift per period
      // −0.04h, −0.05h, −0.06h, −0.09h, −0.16h, −0.09h for N = 25 … 800.
      {"4/cn/T=1p", cn_mod3_half},
      {"4/cn/T=4p", cn_mod3_half},
      {"4/cn/T=10p", cn_mod3_half},
      {"4/cn/T=30p", cn_mod3_half},
      // be, 30 periods: displacement orders 0.20–0.41, energy-type 0.16–0.28 for Δt ≥ h/2, every mass.
      {"4/be/T=30p",
       "over 30 periods backward Euler dissipates most of the energy on the coarse meshes (E_h down to "
       "a few percent of E_h(0)), so the relative errors there approach 1 and the fit over N = 25 … 800 "
       "is pre-asymptotic: displacement orders 0.2–0.4 instead of ½ for Δt ≥ h/2 (at Δt = h/4 and "
       "over 1 to 10 periods every cell is in its band)"},
      // The contact classes (claims_classes.cpp (O)): on S1, ps + consistent's TV ratio 1.025 against ec + mod3's 1.248
      // (N = 50, Δt = h/√3); cn + consistent 10.7, cn-switch 4.42, taylor-flanagan 1.66 in their worst cells.
      {"classes/oscillation/smooth-impact/ps",
       "Paoli-Schatzman (1/4, 0) with the standard mass does not oscillate more than Mod 3 on the smooth impact: its "
       "multiplier acts on the three-level average, not as an impulse on one level, so the impulse mechanism of "
       "(O) does not reach it there (conjecture); measured TV ratio 1.03 against 1.25 for EC + Mod 3"},
      // The contact classes (claims_classes.cpp (O')), the field's benchmarks: on impacting (N = 200, Δt = h/√3) ec + mod3's
      // TV ratio 3.22 against ps + consistent's 3.31; taylor-flanagan + consistent (lumped) 1.77 against 4.10
      // (impacting, N = 200, Δt = h/2) and 5.30 against 5.97 (bouncing, N = 200, Δt = h/2).
      {"classes/oscillation/impacting/ps",
       "on the impacting bar Paoli-Schatzman with the standard mass oscillates as little as Mod 3 (TV ratio 3.31 "
       "against 3.22): its multiplier acts on the three-level average, not as an impulse on one level, as on the "
       "smooth impact (conjecture)"},
      {"classes/oscillation/impacting/taylor-flanagan",
       "on the impacting bar (a stress plateau rho c v0 for 2L/c) Taylor-Flanagan with the lumped standard mass "
       "oscillates less than Mod 3 (TV ratio 1.77 against 4.10 at N = 200): its velocity correction stops the lumped "
       "node once per impact and the plateau has no re-impacts, while the redistributed lambda follows u1's "
       "dispersion behind the fronts (not derived; measured)"},
      {"classes/oscillation/bouncing/taylor-flanagan",
       "on the bouncing bar Taylor-Flanagan with the lumped standard mass oscillates about as little as Mod 3 (TV "
       "ratio 5.30 against 5.97 at N = 200): as on the impacting bar, the impulse mechanism of (O) does not make it "
       "worse there (not derived; measured)"},
      // The contact classes (claims_classes.cpp (D)): dke + consistent on S1, TV ratio 1.05–1.23 over the region against
      // Mod 3's worst pair 1.24–1.34; worst cell N = 100, Δt = h/√3: 1.096 against ec + mod3's 1.298.
      {"classes/oscillation/smooth-impact/dke",
       "on the smooth impact DKE with the standard mass oscillates less than Mod 3 (TV ratio 1.10 against 1.30 at "
       "N = 100, dt = h/sqrt(3)), where (D)'s impulse m_eff dv/dt per impact predicted it most firmly (Mod 3's ratio "
       "there is below the 2.5 at which one impulse clears the band): the impulse estimate is contradicted there "
       "(not explained)"},
      // The contact classes (claims_classes.cpp (P)): penalty (γ₀ = 1) + consistent on S1, worst cell N = 50, Δt = h/√3:
      // TV ratio 0.944 against ec + mod3's 1.248; at Δt = h/2 0.993 (N = 50) and 2.009 (N = 200).
      {"classes/oscillation/smooth-impact/penalty",
       "on the smooth impact the penalty with the standard mass oscillates less than Mod 3 on the coarse meshes (TV "
       "ratio 0.94 against 1.25 at N = 50, dt = h/sqrt(3), below the exact variation): (P)'s ringing grows with N "
       "(0.99 at N = 50, 2.01 at N = 200) but the spring also spreads the exact stress jump of the impact, which (P) "
       "did not count (not derived)"},
      // The contact classes (claims_classes.cpp (T)): two-bars, cn + mod3 on the two bodies against each class by symmetry;
      // ps 6.655 against 6.428 (N = 200, Δt = h/√3), taylor-flanagan 3.543 against 8.194 (N = 200, Δt = h/2).
      {"classes/oscillation/two-bars/ps",
       "on the two bars (by symmetry a free bar hitting a wall, the impacting bar without its gap) Paoli-Schatzman "
       "with the standard mass oscillates within the band of Mod 3 (TV ratio 6.66 against 6.43 at N = 200), as on "
       "the impacting bar: its multiplier acts on the three-level average (conjecture)"},
      {"classes/oscillation/two-bars/taylor-flanagan",
       "on the two bars Taylor-Flanagan with the lumped standard mass oscillates less than Mod 3 (TV ratio 3.54 "
       "against 8.19 at N = 200), as on the impacting bar, the same stress plateau with no re-impacts (not derived; "
       "measured)"},
      // The contact classes (claims_classes.cpp (M)): moreau-jean (θ = ½, e = 0) + consistent, worst cells: smooth-impact
      // 1.129 against ec + mod3's 1.342 (N = 200, Δt = h/√3); impacting 3.327 against ec + mod3's 3.22 (N = 200,
      // Δt = h/√3); two-bars 6.655 against cn + mod3's 6.428 (N = 200, Δt = h/√3). Where it holds: paper (margin
      // 28 %), layered (30 %), bouncing (11 %).
      {"classes/oscillation/smooth-impact/moreau-jean",
       "on the smooth impact Moreau-Jean (1/2, 0) with the standard mass oscillates less than Mod 3 (TV ratio 1.13 "
       "against 1.34 at N = 200, dt = h/sqrt(3)), where (M)'s impulse m_eff v/dt per impact (0.71 v to 0.76 v, "
       "above the band) predicted the opposite: the impulse estimate is contradicted there (conjecture, after the "
       "numbers: the one-step impulse is no larger than the exact stress jump of the impact, so it need not add "
       "variation; not checked)"},
      {"classes/oscillation/impacting/moreau-jean",
       "on the impacting bar Moreau-Jean (1/2, 0) with the standard mass oscillates within the band of Mod 3 (TV "
       "ratio 3.33 against 3.22 at N = 200, dt = h/sqrt(3)), as Paoli-Schatzman does there (3.31): (M)'s impulse "
       "per impact does not show above the band (not explained)"},
      {"classes/oscillation/two-bars/moreau-jean",
       "on the two bars (by symmetry the impacting bar without its gap) Moreau-Jean (1/2, 0) with the standard mass "
       "oscillates within the band of Mod 3 (TV ratio 6.66 against 6.43 at N = 200, dt = h/sqrt(3)), the same "
       "number as Paoli-Schatzman's: (M)'s impulse does not show above the band (not explained)"},
      // The phase-matched mass (claims_phase.cpp (O)), CN + Mod 3, A = 1/4, Δt = h/2, T = 30, N = 400 … 3200: H¹ order
      // 0.375 ± 0.009 (95 %), local orders 0.382, 0.374, 0.369; λ 0.373 ± 0.010, local 0.382, 0.369, 0.368; u holds
      // (0.784 ± 0.023, local 0.801, 0.783, 0.768). With A = 0 on the same meshes (bar1d) the local orders are
      // 0.656, 0.639, 0.663 (u), 0.305, 0.308, 0.318 (H¹), 0.318, 0.319, 0.327 (λ).
      {"7/phase-matched/order-H1", phase_matched_orders},
      {"7/phase-matched/order-lambda", phase_matched_orders},
  };
  return table;
}

}  // namespace mrm::claims
