/// @file claims/ordering.cpp
/// @brief Claim 3: the closer to the contact node the mass is put, the better (Mod 3 < Mod 2 < Mod 1).
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
// Claim 3: the ordering of the paper's Figure 1 ("la solution approchée est d'autant meilleure que la
// répartition de la masse du nœud de contact est faite sur un autre nœud proche du nœud de contact"),
// judged over regions of parameters.
//
// The paper shows curves, not numbers, and names neither the measure nor the horizon. The mechanism
// (mathematics.md §8, lib/fem/period_law.cpp) says what to expect: each redistribution shifts the period of
// the benchmark by ΔP = 2δm_loc + (3/2)δm_glob, −4h/3 (Mod 1), −h/3 (Mod 2), 0 (Mod 3), so the impact
// times drift linearly and the mass-dependent error grows with the horizon, while the
// mass-independent error (the smearing of the fronts, O((h²t)^{1/3}) for Crank–Nicolson) grows more
// slowly. Over one period on a fine mesh the two are comparable and the ranking can go either way;
// after enough periods it should hold. So the claim is judged per cell (scheme, Δt/h, N, horizon): the
// cell holds when error(Mod 3) < error(Mod 2) < error(Mod 1) strictly in every measure the scheme is
// judged in (all eight; Paoli–Schatzman's displacement-type measures and λ are Crank–Nicolson's and are
// merged into its rows, so only its velocity is its own). A row per scheme and Δt/h holds when every
// mesh ranks all its measures at the longest horizon (30 periods); its measured text gives the counts
// at every horizon, and the summary states the region (from which horizon on, for which Δt/h and N).
namespace {

std::string ordering_claim_text(const std::string& scheme, const std::vector<std::string>& ordered) {
  std::vector<std::string> best_first(ordered.rbegin(), ordered.rend());
  return "with " + scheme + ", " + join(best_first, " < ") +
         (scheme == to_string(Scheme::paoli_schatzman)
              ? " in the velocity (its displacements and λ are cn's, merged into cn's rows)"
              : "");
}

}  // namespace

std::vector<ClaimResult> check_ordering(const repro::Sweep& sweep, const std::vector<std::string>& ordered,
                                        Judge& judge) {
  const std::vector<repro::OrderingCell> cells = repro::ordering_cells(sweep, ordered);
  const repro::SweepGrid& g = sweep.grid;
  const std::size_t longest = g.horizons.size() - 1;
  std::vector<ClaimResult> rows;
  for (const std::string& scheme : g.schemes) {
    const std::vector<std::size_t> measures = repro::judged_measures(scheme);
    std::vector<std::string> measure_list;
    for (std::size_t q : measures) measure_list.push_back(measure_names[q]);
    for (double c : g.courants) {
      bool holds = true;
      // The margin: the largest ratio error(better)/error(worse) of a ranked pair at the longest horizon.
      double worst_ratio = 0;
      for (Index n : g.elements)
        for (std::size_t q : measures)
          for (std::size_t k = 0; k + 1 < ordered.size(); ++k)
            worst_ratio = std::max(worst_ratio, sweep.find(scheme, ordered[k + 1], c, n).errors[longest][q] /
                                                    sweep.find(scheme, ordered[k], c, n).errors[longest][q]);
      std::vector<std::string> per_horizon;
      for (std::size_t k = 0; k < g.horizons.size(); ++k) {
        std::vector<std::string> counts;
        for (Index n : g.elements)
          for (const repro::OrderingCell& cell : cells) {
            if (cell.scheme != scheme || cell.courant != c || cell.elements != n || cell.horizon != k) continue;
            const int count = cell.count(measures);
            counts.push_back(std::to_string(count));
            if (k == longest) holds = holds && count == static_cast<int>(measures.size());
          }
        per_horizon.push_back(significant(g.horizons[k]) + " period(s): " + join(counts, " "));
      }
      rows.push_back(
          judge("3/" + scheme + "/dt=" + significant(c) + "h",
                "Ordering (Figure 1) at Δt = " + significant(c) + "h: " + ordering_claim_text(scheme, ordered),
                "measures ranked (of " + std::to_string(measures.size()) + ") for N = " + list_elements(g.elements) +
                    ", per horizon: " + join(per_horizon, "; "),
                "strictly in each of " + join(measure_list, ", ") + " on every mesh N ∈ {" + list_elements(g.elements) +
                    "} over " + significant(g.horizons.back()) +
                    " periods of 3L, the horizon where the period law's drift has had the longest to act (the counts "
                    "at shorter horizons show from when it holds). Basis: the paper's claim, judged where the period "
                    "law (theory) says it can hold; revised after the first run, which judged one period on N = 50 "
                    "… 200 and found the ranking random there, as the law explains",
                at_most("largest error ratio better/worse over N and measures", worst_ratio, 1, 1), holds));
    }
  }
  return rows;
}

