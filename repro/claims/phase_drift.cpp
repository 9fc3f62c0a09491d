/// @file claims/phase_drift.cpp
/// @brief Claim 3's mechanism: the phase drift of the period law against the sweep's measured drifts.
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
// The mechanism of claim 3: the drift of the impact times (mathematics.md §8).
//
// The period law predicts the mass-dependent part of the drift per period, 2ℓ_f + ℓ_c − 3L, from the
// first eigenvalues of the reduced pencils of each mesh (lib/fem/period_law.cpp: −4h/3, −h/3, 0 + O(h²); the
// eigenvalues carry every order in h, so no next term needs estimating). A scheme adds a drift of its own
// that the law does not describe (Crank–Nicolson's release of a smeared front; Mod 3's own drift grows
// with N, −0.04h to −0.16h): the law says nothing about it, so the single masses' drifts are printed,
// not judged. What the law does predict is the differences Mod 1 − Mod 3 and Mod 2 − Mod 3, where the
// scheme's share cancels at leading order. The criterion (theory): each measured difference lies nearer
// the law's than any other value the law could be confused with; the closest alternative is "no mass
// effect", the smallest predicted difference being h/3 (Mod 2), so the tolerance is half of it, h/6 —
// the same rule as the orders' bands (half the distance between the classes). (Tolerances read off
// the data, 0.25h on each mass and 0.1h on the differences, would sit 0.223h and 0.097h from the
// measured values: the derivation fixes the tolerance instead.)
namespace {

double law_drift(const std::string& mass, Index elements) {
  return predict_period(UniformMesh(1.0, elements), mass_redistribution_by_name(mass)).period_error;
}

// The largest |(drift − drift_mod3) − (law − law_mod3)|/h over the cells of the scheme, and the largest
// |drift − law|/h (printed only).
std::pair<double, double> drift_deviations(const repro::Sweep& sweep, const std::string& scheme) {
  double worst = 0, worst_difference = 0;
  for (const std::string& mass : sweep.grid.masses)
    for (double c : sweep.grid.courants)
      for (Index n : sweep.grid.elements) {
        const double h = 1.0 / static_cast<double>(n), d = *sweep.find(scheme, mass, c, n).drift_per_period,
                     d3 = *sweep.find(scheme, "mod3", c, n).drift_per_period;
        worst = std::max(worst, std::abs(d - law_drift(mass, n)) / h);
        worst_difference =
            std::max(worst_difference, std::abs((d - d3) - (law_drift(mass, n) - law_drift("mod3", n))) / h);
      }
  return {worst_difference, worst};
}

}  // namespace

std::vector<ClaimResult> check_phase_drift(const repro::Sweep& sweep, const PhaseDriftSettings& st, Judge& judge) {
  const repro::SweepGrid& g = sweep.grid;
  std::vector<std::string> per_mass;
  for (const std::string& mass : g.masses) {
    double lo = INFINITY, hi = -INFINITY;
    for (double c : g.courants)
      for (Index n : g.elements) {
        const double d = *sweep.find(st.scheme, mass, c, n).drift_per_period * static_cast<double>(n);
        lo = std::min(lo, d);
        hi = std::max(hi, d);
      }
    per_mass.push_back(mass + " " + decimals(lo, 2) + "h to " + decimals(hi, 2) + "h (law " +
                       decimals(law_drift(mass, g.elements.back()) * static_cast<double>(g.elements.back()), 2) + "h)");
  }
  const auto [worst_difference, worst] = drift_deviations(sweep, st.scheme);
  return {judge("3/mechanism/" + st.scheme,
                "Mechanism of claim 3 (period law, mathematics.md §8): with " + st.scheme +
                    ", the impact times of Mod 1 and Mod 2 drift per period against Mod 3's as 2ℓ_f + ℓ_c − 3L "
                    "predicts (−4h/3, −h/3)",
                "drift per period over every Δt/h and N: " + join(per_mass, "; ") +
                    "; largest deviation of the differences to mod3 from the law's " + decimals(worst_difference, 3) +
                    "h (of a single mass's drift, the scheme's share included, not judged: " + decimals(worst, 3) +
                    "h)",
                "in every cell Δt/h ∈ {" + list_reals(g.courants) + "}, N ∈ {" + list_elements(g.elements) + "} over " +
                    significant(g.horizons.back()) + " periods: |(drift − drift_mod3) − (law − law_mod3)| ≤ " +
                    significant(st.difference_tolerance, 3) +
                    "h. Basis (theory): half the smallest difference the law predicts (h/3, Mod 2), the distance "
                    "that tells the law from no mass effect",
                at_most("largest |difference − law's|/h", worst_difference, st.difference_tolerance))};
}

SummaryLine summarize_phase_drift(const repro::Sweep& sweep, const PhaseDriftSettings& st) {
  const repro::SweepGrid& g = sweep.grid;
  const Index n = std::find(g.elements.begin(), g.elements.end(), Index{100}) != g.elements.end() ? 100 : g.elements[0];
  const double c = std::find(g.courants.begin(), g.courants.end(), 0.5) != g.courants.end() ? 0.5 : g.courants[0];
  const double h = 1.0 / static_cast<double>(n);
  std::vector<std::string> at;
  for (const std::string& mass : g.masses)
    at.push_back(repro::mass_label(mass).plain + " " +
                 decimals(*sweep.find(st.scheme, mass, c, n).drift_per_period / h, 2) + "h (law " +
                 decimals(law_drift(mass, n) / h, 2) + "h)");
  const double worst_difference = drift_deviations(sweep, st.scheme).first;
  const bool holds = worst_difference <= st.difference_tolerance;
  SummaryLine line;
  line.key = "mechanism";
  line.claim =
      "H1 Period law, the mechanism of 3: drift −4h/3, −h/3 against Mod 3 (" + scheme_abbreviation(st.scheme) + ")";
  line.verdict = holds ? "reproduced" : "partly reproduced";
  line.holds = "every Δt/h, N of the sweep: differences within " + decimals(worst_difference, 3) + "h of the law's";
  line.fails = holds ? "nowhere in the grid" : "cells beyond " + significant(st.difference_tolerance, 3) + "h";
  line.numbers = "N = " + std::to_string(n) + ", Δt = " + significant(c) + "h, " + significant(g.horizons.back()) +
                 " periods: " + join(at, ", ");
  return line;
}

}  // namespace mrm::claims
