// The Δt study over a family of meshes (time_family.hpp).
//
// The protocol on one mesh (h = 1/N, the benchmark, T = 3 rounded up to a whole largest step).
// Crank–Nicolson with Δt_j = P h / 2^j (P = 4, down to Δt_ref·16 = h/128) is compared with a reference
// of the same mesh and mass, Δt_ref = h/R (R = 2048), at the instants they share, in the eight measures
// of mathematics.md §5 (ReferenceComparison). The reference is checked against a finer one (h/2R): with
// the reference at order 2, its own error is ‖ref − exact‖ ≈ (4/3)‖ref − finer‖ (Richardson), the
// bound b printed per measure.
//
// What is judged, and why (derived before the data).
// - The asymptotic range. The trapezoidal rule's local error is O(ω³Δt³) for a mode of frequency ω;
//   the global error is C Δt² only once ω_max Δt ≲ 1 for the mesh's highest frequency, ω_max = 2/h for
//   the redistributed masses (the lumped-type rows: ω² ≤ 4/h² · c²). So every halving Δt → Δt/2 with
//   Δt ≤ h/2 is judged (h/2 → h/4, …, h/64 → h/128: six halvings), not the finest alone; the coarser ones
//   are printed (pre-asymptotic, no prediction).
// - The floor. A measured error e is the true one up to the reference's, ±b: a local order
//   log₂(e_j/e_{j+1}) moves by at most log₂((1 + 1/F)/(1 − 1/F)) when both errors are ≥ F b; F = 20
//   gives 0.144, inside the tolerance. A halving below the floor is not judged (and is said so).
// - The tolerance. |p − 2| ≤ ¼: half the distance to 1.5, the order a one-step misplacement of a
//   switch would give in L²_t (O(Δt^{3/2})); an error constant C that fluctuates with the position of
//   the switches on the grid moves a local order by log₂(C_j/C_{j+1}), within ¼ for a change of up to
//   2^¼ ≈ 1.19 per halving (fig_time_error's header derives the same for its fitted order).
// - The measures that cannot converge on all levels. The massless node's velocity is V₀ = V₁ + hḞ₀
//   while free and 0 in contact (mathematics.md §7): it jumps by |V₁| ≈ ½ at every impact and
//   release. At a level that falls between the run's switch and the reference's (they differ by
//   O(Δt²)), the two velocities differ by ≈ ½ at node 0, weighted by h/3 in the P1 norm: the
//   L∞-in-time velocity error is then ≈ (h/12)^½ / ‖V‖ whatever Δt (0.09 on N = 40), and the L²-in-time
//   one O(Δt^½); whether such a level exists depends on where the grid falls, not on Δt → 0. These
//   measures (uₜ L∞L², uₜ L²L²) have no order on all levels; they are judged on the levels where both
//   runs are in the same contact state, where V₀ is the same function of the state in both (the
//   all-levels values are printed beside). The displacement measures, u₀ and λ are continuous in time
//   (u₀ = max(0, u₁ + hF₀), λ continuous with the massless node) and are judged on all levels.
// - The verdict on a mesh, per measure: every judged halving within the tolerance (and at least one
//   judged).
#include "time_family.hpp"

#include <cmath>
#include <memory>
#include <stdexcept>

#include "batched/batched_step.hpp"
#include "studies/convergence.hpp"
#include "measures/errors.hpp"

