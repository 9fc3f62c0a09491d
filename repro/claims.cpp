// The claims of the paper as executable checks: mathematics.md §6.
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
// with a very fine numerical one).
//
// Each check below turns one claim into a criterion, stated in the row it returns. The criteria were
// fixed from the mathematics before any number was looked at; the paragraph above each check says
// why the criterion is what it is. Where a claim does not reproduce, the criterion is not loosened:
// the row is listed in the expectation table (paper_expectations, below) with the measured numbers
// and the reason, and reported as "not reproduced". Such expected failures are strict: if a listed
// row holds after all, it is reported as FAILED so that somebody updates the table, and an entry that
// no check produces is reported as well.
#include "claims.hpp"
#include "report_values.hpp"

#include "convergence.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <Eigen/SparseLU>
#include <doctest/doctest.h>
#include <gsl/gsl_errno.h>
#include <gsl/gsl_fit.h>

#include "configurations.hpp"
#include "options.hpp"
#include "table.hpp"
#include "exact_solution.hpp"

namespace mrm::claims {

// ---------------------------------------------------------------------------------------------------
// The expectation table: the rows that do not reproduce, with the numbers that showed it.
//
// Filled in after the checks were written and run once with an empty table (every row expected to
// hold); each entry quotes what was measured then. Nothing here changes a criterion: an entry only
// turns a FAILED row into a "not reproduced" row with its reason.
const Expectations& paper_expectations() {
  // Reasons shared by several rows.
  const std::string sawtooth =
      "the literal Paoli-Schatzman contact row lets a sawtooth in u₀ grow after each release (problem.md §4), which "
      "dominates the H¹ and velocity errors";
  const std::string be_order =
      "every error decreases at every refinement, but the H¹, velocity (and for some, λ) errors have least-squares "
      "orders at or just below the margin ¼ fixed in advance: about ¼ is what a first-order dissipative scheme gives "
      "when it smears the jumps of u_t over a width ∝ √Δt";
  const std::string velocity_order =
      "every error decreases at every refinement, but the velocity errors have least-squares orders just below the "
      "margin ¼ fixed in advance";
  const std::string mod2_beats_mod3_everywhere = "Mod 2 beats Mod 3 on every mesh";
  static const Expectations table = {
      // Claim 1. ps-literal, N = 200, Δt = h/2, T = 300: ½UⁿᵀSUⁿ/E_h(0) first above 1.01 at t = 2.36 (mod1),
      // 2.70 (mod2), 2.64 (mod3), after the first release at t = 2, and up to 66, 96, 43 over the run, while
      // the scheme's own energy stays in [0.61, 1] E_h(0).
      {"1/ps-literal", sawtooth +
                           ": the strain energy of the iterate leaves the bound soon after the first release and "
                           "keeps growing, while the scheme's own β-energy, blind to the sawtooth, stays bounded"},

      // Claim 3, errors mod3 / mod2 / mod1 at N = 50, 100, 200 (Δt = h/2, T = 3).
      // cn: u(0) L²: 0.017/0.0164/0.0216, 0.0113/0.00969/0.00959, 0.00753/0.00607/0.00446.
      {"3/cn/err_u0_L2", "Mod 3 is the worst at N = 100 and 200: the ordering reverses as h decreases"},
      // cn: λ L²: 0.19/0.2/0.228, 0.166/0.166/0.184, 0.14/0.137/0.148.
      {"3/cn/err_lambda_L2", "Mod 2 ties or beats Mod 3 at N = 100 and 200"},
      // cn: u L∞(L²): 0.0244/0.013/0.0247, 0.0162/0.00829/0.0123, 0.0108/0.00613/0.0063.
      {"3/cn/err_u_LinfL2", "Mod 2 is the best on every mesh and Mod 3 the worst at N = 100 and 200"},
      // cn: u_t L∞(L²): 0.155/0.183/0.286, 0.171/0.144/0.206, 0.135/0.122/0.137.
      {"3/cn/err_v_LinfL2", "Mod 2 beats Mod 3 at N = 100 and 200"},
      // cn: u L²(L²): 0.0163/0.0147/0.0269, 0.0108/0.00866/0.0134, 0.00719/0.00543/0.00695.
      {"3/cn/err_u_L2L2", mod2_beats_mod3_everywhere},
      // cn: u_t L²(L²): 0.145/0.163/0.206, 0.138/0.137/0.161, 0.115/0.115/0.126.
      {"3/cn/err_v_L2L2", "Mod 2 ties or beats Mod 3 at N = 100 and 200"},
      // be: u(0) L²: 0.144/0.135/0.122, 0.101/0.0959/0.0882, 0.0706/0.0681/0.0638.
      {"3/be/err_u0_L2", "reversed: Mod 1 is the best and Mod 3 the worst on every mesh"},
      // be: λ L²: 0.262/0.254/0.275, 0.219/0.214/0.227, 0.183/0.181/0.188.
      {"3/be/err_lambda_L2", mod2_beats_mod3_everywhere + " (by a few percent)"},
      // be: u L∞(L²): 0.2/0.184/0.186, 0.141/0.132/0.132, 0.099/0.0941/0.0942.
      {"3/be/err_u_LinfL2", "Mod 3 is the worst on every mesh"},
      // be: u_t L∞(L²): 0.315/0.316/0.312, 0.27/0.271/0.269, 0.23/0.231/0.23.
      {"3/be/err_v_LinfL2", "the three masses agree to 1%, in no consistent order"},
      // be: u L²(L²): 0.135/0.126/0.12, 0.0946/0.0893/0.0859, 0.0664/0.0635/0.0617.
      {"3/be/err_u_L2L2", "reversed: Mod 1 is the best and Mod 3 the worst on every mesh"},
      // be: u L²(H¹): 0.267/0.263/0.265, 0.227/0.224/0.225, 0.192/0.19/0.191.
      {"3/be/err_u_L2H1", "Mod 2 is the best and Mod 3 the worst on every mesh (within 2%)"},
      // be: u_t L²(L²): 0.256/0.252/0.256, 0.22/0.217/0.219, 0.188/0.186/0.187.
      {"3/be/err_v_L2L2", "Mod 2 is the best on every mesh (within 2%)"},
      // ps (algebraic row): its displacements are those of cn (doctest in schemes.cpp), hence the same four
      // displacement rows; its velocity (Uⁿ − Uⁿ⁻¹)/Δt differs from cn's and does follow the ordering.
      {"3/ps/err_u0_L2", "Mod 3 is the worst at N = 100 and 200: the ordering reverses as h decreases"},
      {"3/ps/err_lambda_L2", "Mod 2 ties or beats Mod 3 at N = 100 and 200"},
      {"3/ps/err_u_LinfL2", "Mod 2 is the best on every mesh and Mod 3 the worst at N = 100 and 200"},
      {"3/ps/err_u_L2L2", mod2_beats_mod3_everywhere},
      // ps-literal: u(0) L²: 0.303/0.0657/0.294, 0.182/0.161/0.264, 0.0493/0.0401/0.109; u L∞(H¹):
      // 3.15/0.704/3.03, 2.6/2.3/3.8, 1.01/0.834/2.2; u_t L∞(L²): 7.07/1.53/6.84, 5.95/5.26/8.66,
      // 2.29/1.88/5.06; λ L²: 0.185/0.195/0.224, 0.162/0.163/0.181, 0.137/0.135/0.146. Mod 2 is the best
      // on every mesh in the seven other measures.
      {"3/ps-literal/err_u0_L2", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_lambda_L2", "Mod 2 beats Mod 3 at N = 200"},
      {"3/ps-literal/err_u_LinfL2", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_u_LinfH1", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_v_LinfL2", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_u_L2L2", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_u_L2H1", mod2_beats_mod3_everywhere + "; " + sawtooth},
      {"3/ps-literal/err_v_L2L2", mod2_beats_mod3_everywhere + "; " + sawtooth},

      // Claim 4 in h (N = 50 … 800, T = 3). cn/mod1/C=1: u_t orders 0.248 (L∞(L²)) and 0.246 (L²(L²)),
      // ratios ≤ 0.87.
      {"4/cn/mod1/C=1", velocity_order},
      // cn/mod3/C=0.5: u_t L∞(L²) ratio 1.10 at one refinement (0.155 → 0.0855 overall), orders u L²(H¹)
      // 0.21, u_t L²(L²) 0.23.
      {"4/cn/mod3/C=0.5", "the L∞(L²) velocity error increases at one refinement, and the L²(H¹) and L²(L²) "
                          "velocity errors decrease with least-squares orders below the margin ¼ fixed in advance"},
      // be, all masses and C: orders 0.23–0.25 in u L∞(H¹), u L²(H¹), u_t and λ, ratios 0.84–0.87; u(0) and
      // u L²-type orders ≈ 0.5.
      {"4/be/mod1/C=0.5", be_order},
      {"4/be/mod1/C=1", be_order},
      {"4/be/mod2/C=0.5", be_order},
      {"4/be/mod2/C=1", be_order},
      {"4/be/mod3/C=0.5", be_order},
      {"4/be/mod3/C=1", be_order},
      // ps/mod1/C=1: u_t L²(L²) order 0.247, ratios ≤ 0.85.
      {"4/ps/mod1/C=1", velocity_order},
      // ps/mod3/C=0.5: orders u_t L∞(L²) 0.19, u L²(H¹) 0.21, u_t L²(L²) 0.20, ratios ≤ 0.97.
      {"4/ps/mod3/C=0.5", "every error decreases at every refinement, but the velocity errors and the L²(H¹) error "
                          "have least-squares orders below the margin ¼ fixed in advance"},
      // ps-literal: H¹ and velocity relative errors above 100% that grow with N at C = 0.5 (orders −0.1 to
      // −0.45) and jump by factors up to 18 between meshes at C = 1.
      {"4/ps-literal/mod1/C=0.5", sawtooth},
      {"4/ps-literal/mod1/C=1", sawtooth},
      {"4/ps-literal/mod2/C=0.5", sawtooth},
      {"4/ps-literal/mod2/C=1", sawtooth},
      {"4/ps-literal/mod3/C=0.5", sawtooth},
      {"4/ps-literal/mod3/C=1", sawtooth},

      // Claim 6b, N = 4000: λ 0.0564 above the bound 0.05; u L∞(H¹) 0.0495, u_t 0.049, u L²(H¹) 0.048 just
      // below it; u(0), u L∞(L²), u L²(L²) 0.001–0.0015.
      {"6/exact", "λ's error is above the bound, which assumed rates h^½ in the roughest measures; the orders "
                  "measured for claim 4 (about 1/3 for λ with cn) make an error of this size the discretisation "
                  "error at N = 4000, not a defect of the closed form, whose displacement errors are more than "
                  "an order of magnitude smaller"},
  };
  return table;
}

std::string to_string(Verdict v) {
  switch (v) {
    case Verdict::reproduced: return "reproduced";
    case Verdict::not_reproduced: return "not reproduced";
    case Verdict::failed: return "FAILED";
  }
  return "?";
}

ClaimResult judge(std::string id, std::string claim, std::string measured, std::string criterion, bool holds,
                  const Expectations& expectations, std::vector<std::string>* used) {
  const auto expected_failure = expectations.find(id);
  const bool expected_to_hold = expected_failure == expectations.end();
  if (used && !expected_to_hold) used->push_back(id);
  ClaimResult row{std::move(id), std::move(claim), std::move(measured), std::move(criterion), Verdict::reproduced, ""};
  if (holds && expected_to_hold) return row;
  if (!holds && !expected_to_hold) {
    row.verdict = Verdict::not_reproduced;
    row.reason = "expected failure: " + expected_failure->second;
  } else if (!holds) {
    row.verdict = Verdict::failed;
    row.reason = "the criterion does not hold";
  } else {
    row.verdict = Verdict::failed;
    row.reason = "unexpected pass: the criterion holds although the expectation table lists this row as not "
                 "reproduced; update the table";
  }
  return row;
}

TEST_CASE("a row's verdict follows its criterion and the expectation table, both ways") {
  const Expectations table = {{"x/listed", "it is known not to hold"}};
  std::vector<std::string> used;
  CHECK(judge("x/other", "", "", "", true, table, &used).verdict == Verdict::reproduced);
  CHECK(judge("x/other", "", "", "", false, table, &used).verdict == Verdict::failed);
  const ClaimResult expected = judge("x/listed", "", "", "", false, table, &used);
  CHECK(expected.verdict == Verdict::not_reproduced);
  CHECK(expected.reason.find("it is known not to hold") != std::string::npos);
  const ClaimResult unexpected = judge("x/listed", "", "", "", true, table, &used);
  CHECK(unexpected.verdict == Verdict::failed);
  CHECK(unexpected.reason.find("unexpected pass") != std::string::npos);
  CHECK(used == std::vector<std::string>{"x/listed", "x/listed"});
}

// ---------------------------------------------------------------------------------------------------
// Shared pieces: the schemes and masses of the paper, numbers in the table, the benchmark runs.

SchemeChoice scheme_choice(const std::string& label) {
  SchemeParameters p;
  if (label == "cn") p.scheme = Scheme::crank_nicolson;
  else if (label == "be") p.scheme = Scheme::backward_euler;
  else if (label == "ps" || label == "ps-literal") {
    p.scheme = Scheme::paoli_schatzman;
    p.beta = 0.25;
    p.restitution = 0.0;
    p.contact_row = label == "ps" ? ContactRow::algebraic : ContactRow::literal;
  } else {
    throw std::invalid_argument("unknown scheme \"" + label + "\" (allowed: cn, be, ps, ps-literal)");
  }
  return {label, p};
}

std::vector<SchemeChoice> paper_schemes() {
  return {scheme_choice("cn"), scheme_choice("be"), scheme_choice("ps"), scheme_choice("ps-literal")};
}
std::vector<MassRedistribution> paper_masses() { return {mod1(), mod2(), mod3()}; }

namespace {

// Numbers in the table: three significant digits (the table is read by people; the data files keep
// round-trip precision), deterministic.
std::string sig(double x, int digits = 3) {
  if (!std::isfinite(x)) return cli::format_real(x);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*g", digits, x);
  return buffer;
}
std::string fixed(double x, int decimals) {
  if (!std::isfinite(x)) return cli::format_real(x);
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, x);
  return buffer;
}

// The short names of the eight error measures of mathematics.md §5, in ErrorAccumulator::values order.
const char* const measure_names[8] = {"u(0,·) L²(0,T)", "λ L²(0,T)",  "u L∞(L²)", "u L∞(H¹)",
                                      "u_t L∞(L²)",     "u L²(L²)",  "u L²(H¹)", "u_t L²(L²)"};

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string s;
  for (std::size_t k = 0; k < parts.size(); ++k) s += (k ? separator : "") + parts[k];
  return s;
}

std::string list_elements(const std::vector<Index>& elements) {
  std::vector<std::string> s;
  for (Index n : elements) s.push_back(std::to_string(n));
  return join(s, ", ");
}

}  // namespace

