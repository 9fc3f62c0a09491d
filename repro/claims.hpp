/// @file claims.hpp
/// @brief The claims of the paper (mathematics.md §6) as executable checks with stated criteria.
///
/// Each check takes its inputs explicitly (the schemes, the masses, the meshes, the time steps) and
/// returns table rows: the claim, what was measured (with the numbers), the criterion with its basis
/// (derived from the theory, or from a measured uncertainty; claims/check_all.cpp says which criteria were set
/// after a run, and why), the margin of the measured value against the threshold, and a verdict. A row
/// within 10 % of its threshold is "marginal". A claim that does not reproduce is not weakened until it passes: its
/// row is listed in an `Expectations` table with the reason and the numbers that motivated it, and
/// is reported as "not reproduced"; if such a row unexpectedly holds, it is a failure too, so that
/// the table is updated.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "measures/errors.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"
#include "regions.hpp"
#include "time/schemes.hpp"

namespace mrm::claims {

/// reproduced: the criterion holds (as expected) with a margin above 10 % of its threshold; marginal: it
/// holds, as expected, but within 10 % of its threshold (a pass by a hair, which a small change of the
/// method or of the data could turn); not_reproduced: it does not, as the expectation table says (an
/// expected failure, with its reason); failed: it does not although it was expected to, or it does
/// although it was expected not to.
enum class Verdict { reproduced, marginal, not_reproduced, failed };
std::string to_string(Verdict);

/// The margin of a criterion "measured ≤ threshold" (or ≥): the fraction of the threshold's scale by which
/// the measured value clears it, (threshold − measured)/scale (or (measured − threshold)/scale); > 0 when
/// the criterion holds. The scale is |threshold| unless the criterion says otherwise (a band's half
/// width; the distance from 1 of a ratio that must stay below 1). A row whose fraction is below
/// marginal_fraction reads "marginal". Criteria made of several parts give the tightest part.
struct Margin {
  double measured = 0, threshold = 0, scale = 1;
  bool at_most = true;  ///< measured ≤ threshold (false: ≥)
  std::string what;     ///< what is compared, e.g. "worst |drift difference − law|/h"
  double fraction() const;
  std::string text() const;  ///< "what: measured against threshold, margin 42 %"
};
constexpr double marginal_fraction = 0.1;
/// measured ≤ threshold, scale |threshold| (or `scale`).
Margin at_most(std::string what, double measured, double threshold, double scale = 0);
/// measured ≥ threshold, scale |threshold| (or `scale`).
Margin at_least(std::string what, double measured, double threshold, double scale = 0);
/// The tighter of two margins (the smaller fraction).
Margin tighter(const Margin& a, const Margin& b);

/// One row of the table.
struct ClaimResult {
  std::string id;         ///< "3/cn/err_u0_L2": claim number of mathematics.md §6, then the case
  std::string claim;      ///< what the paper (or mathematics.md) claims, in one sentence
  std::string measured;   ///< what was measured, with the numbers
  std::string criterion;  ///< the criterion and its basis (theory, measured uncertainty, or a revision after a run)
  Margin margin;          ///< the measured value against the threshold
  Verdict verdict;
  std::string reason;  ///< for not_reproduced/failed: why (the expected-failure reason, or what broke)
  /// Numbers of the row that the report quotes, as (name, value): write_latex_table defines each as
  /// `\mrmdef{claims:value:<id, '/' as ':'>:<name>}{value}`.
  std::vector<std::pair<std::string, std::string>> values;
};

/// The rows expected NOT to reproduce, by row id, with the reason (and, in the table's source, the
/// numbers that motivated it). Every other row is expected to reproduce.
using Expectations = std::map<std::string, std::string>;

/// The expectation table of this repository (claims/expectations.cpp, with the measured numbers in comments).
const Expectations& paper_expectations();

/// Gives a row its verdict from whether its criterion holds and what the expectation table says, and
/// keeps the entries of the table that rows used, so that stale entries can be reported.
class Judge {
 public:
  explicit Judge(Expectations expectations = {}) : expectations_(std::move(expectations)) {}
  /// The verdict of a row whose criterion holds iff `holds` (which may add discrete parts, e.g. a count,
  /// to the margin's): reproduced, marginal (holds within marginal_fraction), or as the table says.
  ClaimResult operator()(std::string id, std::string claim, std::string measured, std::string criterion,
                         const Margin& margin, bool holds);
  /// The same, the criterion being the margin alone (holds iff its fraction ≥ 0).
  ClaimResult operator()(std::string id, std::string claim, std::string measured, std::string criterion,
                         const Margin& margin) {
    const bool holds = margin.fraction() >= 0;
    return (*this)(std::move(id), std::move(claim), std::move(measured), std::move(criterion), margin, holds);
  }
  /// One failed row per entry of the table that no row used (a renamed row, a removed check).
  std::vector<ClaimResult> stale() const;

