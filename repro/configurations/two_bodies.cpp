/// @file configurations/two_bodies.cpp
/// @brief Two bars in contact: two-bars reduced by symmetry to one bar, and the true two-body run.
#include "configurations/two_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "parallel.hpp"
#include "time/two_bodies.hpp"
#include "configurations.hpp"

namespace mrm::repro {

// two-bars by symmetry (doc/benchmarks.md: two identical free bars, L = 10, E = ρ = 1, touching, at ±0.1 toward
// each other). Each body in its own frame (ξ from its contact end, w positive away from the other body:
// lib/time/two_bodies.hpp) is a free bar with contact node 0 and ẇ⁰ = −0.1, the gap function between them
// z = w₀ᴬ + w₀ᴮ + g₀ ≥ 0, the same contact stress λ on both. The two bodies have the same mesh and mass, so
// every class's discrete step commutes with the exchange of the bodies: from symmetric data wᴬ = wᴮ = w at
// every level (in exact arithmetic), and each class reduces to a one-bar problem on w:
// - exact enforcement (cn, ps, ec, cn-switch, newmark, explicit, dke: its M-projection of the symmetric
//   two-body state onto z ≥ 0 splits equally) and the impact laws (moreau-jean,
//   taylor-flanagan: the relative velocity ż = 2ẇ₀, v⁺ = −ev⁻ on it is the same law on ẇ₀; equal masses
//   share the correction equally): z ≥ 0 ⇔ w₀ + g₀/2 ≥ 0, a rigid wall at g₀/2;
// - the penalty: the force (γ₀/h) min(0, z) on each body is (γ₀/h) min(0, 2(w₀ + g₀/2)) =
//   (2γ₀/h) min(0, w₀ + g₀/2): the one-bar penalty with γ₀' = 2γ₀ and the wall at g₀/2;
// - Nitsche with the averaged stress {σ} = ½(σᴬ + σᴮ) = σ (Chouly–Hild–Renard's two-body form; a
//   reconstruction: the project's two-body path has no Nitsche): P = γz + {σ} = 2γ(w₀ + g₀/2) + d·w is
//   the one-bar P' with γ' = 2γ; the force on body A, −(1/γ)[P]₋(γe₀ + (θ/2)d) (∂z/∂wᴬ = e₀, ∂{σ}/∂wᴬ =
//   d/2), equals −(1/γ')[P']₋(γ'e₀ + θd); the symmetric term (θ/γ){σ}∂{σ} = (θ/2γ)(d·w)d = (θ/γ')(d·w)d:
//   the one-bar Nitsche with γ₀' = 2γ₀ and the same θ.
// So two-bars runs as that one-bar problem (free bar L = 10, ẇ⁰ = −0.1, wall at g₀/2 = 0, the chain's
// exact solution seen from one body as the reference), labelled "by symmetry" where it is reported
// (fig_classes, claims_classes); the doctest of lib/classes/contact_classes.cpp checks the reduction against the
// true two-body run (two_bodies.hpp: CN + Mod 1/2/3).
std::shared_ptr<const ImpactBenchmark> two_bars_by_symmetry() {
  static const std::shared_ptr<const ImpactBenchmark> reduced = [] {
    ImpactBenchmark b = impact_benchmark("two-bars");
    const BarSegment one = b.configuration.segments.front();
    const double gap = b.configuration.junctions.front().gap;
    b.configuration.segments = {one};
    b.configuration.junctions.clear();
    b.configuration.obstacle = true;
    b.configuration.obstacle_gap = 0.5 * gap;
    b.data.pieces = {{0.0, one.length, {0.0}, {-b.data.pieces.front().velocity.front()}}};
    return std::make_shared<const ImpactBenchmark>(b);
  }();
  return reduced;
}

void reduce_two_bars_by_symmetry(Configuration& configuration) {
  configuration.field = two_bars_by_symmetry();
  if (configuration.scheme.scheme == Scheme::penalty) configuration.scheme.penalty *= 2;
  if (configuration.scheme.scheme == Scheme::nitsche) configuration.scheme.nitsche_gamma *= 2;
}
// Two bodies (two-bars; lib/time/two_bodies.hpp). The unit configuration's chain (the scaling of the field
// benchmarks above), each body in its own frame with its data read off the chain's exact solution at
// t = 0 (its own side of the junction), Crank–Nicolson, and the measures of run_configuration: each
// body's eight errors in its own frame against the chain's exact solution (TwoBodyReference: the same
// relative measures, since the frames only flip signs), the larger of the two per measure; the energy of
// the pair; the contact indicator s = w₁ᴬ + w₁ᴮ + g₀ (TwoBodySimulation::indicator, the one body's
// u₁ + hF₀) for the impacts and windows, with the chatter filter of one transit of the shorter body; the
// penetration −z; TV(λ) against the junction's exact stress.
Measures run_two_bodies(const Configuration& configuration) {
  const Scaling scaling = configuration_scaling(configuration);
  const Configuration c = unit_configuration(configuration, scaling);
  const ImpactBenchmark& b = *configuration_field(c);
  if (c.scheme.scheme != Scheme::crank_nicolson)
    throw InvalidParameter("scheme", b.id +
                                         ": two bodies coupled by one contact multiplier run with Crank-Nicolson "
                                         "only (allowed: cn)");
  for (const BarSegment& segment : b.configuration.segments)
    for (const double f : segment.load)
      if (f != 0.0) throw InvalidParameter("benchmark", b.id + ": two bodies take no load (lib/time/two_bodies.hpp)");
  // The multiplier is the one stress the two bodies' run reports: it keeps no history of the contact
  // stresses that lib/measures/contact_stress.hpp computes from one body's displacement (box, window, recovered).
  if (c.stress != ContactStress::multiplier || c.keep_stress_history)
    throw InvalidParameter("stress", b.id + ": " + to_string(c.stress) +
                                         ": the two bodies' run keeps no stress history (allowed: multiplier)");
  const double dt = c.step();
  Measures m;
  m.steps = c.steps >= 0 ? c.steps : steps_to_reach(c.final_time, dt);
  const std::vector<Index> levels = horizon_levels(c, dt);
  const auto chain = std::make_shared<const ImpactSolution>(b.configuration, b.data, reference_horizon(m.steps, dt));
  std::array<std::shared_ptr<const TwoBodyReference>, 2> exact;
  std::array<TwoBodyPart, 2> parts;
  for (int k = 0; k < 2; ++k) {
    exact[k] = std::make_shared<const TwoBodyReference>(chain, k);
    TwoBodyPart& part = parts[k];
    part.mesh = configuration_mesh(c, k);
    part.redistribution = c.mass;
    part.assembled = k == 0 ? c.assembled_mass : c.assembled_mass_body1;  // assembled once, or null
    const Index n = part.mesh.unknowns();
    part.displacement.resize(n);
    part.velocity.resize(n);
    for (Index i = 0; i < n; ++i) {
      part.displacement[i] = exact[k]->displacement(part.mesh.x(i), 0.0);
      part.velocity[i] = exact[k]->velocity(part.mesh.x(i), 0.0);
    }
  }
  TwoBodySimulation simulation(parts, b.configuration.junctions.front().gap, dt);
  std::array<ErrorAccumulator, 2> errors{ErrorAccumulator(simulation.mesh(0), exact[0]),
                                         ErrorAccumulator(simulation.mesh(1), exact[1])};
  const auto larger = [&] {
    const auto a = ErrorAccumulator::values(errors[0].relative()), e = ErrorAccumulator::values(errors[1].relative());
    ErrorNorms n = errors[0].relative();
    double* fields[8] = {&n.u0_L2,    &n.lambda_L2, &n.u_LinfL2, &n.u_LinfH1,
                         &n.v_LinfL2, &n.u_L2L2,    &n.u_L2H1,   &n.v_L2L2};
    for (std::size_t k = 0; k < 8; ++k) *fields[k] = std::max(a[k], e[k]);
    return n;
  };
  std::size_t next_horizon = 0;
  const double transit = std::min(b.configuration.segments[0].length, b.configuration.segments[1].length);
  ImpactDetector impacts(transit);
  double energy_min = std::numeric_limits<double>::infinity(), energy_max = -energy_min;
  double tv = 0, tv_exact = 0, lambda_previous = 0, exact_previous = 0, penetration = 0;
  for (Index n = 0;; ++n) {
    const double t = simulation.time(), lambda = simulation.multiplier(), energy = simulation.energy();
    for (int k = 0; k < 2; ++k) {
      const Sample s{n, t, &simulation.displacement(k), t, &simulation.velocity(k), true, t, lambda, t, energy};
      errors[k].add(s);
    }
    const double lambda_exact = chain->contact_stress(0, t);
    if (n > 0) tv += std::abs(lambda - lambda_previous), tv_exact += std::abs(lambda_exact - exact_previous);
    lambda_previous = lambda, exact_previous = lambda_exact;
    penetration = std::max(penetration, -simulation.gap());
    impacts.add(t, simulation.indicator());
    while (next_horizon < levels.size() && n == levels[next_horizon]) {
      m.horizon_errors.push_back(larger());
      ++next_horizon;
    }
    if (!std::isfinite(energy)) throw std::runtime_error("the run produced a non-finite energy");
    if (n == 0) m.energy_initial = energy;
    m.energy_final = energy;
    energy_min = std::min(energy_min, energy);
    energy_max = std::max(energy_max, energy);
    if (n == m.steps) break;
    simulation.step();
  }
  m.errors = larger();
  if (tv_exact > 0) m.lambda_tv_ratio = tv / tv_exact, m.stress_l2_error = m.errors.lambda_L2;
  m.stress = ContactStress::multiplier;
  if (!impacts.impacts().empty())
    m.phase = phase_from_contacts(impacts.impacts(), chain->contact_windows(0), chain->horizon(), transit);
  to_configuration_scale(m, scaling, energy_min, energy_max, penetration, impacts);
  return m;
}

}  // namespace mrm::repro
