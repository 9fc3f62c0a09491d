/// @file step_limits.cpp
/// @brief The two limits of the batched step, measured (step_limits.hpp): its memory traffic as a
/// skeleton of its two sweeps, and its kind of arithmetic at the full rate of the vector target.
#include "step_limits.hpp"

#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "step_limits.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace mrm::repro::limits {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;

std::size_t LaneCount() { return hn::Lanes(D()); }

// The skeleton of lib/batched/batched_step.cpp's SweepDown and SweepUpT<false, false> on the interior rows (the
// few head and last rows are left out): the same loads and stores, row for row, in the same order, each
// row's arithmetic replaced by the maximum of what it loaded. The plateau's factors are loaded once, as
// the step holds them in registers.
void TrafficStep(const TrafficArrays& a) {
  const D d;
  const std::size_t W = a.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(a.n);
  const std::ptrdiff_t begin = static_cast<std::ptrdiff_t>(a.plateau_begin),
                       end = static_cast<std::ptrdiff_t>(a.plateau_end);
  const auto at = [&](const double* p, std::ptrdiff_t i) { return hn::Load(d, p + static_cast<std::size_t>(i) * W); };
  const auto put = [&](V v, double* p, std::ptrdiff_t i) { hn::Store(v, d, p + static_cast<std::size_t>(i) * W); };
  const bool plateau = begin < end;
  const V e_flat = plateau ? at(a.elimination, begin) : hn::Zero(d);
  const V ep_flat = plateau ? at(a.elimination_pair, begin) : hn::Zero(d);
  const V q_flat = plateau ? at(a.inverse_pivot, begin) : hn::Zero(d);
  const V c_flat = plateau ? at(a.upward, begin) : hn::Zero(d);
  const V cp_flat = plateau ? at(a.upward_pair, begin) : hn::Zero(d);

  // The sweep down, rows n−2 … 1: off the plateau the factors are loaded, on it they are the registers'.
  const auto down = [&](std::ptrdiff_t i, V e, V ep) {
    const V m = hn::Max(hn::Max(hn::Max(at(a.u, i - 1), at(a.u, i + 1)), at(a.u, i)),
                        hn::Max(hn::Max(at(a.w, i - 1), at(a.w, i + 1)), at(a.w, i)));
    put(hn::Max(m, hn::Max(e, ep)), a.y, i);
  };
  const auto down_loading = [&](std::ptrdiff_t i) { down(i, at(a.elimination, i), at(a.elimination_pair, i)); };
  std::ptrdiff_t i = n - 2;
  for (; i >= std::max<std::ptrdiff_t>(end, 1); --i) down_loading(i);
  for (; i >= std::max<std::ptrdiff_t>(begin, 1); --i) down(i, e_flat, ep_flat);
  for (; i >= 1; --i) down_loading(i);

  // The sweep up, rows 1 … n−2: it writes the new state over y (the caller swaps u and y) and w.
  const auto up = [&](std::ptrdiff_t i, V q, V c, V cp) {
    const V t = hn::Max(hn::Max(at(a.y, i), at(a.u, i)), hn::Max(q, hn::Max(c, cp)));
    const V wi = at(a.w, i);
    put(t, a.y, i);
    put(hn::Max(wi, t), a.w, i);
  };
  const auto up_loading = [&](std::ptrdiff_t i) {
    up(i, at(a.inverse_pivot, i), at(a.upward, i), at(a.upward_pair, i));
  };
  i = 1;
  for (; i < std::min(begin, n - 1); ++i) up_loading(i);
  for (; i < std::min(end, n - 1); ++i) up(i, q_flat, c_flat, cp_flat);
  for (; i < n - 1; ++i) up_loading(i);
}

// Twelve independent chains a ← a·m + c: twelve multiplies and twelve adds per round, enough chains in
// flight to hide the latency of both on the machines this runs on (four cycles, two units: eight chains
// of two operations would do; twelve leave a margin).
double ArithmeticRounds(long rounds, double m, double c) {
  const D d;
  const V mv = hn::Set(d, m), cv = hn::Set(d, c);
  V a0 = hn::Set(d, 0), a1 = hn::Set(d, 1), a2 = hn::Set(d, 2), a3 = hn::Set(d, 3), a4 = hn::Set(d, 4),
    a5 = hn::Set(d, 5), a6 = hn::Set(d, 6), a7 = hn::Set(d, 7), a8 = hn::Set(d, 8), a9 = hn::Set(d, 9),
    a10 = hn::Set(d, 10), a11 = hn::Set(d, 11);
  for (long r = 0; r < rounds; ++r) {
    a0 = a0 * mv + cv, a1 = a1 * mv + cv, a2 = a2 * mv + cv, a3 = a3 * mv + cv;
    a4 = a4 * mv + cv, a5 = a5 * mv + cv, a6 = a6 * mv + cv, a7 = a7 * mv + cv;
    a8 = a8 * mv + cv, a9 = a9 * mv + cv, a10 = a10 * mv + cv, a11 = a11 * mv + cv;
  }
  const V sum = a0 + a1 + a2 + a3 + a4 + a5 + a6 + a7 + a8 + a9 + a10 + a11;
  return hn::GetLane(sum);
}

}  // namespace HWY_NAMESPACE
}  // namespace mrm::repro::limits
HWY_AFTER_NAMESPACE();

#if HWY_ONCE

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>
#include <vector>

#include <doctest/doctest.h>
#include <hwy/aligned_allocator.h>

#include "batched/batched_step.hpp"
#include "batched/lane_array.hpp"

