/// @file field_conjecture.cpp
/// @brief The conjectured orders of Crank–Nicolson with Mod 1/2/3 on the field's benchmarks.
///
/// From the regularity of each benchmark's exact solution and lib/studies/smeared_orders.cpp, with
/// Crank–Nicolson's phase order μ = 2 (crank_nicolson_phase_order at Δt = h/(2c), no blend):
///  - an impact, then a release (bouncing, impacting, layered, two-bars): the release is off by
///    δ = O(h^{2/3}) (release_shift_order), so u(0,·), u in L∞(L²) and in L²(L²) are order 2/3; λ jumps
///    at the release and u_t, u_x jump across the characteristics: order 1/3 for λ in L² and for the
///    energy-type measures (smeared_field_order with s = 1).
///  - a persistent contact under a sudden load (gravity-paper): u_x and u_t have kinks (s = 2: order 1
///    for λ and the energy-type measures) and so u has kinks of its derivative (s = 3: order 5/3 in L²).
///    Mod 2 scales every mass by w = L/(L − 2h/3) = 1 + 2h/(3L) + O(h²): a denser bar whose phase is off
///    by O(h), so its u in L² is order 1 there (on the bars with a release the same O(h) is below the
///    release's O(h^{2/3})). u(0,·) ≡ 0: no measure.
/// Written after a run: the earlier conjecture of these tables (1 for u and ½ for λ on the bars with a
/// release, 2 for u in L² on gravity-paper) assumed a release off by O(h); field_asymptotics' runs up to
/// N = 2560 missed it, and this derivation came after them. field_asymptotics keeps the earlier one
/// for the comparison.
#include "field_conjecture.hpp"

#include <stdexcept>
#include <string>
#include <vector>

#include "exact/impact_solution.hpp"
#include "measures/contact_stress.hpp"
#include "studies/smeared_orders.hpp"

namespace mrm::repro {

namespace {
enum Measure { u0_L2, lambda_L2, u_LinfL2, u_LinfH1, v_LinfL2, u_L2L2, u_L2H1, v_L2L2, measures };

// Crank–Nicolson's phase order at the runs' Δt = h/(2c), without a blend: μ = 2.
PhaseOrder runs_phase_order() { return crank_nicolson_phase_order(0.5, 0.0); }
}  // namespace

bool field_benchmark_releases(const std::string& benchmark) {
  const ImpactBenchmark& b = impact_benchmark(benchmark);
  const std::vector<ContactInterval> windows = exact_contact_windows(b.configuration, b.data, b.final_time);
  return !windows.empty() && !windows.front().open;
}

double field_release_order() { return release_shift_order(runs_phase_order()); }

double field_conjectured_order(const std::string& benchmark, const std::string& mass, std::size_t measure) {
  if (mass != "mod1" && mass != "mod2" && mass != "mod3")
    throw std::invalid_argument("field_conjectured_order: " + mass + " is not mod1, mod2 or mod3");
  if (measure >= measures)
    throw std::invalid_argument("field_conjectured_order: no measure " + std::to_string(measure));
  const PhaseOrder phase = runs_phase_order();
  const bool displacement = measure == u0_L2 || measure == u_LinfL2 || measure == u_L2L2;
  if (field_benchmark_releases(benchmark))
    return displacement ? release_shift_order(phase) : smeared_field_order(1, phase);
  if (measure == u0_L2) return 0;
  if (!displacement) return smeared_field_order(2, phase);
  return mass == "mod2" ? 1.0 : smeared_field_order(3, phase);
}

}  // namespace mrm::repro