SummaryLine summarize_ordering(const repro::Sweep& sweep, const std::string& scheme,
                               const std::vector<std::string>& ordered) {
  const std::vector<repro::OrderingCell> cells = repro::ordering_cells(sweep, ordered);
  const repro::SweepGrid& g = sweep.grid;
  const std::vector<std::size_t> measures = repro::judged_measures(scheme);
  const int all = static_cast<int>(measures.size());
  const auto cell_count = [&](double c, Index n, std::size_t k) {
    for (const repro::OrderingCell& cell : cells)
      if (cell.scheme == scheme && cell.courant == c && cell.elements == n && cell.horizon == k)
        return cell.count(measures);
    throw std::logic_error("ordering summary: missing cell");
  };
  std::vector<std::string> holds, fails, per_horizon;
  int ranked_anywhere = 0, cells_total = 0;
  for (double c : g.courants) {
    // The first horizon from which every mesh is ranked at every longer horizon.
    std::size_t from = g.horizons.size();
    for (std::size_t k = g.horizons.size(); k-- > 0;) {
      bool every = true;
      for (Index n : g.elements) every = every && cell_count(c, n, k) == all;
      if (!every) break;
      from = k;
    }
    if (from < g.horizons.size()) {
      holds.push_back("Δt/h = " + significant(c) + " from " + significant(g.horizons[from]) + " period(s) on, every N");
    } else {
      std::vector<std::string> ns;
      for (Index n : g.elements)
        if (cell_count(c, n, g.horizons.size() - 1) == all) ns.push_back(std::to_string(n));
      if (!ns.empty())
        holds.push_back("Δt/h = " + significant(c) + " at " + significant(g.horizons.back()) +
                        " periods for N = " + join(ns, ", ") + " only");
    }
  }
  for (std::size_t k = 0; k < g.horizons.size(); ++k) {
    int ranked = 0, total = 0;
    for (double c : g.courants)
      for (Index n : g.elements) {
        ranked += cell_count(c, n, k) == all;
        ++total;
      }
    ranked_anywhere += ranked;
    cells_total += total;
    per_horizon.push_back(std::to_string(ranked) + "/" + std::to_string(total) + " at " + significant(g.horizons[k]) +
                          "p");
    if (ranked < total) {
      int fewest = all;
      for (double c : g.courants)
        for (Index n : g.elements) fewest = std::min(fewest, cell_count(c, n, k));
      fails.push_back("at " + significant(g.horizons[k]) + " period(s) " + std::to_string(total - ranked) + " of " +
                      std::to_string(total) + " cells are not ranked in every measure (down to " +
                      std::to_string(fewest) + " of " + std::to_string(all) + ")");
    }
  }
  SummaryLine line;
  line.key = "ordering-" + scheme;
  line.claim = "3 Ordering Mod 3 < Mod 2 < Mod 1, " + scheme_abbreviation(scheme) +
               (scheme == to_string(Scheme::paoli_schatzman) ? " (velocity; the rest is CN's)" : "");
  line.verdict = summary_verdict(ranked_anywhere, cells_total);
  line.holds = holds.empty() ? "in no (Δt/h) for every N" : join(holds, "; ");
  line.fails = fails.empty() ? "nowhere in the grid" : join(fails, "; ");
  line.numbers = "cells ranked in all " + std::to_string(all) + " measures: " + join(per_horizon, ", ") +
                 " (N = " + list_elements(g.elements) + ", Δt/h = " + list_reals(g.courants) + ")";
  return line;
}

TEST_CASE("the ordering check fails when the masses are fed in the wrong order") {
  Judge judge;
  repro::SweepGrid grid;
  grid.schemes = {to_string(Scheme::crank_nicolson)};
  grid.courants = {0.5};
  grid.elements = {20, 40};
  grid.horizons = {1, 10};
  grid.baseline = false;
  const repro::Sweep sweep = repro::run_sweep(grid, 2);
  const std::vector<ClaimResult> right = check_ordering(sweep, {"mod1", "mod2", "mod3"}, judge);
  const std::vector<ClaimResult> swapped = check_ordering(sweep, {"mod3", "mod2", "mod1"}, judge);
  REQUIRE(right.size() == 1);
  REQUIRE(swapped.size() == 1);
  // After 10 periods the drift of Mod 1 and Mod 2 dominates (N = 20, 40: 8 of 8 measures when this test
  // was written): the paper's ranking holds there and the swapped one cannot.
  CAPTURE(right[0].measured);
  CHECK(right[0].verdict == Verdict::reproduced);
  CHECK(swapped[0].verdict == Verdict::failed);
  const SummaryLine line = summarize_ordering(sweep, to_string(Scheme::crank_nicolson), {"mod1", "mod2", "mod3"});
  CHECK(line.holds.find("from") != std::string::npos);
}

}  // namespace mrm::claims