namespace mrm::repro {
namespace limits {
HWY_EXPORT(LaneCount);
HWY_EXPORT(TrafficStep);
HWY_EXPORT(ArithmeticRounds);
}  // namespace limits

std::size_t limit_lanes() { return HWY_DYNAMIC_DISPATCH(limits::LaneCount)(); }

void traffic_step(const TrafficArrays& arrays) {
  if (arrays.lanes != limit_lanes()) throw std::logic_error("traffic_step: the arrays are not of the target's lanes");
  HWY_DYNAMIC_DISPATCH(limits::TrafficStep)(arrays);
}

struct TrafficSkeleton::Store {
  std::vector<batched::LaneArray> arrays;
  TrafficArrays a;
};

TrafficSkeleton::TrafficSkeleton(std::size_t n, std::size_t plateau_rows, std::size_t spacing)
    : store_(std::make_unique<Store>()) {
  TrafficArrays& a = store_->a;
  a.n = n, a.lanes = limit_lanes(), a.plateau_begin = 1, a.plateau_end = std::min(n, 1 + plateau_rows);
  // The step's arrays where its group puts them (batched/lane_array.hpp): a group allocates U, y, W′, X, ε,
  // εε, 1/p, c, cc in that order, slots 0 … 8 (X, slot 3, is the three-level step's and is not streamed here);
  // or slot k at k·spacing bytes.
  for (std::size_t slot = 0; slot < 9; ++slot) {
    store_->arrays.emplace_back(n * a.lanes, spacing ? slot * spacing % 4096 : batched::lane_array_offset(slot));
    std::fill(store_->arrays.back().get(), store_->arrays.back().get() + n * a.lanes, 0.5);
  }
  auto& v = store_->arrays;
  a.u = v[0].get(), a.y = v[1].get(), a.w = v[2].get();
  a.elimination = v[4].get(), a.elimination_pair = v[5].get();
  a.inverse_pivot = v[6].get(), a.upward = v[7].get(), a.upward_pair = v[8].get();
}

TrafficSkeleton::~TrafficSkeleton() = default;

void TrafficSkeleton::step() {
  traffic_step(store_->a);
  std::swap(store_->a.u, store_->a.y);
}

std::size_t TrafficSkeleton::lanes() const { return store_->a.lanes; }

double arithmetic_rounds(long rounds, double m, double c) {
  return HWY_DYNAMIC_DISPATCH(limits::ArithmeticRounds)(rounds, m, c);
}

TEST_CASE("the traffic skeleton stores, row by row, the maximum of what the batched step's sweeps load there") {
  // On every target with at least two lanes: n = 12 rows, the plateau [4, 8). Row i of lane j holds
  // distinct numbers in every array; the sweep down stores in yᵢ the maximum of uᵢ₋₁…uᵢ₊₁, wᵢ₋₁…wᵢ₊₁
  // and of the factors it uses (row i's, or row 4's on the plateau), the sweep up the maximum of that,
  // uᵢ and its factors in yᵢ, and max(wᵢ, yᵢ) in wᵢ; rows 0 and n−1 are not touched.
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    const std::size_t n = 12, W = limit_lanes();
    REQUIRE(W == target.lanes);
    std::vector<std::vector<double>> v(8, std::vector<double>(n * W));
    for (std::size_t k = 0; k < 8; ++k)
      for (std::size_t r = 0; r < n * W; ++r) v[k][r] = std::sin(1.0 + static_cast<double>(k * 131 + r));
    std::vector<hwy::AlignedFreeUniquePtr<double[]>> arrays;
    for (std::size_t k = 0; k < 8; ++k) {
      arrays.push_back(hwy::AllocateAligned<double>(n * W));
      std::copy(v[k].begin(), v[k].end(), arrays[k].get());
    }
    TrafficArrays a;
    a.n = n, a.lanes = W, a.plateau_begin = 4, a.plateau_end = 8;
    a.u = arrays[0].get(), a.w = arrays[1].get(), a.y = arrays[2].get();
    a.elimination = arrays[3].get(), a.elimination_pair = arrays[4].get();
    a.inverse_pivot = arrays[5].get(), a.upward = arrays[6].get(), a.upward_pair = arrays[7].get();
    traffic_step(a);
    for (std::size_t j = 0; j < W; ++j)
      for (std::size_t i = 0; i < n; ++i) {
        const auto of = [&](std::size_t k, std::size_t row) { return v[k][row * W + j]; };
        const std::size_t f = i >= 4 && i < 8 ? 4 : i;
        double y = of(2, i), w = of(1, i);
        if (i >= 1 && i + 1 < n) {
          const double down = std::max(
              {of(0, i - 1), of(0, i), of(0, i + 1), of(1, i - 1), of(1, i), of(1, i + 1), of(3, f), of(4, f)});
          y = std::max({down, of(0, i), of(5, f), of(6, f), of(7, f)});
          w = std::max(w, y);
        }
        CAPTURE(i);
        CHECK(arrays[2][i * W + j] == y);
        CHECK(arrays[1][i * W + j] == w);
      }
  }
  use_batch_target(0);
}

TEST_CASE("the arithmetic rounds are twelve chains a <- a m + c, as many rounds as asked") {
  // Chain k starts at k; after r rounds the twelve values, summed in order, are the scalar ones bit for
  // bit (lane-wise IEEE operations, no fused multiply-add).
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const long rounds : {0L, 1L, 7L, 100L}) {
      double chains[12], sum = 0;
      for (int k = 0; k < 12; ++k) chains[k] = k;
      for (long r = 0; r < rounds; ++r)
        for (double& a : chains) a = a * 0.75 + 0.5;
      for (const double a : chains) sum += a;
      CHECK(arithmetic_rounds(rounds, 0.75, 0.5) == sum);
    }
  }
  use_batch_target(0);
}

}  // namespace mrm::repro

#endif  // HWY_ONCE