ErrorNorms ErrorCache::errors(const SchemeChoice& scheme, const MassRedistribution& mass, Index elements,
                              double courant, double final_time) {
  const std::string key = scheme.label + "|" + to_string(scheme.parameters.scheme) + "|" +
                          cli::format_real(scheme.parameters.beta) + "|" + to_string(scheme.parameters.contact_row) +
                          "|" + mass.name + "|" + std::to_string(elements) + "|" + cli::format_real(courant) + "|" +
                          cli::format_real(final_time);
  const auto found = cache_.find(key);
  if (found != cache_.end()) return found->second;
  repro::Configuration configuration;
  configuration.scheme = scheme.parameters;
  configuration.mass = mass;
  configuration.elements = elements;
  configuration.courant = courant;
  configuration.final_time = final_time;
  return cache_[key] = repro::run_configuration(configuration).errors;
}

// ---------------------------------------------------------------------------------------------------
// The observed order: the slope of the least-squares line through (log x_k, log y_k) (mathematics.md §5),
// lib/convergence's fit (GSL, checked there by its own doctest). Data that admit no order (steps
// that were not refined, an error that vanished) give NaN, which fails every criterion on the order.
static double least_squares_order(const std::vector<double>& x, const std::vector<double>& y) {
  try {
    return fit_order(x, y).order;
  } catch (const std::invalid_argument&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

// ---------------------------------------------------------------------------------------------------
// Claim 1: stability (paper §2: the redistributed semi-discrete problem is a Lipschitz ODE, well
// posed, and the schemes do not blow up).
//
// The bound. For the two-level schemes the discrete energy E_hⁿ = ½VᵀMV + ½UᵀSU controls every
// other quantity (½UᵀSU bounds U in H¹, hence pointwise; ½VᵀM̄V bounds the velocity on the nodes with
// inertia). For Paoli–Schatzman it does not: its energy (schemes.cpp) contains U only through the
// β-average, for β = ¼ through (Uⁿ⁺¹ + Uⁿ)/2, which cannot see a sawtooth (−1)ⁿ. So "no blow-up" is
// checked as: every value finite, E_hⁿ bounded, and the strain energy of the iterate itself,
// ½UⁿᵀSUⁿ, under the same bound. (The first version of this check bounded E_hⁿ only; the strain
// energy was added, making the check stricter, when the errors of claim 3 showed the literal
// Paoli–Schatzman form with H¹ errors above 100%.) Crank–Nicolson conserves E_h exactly while the contact
// status is unchanged, and changes it by jumps of size O(h) at impacts and releases (mathematics.md §4);
// Paoli–Schatzman (¼, 0) with the algebraic row is Crank–Nicolson; its literal form conserves its own
// energy likewise. Backward Euler never increases it. Hence the bounds, fixed in advance:
// E_hⁿ ≤ 1.01 E_h(0) for CN and PS over 100 periods (the jumps at h = 1/200 are a fraction of a
// percent, and an exponential growth of even 1e-4 per period would already exceed 1% over 100
// periods), and E_hⁿ ≤ (1 + 1e-12) E_h(0) for BE (round-off only). The contrast: the consistent mass
// with exact contact and CN is known to be ill-behaved (mathematics.md §3) — the very reason for the
// method — so the same run with the consistent mass is expected to exceed the same bound.
namespace {

struct StabilityRun {
  bool finite = true;
  bool bounded = true;
  double e0 = 0, e_max = 0, e_min = 0, strain_max = 0;
  double first_violation_time = 0;
  Index steps = 0;
};

StabilityRun stability_run(const SchemeChoice& scheme, const MassRedistribution& mass, Index elements, double courant,
                           double final_time, double bound) {
  const UniformMesh mesh(1.0, elements);
  const double dt = courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, scheme.parameters, dt);
  StabilityRun r;
  const Tridiagonal& stiffness = simulation.stiffness();
  r.e0 = r.e_max = r.e_min = simulation.sample().energy;
  r.steps = steps_to_reach(final_time, dt);
  for (Index k = 0; k < r.steps; ++k) {
    simulation.step();
    const Sample s = simulation.sample();
    const bool finite = std::isfinite(s.energy) && std::isfinite(s.multiplier) && s.displacement->allFinite() &&
                        s.velocity->allFinite();
    const double strain = finite ? 0.5 * stiffness.bilinear(*s.displacement, *s.displacement) : 0.0;
    if (finite) {
      r.e_max = std::max(r.e_max, s.energy);
      r.e_min = std::min(r.e_min, s.energy);
      r.strain_max = std::max(r.strain_max, strain);
    }
    if (!finite) {
      r.finite = r.bounded = false;
      r.first_violation_time = s.time;
      return r;  // nothing more to measure
    }
    if (r.bounded && (s.energy > bound * r.e0 || strain > bound * r.e0)) {
      r.bounded = false;  // run on: the table reports how far it goes
      r.first_violation_time = s.time;
    }
  }
  return r;
}

bool is_dissipative(const SchemeChoice& scheme) { return scheme.parameters.scheme == Scheme::backward_euler; }

std::string stability_criterion(const StabilitySettings& st) {
  return "every value finite, and E_hⁿ and ½UⁿᵀSUⁿ ≤ " + sig(st.bound_conserving) +
         " E_h(0) (CN, PS: energy conserved up to O(h) jumps at status changes) or ≤ (1 + " +
         sig(st.bound_dissipative - 1) + ") E_h(0) (BE: dissipative) at every step, "
         "N = " + std::to_string(st.elements) + ", Δt = " + sig(st.courant) + "h, T = " + sig(st.final_time);
}

std::string describe(const StabilityRun& r) {
  if (!r.finite) return "non-finite value at t = " + sig(r.first_violation_time, 4);
  auto ratio = [](double x) { return x < 10 ? fixed(x, 6) : sig(x, 3); };
  std::string s = "E_hⁿ/E_h(0) in [" + ratio(r.e_min / r.e0) + ", " + ratio(r.e_max / r.e0) +
                  "], max ½UⁿᵀSUⁿ/E_h(0) = " + ratio(r.strain_max / r.e0);
  if (!r.bounded) return s + ", bound first exceeded at t = " + sig(r.first_violation_time, 4);
  return s;
}

}  // namespace

std::vector<ClaimResult> check_stability(const std::vector<SchemeChoice>& schemes,
                                         const std::vector<MassRedistribution>& masses,
                                         const StabilitySettings& settings, const Expectations& expectations,
                                         std::vector<std::string>* used) {
  std::vector<ClaimResult> rows;
  for (const SchemeChoice& scheme : schemes) {
    const double bound = is_dissipative(scheme) ? settings.bound_dissipative : settings.bound_conserving;
    bool holds = true;
    std::vector<std::string> measured;
    std::vector<std::string> names;
    for (const MassRedistribution& mass : masses) {
      const StabilityRun r =
          stability_run(scheme, mass, settings.elements, settings.courant, settings.final_time, bound);
      holds = holds && r.finite && r.bounded;
      measured.push_back(mass.name + ": " + describe(r));
      names.push_back(mass.name);
    }
    rows.push_back(judge("1/" + scheme.label, "Stability: " + scheme.label + " with " + join(names, ", ") +
                                                  " does not blow up over " + sig(settings.final_time / 3) + " periods",
                         join(measured, "; "), stability_criterion(settings), holds, expectations, used));
  }
  return rows;
}

ClaimResult check_consistent_mass_blows_up(const SchemeChoice& scheme, const StabilitySettings& settings,
                                           const Expectations& expectations, std::vector<std::string>* used) {
  const double bound = is_dissipative(scheme) ? settings.bound_dissipative : settings.bound_conserving;
  const StabilityRun r =
      stability_run(scheme, consistent_mass(), settings.elements, settings.courant, settings.final_time, bound);
  return judge("1/" + scheme.label + "/consistent",
               "Contrast (the method's motivation, problem.md §3): " + scheme.label +
                   " with the consistent mass and exact contact is unstable",
               "consistent: " + describe(r),
               "the same run (N = " + std::to_string(settings.elements) + ", Δt = " + sig(settings.courant) +
                   "h, T = " + sig(settings.final_time) + ") exceeds the same bound or produces a non-finite value",
               !(r.finite && r.bounded), expectations, used);
}

TEST_CASE("the stability check fails on an unstable configuration and passes on a stable one") {
  StabilitySettings st;
  st.elements = 40;
  st.final_time = 60;
  const Expectations none;
  // The consistent mass with CN, fed to the check as if it were one of the paper's masses.
  const std::vector<ClaimResult> broken = check_stability({scheme_choice("cn")}, {consistent_mass()}, st, none);
  REQUIRE(broken.size() == 1);
  CAPTURE(broken[0].measured);
  CHECK(broken[0].verdict == Verdict::failed);
  const std::vector<ClaimResult> fine = check_stability({scheme_choice("cn"), scheme_choice("be")}, {mod3()}, st, none);
  for (const ClaimResult& row : fine) {
    CAPTURE(row.measured);
    CHECK(row.verdict == Verdict::reproduced);
  }
}

// ---------------------------------------------------------------------------------------------------
// Claim 2: total mass (paper §2: "la masse totale du matériau est préservée").
//
// The total mass is 1ᵀM^mod1 over all nodes 0..N, L for the consistent mass. Summing the 3N + 1
// positive entries in floating point commits a relative error of at most about (3N + 1)ε, so the
// criterion is |1ᵀM^mod1 − L| ≤ 4(N + 1)εL for Mod 2 and Mod 3, and |1ᵀM^mod1 − (L − 2h/3)| ≤ 4(N + 1)εL
// for Mod 1 (it drops row and column 0, M_00 + 2M_01 = 2h/3): "exactly 2h/3" up to that round-off.
namespace {

struct MassDeviation {
  double worst_ratio = 0;      // max |deviation| / tolerance
  double worst_relative = 0;   // max |deviation| / L
  std::string worst_mesh;
};

MassDeviation mass_deviation(const MassRedistribution& mass, const std::vector<UniformMesh>& meshes, double lost) {
  MassDeviation d;
  for (const UniformMesh& mesh : meshes) {
    const double expected = mesh.length - lost * mesh.h();
    const double deviation = std::abs(total_mass(mesh, mass) - expected);
    const double tolerance =
        4.0 * static_cast<double>(mesh.elements + 1) * std::numeric_limits<double>::epsilon() * mesh.length;
    if (deviation / tolerance >= d.worst_ratio) {
      d.worst_ratio = deviation / tolerance;
      d.worst_mesh = "L = " + sig(mesh.length) + ", N = " + std::to_string(mesh.elements);
    }
    d.worst_relative = std::max(d.worst_relative, deviation / mesh.length);
  }
  return d;
}

std::string list_meshes(const std::vector<UniformMesh>& meshes) {
  std::vector<std::string> s;
  for (const UniformMesh& m : meshes) s.push_back("(" + sig(m.length) + ", " + std::to_string(m.elements) + ")");
  return join(s, " ");
}

}  // namespace

std::vector<ClaimResult> check_mass(const std::vector<MassRedistribution>& preserving,
                                    const std::vector<MassRedistribution>& dropping,
                                    const std::vector<UniformMesh>& meshes, const Expectations& expectations,
                                    std::vector<std::string>* used) {
  std::vector<ClaimResult> rows;
  const std::string tolerance = "≤ 4(N + 1)εL on every mesh (L, N) of " + list_meshes(meshes);
  for (const auto& [masses, lost] : {std::pair{&preserving, 0.0}, std::pair{&dropping, 2.0 / 3.0}}) {
    for (const MassRedistribution& mass : *masses) {
      const MassDeviation d = mass_deviation(mass, meshes, lost);
      const bool preserves = lost == 0.0;
      rows.push_back(judge(
          "2/" + mass.name,
          "Mass: " + mass.name + (preserves ? " preserves the total mass L" : " loses exactly 2h/3 of the total mass"),
          "max |deviation|/L = " + sig(d.worst_relative) + ", at most " + fixed(d.worst_ratio, 3) +
              " × the tolerance (worst: " + d.worst_mesh + ")",
          (preserves ? "|1ᵀM 1 − L| " : "|1ᵀM 1 − (L − 2h/3)| ") + tolerance, d.worst_ratio <= 1.0, expectations,
          used));
    }
  }
  return rows;
}

TEST_CASE("the mass check fails for a weight that loses mass and for a wrong claim about Mod 2") {
  const std::vector<UniformMesh> meshes = {UniformMesh(1.0, 10), UniformMesh(2.5, 1000)};
  MassRedistribution leaky = mod3();
  leaky.name = "leaky";
  leaky.weight = [](Index i, Index j, const UniformMesh&) {  // only half of the lost 2h/3 moved to node 1
    return (i == 0 || j == 0) ? 0.0 : (i == 1 && j == 1) ? 1.5 : 1.0;
  };
  const Expectations none;
  for (const ClaimResult& row : check_mass({leaky}, {mod2()}, meshes, none)) {
    CAPTURE(row.id);
    CAPTURE(row.measured);
    CHECK(row.verdict == Verdict::failed);
  }
  for (const ClaimResult& row : check_mass({mod2(), mod3()}, {mod1()}, meshes, none)) {
    CAPTURE(row.id);
    CHECK(row.verdict == Verdict::reproduced);
  }
}

// ---------------------------------------------------------------------------------------------------
// Claim 3: the ordering of the paper's Figure 1 ("la solution approchée est d'autant meilleure que la
// répartition de la masse du nœud de contact est faite sur un autre nœud proche du nœud de contact").
//
// The paper shows curves, not numbers, and does not say in which measure "better" holds; so the claim
// is checked in each of the eight relative errors of mathematics.md §5 separately, one row per scheme and
// measure: it holds in a measure if error(Mod 3) < error(Mod 2) < error(Mod 1) strictly on every mesh
// tried (N = 50, 100, 200, Δt = h/2, one period: the free flight, the contact and the release that a
// figure of the contact point shows).
std::vector<ClaimResult> check_ordering(const std::vector<SchemeChoice>& schemes,
                                        const std::vector<MassRedistribution>& ordered,
                                        const OrderingSettings& settings, ErrorCache& cache,
                                        const Expectations& expectations, std::vector<std::string>* used) {
  if (ordered.size() < 2) throw std::invalid_argument("check_ordering: needs at least two masses");
  std::vector<std::string> names;
  for (const MassRedistribution& m : ordered) names.push_back(m.name);
  std::vector<std::string> best_first(names.rbegin(), names.rend());
  std::vector<ClaimResult> rows;
  for (const SchemeChoice& scheme : schemes) {
    // errors[mesh][mass][measure]
    std::vector<std::vector<std::array<double, 8>>> errors;
    for (Index n : settings.elements) {
      errors.emplace_back();
      for (const MassRedistribution& m : ordered)
        errors.back().push_back(
            ErrorAccumulator::values(cache.errors(scheme, m, n, settings.courant, settings.final_time)));
    }
    for (std::size_t q = 0; q < 8; ++q) {
      bool holds = true;
      std::vector<std::string> measured;
      for (std::size_t i = 0; i < settings.elements.size(); ++i) {
        std::vector<std::string> values;
        for (std::size_t k = ordered.size(); k-- > 0;) values.push_back(sig(errors[i][k][q]));
        for (std::size_t k = 0; k + 1 < ordered.size(); ++k) holds = holds && errors[i][k + 1][q] < errors[i][k][q];
        measured.push_back("N = " + std::to_string(settings.elements[i]) + ": " + join(values, " / "));
      }
      rows.push_back(judge("3/" + scheme.label + "/" + ErrorAccumulator::names[q],
                           "Ordering (Figure 1): with " + scheme.label + ", " + join(best_first, " < ") + " in " +
                               measure_names[q],
                           join(best_first, " / ") + " errors: " + join(measured, "; "),
                           "error(" + join(best_first, ") < error(") + ") strictly on every mesh, N = " +
                               list_elements(settings.elements) + ", Δt = " + sig(settings.courant) +
                               "h, T = " + sig(settings.final_time),
                           holds, expectations, used));
    }
  }
  return rows;
}

TEST_CASE("the ordering check fails when the masses are fed in the wrong order or replaced by a bad one") {
  OrderingSettings st;
  st.elements = {20, 40};
  ErrorCache cache;
  const Expectations none;
  // The true order (Mod 1 worst … Mod 3 best) and the swapped one give opposite verdicts in every
  // measure where the errors differ: whatever holds for one fails for the other.
  const SchemeChoice cn = scheme_choice("cn");
  const std::vector<ClaimResult> right = check_ordering({cn}, {mod1(), mod2(), mod3()}, st, cache, none);
  const std::vector<ClaimResult> swapped = check_ordering({cn}, {mod3(), mod2(), mod1()}, st, cache, none);
  REQUIRE(right.size() == 8);
  REQUIRE(swapped.size() == 8);
  int right_pass = 0, swapped_pass = 0;
  for (std::size_t q = 0; q < 8; ++q) {
    CAPTURE(right[q].measured);
    right_pass += right[q].verdict == Verdict::reproduced;
    swapped_pass += swapped[q].verdict == Verdict::reproduced;
    CHECK(!(right[q].verdict == Verdict::reproduced && swapped[q].verdict == Verdict::reproduced));
  }
  CHECK(right_pass > 0);  // the real ordering holds somewhere, so the swapped one fails there
  CHECK(right_pass + swapped_pass <= 8);
  // A "Mod 3" that puts the lost mass far from the contact node (spread over the first half of the bar)
  // must not beat the real Mod 3 in the measures where Mod 3 beats Mod 2.
  const MassRedistribution far = spread_over_first_nodes(10);
  const std::vector<ClaimResult> wrong = check_ordering({scheme_choice("cn")}, {far, mod3()}, st, cache, none);
  const std::vector<ClaimResult> reversed = check_ordering({scheme_choice("cn")}, {mod3(), far}, st, cache, none);
  int wrong_pass = 0, reversed_pass = 0;
  for (std::size_t q = 0; q < 8; ++q) {
    wrong_pass += wrong[q].verdict == Verdict::reproduced;
    reversed_pass += reversed[q].verdict == Verdict::reproduced;
  }
  CHECK(reversed_pass < wrong_pass);
}

// ---------------------------------------------------------------------------------------------------
// Claim 4: convergence as h, Δt → 0 (paper §2), and an error estimate in time for Crank–Nicolson.
//
// In h (with Δt = C h, C = ½ and 1, mathematics.md §5): the paper proves convergence without a rate. The
// exact solution is only Lipschitz (u_x and u_t jump across characteristics, λ jumps at impact and
// release), so the rates in the energy norms are at best ½. "Converges" is checked as: every one of
// the eight relative errors decreases at every refinement (N = 50 … 800, doubling), and its least-
// squares order in h is at least ¼ — a margin above 0 so that an error that stagnates, or decreases
// by round-off only, does not pass.
//
// In time at fixed h: the paper says an estimate is proved for Crank–Nicolson but gives no order. At
// fixed h the semi-discrete problem is a Lipschitz ODE; its solution is compared with a reference of
// the same h and a much smaller Δt (mathematics.md §5), at the instants of the coarsest Δt. The criterion
// is the same (decrease at every halving of Δt, least-squares order ≥ ¼); the observed order and the
// local order of each halving are reported, so that the range where an order holds can be read off.
std::vector<ClaimResult> check_convergence(const std::vector<SchemeChoice>& schemes,
                                           const std::vector<MassRedistribution>& masses,
                                           const ConvergenceSettings& settings, ErrorCache& cache,
                                           const Expectations& expectations, std::vector<std::string>* used) {
  std::vector<double> h;
  for (Index n : settings.elements) h.push_back(1.0 / static_cast<double>(n));
  std::vector<ClaimResult> rows;
  for (const SchemeChoice& scheme : schemes) {
    for (const MassRedistribution& mass : masses) {
      for (double courant : settings.courants) {
        std::vector<std::array<double, 8>> e;
        for (Index n : settings.elements)
          e.push_back(ErrorAccumulator::values(cache.errors(scheme, mass, n, courant, settings.final_time)));
        bool holds = true;
        std::vector<std::string> orders, broken;
        for (std::size_t q = 0; q < 8; ++q) {
          std::vector<double> y;
          for (const auto& v : e) y.push_back(v[q]);
          bool decreasing = true;
          double worst_ratio = 0;
          for (std::size_t i = 0; i + 1 < y.size(); ++i) {
            decreasing = decreasing && y[i + 1] < y[i];
            worst_ratio = std::max(worst_ratio, y[i + 1] / y[i]);
          }
          const bool positive = std::all_of(y.begin(), y.end(), [](double v) { return v > 0 && std::isfinite(v); });
          const double order = positive ? least_squares_order(h, y) : std::numeric_limits<double>::quiet_NaN();
          const bool ok = decreasing && positive && order >= settings.minimum_order;
          holds = holds && ok;
          orders.push_back(std::string(measure_names[q]) + " " + fixed(order, 3));
          if (!ok)
            broken.push_back(std::string(measure_names[q]) + " (errors " + sig(y.front()) + " → " + sig(y.back()) +
                             ", worst ratio e(h/2)/e(h) = " + fixed(worst_ratio, 2) + ")");
        }
        std::string measured = "orders: " + join(orders, ", ");
        if (!broken.empty()) measured += ". Criterion not met by: " + join(broken, "; ");
        rows.push_back(judge("4/" + scheme.label + "/" + mass.name + "/C=" + sig(courant),
                             "Convergence in h: " + scheme.label + " with " + mass.name + ", Δt = " + sig(courant) +
                                 "h",
                             measured,
                             "each of the 8 errors decreases at every refinement N = " +
                                 list_elements(settings.elements) + " and its least-squares order in h is ≥ " +
                                 sig(settings.minimum_order) + " (T = " + sig(settings.final_time) + ")",
                             holds, expectations, used));
      }
    }
  }
  return rows;
}

TEST_CASE("the convergence check fails for a weight that is not 1 + O(h)") {
  // Doubling every weight doubles the mass: the discrete waves travel at 1/√2 and the errors stagnate.
  MassRedistribution heavy = mod1();
  heavy.name = "heavy";
  heavy.weight = [](Index i, Index j, const UniformMesh&) { return (i == 0 || j == 0) ? 0.0 : 2.0; };
  ConvergenceSettings st;
  st.elements = {20, 40, 80};
  st.courants = {0.5};
  ErrorCache cache;
  const std::vector<ClaimResult> rows = check_convergence({scheme_choice("cn")}, {heavy, mod3()}, st, cache, {});
  REQUIRE(rows.size() == 2);
  CAPTURE(rows[0].measured);
  CAPTURE(rows[1].measured);
  CHECK(rows[0].verdict == Verdict::failed);
}

namespace {

// The displacement of a run at the instants k Δt₀ (Δt₀ the coarsest step), k = 0 … K.
std::vector<Eigen::VectorXd> snapshots(const SchemeChoice& scheme, const MassRedistribution& mass,
                                       const UniformMesh& mesh, double courant, double coarsest, Index count) {
  const double ratio = coarsest / courant;
  const Index stride = static_cast<Index>(std::llround(ratio));
  if (stride < 1 || std::abs(ratio - static_cast<double>(stride)) > 1e-9 * ratio)
    throw std::invalid_argument("check_time_convergence: every Courant number must divide the coarsest one");
  BarSimulation simulation(benchmark_problem(), mesh, mass, scheme.parameters, courant * mesh.h());
  std::vector<Eigen::VectorXd> u;
  run(simulation, stride * count, [&](const Sample& s) {
    if (s.level % stride == 0) u.push_back(*s.displacement);
  });
  return u;
}

}  // namespace

std::vector<ClaimResult> check_time_convergence(const SchemeChoice& scheme,
                                                const std::vector<MassRedistribution>& masses,
                                                const TimeConvergenceSettings& settings,
                                                const Expectations& expectations, std::vector<std::string>* used) {
  const UniformMesh mesh(1.0, settings.elements);
  const double coarsest = settings.courants.front();
  const Index count = steps_to_reach(settings.final_time, coarsest * mesh.h());
  const Tridiagonal m = p1_mass(mesh), s = p1_stiffness(mesh);
  std::vector<double> dt;
  for (double c : settings.courants) dt.push_back(c * mesh.h());
  const char* const names[3] = {"u L∞(L²)", "u L∞(H¹)", "u(0,·) L∞"};
  std::vector<ClaimResult> rows;
  for (const MassRedistribution& mass : masses) {
    const std::vector<Eigen::VectorXd> reference =
        snapshots(scheme, mass, mesh, settings.reference_courant, coarsest, count);
    double ref_l2 = 0, ref_h1 = 0, ref_u0 = 0;
    for (const Eigen::VectorXd& r : reference) {
      ref_l2 = std::max(ref_l2, std::sqrt(m.bilinear(r, r)));
      ref_h1 = std::max(ref_h1, std::sqrt(s.bilinear(r, r)));
      ref_u0 = std::max(ref_u0, std::abs(r[0]));
    }
    std::vector<std::vector<double>> errors(3);
    for (double c : settings.courants) {
      const std::vector<Eigen::VectorXd> u = snapshots(scheme, mass, mesh, c, coarsest, count);
      double l2 = 0, h1 = 0, u0 = 0;
      for (std::size_t k = 0; k < u.size(); ++k) {
        const Eigen::VectorXd d = u[k] - reference[k];
        l2 = std::max(l2, std::sqrt(m.bilinear(d, d)));
        h1 = std::max(h1, std::sqrt(s.bilinear(d, d)));
        u0 = std::max(u0, std::abs(d[0]));
      }
      errors[0].push_back(l2 / ref_l2);
      errors[1].push_back(h1 / ref_h1);
      errors[2].push_back(u0 / ref_u0);
    }
    bool holds = true;
    std::vector<std::string> measured;
    for (int q = 0; q < 3; ++q) {
      const std::vector<double>& y = errors[q];
      bool decreasing = true;
      std::vector<std::string> local;
      for (std::size_t i = 0; i + 1 < y.size(); ++i) {
        decreasing = decreasing && y[i + 1] < y[i];
        local.push_back(y[i + 1] > 0 && y[i] > 0 ? fixed(std::log(y[i] / y[i + 1]) / std::log(dt[i] / dt[i + 1]), 2)
                                                 : "nan");
      }
      const bool positive = std::all_of(y.begin(), y.end(), [](double v) { return v > 0 && std::isfinite(v); });
      const double order = positive ? least_squares_order(dt, y) : std::numeric_limits<double>::quiet_NaN();
      holds = holds && decreasing && positive && order >= settings.minimum_order;
      measured.push_back(std::string(names[q]) + ": order " + fixed(order, 2) + " (local " + join(local, ", ") +
                         "; errors " + sig(y.front()) + " → " + sig(y.back()) + ")");
    }
    std::vector<std::string> ratios;
    for (double c : settings.courants) ratios.push_back(sig(c));
    rows.push_back(judge(
        "4t/" + scheme.label + "/" + mass.name,
        "Error estimate in time: " + scheme.label + " with " + mass.name + " converges in Δt at fixed h",
        join(measured, "; "),
        "against a reference with Δt = h/" + sig(1 / settings.reference_courant) + " (same h = 1/" +
            std::to_string(settings.elements) + "), at the instants of the coarsest Δt up to T = " +
            sig(settings.final_time) + ", each error decreases at every refinement Δt/h = " + join(ratios, ", ") +
            " and its least-squares order in Δt is ≥ " + sig(settings.minimum_order),
        holds, expectations, used));
  }
  return rows;
}

TEST_CASE("the convergence-in-time check fails when the time step is not refined") {
  TimeConvergenceSettings st;
  st.elements = 20;
  st.courants = {1, 1, 1};
  st.reference_courant = 1.0 / 16;
  const std::vector<ClaimResult> stagnant = check_time_convergence(scheme_choice("cn"), {mod3()}, st, {});
  REQUIRE(stagnant.size() == 1);
  CHECK(stagnant[0].verdict == Verdict::failed);
  st.courants = {1, 0.5, 0.25};
  const std::vector<ClaimResult> refined = check_time_convergence(scheme_choice("cn"), {mod3()}, st, {});
  CAPTURE(refined[0].measured);
  CHECK(refined[0].verdict == Verdict::reproduced);
}

// ---------------------------------------------------------------------------------------------------
// Claim 5: energy. Crank–Nicolson's discrete energy Eⁿ = ½VᵀMV + ½UᵀSU is exactly conserved by a step
// that keeps the contact status (in contact both levels have u₀ = 0, free both have λ = 0: the contact
// force does no work), so the criterion is |Eⁿ⁺¹ − Eⁿ| ≤ round-off there, and the energy
// changes only at impacts and releases, by jumps that should vanish with h (the kinetic energy of the
// O(h) mass next to the contact node): their total Σ|ΔE| over one period must decrease at every
// refinement. Backward Euler's step satisfies Eⁿ⁺¹ − Eⁿ = −½(Vⁿ⁺¹ − Vⁿ)ᵀM(Vⁿ⁺¹ − Vⁿ) − ½(Uⁿ⁺¹ −
// Uⁿ)ᵀS(Uⁿ⁺¹ − Uⁿ) + (contact work ≤ 0): the criterion is Eⁿ⁺¹ ≤ Eⁿ + round-off at every step.
// The contact status of a level is u₀ⁿ = 0 (the closed-form step puts u₀ exactly on the obstacle).
//
// Round-off. The velocity Vⁿ⁺¹ = 2(Uⁿ⁺¹ − Uⁿ)/Δt − Vⁿ (BE: (Uⁿ⁺¹ − Uⁿ)/Δt) turns the solve's relative
// round-off ε in U into ε·|U|/Δt in V, node by node; the kinetic energy ½VᵀMV sums N such
// contributions of random sign. So a step that conserves E exactly in exact arithmetic changes it by
// about ε√N (L/Δt)·E in floating point, and the allowance is 16 times that. (The first version of
// this check allowed 1e-12 E(0), which forgot the 1/Δt: it measured 2.3e-12 at N = 400, Δt = h/2.
// A scan over N = 50 … 1600 and Δt/h = ¼, ½, 1 then gave 2.1 to 45 in units of ε/Δt, growing like
// √N as derived: round-off, not a failure of conservation. The allowance is still 1e-11 at N = 400,
// while backward Euler's real losses are of order 1e-5 per step there.)
namespace {

struct EnergyTrace {
  double e0 = 0, e_final = 0, round_off = 0;
  double max_same_status = 0;   // max |ΔE| / E(0) over steps that keep the status
  double jump_sum = 0;          // Σ |ΔE| / E(0) over steps that change it
  double max_increase = 0;      // max (ΔE) / E(0)
  int changes = 0;
  int increases = 0;            // steps with ΔE > round-off
};

// The round-off allowance of an energy change, relative to E(0): factor · ε √N (L/Δt).
double energy_round_off(const UniformMesh& mesh, double dt, double factor) {
  return factor * std::numeric_limits<double>::epsilon() * std::sqrt(static_cast<double>(mesh.elements)) *
         mesh.length / dt;
}

std::string round_off_text(const EnergySettings& settings) {
  return sig(settings.round_off_factor) + " ε √N (L/Δt) E_h(0)";
}

EnergyTrace energy_trace(const SchemeChoice& scheme, const MassRedistribution& mass, Index elements,
                         const EnergySettings& settings) {
  const UniformMesh mesh(1.0, elements);
  const double dt = settings.courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, mass, scheme.parameters, dt);
  EnergyTrace t;
  t.round_off = energy_round_off(mesh, dt, settings.round_off_factor);
  t.e0 = simulation.sample().energy;
  double e = t.e0;
  bool contact = (*simulation.sample().displacement)[0] == 0.0;
  const Index steps = steps_to_reach(settings.final_time, dt);
  for (Index k = 0; k < steps; ++k) {
    simulation.step();
    const Sample s = simulation.sample();
    const bool now = (*s.displacement)[0] == 0.0;
    const double change = (s.energy - e) / t.e0;
    if (now == contact) {
      t.max_same_status = std::max(t.max_same_status, std::abs(change));
    } else {
      t.jump_sum += std::abs(change);
      ++t.changes;
    }
    t.max_increase = std::max(t.max_increase, change);
    if (!(change <= t.round_off)) ++t.increases;  // a NaN counts as an increase
    e = s.energy;
    contact = now;
  }
  t.e_final = e;
  return t;
}

}  // namespace

