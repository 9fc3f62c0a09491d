// The claims rows of the phase-matched interior mass and of the contact stress (claims_phase.hpp).
//
// Claim (a prediction): with the interior mass blended so that Crank–Nicolson's leading phase
// errors cancel (A = ½ − (Δt/h)² = ¼ at Δt = h/2; lib/fem/interior_mass.cpp), a wave front is smeared over
// W ≈ (h⁴t)^{1/5} instead of (h²t)^{1/3} (mathematics.md §9 with phase order μ = 4 for 2), so on the
// paper's benchmark over ten periods the errors of CN + Mod 3 fall. The thresholds are
// targets fixed before the measurement, below what an independent check measures (ratios 2.9, 1.8, 1.8
// and orders 0.91, 0.44–0.46 for N = 50 … 400): the u error (L²(0,T;L²)) at least 2.5× lower and the H¹ and
// λ errors at least 1.6× lower than with A = 0 at N = 400, and the fitted orders over N = 50 … 400 at
// least 0.85 (u) and 0.4 (H¹, λ). These are targets, not derived bounds: the derivation gives the orders
// h^{4/5} and h^{2/5} asymptotically and says nothing about the constant of the ratio.
//
// Claim (the field's benchmarks, doc/benchmarks.md; derived before the rows were written): the same
// gain on bouncing (Doyen-Ern-Piperno) and impacting (SDNV100), each over its natural horizon (24 and 5.8
// transits L/c). Their errors are those of fronts: bouncing's gravity is a constant load whose rigid
// motion (quadratic in t, constant in x) is exact in P1 and in the trapezoidal rule, and impacting's
// free flight is a rigid translation; the fronts are born at each impact (velocity jumps 10 and
// 100 m/s). So the derivation predicts the sign, a lower error with the matched mass, and, as a
// conjecture dropping every constant but the phase coefficient C, the size: W₂/W₄ for u and
// (W₂/W₄)^{1/2} for H¹ and λ, W = smearing_width(1/N, t) with t the horizon in transits (printed, not
// judged). The criterion is the sign (ratio at least 1), on one coarse mesh (N = 200: bouncing's runs
// are the dearest per step, its exact solution having many wave pieces); the margin says by how much.
// Where it might not hold: a benchmark whose error is not the fronts' (a smooth one, S2: the argument
// does not apply), and meshes where the A = 0 errors are still pre-asymptotic (measured by
// fig_phase_matched: on bouncing they do not decrease over its field meshes, N = 50 ... 200, at A = 0,
// which inflates the ratio).
#include "claims_phase.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <string>

#include "configurations.hpp"
#include "exact/benchmarks.hpp"
#include "measures/contact_stress.hpp"
#include "exact/impact_solution.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"
#include "report_values.hpp"
#include "sweep.hpp"