 private:
  Expectations expectations_;
  std::vector<std::string> used_;
};

/// A time scheme as the paper names it: the registry's id (mrm::scheme_registry; Paoli–Schatzman is
/// (¼, 0) with the algebraic contact row) or "ps-literal" (the three-level formula on the contact row
/// too, mathematics.md §4).
struct SchemeChoice {
  std::string label;
  SchemeParameters parameters;
};
SchemeChoice scheme_choice(const std::string& label);  ///< throws std::invalid_argument for an unknown label
SchemeChoice scheme_choice(Scheme scheme);             ///< labelled by its id (mrm::to_string)
std::vector<SchemeChoice> paper_schemes();             ///< cn, be, ps, ps-literal
std::vector<MassRedistribution> paper_masses();        ///< mod1, mod2, mod3

/// One line of the summary that opens the claims table: a claim, its verdict word, the region where it
/// holds and where it fails, and the decisive numbers. `key` names it in the report's macros.
struct SummaryLine {
  std::string key, claim, verdict, holds, fails, numbers;
};

// ---- Claim 1: stability ---------------------------------------------------------------------------

struct StabilitySettings {
  Index elements = 200;
  double courant = 0.5;
  double final_time = 300;                 ///< 100 periods of the benchmark
  double bound_conserving = 1.01;          ///< E_hⁿ ≤ 1.01 E_h(0) for Crank–Nicolson and Paoli–Schatzman
  double bound_dissipative = 1.0 + 1e-12;  ///< E_hⁿ ≤ (1 + 1e-12) E_h(0) for backward Euler
};
/// Every scheme × mass runs to the final time with finite values and a bounded energy.
std::vector<ClaimResult> check_stability(const std::vector<SchemeChoice>& schemes,
                                         const std::vector<MassRedistribution>& masses,
                                         const StabilitySettings& settings, Judge& judge);
/// The contrast of the method's motivation: this scheme with the consistent mass does blow up (exceeds
/// the same bound, or produces a non-finite value) within the same run.
ClaimResult check_consistent_mass_blows_up(const SchemeChoice& scheme, const StabilitySettings& settings, Judge& judge);

// ---- Claim 2: total mass --------------------------------------------------------------------------

/// `preserving` keep the total mass 1ᵀM^mod1 = L to round-off, `dropping` lose exactly 2h/3, on every
/// mesh (length, elements) given.
std::vector<ClaimResult> check_mass(const std::vector<MassRedistribution>& preserving,
                                    const std::vector<MassRedistribution>& dropping,
                                    const std::vector<UniformMesh>& meshes, Judge& judge);

// ---- Claim 3: ordering of the errors (the paper's Figure 1), over regions -------------------------

/// One row per scheme of the sweep and horizon: the ranking `ordered` (worst first; the paper:
/// mod1, mod2, mod3) holds strictly in every measure the scheme is judged in (judged_measures) in
/// every (Δt/h, N) cell of that horizon. The measured text gives the count per cell.
std::vector<ClaimResult> check_ordering(const repro::Sweep& sweep, const std::vector<std::string>& ordered,
                                        Judge& judge);
/// The summary of claim 3 for one scheme: where (Δt/h, horizon, N) the ranking holds in every judged
/// measure, where it does not, and the counts that decide it.
SummaryLine summarize_ordering(const repro::Sweep& sweep, const std::string& scheme,
                               const std::vector<std::string>& ordered);

/// The mechanism of claim 3 (mathematics.md §8): the measured drift of the impact times per period of
/// Mod 1 and Mod 2 relative to Mod 3 (where the scheme's own share cancels) against the period law's, in
/// every (Δt/h, N) cell of `scheme`: within `difference_tolerance`·h (h/6, half the smallest predicted
/// difference, claims/phase_drift.cpp).
struct PhaseDriftSettings {
  std::string scheme = to_string(Scheme::crank_nicolson);
  double difference_tolerance = 1.0 / 6;
};
std::vector<ClaimResult> check_phase_drift(const repro::Sweep& sweep, const PhaseDriftSettings& settings, Judge& judge);
SummaryLine summarize_phase_drift(const repro::Sweep& sweep, const PhaseDriftSettings& settings);

/// The sensitivity of claim 3 to the reconstruction of the masses (the paper names them in words only):
/// variants of Mod 2 (the lost mass spread on the diagonal only) and of Mod 3 (spread over nodes 1–2,
/// ¾ on node 1 and ¼ on node 2), each in place of the reconstruction, in the cells given: the number of
/// measures ranked as the paper says, beside the reconstruction's, and each variant's drift per period
/// beside the period law's.
struct SensitivitySettings {
  std::string scheme = to_string(Scheme::crank_nicolson);
  double courant = 0.5;
  std::vector<Index> elements = {100, 200};
  double periods = 30;
};
std::vector<ClaimResult> check_reconstruction_sensitivity(const SensitivitySettings& settings, Judge& judge);

// ---- Claim 4: convergence --------------------------------------------------------------------------

/// One row per scheme (and the baseline) and horizon: in every (mass, Δt/h) cell the least-squares
/// order in h of every judged measure lies within the tolerance of its prediction (predicted_orders,
/// mathematics.md §9).
std::vector<ClaimResult> check_convergence(const repro::Sweep& sweep, Judge& judge);
SummaryLine summarize_convergence(const repro::Sweep& sweep);

struct TimeConvergenceSettings {
  std::vector<long> meshes = {24, 32, 40};  ///< a family of meshes (fig_time_error runs the full one)
  std::vector<double> courants = {0.0625, 0.03125, 0.015625, 0.0078125};  ///< Δt/h; each divides the first
  double reference_courant = 1.0 / 2048;  ///< the reference: same h, this much smaller Δt
  double final_time = 3;
  double predicted_order = 2;  ///< the trapezoidal rule on the semi-discrete Lipschitz ODE
  double tolerance = 0.25;
};
/// The error in time at fixed h against a reference of the same h with a much smaller Δt, in the eight
/// measures (ReferenceComparison, at the common instants): the local order of the finest halving of Δt
/// lies within the tolerance of the predicted order. Reports every local order and the least-squares
/// order over the three finest steps.
std::vector<ClaimResult> check_time_convergence(const SchemeChoice& scheme,
                                                const std::vector<MassRedistribution>& masses,
                                                const TimeConvergenceSettings& settings, Judge& judge);

// ---- Claim 5: energy -------------------------------------------------------------------------------

struct EnergySettings {
  std::vector<Index> elements = {50, 100, 200, 400};
  double courant = 0.5;
  double final_time = 3;
  /// An energy change counts as round-off if |ΔE| ≤ round_off_factor · ε √N (L/Δt) · E_h(0) (claims/energy.cpp).
  double round_off_factor = 16;
};
/// Conservation: |E_hⁿ⁺¹ − E_hⁿ| within round-off at every step that keeps the contact status, and
/// the sum of |E_hⁿ⁺¹ − E_hⁿ| over the steps that change it decreases at every refinement.
std::vector<ClaimResult> check_energy_conservation(const SchemeChoice& scheme,
                                                   const std::vector<MassRedistribution>& masses,
                                                   const EnergySettings& settings, Judge& judge);
/// Dissipation: E_hⁿ⁺¹ ≤ E_hⁿ + round-off at every step, on every mesh.
std::vector<ClaimResult> check_energy_dissipation(const SchemeChoice& scheme,
                                                  const std::vector<MassRedistribution>& masses,
                                                  const EnergySettings& settings, Judge& judge);

// ---- Claim 6: agreement with independent computations ----------------------------------------------

/// One run whose steps are compared with a general-purpose solve. `model` is the discrete problem the
/// step is rebuilt from (mathematics.md §4 formulas); it is the run's own scheme except in the test that
/// shows the check fails when the step does not solve the stated problem.
struct ContactStepCase {
  SchemeChoice run;
  SchemeChoice model;
  MassRedistribution mass;
};
std::vector<ContactStepCase> paper_contact_step_cases();  ///< every scheme × mod1..3, and the consistent mass
struct ContactStepSettings {
  Index elements = 100;
  double courant = 0.5;
  double final_time = 3;
  Index every = 25;          ///< compare at every status change and at every `every`-th step
  double tolerance = 1e-10;  ///< relative difference allowed (round-off of an O(1)-conditioned solve)
};
/// At steps of a real run, the closed-form contact step (ContactSolver inside BarSimulation) against
/// Eigen's SparseLU on the full saddle-point system (U, λ) rebuilt from the public state (Uⁿ, Vⁿ or
/// Uⁿ⁻¹, λⁿ) with the active set fixed to the one found.
std::vector<ClaimResult> check_contact_step(const std::vector<ContactStepCase>& cases,
                                            const ContactStepSettings& settings, Judge& judge);

struct FineSolutionSettings {
  Index elements = 4000;
  double courant = 0.5;
  double final_time = 3;
};
/// The closed-form solution against a very fine numerical solution (Crank–Nicolson, Mod 3): the errors
/// decay from N/4 to N at the predicted orders, less claim 4's tolerance (a wrong closed form: order 0).
/// `exact` is the solution checked (the benchmark's is ExactSolution(1, ½)).
ClaimResult check_exact_solution(const ExactSolution& exact, const FineSolutionSettings& settings, Judge& judge);

// ---- All of them ----------------------------------------------------------------------------------

/// Runs every check above with the settings of this repository, in order; adds a failed row for an
/// entry of `expectations` that no check used (a stale expectation). `progress` (may be null) gets one
/// line per check with its wall time (never part of the table).
struct ClaimsReport {
  std::vector<ClaimResult> rows;
  std::vector<SummaryLine> summary;  ///< at most 12 lines
  repro::Sweep sweep;                ///< the sweep the region checks judged
};
/// With `only` not empty, the checks of the rows whose id starts with `only` alone: a block of checks runs if
/// one of its rows' prefixes and `only` is a prefix of the other, and the report holds the rows that start
/// with `only`, no summary and no sweep unless a block needs it. Throws std::invalid_argument (before any
/// check runs) if no block's rows can start with `only`, and std::runtime_error if none does.
ClaimsReport check_all(const Expectations& expectations, std::ostream* progress = nullptr,
                       const std::string& only = "");
/// Throws std::invalid_argument, naming the rows' prefixes, if no block of check_all can give a row that
/// starts with `only` (or `only` is empty).
void require_claim_row_prefix(const std::string& only);

// ---- Output ---------------------------------------------------------------------------------------

/// The summary as plain text (one block per line: claim, verdict, holds, fails, numbers).
void write_text_summary(std::ostream& out, const std::vector<SummaryLine>& summary);
/// The terminal's summary: one line per claim with its verdict, and the counts of the rows' verdicts; at
/// most 12 lines of at most 100 columns (the regions and numbers are in write_text_summary's table).
void write_short_summary(std::ostream& out, const std::vector<SummaryLine>& summary,
                         const std::vector<ClaimResult>& rows);
/// The summary as \mrmdef lines for the report: claim:KEY:verdict, :holds, :fails, :numbers (LaTeX-escaped).
void write_latex_summary(std::ostream& out, const std::vector<SummaryLine>& summary);
/// The summary as two LaTeX longtables, each a report value: \mrmdef{claims:summary:paper} (the lines of
/// the paper's claims) and \mrmdef{claims:summary:project} (this project's; paper_claim_line), each line
/// with where it holds and where it fails and its numbers under it. The verdict of each line is not in
/// them: the report states it once, from claim:KEY:verdict (write_latex_summary).
void write_latex_summary_table(std::ostream& out, const std::vector<SummaryLine>& summary);
/// The table as plain text with word-wrapped columns (claim | measured | criterion | verdict).
void write_text_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// The table as Markdown.
void write_markdown_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// The table as two LaTeX longtables (booktabs rules, p{} columns for an A4 page), each a report value:
/// \mrmdef{claims:table:paper} (the rows of the paper's claims) and \mrmdef{claims:table:project} (this
/// project's hypotheses and checks; paper_claim_row), each in the rows' order; then each group's verdict
/// counts and the rows' values. Needs the packages longtable, booktabs and array.
void write_latex_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// Whether the row with this id checks a claim of the paper (claims 1 to 5 of mathematics.md §6, and
/// the sensitivity of claim 3 to the reconstruction of the masses) rather than one of this project's
/// own hypotheses and checks: the mechanism of claim 3 (the period law, mathematics.md §8), the
/// comparisons with independent computations (claim 6), the contact classes, the phase-matched mass and
/// the contact stress (group 7). The report prints the two kinds in two tables.
bool paper_claim_row(const std::string& id);
/// The same for a line of the summary, by its key: "mechanism" and "independent" are this project's.
bool paper_claim_line(const SummaryLine& line);
/// Escapes LaTeX's special characters and writes E_h and u_t as math; the Unicode symbols stay as they
/// are, for the report's preamble to typeset (\newunicodechar in paper/report.tex).
std::string latex_escape(const std::string& text);

}  // namespace mrm::claims
