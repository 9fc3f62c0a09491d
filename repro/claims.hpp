/// @file claims.hpp
/// @brief The claims of the paper (mathematics.md §6) as executable checks with stated criteria.
///
/// Each check takes its inputs explicitly (the schemes, the masses, the meshes, the time steps) and
/// returns table rows: the claim, what was measured (with the numbers), the criterion and a verdict.
/// The criteria were fixed from the mathematics before the numbers were looked at (claims.cpp says
/// why each one is what it is). A claim that does not reproduce is not weakened until it passes: its
/// row is listed in an `Expectations` table with the reason and the numbers that motivated it, and
/// is reported as "not reproduced"; if such a row unexpectedly holds, it is a failure too, so that
/// the table is updated.
#pragma once

#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "errors.hpp"
#include "mass_redistribution.hpp"
#include "p1.hpp"
#include "schemes.hpp"

namespace mrm::claims {

/// reproduced: the criterion holds (as expected); not_reproduced: it does not, as the expectation
/// table says (an expected failure, with its reason); failed: it does not although it was expected
/// to, or it does although it was expected not to.
enum class Verdict { reproduced, not_reproduced, failed };
std::string to_string(Verdict);

/// One row of the table.
struct ClaimResult {
  std::string id;         ///< "3/cn/err_u0_L2": claim number of mathematics.md §6, then the case
  std::string claim;      ///< what the paper (or mathematics.md) claims, in one sentence
  std::string measured;   ///< what was measured, with the numbers
  std::string criterion;  ///< the criterion, stated in advance
  Verdict verdict;
  std::string reason;     ///< for not_reproduced/failed: why (the expected-failure reason, or what broke)
};

/// The rows expected NOT to reproduce, by row id, with the reason (and, in the table's source, the
/// numbers that motivated it). Every other row is expected to reproduce.
using Expectations = std::map<std::string, std::string>;

/// The expectation table of this repository (claims.cpp, with the measured numbers in comments).
const Expectations& paper_expectations();

/// The verdict of a row from whether its criterion holds and what was expected; marks the id as
/// used in `used` (if given), so that stale entries of the table can be reported.
ClaimResult judge(std::string id, std::string claim, std::string measured, std::string criterion, bool holds,
                  const Expectations& expectations, std::vector<std::string>* used = nullptr);

/// A time scheme as the paper names it: "cn", "be", "ps" (Paoli–Schatzman (¼, 0), algebraic contact
/// row) and "ps-literal" (the three-level formula on the contact row too, mathematics.md §4).
struct SchemeChoice {
  std::string label;
  SchemeParameters parameters;
};
SchemeChoice scheme_choice(const std::string& label);  ///< throws std::invalid_argument for another label
std::vector<SchemeChoice> paper_schemes();             ///< cn, be, ps, ps-literal
std::vector<MassRedistribution> paper_masses();        ///< mod1, mod2, mod3

/// A memo of benchmark runs (mathematics.md §2, L = 1, a = ½, Δt = C h) and their relative errors
/// (mathematics.md §5), shared by the checks that need the same runs.
class ErrorCache {
 public:
  ErrorNorms errors(const SchemeChoice& scheme, const MassRedistribution& mass, Index elements, double courant,
                    double final_time);

