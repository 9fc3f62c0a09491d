/// @file claims/check_all.cpp
/// @brief All the claims in one run: the list of groups, the summary lines that open the table.
//
// The paper (Dabaghi, Krejčí, Petrov, Pousin, Renard, CSMA 2015) makes five claims that a reviewer can
// check on the benchmark of mathematics.md §2 (L = 1, u⁰ = (1 − x)/2, v⁰ = 0, f = 0, period 3, E = 1/8):
//
//   1. mass redistribution gives stable schemes (no blow-up);
//   2. Mod 2 and Mod 3 preserve the total mass, Mod 1 does not;
//   3. the closer to the contact node the mass is put, the better: Mod 3 < Mod 2 < Mod 1 (its Figure 1);
//   4. the method converges as h, Δt → 0, and Crank–Nicolson has an error estimate in time;
//   5. Crank–Nicolson (nearly) conserves the energy, backward Euler dissipates it;
//
// and a sixth check is ours: the numbers behind the others come from computations that agree with
// independent ones (the closed-form contact step with a general sparse solve, the closed-form solution
// with a very fine numerical one). Each claim is a file of this folder; this one runs them all.
//
// Each check turns one claim into a criterion, stated in the row it returns with its basis, and every
// row prints its margin: the measured value against the threshold, as a fraction of it (a row within
// 10 % reads "marginal", not "reproduced"). The criteria derived from the theory: the mass's round-off
// 4(N + 1)εL, the contact step's 1e-10 against a sparse LU, the energy bounds of claim 1 (1.01 E_h(0)
// for the conserving schemes, round-off for backward Euler, whose energy does not increase), the
// strain energy of the iterate bounded as well as its energy (the literal Paoli–Schatzman form hides a
// sawtooth from its own energy), claim 5's round-off allowance with the 1/Δt of the velocity recovery,
// claim 3 judged in the region where the period law says the ranking can hold (30 periods, the sweep:
// on one period of N = 50 … 200 the ranking is random), claim 4's predicted orders ± half the distance
// between the classes, the mechanism's tolerance h/6 on the differences (half the smallest difference
// the law predicts) and claim 6's predicted rates between two meshes. Some of these criteria were set
// after a run, and the check of each states its reason. A convention, not derived: "no blow-up" over
// the large-step region means E_h ≤ 2 E_h(0). The predicted orders themselves (h^⅔, h^⅓ from the
// smearing of the fronts plus the shift of the release) are a heuristic, a conjecture, and the rows
// that use them say so. Where a claim does not reproduce, the criterion is not loosened: the row is
// listed in the expectation table (paper_expectations, claims/expectations.cpp) with the measured
// numbers and the reason, and reported as "not reproduced". Such expected failures are strict: if a
// listed row holds after all, it is reported as FAILED so that somebody updates the table, and an
// entry that no check produces is reported as well.
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
#include "claims/claims_classes.hpp"
#include "claims/claims_phase.hpp"