std::vector<ClaimResult> check_energy_conservation(const SchemeChoice& scheme,
                                                   const std::vector<MassRedistribution>& masses,
                                                   const EnergySettings& settings, const Expectations& expectations,
                                                   std::vector<std::string>* used) {
  std::vector<ClaimResult> rows;
  std::vector<double> h;
  for (Index n : settings.elements) h.push_back(1.0 / static_cast<double>(n));
  for (const MassRedistribution& mass : masses) {
    double max_same = 0, worst_share = 0;  // worst_share: max over meshes of max_same_status / round-off
    std::vector<double> jumps;
    std::vector<std::string> per_mesh;
    for (Index n : settings.elements) {
      const EnergyTrace t = energy_trace(scheme, mass, n, settings);
      max_same = std::max(max_same, t.max_same_status);
      worst_share = std::max(worst_share, t.max_same_status / t.round_off);
      jumps.push_back(t.jump_sum);
      per_mesh.push_back("N = " + std::to_string(n) + ": " + std::to_string(t.changes) + " changes, " +
                         sig(t.jump_sum));
    }
    bool shrinking = std::isfinite(max_same);
    for (std::size_t i = 0; i + 1 < jumps.size(); ++i) shrinking = shrinking && jumps[i + 1] < jumps[i];
    const bool positive = std::all_of(jumps.begin(), jumps.end(), [](double v) { return v > 0 && std::isfinite(v); });
    const std::string order = positive ? ", order in h " + fixed(least_squares_order(h, jumps), 2) : "";
    const bool holds = worst_share <= 1.0 && shrinking;
    rows.push_back(judge("5/" + scheme.label + "/" + mass.name,
                         "Energy: " + scheme.label + " with " + mass.name +
                             " conserves E_h up to jumps at status changes that shrink with h",
                         "max |ΔE|/E_h(0) over steps keeping the status: " + sig(max_same) + " (at most " +
                             fixed(worst_share, 3) + " × the round-off allowance); Σ|ΔE|/E_h(0) at status changes: " +
                             join(per_mesh, "; ") + order,
                         "|ΔE| ≤ " + round_off_text(settings) +
                             " (round-off) at every step keeping the contact status, and Σ|ΔE| over the steps changing "
                             "it decreases at every refinement N = " + list_elements(settings.elements) +
                             " (Δt = " + sig(settings.courant) + "h, T = " + sig(settings.final_time) + ")",
                         holds, expectations, used));
  }
  return rows;
}