 private:
  std::map<std::string, ErrorNorms> cache_;
};

// ---- Claim 1: stability ---------------------------------------------------------------------------

struct StabilitySettings {
  Index elements = 200;
  double courant = 0.5;
  double final_time = 300;   ///< 100 periods of the benchmark
  double bound_conserving = 1.01;  ///< E_hⁿ ≤ 1.01 E_h(0) for Crank–Nicolson and Paoli–Schatzman
  double bound_dissipative = 1.0 + 1e-12;  ///< E_hⁿ ≤ (1 + 1e-12) E_h(0) for backward Euler
};
/// Every scheme × mass runs to the final time with finite values and a bounded energy.
std::vector<ClaimResult> check_stability(const std::vector<SchemeChoice>& schemes,
                                         const std::vector<MassRedistribution>& masses,
                                         const StabilitySettings& settings, const Expectations& expectations,
                                         std::vector<std::string>* used = nullptr);
/// The contrast of the method's motivation: this scheme with the consistent mass does blow up (exceeds
/// the same bound, or produces a non-finite value) within the same run.
ClaimResult check_consistent_mass_blows_up(const SchemeChoice& scheme, const StabilitySettings& settings,
                                           const Expectations& expectations, std::vector<std::string>* used = nullptr);

// ---- Claim 2: total mass --------------------------------------------------------------------------

/// `preserving` keep the total mass 1ᵀM^mod1 = L to round-off, `dropping` lose exactly 2h/3, on every
/// mesh (length, elements) given.
std::vector<ClaimResult> check_mass(const std::vector<MassRedistribution>& preserving,
                                    const std::vector<MassRedistribution>& dropping,
                                    const std::vector<UniformMesh>& meshes, const Expectations& expectations,
                                    std::vector<std::string>* used = nullptr);

// ---- Claim 3: ordering of the errors (the paper's Figure 1) ---------------------------------------

struct OrderingSettings {
  std::vector<Index> elements = {50, 100, 200};
  double courant = 0.5;
  double final_time = 3;  ///< one period: free flight, contact, release
};
/// For each scheme and each of the 8 error measures: error(ordered[k+1]) < error(ordered[k]) for all k
/// on every mesh, with `ordered` from worst to best (the paper: mod1, mod2, mod3).
std::vector<ClaimResult> check_ordering(const std::vector<SchemeChoice>& schemes,
                                        const std::vector<MassRedistribution>& ordered,
                                        const OrderingSettings& settings, ErrorCache& cache,
                                        const Expectations& expectations, std::vector<std::string>* used = nullptr);

// ---- Claim 4: convergence --------------------------------------------------------------------------

struct ConvergenceSettings {
  std::vector<Index> elements = {50, 100, 200, 400, 800};
  std::vector<double> courants = {0.5, 1.0};
  double final_time = 3;
  double minimum_order = 0.25;
};
/// For each scheme × mass × Courant number: every error measure decreases at every refinement and its
/// least-squares order in h is at least `minimum_order`.
std::vector<ClaimResult> check_convergence(const std::vector<SchemeChoice>& schemes,
                                           const std::vector<MassRedistribution>& masses,
                                           const ConvergenceSettings& settings, ErrorCache& cache,
                                           const Expectations& expectations, std::vector<std::string>* used = nullptr);

struct TimeConvergenceSettings {
  Index elements = 100;
  std::vector<double> courants = {4, 2, 1, 0.5, 0.25, 0.125};  ///< Δt/h, from the coarsest; each divides the first
  double reference_courant = 1.0 / 128;  ///< the reference: same h, this much smaller Δt
  double final_time = 3;
  double minimum_order = 0.25;
};
/// The error in time at fixed h against a reference of the same h with a much smaller Δt: it decreases
/// at every refinement of Δt with a least-squares order of at least `minimum_order`, in L∞(0,T; L²),
/// L∞(0,T; H¹) of u and L∞(0,T) of u(0,·) (at the instants of the coarsest Δt). Reports the observed
/// order and the local order of each halving.
std::vector<ClaimResult> check_time_convergence(const SchemeChoice& scheme,
                                                const std::vector<MassRedistribution>& masses,
                                                const TimeConvergenceSettings& settings,
                                                const Expectations& expectations,
                                                std::vector<std::string>* used = nullptr);

// ---- Claim 5: energy -------------------------------------------------------------------------------

struct EnergySettings {
  std::vector<Index> elements = {50, 100, 200, 400};
  double courant = 0.5;
  double final_time = 3;
  /// An energy change counts as round-off if |ΔE| ≤ round_off_factor · ε √N (L/Δt) · E_h(0) (claims.cpp).
  double round_off_factor = 16;
};
/// Conservation: |E_hⁿ⁺¹ − E_hⁿ| within round-off at every step that keeps the contact status, and
/// the sum of |E_hⁿ⁺¹ − E_hⁿ| over the steps that change it decreases at every refinement.
std::vector<ClaimResult> check_energy_conservation(const SchemeChoice& scheme,
                                                   const std::vector<MassRedistribution>& masses,
                                                   const EnergySettings& settings, const Expectations& expectations,
                                                   std::vector<std::string>* used = nullptr);
/// Dissipation: E_hⁿ⁺¹ ≤ E_hⁿ + round-off at every step, on every mesh.
std::vector<ClaimResult> check_energy_dissipation(const SchemeChoice& scheme,
                                                  const std::vector<MassRedistribution>& masses,
                                                  const EnergySettings& settings, const Expectations& expectations,
                                                  std::vector<std::string>* used = nullptr);

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
                                            const ContactStepSettings& settings, const Expectations& expectations,
                                            std::vector<std::string>* used = nullptr);

struct FineSolutionSettings {
  Index elements = 4000;
  double courant = 0.5;
  double final_time = 3;
  double bound = 0.05;  ///< every relative error of mathematics.md §5 below this
};
/// The closed-form solution against a very fine numerical solution (Crank–Nicolson, Mod 3).
/// `exact` is the solution checked (the benchmark's is ExactSolution(1, ½)).
ClaimResult check_exact_solution(const ExactSolution& exact, const FineSolutionSettings& settings,
                                 const Expectations& expectations, std::vector<std::string>* used = nullptr);

// ---- All of them ----------------------------------------------------------------------------------

/// Runs every check above with the settings of this repository, in order; adds a failed row for an
/// entry of `expectations` that no check used (a stale expectation). `progress` (may be null) gets one
/// line per check with its wall time (never part of the table).
std::vector<ClaimResult> check_all(const Expectations& expectations, std::ostream* progress = nullptr);

/// One failed row per entry of `expectations` whose id is not in `used`.
std::vector<ClaimResult> stale_expectations(const Expectations& expectations, const std::vector<std::string>& used);

// ---- Output ---------------------------------------------------------------------------------------

/// The table as plain text with word-wrapped columns (claim | measured | criterion | verdict).
void write_text_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// The table as Markdown.
void write_markdown_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// The table as a LaTeX longtable (booktabs rules, p{} columns for an A4 page); needs the packages
/// longtable, booktabs and array.
void write_latex_table(std::ostream& out, const std::vector<ClaimResult>& rows);
/// Escapes LaTeX special characters and turns the few Unicode symbols used in the table into math;
/// throws std::invalid_argument on any other non-ASCII character.
std::string latex_escape(const std::string& text);

}  // namespace mrm::claims
