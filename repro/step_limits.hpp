/// @file step_limits.hpp
/// @brief What bounds the batched step from below on this machine (bench_step): the time
/// of its memory traffic alone and the rate of its arithmetic alone, each measured at the vector target
/// the batched step uses (step_limits.cpp).
///
/// The batched step (lib/batched/batched_step.cpp) does two things per node, step and run: it moves bytes (the
/// state and the sweeps' intermediate, 64 bytes on the plateau of the factors, 104 off it) and it
/// performs about 32 double operations (bench_step.cpp counts them). Neither can take less time than it
/// takes the machine to do it with nothing else in the way, so the larger of the two is a limit for the
/// step. A byte count divided by a bandwidth is not that limit: which level of the cache the bytes come
/// from depends on the order of the accesses (the sweep up starts on the rows the sweep down has just
/// written). The traffic of the step is therefore timed itself, as a skeleton: the same loads and stores
/// in the same order over arrays of the same layout, with the arithmetic replaced by lane-wise maxima
/// (one per loaded value, no chain from row to row, values that cannot grow).
#pragma once

#include <cstddef>
#include <memory>

namespace mrm::repro {

/// The arrays of one group of the batched step (interleaved: row i of lane j at i·lanes + j, `n` rows),
/// and the plateau [plateau_begin, plateau_end) of its factors, where the step holds them in registers
/// and the skeleton does not load them.
struct TrafficArrays {
  std::size_t n = 0, lanes = 0, plateau_begin = 0, plateau_end = 0;
  double *u = nullptr, *w = nullptr, *y = nullptr;                   // the state and the sweeps' intermediate
  const double *elimination = nullptr, *elimination_pair = nullptr;  // read by the sweep down
  const double *inverse_pivot = nullptr, *upward = nullptr, *upward_pair = nullptr;  // read by the sweep up
};

/// The lanes of the vector target now chosen (lib/batched/batched_step.hpp, use_batch_target).
std::size_t limit_lanes();

/// One step's memory traffic of the two-level batched step (Crank–Nicolson) on its interior rows, on the
/// target now chosen: the sweep down from row n−2 to 1 reads uᵢ₋₁, uᵢ, uᵢ₊₁, wᵢ₋₁, wᵢ, wᵢ₊₁ (and off the
/// plateau εᵢ, its pair product) and writes yᵢ; the sweep up from row 1 to n−2 reads yᵢ, uᵢ, wᵢ (and off
/// the plateau 1/pᵢ, ℓᵢ/pᵢ, its pair product) and writes yᵢ and wᵢ. Rows 0 and n−1 (the contact row and
/// the last one, two of n) are left out. The caller swaps u and y after it, as the step does. Every
/// stored value is the maximum of the values the row loaded.
void traffic_step(const TrafficArrays& arrays);

/// The arrays of one group for traffic_step, owned: `n` rows of limit_lanes() lanes (every value ½), each
/// at the page offset of the step's array (lib/batched/lane_array.hpp), or with `spacing` > 0 (a multiple of
/// 64) the k-th at k·spacing bytes modulo 4096 (arrays that alias a few rows apart, as an allocator may place
/// them); the plateau [1, 1 + plateau_rows) (where it lies does not change the traffic). step() is one
/// step's traffic followed by the exchange of u and y.
class TrafficSkeleton {
 public:
  TrafficSkeleton(std::size_t n, std::size_t plateau_rows, std::size_t spacing = 0);
  ~TrafficSkeleton();
  void step();
  std::size_t lanes() const;

 private:
  struct Store;
  std::unique_ptr<Store> store_;
};

/// `rounds` rounds of the step's kind of arithmetic at the full rate of the target now chosen: twelve
/// independent chains aᵢ ← aᵢ·m + c (a multiply and an add, not fused, as the step's), 24 vector
/// operations per round; returns the sum of the chains' last values (so that nothing is left out).
double arithmetic_rounds(long rounds, double m, double c);
/// The vector operations of one round of arithmetic_rounds.
inline constexpr double arithmetic_operations_per_round = 24;

}  // namespace mrm::repro