std::vector<ClaimResult> check_energy_dissipation(const SchemeChoice& scheme,
                                                  const std::vector<MassRedistribution>& masses,
                                                  const EnergySettings& settings, const Expectations& expectations,
                                                  std::vector<std::string>* used) {
  std::vector<ClaimResult> rows;
  for (const MassRedistribution& mass : masses) {
    int increases = 0;
    double max_increase = 0;
    std::vector<std::string> per_mesh;
    for (Index n : settings.elements) {
      const EnergyTrace t = energy_trace(scheme, mass, n, settings);
      increases += t.increases;
      max_increase = std::max(max_increase, t.max_increase);
      per_mesh.push_back("N = " + std::to_string(n) + ": E_h(T)/E_h(0) = " + fixed(t.e_final / t.e0, 4));
    }
    rows.push_back(judge("5/" + scheme.label + "/" + mass.name,
                         "Energy: " + scheme.label + " with " + mass.name + " never increases the energy",
                         std::to_string(increases) + " steps with an increase; largest ΔE/E_h(0) = " +
                             sig(max_increase) + "; " + join(per_mesh, "; "),
                         "Eⁿ⁺¹ ≤ Eⁿ + " + round_off_text(settings) + " (round-off) at every step, N = " +
                             list_elements(settings.elements) + " (Δt = " + sig(settings.courant) +
                             "h, T = " + sig(settings.final_time) + ")",
                         increases == 0, expectations, used));
  }
  return rows;
}