namespace mrm::claims {

std::vector<ClaimResult> check_phase_matched(const PhaseMatchedSettings& settings, Judge& judge) {
  enum { lambda_L2 = 1, u_L2L2 = 5, u_L2H1 = 6 };  // the order of ErrorAccumulator::names
  std::vector<repro::Configuration> runs;
  std::vector<double> steps;
  for (const double blend : {0.0, 0.25})
    for (Index n = settings.coarsest; n <= settings.finest; n *= 2) {
      repro::Configuration c;
      c.mass = mod3(blend);
      c.elements = n;
      c.courant = 0.5;
      c.final_time = settings.final_time;
      runs.push_back(c);
      if (blend == 0.0) steps.push_back(1.0 / static_cast<double>(n));
    }
  const std::vector<repro::Measures> measures = repro::run_batched(runs);
  const std::size_t levels = steps.size();
  auto error = [&](std::size_t blend, std::size_t level, int k) {
    return ErrorAccumulator::values(measures[blend * levels + level].errors)[static_cast<std::size_t>(k)];
  };
  const std::string where = "CN + Mod 3, paper's benchmark, Δt = h/2, T = " + decimals(settings.final_time, 0);
  std::vector<ClaimResult> rows;
  const std::pair<int, const char*> measures_shown[] = {{u_L2L2, "u"}, {u_L2H1, "H1"}, {lambda_L2, "lambda"}};
  for (const auto& [k, name] : measures_shown) {
    const double ratio = error(0, levels - 1, k) / error(1, levels - 1, k);
    const double target = k == u_L2L2 ? settings.ratio_u : settings.ratio_h1_lambda;
    rows.push_back(judge(
        "7/phase-matched/ratio-" + std::string(name),
        "The phase-matched mass (A = 1/4) lowers the " + std::string(ErrorAccumulator::names[k]) + " error of " + where,
        "error(A = 0)/error(A = 1/4) at N = " + std::to_string(settings.finest) + ": " +
            significant(error(0, levels - 1, k)) + "/" + significant(error(1, levels - 1, k)) + " = " +
            significant(ratio),
        "at least the target " + significant(target) + " (a prediction, not a derived bound)",
        at_least("ratio", ratio, target)));
  }
  for (const auto& [k, name] : measures_shown) {
    std::vector<double> errors;
    for (std::size_t l = 0; l < levels; ++l) errors.push_back(error(1, l, k));
    const double order = fit_order(steps, errors).order;
    const double target = k == u_L2L2 ? settings.order_u : settings.order_h1_lambda;
    rows.push_back(judge(
        "7/phase-matched/order-" + std::string(name),
        "With A = 1/4 the " + std::string(ErrorAccumulator::names[k]) + " error of " + where +
            " converges at the predicted order",
        "least-squares order over N = " + std::to_string(settings.coarsest) + " ... " +
            std::to_string(settings.finest) + ": " + decimals(order, 3),
        "at least the target " + significant(target) + " (the smearing argument gives 4/5 and 2/5 asymptotically)",
        at_least("order", order, target)));
  }
  // The field's benchmarks: A = 0 against A = 1/4 at Δt = h/2 on one mesh, over each one's horizon.
  std::vector<repro::Configuration> field;
  for (const std::string& b : settings.field_benchmarks)
    for (const double blend : {0.0, 0.25})
      field.push_back(repro::study_configuration(b, Scheme::crank_nicolson, mod3(blend), settings.field_elements, 0.5,
                                                 impact_benchmark(b).final_time));
  const std::vector<repro::Measures> field_measures = repro::run_batched(field);
  for (std::size_t b = 0; b < settings.field_benchmarks.size(); ++b) {
    const repro::Configuration& c = field[2 * b];
    const double transits = c.final_time * c.courant / (c.step() * static_cast<double>(c.elements));
    const double h = 1.0 / static_cast<double>(c.elements);
    const double predicted = smearing_width(h, transits, crank_nicolson_phase_order(0.5, 0.0)) /
                             smearing_width(h, transits, crank_nicolson_phase_order(0.5, 0.25));
    for (const auto& [k, name] : measures_shown) {
      const double a0 = ErrorAccumulator::values(field_measures[2 * b].errors)[static_cast<std::size_t>(k)];
      const double a14 = ErrorAccumulator::values(field_measures[2 * b + 1].errors)[static_cast<std::size_t>(k)];
      const double ratio = a0 / a14;
      const double guess = k == u_L2L2 ? predicted : std::sqrt(predicted);
      rows.push_back(judge(
          "7/phase-matched/" + settings.field_benchmarks[b] + "-" + name,
          "The phase-matched mass (A = 1/4) lowers the " + std::string(ErrorAccumulator::names[k]) + " error of CN + " +
              "Mod 3 on the field's benchmark " + settings.field_benchmarks[b] + " (its fronts' phase error)",
          "error(A = 0)/error(A = 1/4) at N = " + std::to_string(settings.field_elements) +
              ", dt = h/2, T = " + significant(c.final_time) + " (" + decimals(transits, 1) +
              " transits): " + significant(a0) + "/" + significant(a14) + " = " + significant(ratio) +
              "; the smearing argument's size (a conjecture) " + significant(guess),
          "at least 1 (the derivation gives the sign: the matched mass has the smaller phase error at every "
          "kh below the grid scale; the size is a conjecture and is not judged)",
          at_least("ratio", ratio, 1.0)));
    }
  }
  return rows;
}

// Claim (derived in lib/measures/contact_stress.cpp before any measurement): the wake of the smeared fronts
// makes TV(λ_h)/TV(λ) grow like N^{1/2} where λ jumps; a window whose transfer decays faster than
// (kδ)^{−(μ+1)/2} (the cubic B-spline, p = 4), of width δ = 8W matched to the smearing width, keeps it
// bounded, with an L² error of the order W^{1/2} of λ_h's; where λ is smooth the window only adds its
// bias O(δ² λ''), so the default stress gates it (§6): the window where the multiplier rattles, the
// multiplier where it does not. The criteria, each stated before the numbers, on CN + Mod 3 at Δt = h/2:
//   where λ jumps (the paper's benchmark, bouncing, impacting): (1) the ratio at most 2 on every mesh, a
//   convention for "bounded" chosen when the stress study was written; (2) no growth: the least-squares
//   slope of log(ratio) against log N at most 1/12, half-way between the window's predicted 0 and the next
//   mechanism's 1/6 (the box window's N^{1/6}), so that a stress that behaves like the box fails; (3) its L²
//   error no larger than the multiplier's at the same N (a smoothing that costs accuracy is no cure);
//   where λ is smooth (S1 over T = 2 and 30, S2): on a mesh where the gate keeps the multiplier (G ≤ τ)
//   the stress is the multiplier, its error and order by construction, so what is judged there is the
//   gate's distance from firing, G against τ; on a mesh where it picks the window, (3) again; and if it
//   picks the window on any mesh, (4) the L² order (least squares over the meshes) at least the
//   multiplier's less 2σ, σ² the sum of the two fits' squared standard errors: the default keeps the
//   multiplier's convergence. fig_stress measures the same criteria on N = 100 … 3200.
std::vector<ClaimResult> check_contact_stress(const StressSettings& settings, Judge& judge) {
  const ContactStress stress = ContactStress::gated;
  const std::string name = to_string(stress);
  std::vector<double> steps;
  for (Index n = settings.coarsest; n <= settings.finest; n *= 2) steps.push_back(1.0 / static_cast<double>(n));
  auto horizon = [](const StressCase& c) {
    return c.final_time < 0 ? mrm::benchmark(c.benchmark).final_time : c.final_time;
  };
  std::vector<repro::Configuration> runs;
  for (const StressCase& sc : settings.cases)
    for (Index n = settings.coarsest; n <= settings.finest; n *= 2) {
      repro::Configuration c =
          repro::study_configuration(sc.benchmark, Scheme::crank_nicolson, mod3(), n, 0.5, horizon(sc));
      c.keep_stress_history = true;
      c.measure_errors = false;
      runs.push_back(c);
    }
  const std::vector<repro::Measures> measures = repro::run_batched(runs);
  std::vector<ClaimResult> rows;
  const std::size_t levels = steps.size();
  for (std::size_t k = 0; k < settings.cases.size(); ++k) {
    const StressCase& sc = settings.cases[k];
    std::vector<double> ratios, raw_ratios, l2, raw_l2;
    double worst_ratio = 0, worst_l2 = -1e300;  // worst_l2: the largest stress/multiplier L² error ratio
    double fired_l2 = -1e300, kept_G = -1e300;  // the same where the gate picked the window; G where it did not
    std::string l2_text, gate_text;
    for (std::size_t l = 0; l < levels; ++l) {
      const repro::StressHistory& h = *measures[k * levels + l].stress_history;
      const repro::StressMeasures s = repro::stress_measures(h, stress);
      const repro::StressMeasures raw = repro::stress_measures(h, ContactStress::multiplier);
      const double G = total_variation(h.values(ContactStress::multiplier)) /
                       total_variation(h.values(ContactStress::window));  // the gate's indicator (§6)
      ratios.push_back(s.tv_ratio), raw_ratios.push_back(raw.tv_ratio);
      l2.push_back(s.l2_error), raw_l2.push_back(raw.l2_error);
      worst_ratio = std::max(worst_ratio, s.tv_ratio);
      worst_l2 = std::max(worst_l2, s.l2_error / raw.l2_error);
      if (G > gate_threshold)
        fired_l2 = std::max(fired_l2, s.l2_error / raw.l2_error);
      else
        kept_G = std::max(kept_G, G);
      l2_text += (l2_text.empty() ? "" : ", ") + significant(s.l2_error) + "/" + significant(raw.l2_error);
      gate_text +=
          (gate_text.empty() ? "" : " ") + significant(G) + (G > gate_threshold ? " (window)" : " (multiplier)");
    }
    const std::string where = "CN + Mod 3, " + sc.benchmark + ", dt = h/2, T = " + significant(horizon(sc));
    const std::string meshes = "N = " + std::to_string(settings.coarsest) + " ... " + std::to_string(settings.finest);
    std::string measured =
        "gate indicator G = TV(multiplier)/TV(window) at " + meshes + ": " + gate_text + "; TV ratio of " + name + ":";
    for (double r : ratios) measured += " " + significant(r);
    if (sc.jumps) {
      const double slope = -fit_order(steps, ratios).order;
      measured += " (slope " + decimals(slope, 3) + "; the multiplier's:";
      for (double r : raw_ratios) measured += " " + significant(r);
      measured += "); L2 errors stress/multiplier: " + l2_text;
      const Margin margin = tighter(tighter(at_most("largest TV ratio", worst_ratio, settings.ratio),
                                            at_most("slope of the TV ratio in N", slope, settings.slope)),
                                    at_most("largest L2 error ratio stress/multiplier", worst_l2, 1.0));
      rows.push_back(judge("7/stress/bounded/" + sc.key,
                           "The " + name +
                               " contact stress keeps TV(stress) / TV(lambda) bounded as the mesh is refined, with an "
                               "L2 error no larger than the multiplier's (" +
                               where + ")",
                           measured,
                           "ratio at most " + significant(settings.ratio) +
                               " on every mesh (a convention for bounded), slope at most " +
                               decimals(settings.slope, 3) +
                               " (half-way between the predicted 0 and the box window's 1/6), L2 error at most the "
                               "multiplier's on every mesh. Basis (theory): contact_stress.cpp sections 1-2",
                           margin));
    } else {
      const OrderFit own = fit_order(steps, l2), raw = fit_order(steps, raw_l2);
      const double sigma = std::hypot(own.order_std_error, raw.order_std_error);
      measured += "; L2 errors stress/multiplier: " + l2_text + "; L2 orders " + decimals(own.order, 3) + " +- " +
                  significant(own.order_std_error, 2) + " against the multiplier's " + decimals(raw.order, 3) + " +- " +
                  significant(raw.order_std_error, 2);
      // The margins of what can fail: the gate's distance from firing where it kept the multiplier, the
      // L² ratio where it picked the window, and then the order.
      std::optional<Margin> margin;
      auto add = [&](const Margin& m) { margin = margin ? tighter(*margin, m) : m; };
      if (kept_G > -1e300) add(at_most("largest G where the gate kept the multiplier", kept_G, gate_threshold));
      if (fired_l2 > -1e300) {
        add(at_most("largest L2 error ratio stress/multiplier where the gate picked the window", fired_l2, 1.0));
        add(at_least("L2 order", own.order, raw.order - 2 * sigma));
      }
      rows.push_back(judge("7/stress/smooth/" + sc.key,
                           "On a smooth benchmark the " + name +
                               " contact stress is as accurate as the multiplier and converges as fast (" + where + ")",
                           measured,
                           "on every mesh the gate keeps the multiplier (G at most " + significant(gate_threshold) +
                               ": the stress is the multiplier) or picks a window whose L2 error is at most the "
                               "multiplier's; where it picks the window, an L2 order at least the multiplier's less 2 "
                               "sigma (the two fits' combined standard error, " +
                               meshes +
                               "). Basis (theory): the window's bias O(delta^2 lambda'') on a smooth lambda, "
                               "contact_stress.cpp section 6",
                           *margin));
    }
  }
  return rows;
}

}  // namespace mrm::claims