namespace mrm::claims {

// ---------------------------------------------------------------------------------------------------
// Claim 1 over a region: Crank–Nicolson at large steps and over long runs.
//
// check_stability (claims/stability.cpp) runs 100 periods at Δt = h/2. The paper says the method gives stable schemes; the
// energy balance of Crank–Nicolson with a massless contact node (mathematics.md §12) says more: a step
// that keeps the contact status conserves E_h, an impact loses energy and a release gains some, at most
// c²h v²/8 per switch (c = Δt/h). For Δt ≲ h the gains and losses nearly cancel; for Δt ≫ h the
// gains win. So "no blow-up", E_hⁿ ≤ 2 E_h(0), is checked over a region, the grid of
// repro::StabilityGrid that fig_stability_map draws: Δt/h from ¼ to 40 on N = 16 … 128 over 100
// periods (Mod 3), every N from 4 to 40 at Δt/h ≤ 2, and 1000 periods at Δt = h (Mod 1, 2, 3). The rows are
// made in check_all below.

// ---------------------------------------------------------------------------------------------------
// All of them, and the summary that opens the table.

namespace {
// The blocks of checks below and the prefixes of their rows (the sweep serves claims 3 and 4).
const std::vector<std::string>& claim_row_prefixes() {
  static const std::vector<std::string> prefixes{
      "1/", "2/", "3/", "4/", "4t/", "5/", "6/step/", "6/exact", "classes/", "7/phase-matched/", "7/stress/"};
  return prefixes;
}
// Whether a row that starts with `prefix` can start with `only` (either is a prefix of the other).
bool overlaps(const std::string& prefix, const std::string& only) {
  const std::size_t n = std::min(prefix.size(), only.size());
  return prefix.compare(0, n, only, 0, n) == 0;
}
}  // namespace

void require_claim_row_prefix(const std::string& only) {
  bool any = false;
  for (const std::string& p : claim_row_prefixes()) any = any || overlaps(p, only);
  if (only.empty() || !any)
    throw std::invalid_argument("no claims row starts with \"" + only + "\" (allowed: a row's id or a prefix of one: " +
                                join(claim_row_prefixes(), ", ") + ", ...)");
}

ClaimsReport check_all(const Expectations& expectations, std::ostream* progress, const std::string& only) {
  ClaimsReport report;
  std::vector<ClaimResult>& rows = report.rows;
  Judge judge(expectations);
  const auto wanted = [&](std::initializer_list<const char*> prefixes) {
    if (only.empty()) return true;
    for (const char* p : prefixes)
      if (overlaps(p, only)) return true;
    return false;
  };
  if (!only.empty()) require_claim_row_prefix(only);  // before any check runs
  auto timed = [&](const char* name, std::initializer_list<const char*> prefixes, const std::function<void()>& body) {
    if (!wanted(prefixes)) return;
    const auto start = std::chrono::steady_clock::now();
    body();
    if (progress)
      *progress << "check_claims: " << name << ": "
                << decimals(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2)
                << " s\n";
  };
  auto append = [&](std::vector<ClaimResult> more) { rows.insert(rows.end(), more.begin(), more.end()); };
  const auto rows_with = [&](const std::string& prefix) {
    std::vector<const ClaimResult*> r;
    for (const ClaimResult& row : rows)
      if (row.id.compare(0, prefix.size(), prefix) == 0) r.push_back(&row);
    return r;
  };
  // A claim whose rows all hold reads "reproduced", or "marginal" if one of them holds within 10 %.
  const auto verdict_of = [&](const std::vector<const ClaimResult*>& r) {
    int holding = 0, marginal = 0;
    for (const ClaimResult* row : r) {
      holding += row->verdict == Verdict::reproduced || row->verdict == Verdict::marginal;
      marginal += row->verdict == Verdict::marginal;
    }
    const int total = static_cast<int>(r.size());
    return holding == total && marginal > 0 ? std::string("marginal") : summary_verdict(holding, total);
  };

  timed("sweep (claims 3 and 4)", {"3/", "4/"},
        [&] { report.sweep = repro::run_sweep(repro::SweepGrid(), 0, progress); });
  const repro::Sweep& sweep = report.sweep;

  SummaryLine stability_line;
  timed("1 stability", {"1/"}, [&] {
    const StabilitySettings st;
    append(check_stability(paper_schemes(), paper_masses(), st, judge));
    rows.push_back(check_consistent_mass_blows_up(scheme_choice(Scheme::crank_nicolson), st, judge));
    // Over a region the meshes are coarse (N = 16: the O(h) jumps at impacts and releases are a few
    // percent of E_h(0)), so "no blow-up" is the energy staying below twice its initial value: a
    // convention, chosen when the check was written, not a derived bound (the margins show each cell's
    // distance to it). The grid is fig_stability_map's (repro::StabilityGrid): one set of meshes.
    const repro::StabilityRegion region = repro::run_stability_region();
    const repro::StabilityGrid& grid = region.grid;
    const double blow_up = grid.threshold;
    std::vector<std::string> per_courant;
    double worst = 0;
    for (double c : grid.courants) {
      per_courant.push_back(significant(c) + ": " + magnitude(region.worst_at(c)));
      worst = std::max(worst, region.worst_at(c));
    }
    rows.push_back(judge("1/cn/large-steps", "Stability over a region: cn with mod3 for Δt/h from ¼ to 40",
                         "largest E_hⁿ/E_h(0) over N = " + list_elements(grid.meshes) + " and " +
                             significant(grid.periods) + " periods, per Δt/h: " + join(per_courant, ", "),
                         "E_hⁿ ≤ " + significant(blow_up) +
                             " E_h(0) at every step, every N and Δt/h. Basis: a convention for \"no blow-up\", "
                             "chosen when the check was written",
                         at_most("largest E_hⁿ/E_h(0) − 1", worst - 1, blow_up - 1)));
    double long_worst = 0;
    std::vector<std::string> per_mass, long_failures;
    for (const repro::StabilityCell& cell : region.long_runs) {
      long_worst = std::max(long_worst, cell.largest);
      per_mass.push_back(repro::mass_label(cell.mass).plain + ", N = " + std::to_string(cell.elements) + ": " +
                         magnitude(cell.largest));
      if (cell.largest > blow_up)
        long_failures.push_back(repro::mass_label(cell.mass).plain + ", N = " + std::to_string(cell.elements) + " (" +
                                magnitude(cell.largest) + " E(0))");
    }
    rows.push_back(judge("1/cn/1000-periods",
                         "Stability over a long run: cn at Δt = h over " + significant(grid.long_periods) + " periods",
                         "largest E_hⁿ/E_h(0): " + join(per_mass, ", "),
                         "E_hⁿ ≤ " + significant(blow_up) + " E_h(0) at every step (the same convention)",
                         at_most("largest E_hⁿ/E_h(0) − 1", long_worst - 1, blow_up - 1)));
    std::vector<std::string> scan_failures, beyond;
    for (const auto& [n, largest] : region.scan_failures())
      scan_failures.push_back("N = " + std::to_string(n) + " (" + magnitude(largest) + " E(0))");
    for (double c : grid.courants)
      if (c > region.bounded_up_to()) beyond.push_back(significant(c));
    stability_line.key = "stability";
    stability_line.claim = "1 Stability (no blow-up)";
    stability_line.verdict = verdict_of(rows_with("1/"));
    stability_line.holds = "CN, BE, PS (algebraic row), Mod 1–3, N = " + std::to_string(st.elements) +
                           ", Δt = " + significant(st.courant) +
                           "h, 100 periods; CN, Mod 3, 100 periods, E ≤ 2 E(0) for Δt/h ≤ " +
                           significant(region.bounded_up_to()) + " on N = " + list_elements(grid.meshes) +
                           " and for Δt/h ≤ " + significant(grid.scan_up_to) + " on every N from " +
                           std::to_string(region.bounded_from()) + " to " + std::to_string(grid.scan.back());
    stability_line.fails = "CN at Δt/h = " + join(beyond, ", ") + "; Δt/h ≤ " + significant(grid.scan_up_to) + " on " +
                           (scan_failures.empty() ? std::string("none") : join(scan_failures, ", ")) + "; " +
                           significant(grid.long_periods) + " periods at Δt = h: " +
                           (long_failures.empty() ? std::string("none") : join(long_failures, ", ")) +
                           "; PS with the literal row (sawtooth); CN with the consistent mass (the contrast)";
    stability_line.numbers = "largest E/E(0), CN, Mod 3, " + significant(grid.periods) +
                             " periods, per Δt/h: " + join(per_courant, ", ") + "; " + significant(grid.long_periods) +
                             " periods, Δt = h: " + join(per_mass, ", ");
  });
  timed("2 mass", {"2/"}, [&] {
    std::vector<UniformMesh> meshes;
    for (double length : {1.0, 2.5})
      for (Index n : {2, 3, 10, 50, 200, 1000, 10000}) meshes.emplace_back(length, n);
    append(check_mass({mod2(), mod3()}, {mod1()}, meshes, judge));
  });
  timed("3 ordering", {"3/"}, [&] {
    append(check_ordering(sweep, sweep.grid.masses, judge));
    append(check_phase_drift(sweep, PhaseDriftSettings(), judge));
    append(check_reconstruction_sensitivity(SensitivitySettings(), judge));
  });
  timed("4 convergence in h", {"4/"}, [&] { append(check_convergence(sweep, judge)); });
  timed("4 convergence in time", {"4t/"}, [&] {
    append(check_time_convergence(scheme_choice(Scheme::crank_nicolson), paper_masses(), TimeConvergenceSettings(),
                                  judge));
  });
  timed("5 energy", {"5/"}, [&] {
    append(check_energy_conservation(scheme_choice(Scheme::crank_nicolson), paper_masses(), EnergySettings(), judge));
    append(check_energy_dissipation(scheme_choice(Scheme::backward_euler), paper_masses(), EnergySettings(), judge));
  });
  timed("6 contact step", {"6/step/"},
        [&] { append(check_contact_step(paper_contact_step_cases(), ContactStepSettings(), judge)); });
  timed("6 exact solution", {"6/exact"},
        [&] { rows.push_back(check_exact_solution(ExactSolution(1.0, 0.5), FineSolutionSettings(), judge)); });
  timed("classes", {"classes/"}, [&] { append(check_classes(ClassesSettings(), judge)); });  // claims_classes.cpp
  timed("7 phase-matched mass", {"7/phase-matched/"},
        [&] { append(check_phase_matched(PhaseMatchedSettings(), judge)); });  // claims_phase
  timed("7 contact stress", {"7/stress/"},
        [&] { append(check_contact_stress(StressSettings(), judge)); });  // claims_phase
  if (!only.empty()) {  // the rows asked for, without the summary (which needs every row)
    std::vector<ClaimResult> kept;
    for (const ClaimResult& row : rows)
      if (row.id.compare(0, only.size(), only) == 0) kept.push_back(row);
    if (kept.empty()) throw std::runtime_error("no claims row starts with \"" + only + "\"");
    rows = std::move(kept);
    return report;
  }
  append(judge.stale());

  // The summary: one line per claim (claim 3 per scheme, with its mechanism and its sensitivity).
  const auto ids = [&](const std::vector<const ClaimResult*>& r, Verdict v) {
    std::vector<std::string> s;
    for (const ClaimResult* row : r)
      if ((row->verdict == Verdict::reproduced || row->verdict == Verdict::marginal) == (v == Verdict::reproduced))
        s.push_back(readable_row(row->id));
    return s.empty() ? std::string("none") : join(s, "; ");
  };
  std::vector<SummaryLine>& summary = report.summary;
  summary.push_back(stability_line);
  {
    const auto r = rows_with("2/");
    summary.push_back({"mass", "2 Mod 2, Mod 3 keep the total mass, Mod 1 loses 2h/3", verdict_of(r),
                       ids(r, Verdict::reproduced), ids(r, Verdict::failed), r.front()->measured});
  }
  for (const std::string& scheme : sweep.grid.schemes)
    summary.push_back(summarize_ordering(sweep, scheme, sweep.grid.masses));
  summary.push_back(summarize_phase_drift(sweep, PhaseDriftSettings()));
  {
    const auto r = rows_with("3/sensitivity/");
    std::vector<std::string> numbers;
    for (const ClaimResult* row : r) numbers.push_back(readable_segment(row->id.substr(14)) + ": " + row->measured);
    summary.push_back({"sensitivity", "3 Verdict independent of the reconstruction (Mod 2, Mod 3 variants)",
                       verdict_of(r), ids(r, Verdict::reproduced), ids(r, Verdict::failed), join(numbers, "; ")});
  }
  summary.push_back(summarize_convergence(sweep));
  {
    const auto r = rows_with("4t/");
    std::vector<std::string> numbers, meshes;  // the range of the local orders, mesh by mesh
    for (const ClaimResult* row : r) numbers.push_back(readable_segment(row->id.substr(6)) + ": " + row->measured);
    for (long n : TimeConvergenceSettings().meshes) meshes.push_back(std::to_string(n));
    summary.push_back({"time",
                       "4 Error estimate in time: CN at order 2 in Δt, every halving (N = " + join(meshes, ", ") + ")",
                       verdict_of(r), ids(r, Verdict::reproduced), ids(r, Verdict::failed), join(numbers, "; ")});
  }
  {
    const auto r = rows_with("5/");
    summary.push_back({"energy", "5 CN conserves E_h between contact events, BE dissipates", verdict_of(r),
                       ids(r, Verdict::reproduced), ids(r, Verdict::failed), r.front()->measured});
  }
  {
    const auto r = rows_with("6/");
    summary.push_back({"independent", "H2 Independent checks: contact step vs sparse LU; closed form vs fine solution",
                       verdict_of(r), ids(r, Verdict::reproduced), ids(r, Verdict::failed), r.back()->measured});
  }
  if (summary.size() > 12) throw std::logic_error("the claims summary has more than 12 lines");
  return report;
}

}  // namespace mrm::claims