TEST_CASE("the energy checks fail for a scheme that does not conserve, or one that gains energy") {
  EnergySettings st;
  st.elements = {20, 40};
  // Backward Euler presented as a conserving scheme.
  const std::vector<ClaimResult> be = check_energy_conservation(scheme_choice("be"), {mod3()}, st, {});
  REQUIRE(be.size() == 1);
  CAPTURE(be[0].measured);
  CHECK(be[0].verdict == Verdict::failed);
  // Crank–Nicolson with the consistent mass presented as a dissipative scheme: it gains energy.
  st.final_time = 30;
  const std::vector<ClaimResult> cn = check_energy_dissipation(scheme_choice("cn"), {consistent_mass()}, st, {});
  CAPTURE(cn[0].measured);
  CHECK(cn[0].verdict == Verdict::failed);
  // And the real claims, on small meshes.
  st.final_time = 3;
  CHECK(check_energy_conservation(scheme_choice("cn"), {mod3()}, st, {})[0].verdict == Verdict::reproduced);
  CHECK(check_energy_dissipation(scheme_choice("be"), {mod3()}, st, {})[0].verdict == Verdict::reproduced);
}

// ---------------------------------------------------------------------------------------------------
// Claim 6a: the closed-form contact step against a general-purpose solve, inside real runs.
//
// The step is rebuilt from the public state of the run alone — Uⁿ, the velocity (Vⁿ for the two-level
// schemes, (Uⁿ − Uⁿ⁻¹)/Δt for Paoli–Schatzman, from which Uⁿ⁻¹ is recovered) and λⁿ — with the
// formulas of mathematics.md §4 (f = 0 here: the benchmark):
//
//   CN   (M + θS)Uⁿ⁺¹ + θλⁿ⁺¹e₀ = (M − θS)Uⁿ + Δt MVⁿ − θλⁿe₀,           θ = Δt²/4,
//   BE   (M + Δt²S)Uⁿ⁺¹ + Δt²λⁿ⁺¹e₀ = MUⁿ + Δt MVⁿ,
//   PS   (M + βΔt²S)Uⁿ⁺¹ + Δt²λⁿe₀ = (2M − (1−2β)Δt²S)Uⁿ − (M + βΔt²S)Uⁿ⁻¹,  obstacle −e u₀ⁿ⁻¹,
//
// and, when the contact node is massless and the contact row algebraic (every scheme but the literal
// PS), row 0 replaced by the contact row S₀·Uⁿ⁺¹ + λ = 0 (paper eq. (6)). The active set is fixed to
// the one the run found (u₀ on the obstacle, or λ = 0), the (N + 1) × (N + 1) saddle-point system in
// (U, λ) is assembled from triplets and solved by Eigen's SparseLU. The criterion: the differences in
// Uⁿ⁺¹ and λ, relative to the largest |U| and |λ| of the compared steps, are ≤ 1e-10 (a few hundred
// round-offs for these well-conditioned systems), and the run's step satisfies the complementarity
// 0 ≤ u₀ − g ⊥ λ ≤ 0 exactly. The steps compared: every step that changes the contact status (the
// delicate ones) and every 25th step (levels ≥ 2 for PS, whose first step is a CN start).
std::vector<ContactStepCase> paper_contact_step_cases() {
  std::vector<ContactStepCase> cases;
  for (const SchemeChoice& s : paper_schemes()) {
    for (const MassRedistribution& m : paper_masses()) cases.push_back({s, s, m});
    if (s.label != "ps") cases.push_back({s, s, consistent_mass()});  // the algebraic row needs a massless node
  }
  return cases;
}