namespace mrm::repro {

bool judged_on_matched_levels(std::size_t measure) {
  const std::string name = ErrorAccumulator::names[measure];
  return name == "err_v_LinfL2" || name == "err_v_L2L2";
}

const std::array<double, 8>& TimeFamilyMesh::judged_errors(std::size_t j, std::size_t measure) const {
  return judged_on_matched_levels(measure) ? matched[j] : all[j];
}

namespace {

bool in_contact(const Sample& s) { return s.has_multiplier && s.multiplier < 0; }

}  // namespace

TimeFamilyMesh time_family_mesh(long elements, const MassRedistribution& mass, const SchemeParameters& parameters,
                                const TimeFamilySettings& st) {
  const UniformMesh mesh(1.0, elements);
  const double h = mesh.h();
  const long r = st.reference_ratio;
  const double dt_fine = h / static_cast<double>(2 * r);
  // The steps in units of the finer reference's: 2 P R / 2^j, down to 2 · finest_divisor.
  std::vector<long> ratio;
  const double first = 2 * st.largest_courant * static_cast<double>(r);
  if (!(first >= 1 && std::abs(first - std::round(first)) <= 1e-9 * first))
    throw std::invalid_argument("time family: the largest step is not a whole number of reference steps");
  for (long m = std::lround(first); m >= 2 * st.finest_divisor && m % 2 == 0; m /= 2) ratio.push_back(m);
  if (ratio.size() < 2) throw std::invalid_argument("time family: fewer than two steps");
  const Index coarse_steps = steps_to_reach(st.final_time, static_cast<double>(ratio[0]) * dt_fine);
  const Index fine_steps = coarse_steps * ratio[0];
  TimeFamilyMesh out;
  out.elements = elements;
  out.final_time_used = static_cast<double>(fine_steps) * dt_fine;

  // The finer reference and the reference: from N = 100 on, in two vector lanes of one batch, the
  // reference stepping at every other step (BatchedSimulation::step(advance): each lane bitwise its run
  // stepped alone), compared where they are (ReferenceComparison::measure on the lanes, nothing copied
  // out). On smaller meshes the batch's bookkeeping per step costs more than the lanes save (measured with
  // T = 1, CPU time of time_family_mesh against the two chains stepped alone: 1.05–1.4 at N = 24, 40, 64,
  // 0.9–1.2 at 96 and 128, 0.59–0.94 at 256; a noisy host, so the crossover is only located, not fitted):
  // there each chain is a batch of its own, stepped alone. Either way, the same bits.
  const bool in_lanes = elements >= 100;
  std::vector<BatchedSimulation> chains;  // one batch of both chains, or one batch each
  {
    std::vector<BarSimulation> both_chains;
    both_chains.emplace_back(benchmark_problem(), mesh, mass, parameters, dt_fine);
    both_chains.emplace_back(benchmark_problem(), mesh, mass, parameters, 2 * dt_fine);
    if (in_lanes) {
      chains.emplace_back(std::move(both_chains));
    } else {
      for (BarSimulation& chain : both_chains) {
        std::vector<BarSimulation> one;
        one.push_back(std::move(chain));
        chains.emplace_back(std::move(one));
      }
    }
  }
  const std::vector<char> finer_only = {1, 0}, both = {1, 1};
  const auto chain_step = [&](bool reference_too) {
    if (in_lanes) return chains[0].step(reference_too ? both : finer_only);
    chains[0].step();
    if (reference_too) chains[1].step();
  };
  const auto chain_sample = [&](std::size_t j, LaneVectors& lanes) {  // 0: the finer, 1: the reference
    return in_lanes ? chains[0].sample(j, lanes) : chains[j].sample(0, lanes);
  };
  LaneVectors fine_lanes{}, reference_lanes{};
  std::vector<std::unique_ptr<BarSimulation>> runs;
  std::vector<ReferenceComparison> all, matched;
  for (long m : ratio) {
    runs.push_back(
        std::make_unique<BarSimulation>(benchmark_problem(), mesh, mass, parameters, static_cast<double>(m) * dt_fine));
    out.dt.push_back(static_cast<double>(m) * dt_fine);
  }
  ratio.push_back(2);  // the reference, checked against the finer one: the last comparison
  out.mismatched.assign(ratio.size(), 0);
  for (std::size_t j = 0; j < ratio.size(); ++j) {
    all.emplace_back(mesh);
    matched.emplace_back(mesh);
    const Sample fine = chain_sample(0, fine_lanes);
    LaneVectors lanes{};
    const Sample s = j + 1 < ratio.size() ? runs[j]->sample() : chain_sample(1, lanes);
    if (j + 1 < ratio.size()) lanes = own_lanes(s);
    const ReferenceComparison::Level level = all.back().measure(s, lanes, fine, fine_lanes);
    all.back().add(level);
    matched.back().add(level);
  }
  // The runs compare with the finer reference's samples only through the reference: run j against
  // the reference (h/R) at its levels, the reference against the finer one.
  for (Index k = 1; k <= fine_steps; ++k) {
    chain_step(k % 2 == 0);
    if (k % 2 != 0) continue;
    const Sample ref = chain_sample(1, reference_lanes), fine = chain_sample(0, fine_lanes);
    const std::size_t last = ratio.size() - 1;
    // One measurement per level for both comparisons (the same numbers, measured once).
    const ReferenceComparison::Level reference_level = all[last].measure(ref, reference_lanes, fine, fine_lanes);
    all[last].add(reference_level);
    if (in_contact(ref) == in_contact(fine))
      matched[last].add(reference_level);
    else
      ++out.mismatched[last];
    for (std::size_t j = 0; j < last; ++j) {
      if (k % ratio[j] != 0) continue;
      runs[j]->step();
      const Sample run = runs[j]->sample();
      const ReferenceComparison::Level level = all[j].measure(run, own_lanes(run), ref, reference_lanes);
      all[j].add(level);
      if (in_contact(run) == in_contact(ref))
        matched[j].add(level);
      else
        ++out.mismatched[j];
    }
  }
  const std::size_t steps = ratio.size() - 1;
  for (std::size_t j = 0; j < steps; ++j) {
    out.all.push_back(all[j].relative());
    out.matched.push_back(matched[j].relative());
    if (out.mismatched[j] > 0) out.velocity_jump_sampled = true;
  }
  out.reference_mismatched = out.mismatched[steps];
  out.mismatched.pop_back();
  const std::array<double, 8> ref_all = all[steps].relative(), ref_matched = matched[steps].relative();
  for (std::size_t q = 0; q < 8; ++q)
    out.reference_bound[q] = 4.0 / 3.0 * (judged_on_matched_levels(q) ? ref_matched[q] : ref_all[q]);
  for (const auto* block : {&out.all, &out.matched})
    for (const auto& e : *block)
      for (double v : e)
        if (!std::isfinite(v))
          throw std::runtime_error("time family: a non-finite error on N = " + std::to_string(elements));
  for (double b : out.reference_bound)
    if (!std::isfinite(b)) throw std::runtime_error("time family: a non-finite reference bound");

  // The local orders and the verdicts.
  for (std::size_t q = 0; q < 8; ++q) {
    out.lowest[q] = HUGE_VAL;
    out.highest[q] = -HUGE_VAL;
    bool holds = true;
    for (std::size_t j = 0; j + 1 < steps; ++j) {
      const double a = out.judged_errors(j, q)[q], b = out.judged_errors(j + 1, q)[q];
      const double p = a > 0 && b > 0 ? std::log2(a / b) / std::log2(out.dt[j] / out.dt[j + 1]) : std::nan("");
      const bool judged =
          out.dt[j] <= st.asymptotic_courant * h * (1 + 1e-12) && b >= st.floor_factor * out.reference_bound[q];
      out.local[q].push_back(p);
      out.judged[q].push_back(judged);
      if (!judged) continue;
      ++out.judged_count[q];
      if (!std::isfinite(p)) {
        holds = false;
        continue;
      }
      out.lowest[q] = std::min(out.lowest[q], p);
      out.highest[q] = std::max(out.highest[q], p);
      holds = holds && std::abs(p - st.predicted_order) <= st.tolerance;
    }
    out.holds[q] = holds && out.judged_count[q] > 0;
    // The onset: walk back from the finest halving while the halvings hold (below the floor: skipped).
    std::size_t onset = steps - 1;
    for (std::size_t j = steps - 1; j-- > 0;) {
      const double p = out.local[q][j];
      const bool floor = out.judged_errors(j + 1, q)[q] < st.floor_factor * out.reference_bound[q];
      if (!floor && !(std::abs(p - st.predicted_order) <= st.tolerance)) break;
      onset = j;
    }
    out.onset[q] = onset;
  }
  return out;
}

std::vector<long> time_family_meshes(long from, long to, long by, long powers_to) {
  if (!(from >= 2 && to >= from && by >= 1)) throw std::invalid_argument("time family: bad mesh range");
  std::vector<long> meshes;
  for (long n = from; n <= to; n += by) meshes.push_back(n);
  for (long p = 2; p <= powers_to; p *= 2)
    if (p > to) meshes.push_back(p);
  return meshes;
}

}  // namespace mrm::repro