namespace {

struct RebuiltStep {
  Tridiagonal a;
  Eigen::VectorXd b;
  double kappa = 0, obstacle = 0;
};

RebuiltStep rebuild_step(const SchemeParameters& p, const Tridiagonal& m, const Tridiagonal& s, double dt,
                         const Eigen::VectorXd& u, const Eigen::VectorXd& velocity, double multiplier) {
  const double dt2 = dt * dt;
  RebuiltStep r;
  const bool massless = contact_node_is_massless(m);
  switch (p.scheme) {
    case Scheme::crank_nicolson: {
      const double theta = dt2 / 4;
      r.a = m.plus(theta, s);
      r.b = m.plus(-theta, s) * u + dt * (m * velocity);
      r.b[0] -= theta * multiplier;
      r.kappa = theta;
      break;
    }
    case Scheme::backward_euler:
      r.a = m.plus(dt2, s);
      r.b = m * u + dt * (m * velocity);
      r.kappa = dt2;
      break;
    case Scheme::paoli_schatzman: {
      const Eigen::VectorXd u_previous = u - dt * velocity;
      r.a = m.plus(p.beta * dt2, s);
      r.b = m.scaled(2.0).plus(-(1 - 2 * p.beta) * dt2, s) * u - r.a * u_previous;
      r.kappa = dt2;
      r.obstacle = -p.restitution * u_previous[0];
      break;
    }
  }
  const bool algebraic = massless && (p.scheme != Scheme::paoli_schatzman || p.contact_row == ContactRow::algebraic);
  if (algebraic) {
    r.a.diag[0] = s.diag[0];
    r.a.upper[0] = s.upper[0];
    r.b[0] = 0.0;
    r.kappa = 1.0;
  }
  return r;
}

// A U + κλe₀ = b with the last row u₀ = g (active) or λ = 0 (inactive), by sparse LU.
Eigen::VectorXd saddle_point_solve(const RebuiltStep& r, bool active) {
  const Index n = r.a.size();
  std::vector<Eigen::Triplet<double>> t;
  for (Index i = 0; i < n; ++i) {
    t.emplace_back(i, i, r.a.diag[i]);
    if (i > 0) t.emplace_back(i, i - 1, r.a.lower[i]);
    if (i + 1 < n) t.emplace_back(i, i + 1, r.a.upper[i]);
  }
  t.emplace_back(0, n, r.kappa);
  t.emplace_back(n, active ? 0 : n, 1.0);
  Eigen::SparseMatrix<double> k(n + 1, n + 1);
  k.setFromTriplets(t.begin(), t.end());
  Eigen::VectorXd rhs(n + 1);
  rhs << r.b, (active ? r.obstacle : 0.0);
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  lu.compute(k);
  if (lu.info() != Eigen::Success) throw std::runtime_error("check_contact_step: sparse LU failed");
  Eigen::VectorXd x = lu.solve(rhs);
  if (lu.info() != Eigen::Success) throw std::runtime_error("check_contact_step: sparse LU solve failed");
  return x;
}

struct StepComparison {
  int compared = 0, status_changes = 0;
  double u_difference = 0, u_scale = 0, lambda_difference = 0, lambda_scale = 0;
  bool complementarity = true;
};

StepComparison compare_steps(const ContactStepCase& c, const ContactStepSettings& settings) {
  const UniformMesh mesh(1.0, settings.elements);
  const double dt = settings.courant * mesh.h();
  BarSimulation simulation(benchmark_problem(), mesh, c.mass, c.run.parameters, dt);
  const bool three_level = c.run.parameters.scheme == Scheme::paoli_schatzman;
  StepComparison cmp;
  bool contact = false;
  const Index steps = steps_to_reach(settings.final_time, dt);
  for (Index k = 0; k < steps; ++k) {
    const Sample before = simulation.sample();
    const Eigen::VectorXd u = *before.displacement, velocity = *before.velocity;
    const double multiplier = before.multiplier;
    simulation.step();
    const Sample after = simulation.sample();
    const RebuiltStep r = rebuild_step(c.model.parameters, simulation.mass(), simulation.stiffness(), dt, u, velocity,
                                       multiplier);
    const double u0 = (*after.displacement)[0];
    const bool active = u0 == r.obstacle;
    const bool changed = active != contact;
    contact = active;
    cmp.status_changes += changed;
    cmp.complementarity = cmp.complementarity && u0 >= r.obstacle && after.multiplier <= 0.0 &&
                          (u0 - r.obstacle) * after.multiplier == 0.0;
    if (three_level && before.level < 2) continue;
    if (!changed && k % settings.every != 0) continue;
    const Eigen::VectorXd x = saddle_point_solve(r, active);
    const Index n = mesh.unknowns();
    cmp.u_difference = std::max(cmp.u_difference, (*after.displacement - x.head(n)).cwiseAbs().maxCoeff());
    cmp.u_scale = std::max(cmp.u_scale, x.head(n).cwiseAbs().maxCoeff());
    cmp.lambda_difference = std::max(cmp.lambda_difference, std::abs(after.multiplier - x[n]));
    cmp.lambda_scale = std::max(cmp.lambda_scale, std::abs(x[n]));
    ++cmp.compared;
  }
  return cmp;
}

}  // namespace

std::vector<ClaimResult> check_contact_step(const std::vector<ContactStepCase>& cases,
                                            const ContactStepSettings& settings, const Expectations& expectations,
                                            std::vector<std::string>* used) {
  // One row per scheme (as run), gathering its masses.
  std::vector<std::string> labels;
  for (const ContactStepCase& c : cases)
    if (std::find(labels.begin(), labels.end(), c.run.label) == labels.end()) labels.push_back(c.run.label);
  std::vector<ClaimResult> rows;
  for (const std::string& label : labels) {
    bool holds = true;
    std::vector<std::string> measured, names;
    for (const ContactStepCase& c : cases) {
      if (c.run.label != label) continue;
      const StepComparison cmp = compare_steps(c, settings);
      const double du = cmp.u_scale > 0 ? cmp.u_difference / cmp.u_scale : cmp.u_difference;
      const double dl = cmp.lambda_scale > 0 ? cmp.lambda_difference / cmp.lambda_scale : cmp.lambda_difference;
      holds = holds && cmp.compared > 0 && du <= settings.tolerance && dl <= settings.tolerance && cmp.complementarity;
      names.push_back(c.mass.name);
      measured.push_back(c.mass.name + ": " + std::to_string(cmp.compared) + " steps (" +
                         std::to_string(cmp.status_changes) + " status changes), ΔU " + sig(du, 2) + ", Δλ " +
                         sig(dl, 2) + (cmp.complementarity ? "" : ", complementarity VIOLATED"));
    }
    rows.push_back(judge("6/step/" + label,
                         "The closed-form contact step of " + label + " (" + join(names, ", ") +
                             ") solves the step's saddle-point system",
                         join(measured, "; "),
                         "against Eigen's SparseLU on the full (U, λ) system rebuilt from (Uⁿ, Vⁿ or Uⁿ⁻¹, λⁿ) with "
                         "the active set fixed: max|ΔU|/max|U| and max|Δλ|/max|λ| ≤ " + sig(settings.tolerance) +
                             ", complementarity exact; every status change and every " +
                             std::to_string(settings.every) + "th step, N = " + std::to_string(settings.elements) +
                             ", Δt = " + sig(settings.courant) + "h, T = " + sig(settings.final_time),
                         holds, expectations, used));
  }
  return rows;
}

TEST_CASE("the contact-step check fails when the step does not solve the stated problem") {
  ContactStepSettings st;
  st.elements = 30;
  // Crank–Nicolson run, compared with the backward-Euler problem; then the honest comparisons.
  const std::vector<ClaimResult> wrong =
      check_contact_step({{scheme_choice("cn"), scheme_choice("be"), mod3()}}, st, {});
  REQUIRE(wrong.size() == 1);
  CAPTURE(wrong[0].measured);
  CHECK(wrong[0].verdict == Verdict::failed);
  const std::vector<ClaimResult> right = check_contact_step(paper_contact_step_cases(), st, {});
  CHECK(right.size() == 4);
  for (const ClaimResult& row : right) {
    CAPTURE(row.measured);
    CHECK(row.verdict == Verdict::reproduced);
  }
}

// ---------------------------------------------------------------------------------------------------
// Claim 6b: the closed-form solution (mathematics.md §2) against a very fine numerical solution
// (Crank–Nicolson, Mod 3, N = 4000, Δt = h/2, one period).
//
// The bound. The exact solution is Lipschitz with derivatives that jump across characteristics, so
// the P1 errors in the roughest measures (u_x, u_t, λ) are expected to decay like h^½ at best:
// h^½ = 0.016 at N = 4000; allowing a constant of 3 gives the bound 0.05 on all eight relative errors.
// A mistake in the closed form (a wrong phase, sign, period or amplitude) gives relative errors of
// order 1 in most measures, far above it.
ClaimResult check_exact_solution(const ExactSolution& exact, const FineSolutionSettings& settings,
                                 const Expectations& expectations, std::vector<std::string>* used) {
  repro::Configuration configuration;
  configuration.scheme = scheme_choice("cn").parameters;
  configuration.mass = mod3();
  configuration.elements = settings.elements;
  configuration.courant = settings.courant;
  configuration.final_time = settings.final_time;
  const auto values = ErrorAccumulator::values(repro::run_configuration(configuration, {}, &exact).errors);
  bool holds = true;
  std::vector<std::string> measured;
  for (std::size_t q = 0; q < 8; ++q) {
    holds = holds && values[q] <= settings.bound;
    measured.push_back(std::string(measure_names[q]) + " " + sig(values[q]));
  }
  return judge("6/exact", "The closed-form solution agrees with a very fine numerical solution",
               "relative errors: " + join(measured, ", "),
               "all 8 relative errors ≤ " + sig(settings.bound) + " (≈ 3h^½) for cn, mod3, N = " +
                   std::to_string(settings.elements) + ", Δt = " + sig(settings.courant) + "h, T = " +
                   sig(settings.final_time),
               holds, expectations, used);
}

TEST_CASE("the exact-solution check fails for a wrong closed form") {
  FineSolutionSettings st;
  st.elements = 400;
  const ClaimResult wrong = check_exact_solution(ExactSolution(1.0, 0.4), st, {});
  CAPTURE(wrong.measured);
  CHECK(wrong.verdict == Verdict::failed);
}

// ---------------------------------------------------------------------------------------------------
// An entry of the expectation table that no check produced (a renamed row, a removed check) would
// silently excuse nothing; it is reported as a failed row of its own.
std::vector<ClaimResult> stale_expectations(const Expectations& expectations, const std::vector<std::string>& used) {
  std::vector<ClaimResult> rows;
  for (const auto& [id, reason] : expectations) {
    if (std::find(used.begin(), used.end(), id) != used.end()) continue;
    rows.push_back({id, "Expectation table entry", "no check produced this row", "every entry names a row",
                    Verdict::failed, "stale expectation: remove or rename the entry"});
  }
  return rows;
}

TEST_CASE("an expectation that no check uses is reported as a failure") {
  const Expectations table = {{"a", "x"}, {"b", "y"}};
  const std::vector<ClaimResult> rows = stale_expectations(table, {"a"});
  REQUIRE(rows.size() == 1);
  CHECK(rows[0].id == "b");
  CHECK(rows[0].verdict == Verdict::failed);
  CHECK(stale_expectations(table, {"b", "a"}).empty());
}

// ---------------------------------------------------------------------------------------------------
// All the checks, with the settings of this repository (chosen so that they run in well under a
// minute on a small machine; the stability runs dominate).
std::vector<ClaimResult> check_all(const Expectations& expectations, std::ostream* progress) {
  std::vector<ClaimResult> rows;
  std::vector<std::string> used;
  ErrorCache cache;
  auto timed = [&](const char* name, const std::function<void()>& body) {
    const auto start = std::chrono::steady_clock::now();
    body();
    if (progress)
      *progress << "check_claims: " << name << ": "
                << fixed(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 2) << " s\n";
  };
  auto append = [&](std::vector<ClaimResult> more) { rows.insert(rows.end(), more.begin(), more.end()); };

  timed("1 stability", [&] {
    const StabilitySettings st;
    append(check_stability(paper_schemes(), paper_masses(), st, expectations, &used));
    rows.push_back(check_consistent_mass_blows_up(scheme_choice("cn"), st, expectations, &used));
  });
  timed("2 mass", [&] {
    std::vector<UniformMesh> meshes;
    for (double length : {1.0, 2.5})
      for (Index n : {2, 3, 10, 50, 200, 1000, 10000}) meshes.emplace_back(length, n);
    append(check_mass({mod2(), mod3()}, {mod1()}, meshes, expectations, &used));
  });
  timed("3 ordering", [&] {
    append(check_ordering(paper_schemes(), paper_masses(), OrderingSettings(), cache, expectations, &used));
  });
  timed("4 convergence in h", [&] {
    append(check_convergence(paper_schemes(), paper_masses(), ConvergenceSettings(), cache, expectations, &used));
  });
  timed("4 convergence in time", [&] {
    append(check_time_convergence(scheme_choice("cn"), paper_masses(), TimeConvergenceSettings(), expectations, &used));
  });
  timed("5 energy", [&] {
    append(check_energy_conservation(scheme_choice("cn"), paper_masses(), EnergySettings(), expectations, &used));
    append(check_energy_dissipation(scheme_choice("be"), paper_masses(), EnergySettings(), expectations, &used));
  });
  timed("6 contact step", [&] {
    append(check_contact_step(paper_contact_step_cases(), ContactStepSettings(), expectations, &used));
  });
  timed("6 exact solution", [&] {
    rows.push_back(check_exact_solution(ExactSolution(1.0, 0.5), FineSolutionSettings(), expectations, &used));
  });

  append(stale_expectations(expectations, used));
  return rows;
}

// ---------------------------------------------------------------------------------------------------
// Output: the same rows as a word-wrapped text table (stdout), Markdown and LaTeX (for the report),
// all three written by repro/table.
namespace {

std::string verdict_text(const ClaimResult& r) {
  return r.reason.empty() ? to_string(r.verdict) : to_string(r.verdict) + " (" + r.reason + ")";
}

}  // namespace

// Rows of one group share their criterion and often their reason: from the second row on, the text
// table says "as above" instead of repeating them (the Markdown table repeats everything).
void write_text_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  repro::Table table({"claim", "measured", "criterion", "verdict"});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ClaimResult& r = rows[k];
    const bool same_criterion = k > 0 && rows[k - 1].criterion == r.criterion;
    const bool same_reason = k > 0 && !r.reason.empty() && rows[k - 1].reason == r.reason;
    table.add_row({"[" + r.id + "] " + r.claim, r.measured, same_criterion ? "(as above)" : r.criterion,
                   same_reason ? to_string(r.verdict) + " (as above)" : verdict_text(r)});
  }
  table.write_text(out, {34, 58, 40, 30});
  int counts[3] = {0, 0, 0};
  for (const ClaimResult& r : rows) ++counts[static_cast<int>(r.verdict)];
  out << rows.size() << " rows: " << counts[0] << " reproduced, " << counts[1]
      << " not reproduced (expected failures), " << counts[2] << " FAILED\n";
}

void write_markdown_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  repro::Table table({"claim", "measured", "criterion", "verdict"});
  for (const ClaimResult& r : rows)
    table.add_row({"**" + r.id + "** " + r.claim, r.measured, r.criterion, verdict_text(r)});
  table.write_markdown(out);
}

std::string latex_escape(const std::string& text) {
  static const std::pair<const char*, const char*> symbols[] = {
      {"λ", "\\ensuremath{\\lambda}"}, {"Δ", "\\ensuremath{\\Delta}"}, {"≤", "\\ensuremath{\\le}"},
      {"≥", "\\ensuremath{\\ge}"}, {"×", "\\ensuremath{\\times}"}, {"∞", "\\ensuremath{\\infty}"},
      {"²", "\\ensuremath{^2}"}, {"¹", "\\ensuremath{^1}"}, {"ⁿ", "\\ensuremath{^n}"}, {"⁺", "\\ensuremath{^+}"},
      {"⁻", "\\ensuremath{^-}"}, {"ᵀ", "\\ensuremath{^T}"}, {"½", "\\ensuremath{\\frac12}"},
      {"¼", "\\ensuremath{\\frac14}"}, {"·", "\\ensuremath{\\cdot}"}, {"−", "\\ensuremath{-}"},
      {"→", "\\ensuremath{\\to}"}, {"ε", "\\ensuremath{\\varepsilon}"}, {"θ", "\\ensuremath{\\theta}"},
      {"β", "\\ensuremath{\\beta}"}, {"₀", "\\ensuremath{_0}"}, {"≈", "\\ensuremath{\\approx}"}, {"–", "--"},
      {"—", "---"}, {"…", "\\dots{}"}, {"§", "\\S{}"}, {"é", "\\'e"}, {"√", "\\ensuremath{\\surd}"},
      {"Σ", "\\ensuremath{\\Sigma}"}, {"∝", "\\ensuremath{\\propto}"}, {"è", "\\`e"}, {"č", "\\v{c}"},
      {"œ", "\\oe{}"}, {"ₜ", "\\ensuremath{_t}"},
  };

  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    // The discrete energy's symbol, a subscript, not an escaped underscore.
    if (text.compare(i, 3, "E_h") == 0) {
      out += "\\ensuremath{E_h}";
      i += 3;
      continue;
    }
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (c < 0x80) {
      switch (c) {
        case '\\': out += "\\textbackslash{}"; break;
        case '{': case '}': case '$': case '&': case '#': case '_': case '%':
          out += '\\';
          out += static_cast<char>(c);
          break;
        case '^': out += "\\textasciicircum{}"; break;
        case '~': out += "\\textasciitilde{}"; break;
        case '<': out += "\\ensuremath{<}"; break;
        case '>': out += "\\ensuremath{>}"; break;
        case '|': out += "\\ensuremath{|}"; break;
        default: out += static_cast<char>(c);
      }
      ++i;
      continue;
    }
    bool found = false;
    for (const auto& [utf8, latex] : symbols) {
      const std::size_t n = std::char_traits<char>::length(utf8);
      if (text.compare(i, n, utf8) == 0) {
        out += latex;
        i += n;
        found = true;
        break;
      }
    }
    if (!found) {
      std::size_t n = 1;
      while (i + n < text.size() && (static_cast<unsigned char>(text[i + n]) & 0xC0) == 0x80) ++n;
      throw std::invalid_argument("latex_escape: no LaTeX form for the character \"" + text.substr(i, n) + "\"");
    }
  }
  return out;
}

TEST_CASE("every reason of the expectation table has a LaTeX form") {
  for (const auto& [id, reason] : paper_expectations()) {
    CAPTURE(id);
    CHECK_NOTHROW(latex_escape(id + " " + reason));
  }
}

TEST_CASE("LaTeX escaping handles the special characters and the table's symbols") {
  CHECK(latex_escape("a_b & 50% #1 {x} $") == "a\\_b \\& 50\\% \\#1 \\{x\\} \\$");
  CHECK(latex_escape("λ ≤ 0.5h^½") ==
        "\\ensuremath{\\lambda} \\ensuremath{\\le} 0.5h\\textasciicircum{}\\ensuremath{\\frac12}");
  CHECK(latex_escape("a\\b ~") == "a\\textbackslash{}b \\textasciitilde{}");
  CHECK_THROWS_AS(latex_escape("日本"), std::invalid_argument);
  CHECK(latex_escape("E_hⁿ/E_h(0)") == "\\ensuremath{E_h}\\ensuremath{^n}/\\ensuremath{E_h}(0)");
}

// Rows of one group share their criterion and often their reason: from the second row on, the LaTeX
// table says "as above" instead of repeating them, and a reason gets a line of its own under its row,
// across the three last columns, so that the table stays a few pages long.
namespace {

// The report's name of one segment of a row id ("cn" → "CN", "mod3" → "Mod 3", "err_u0_L2" →
// "u(0,·) in L²(0,T)", "C=0.5" → "Δt = 0.5h"), in the report's notation; an unknown segment is kept.
std::string readable_segment(const std::string& segment) {
  static const std::pair<const char*, const char*> names[] = {
      {"cn", "CN"}, {"be", "BE"}, {"ps", "PS(¼, 0), algebraic row"}, {"ps-literal", "PS(¼, 0), literal row"},
      {"mod1", "Mod 1"}, {"mod2", "Mod 2"}, {"mod3", "Mod 3"}, {"consistent", "consistent mass"},
      {"err_u0_L2", "u(0,·) in L²(0,T)"}, {"err_lambda_L2", "λ in L²(0,T)"}, {"err_u_LinfL2", "u in L∞(0,T;L²)"},
      {"err_u_LinfH1", "u in L∞(0,T;H¹)"}, {"err_v_LinfL2", "uₜ in L∞(0,T;L²)"}, {"err_u_L2L2", "u in L²(0,T;L²)"},
      {"err_u_L2H1", "u in L²(0,T;H¹)"}, {"err_v_L2L2", "uₜ in L²(0,T;L²)"}, {"step", "contact step"},
      {"exact", "exact solution"},
  };
  for (const auto& [id, name] : names)
    if (segment == id) return name;
  if (segment.rfind("C=", 0) == 0) return "Δt = " + segment.substr(2) + "h";
  return segment;
}

std::string readable_id(const std::string& id) {
  std::string out;
  std::size_t begin = 0;
  for (bool first = true;; first = false) {
    const std::size_t end = id.find('/', begin);
    const std::string segment = id.substr(begin, end == std::string::npos ? std::string::npos : end - begin);
    out += first ? (segment == "4t" ? std::string("4 (time)") : segment) : ", " + readable_segment(segment);
    if (end == std::string::npos) return out;
    begin = end + 1;
  }
}

TEST_CASE("a row id reads in the report's notation") {
  CHECK(readable_id("3/ps-literal/err_u_LinfH1") == "3, PS(¼, 0), literal row, u in L∞(0,T;H¹)");
  CHECK(readable_id("4/cn/mod1/C=0.5") == "4, CN, Mod 1, Δt = 0.5h");
  CHECK(readable_id("4t/cn/mod3") == "4 (time), CN, Mod 3");
  CHECK(readable_id("6/exact") == "6, exact solution");
  CHECK(readable_id("9/new-case") == "9, new-case");  // an unknown segment is kept as it is
  // Every id of the current table has a LaTeX form.
  for (const auto& [id, reason] : paper_expectations()) {
    CAPTURE(id);
    CHECK_NOTHROW(latex_escape(readable_id(id)));
  }
}

}  // namespace

void write_latex_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  const std::string column = ">{\\raggedright\\arraybackslash}p{";
  repro::LatexLayout layout;
  layout.before = "{\\footnotesize\\setlength{\\tabcolsep}{3pt}\n";
  layout.columns = column + "0.20\\linewidth}" + column + "0.40\\linewidth}" + column + "0.23\\linewidth}" + column +
                   "0.11\\linewidth}";
  layout.longtable = true;
  layout.rule_between_rows = true;
  layout.note_columns = column + "0.76\\linewidth}";
  layout.after_end = "}";
  repro::Table table({"Claim", "Measured", "Criterion", "Verdict"});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ClaimResult& r = rows[k];
    const bool same_criterion = k > 0 && rows[k - 1].criterion == r.criterion;
    const bool same_reason = k > 0 && rows[k - 1].reason == r.reason;
    const std::string verdict = r.verdict == Verdict::reproduced       ? "reproduced"
                                : r.verdict == Verdict::not_reproduced ? "\\textbf{not reproduced}"
                                                                       : "\\textbf{FAILED}";
    table.add_row({"\\textbf{" + latex_escape(readable_id(r.id)) + ".} " + latex_escape(r.claim), latex_escape(r.measured),
                   same_criterion ? std::string("\\emph{as above}") : latex_escape(r.criterion), verdict},
                  r.reason.empty() ? std::string()
                                   : "\\emph{Why:} " + (same_reason ? std::string("as above.") : latex_escape(r.reason)));
  }
  // Everything as the report's values: the report reads this file in its preamble, prints the summary
  // before the detail (\mrm{claims:summary}) and the table in its appendix (\mrm{claims:table}).
  out << "% The claims of the paper as executable checks: generated by check_claims --tex (do not edit).\n"
         "% Needs \\usepackage{longtable,booktabs,array} and the report's \\mrmdef.\n";
  std::ostringstream table_tex;
  table.write_latex(table_tex, layout);
  out << "\\mrmdef{claims:table}{" << table_tex.str() << "}\n";

  // The summary the report puts before the detail: per claim number, how many rows, how many
  // reproduced, how many not (all of them expected failures, or the run would have failed) and how
  // many failed; as a tabular (\mrm{claims:summary}) and as values (\mrm{claims:K:reproduced}, ...).
  std::vector<std::string> numbers;
  for (const ClaimResult& r : rows) {
    const std::string number = r.id.substr(0, r.id.find('/'));
    if (std::find(numbers.begin(), numbers.end(), number) == numbers.end()) numbers.push_back(number);
  }
  repro::Table summary({"claim", "rows", "reproduced", "not reproduced (expected)", "failed"});
  for (const std::string& number : numbers) {
    long total = 0, reproduced = 0, expected = 0, failed = 0;
    for (const ClaimResult& r : rows) {
      if (r.id.substr(0, r.id.find('/')) != number) continue;
      ++total;
      reproduced += r.verdict == Verdict::reproduced;
      expected += r.verdict == Verdict::not_reproduced;
      failed += r.verdict == Verdict::failed;
    }
    // The verdict word of the claim: every row reproduced, none, or some.
    const std::string verdict = reproduced == total ? "reproduced" : reproduced == 0 ? "not reproduced"
                                                                                     : "partly reproduced";
    tex_define(out, "claims:" + number + ":verdict", verdict);
    summary.add_row({number == "4t" ? "4 (time)" : number, std::to_string(total), std::to_string(reproduced),
                     std::to_string(expected), std::to_string(failed)});
    for (const auto& [key, value] : {std::pair<const char*, long>{"rows", total}, {"reproduced", reproduced},
                                     {"expected", expected}, {"failed", failed}})
      tex_define(out, "claims:" + number + ":" + key, std::to_string(value));
  }
  repro::LatexLayout summary_layout;
  summary_layout.columns = "lrrrr";
  summary_layout.final_newline = false;
  std::ostringstream summary_tex;
  summary.write_latex(summary_tex, summary_layout);
  out << "\\mrmdef{claims:summary}{" << summary_tex.str() << "}\n";
}

}  // namespace mrm::claims
