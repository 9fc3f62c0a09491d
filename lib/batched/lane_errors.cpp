/// @file lane_errors.cpp
/// @brief The error measures of a level of a batch's runs in one pass over the nodes
/// (ErrorAccumulator::add_lanes): the lanes' error sums on vectors of lanes (Google Highway), each lane
/// with the bits of the run's own accumulator.
#include "measures/errors.hpp"

#include <cstddef>

/// @cond MRM_INTERNAL (the Highway plumbing of the one-pass sums of a batch's lanes, add_lanes)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batched/lane_errors.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>
/// @endcond

#if HWY_ONCE
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <memory>
#include <random>
#include <utility>
#include <vector>

#include <doctest/doctest.h>

#include "batched/batched_step.hpp"
#include "batched/kernels.hpp"
#include "exact/characteristics.hpp"
#include "measures/error_sums.hpp"
#endif  // HWY_ONCE

// The error's sums of W runs at once (add_lanes): runs of one batch, their entries interleaved (node i of
// lane j at w[i·W + j], lib/batched/batched_step.hpp), against the same closed-form runs. error_run_sums' arithmetic,
// operation for operation, on vectors of lanes (every operation lane-wise, IEEE-754 rounding as the scalar
// one, no contraction into fused multiply-adds: -ffp-contract=off and no MulAdd here), so lane j gets
// the bits error_run_sums gives for the run alone; the lane-independent values (a + b x_i, b (x_i − x_{i−1}))
// are formed once, as scalars, as there. One pass over the nodes instead of one per lane, each node's
// lanes one aligned load (Google Highway: the widest target of the processor, chosen at run time, as
// for the batched step).
/// @cond MRM_INTERNAL (the kernel: not part of the library's interface)
HWY_BEFORE_NAMESPACE();
namespace mrm::error_lanes {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Templates over the vector tag D: the full width of the target and the capped widths of 4 and 2
// doubles, for the lanes of a batch's narrower groups (strides 4 and 2, lib/batched/batched_step.cpp). The same
// operations in the same order at every width.
using Full = hn::ScalableTag<double>;
using Four = hn::CappedTag<double, 4>;
using Two = hn::CappedTag<double, 2>;

// Lanes 0 … W−1 (W a multiple of Lanes(d)): their e₀, e_{n−1}, D and Q in e0[j], last[j], ...
template <class D>
void LaneRunSumsT(D d, const double* w, std::size_t W, const double* x, const ExactSolution::AffineRun* runs, int count,
                  double* e0_out, double* last_out, double* differences_out, double* squares_out) {
  using V = hn::Vec<D>;
  for (std::size_t c = 0; c < W; c += hn::Lanes(d)) {
    const double* wc = w + c;
    const auto at = [&](long i) { return hn::LoadU(d, wc + static_cast<std::size_t>(i) * W); };
    const V e0 = at(0) - hn::Set(d, runs[0].intercept + runs[0].slope * x[0]);
    V ed = hn::Zero(d), es = hn::Zero(d), e_prev = e0;
    for (int k = 0; k < count; ++k) {
      const double a = runs[k].intercept, b = runs[k].slope;
      const long first = std::max(runs[k].first, 1L), end = runs[k].end;
      if (first >= end) continue;
      {
        const V e = at(first) - hn::Set(d, a + b * x[first]), de = e - e_prev;
        ed = ed + de * de, es = es + e * e;
      }
      V d0 = hn::Zero(d), d1 = d0, s0 = d0, s1 = d0;
      long i = first + 1;
      if (b == 0) {
        const V av = hn::Set(d, a);
        V wp = at(i - 1);
        for (; i + 1 < end; i += 2) {
          const V wi = at(i), wn = at(i + 1);
          const V de0 = wi - wp, e0i = wi - av, de1 = wn - wi, e1i = wn - av;
          d0 = d0 + de0 * de0, s0 = s0 + e0i * e0i;
          d1 = d1 + de1 * de1, s1 = s1 + e1i * e1i;
          wp = wn;
        }
        if (i < end) {
          const V wi = at(i), de = wi - wp, e = wi - av;
          d0 = d0 + de * de, s0 = s0 + e * e;
        }
      } else {
        const auto term = [&](long j, V wi, V wp, V& de, V& e) {
          de = (wi - wp) - hn::Set(d, b * (x[j] - x[j - 1]));
          e = wi - hn::Set(d, a + b * x[j]);
        };
        V wp = at(i - 1);
        for (; i + 1 < end; i += 2) {
          const V wi = at(i), wn = at(i + 1);
          V de0, e0i, de1, e1i;
          term(i, wi, wp, de0, e0i);
          term(i + 1, wn, wi, de1, e1i);
          d0 = d0 + de0 * de0, s0 = s0 + e0i * e0i;
          d1 = d1 + de1 * de1, s1 = s1 + e1i * e1i;
          wp = wn;
        }
        if (i < end) {
          V de, e;
          term(i, at(i), wp, de, e);
          d0 = d0 + de * de, s0 = s0 + e * e;
        }
      }
      ed = ed + (d0 + d1), es = es + (s0 + s1);
      e_prev = at(end - 1) - hn::Set(d, a + b * x[end - 1]);
    }
    hn::StoreU(e0, d, e0_out + c);
    hn::StoreU(e_prev, d, last_out + c);
    hn::StoreU(ed, d, differences_out + c);
    hn::StoreU(es, d, squares_out + c);
  }
}

// Lanes 0 … W−1 (W a multiple of Lanes(d)) against one interpolant w_I (wi, n entries: a reference
// other than the closed form, evaluated once for the lanes at the same instant): add_vectors' sums of
// the error e = W − w_I, lane-wise in its order, e₀, e_{n−1}, D and Q in e0[j], last[j], ...
template <class D>
void LaneInterpolantSumsT(D d, const double* w, std::size_t W, const double* wi, long n, double* e0_out,
                          double* last_out, double* differences_out, double* squares_out) {
  using V = hn::Vec<D>;
  for (std::size_t c = 0; c < W; c += hn::Lanes(d)) {
    const double* wc = w + c;
    const auto at = [&](long i) { return hn::LoadU(d, wc + static_cast<std::size_t>(i) * W); };
    const V e0 = at(0) - hn::Set(d, wi[0]);
    V ed = hn::Zero(d), es = hn::Zero(d), e_prev = e0;
    for (long i = 1; i < n; ++i) {
      const V e = at(i) - hn::Set(d, wi[i]), de = e - e_prev;
      ed = ed + de * de, es = es + e * e;
      e_prev = e;
    }
    hn::StoreU(e0, d, e0_out + c);
    hn::StoreU(e_prev, d, last_out + c);
    hn::StoreU(ed, d, differences_out + c);
    hn::StoreU(es, d, squares_out + c);
  }
}

// The entry points, one per width (where a capped width is the full one, the same code twice).
#define MRM_LANE_SUMS(suffix, Tag)                                                                                     \
  void LaneRunSums##suffix(const double* w, std::size_t W, const double* x, const ExactSolution::AffineRun* runs,      \
                           int count, double* e0, double* last, double* differences, double* squares) {                \
    LaneRunSumsT(Tag(), w, W, x, runs, count, e0, last, differences, squares);                                         \
  }                                                                                                                    \
  void LaneInterpolantSums##suffix(const double* w, std::size_t W, const double* wi, long n, double* e0, double* last, \
                                   double* differences, double* squares) {                                             \
    LaneInterpolantSumsT(Tag(), w, W, wi, n, e0, last, differences, squares);                                          \
  }
MRM_LANE_SUMS(, Full)
MRM_LANE_SUMS(4, Four)
MRM_LANE_SUMS(2, Two)
#undef MRM_LANE_SUMS

}  // namespace HWY_NAMESPACE
}  // namespace mrm::error_lanes
HWY_AFTER_NAMESPACE();
/// @endcond

#if HWY_ONCE
namespace mrm {
/// @cond MRM_INTERNAL
namespace error_lanes {
HWY_EXPORT(LaneRunSums);
HWY_EXPORT(LaneRunSums4);
HWY_EXPORT(LaneRunSums2);
HWY_EXPORT(LaneInterpolantSums);
HWY_EXPORT(LaneInterpolantSums4);
HWY_EXPORT(LaneInterpolantSums2);
}  // namespace error_lanes
/// @endcond

using namespace error_sums;

// One level of a batch's runs. Runs on the same mesh whose sample instants give the same affine runs of
// the closed form (checked run by run, not assumed: the runs may differ in Δt) and that lie in the lanes
// of the same vectors form a set; the error's sums of every lane of those vectors are formed in one
// pass (LaneRunSums: each lane error_run_sums' bits), the interpolant's once, and each run of the set
// takes its lane's. Every other run is added alone (add).
std::size_t ErrorAccumulator::add_lanes(const Lane* level, std::size_t count) {
  using Run = ExactSolution::AffineRun;
  struct Runs {
    Run u[32], v[32];
    int u_count = 0, v_count = 0;
    bool has_interpolant = false;  // zu and zv formed (interpolant_of)
    InterpolantSums zu{}, zv{};
  };
  const auto same = [](const Run* a, int na, const Run* b, int nb) {
    if (na != nb) return false;
    for (int k = 0; k < na; ++k)
      if (a[k].first != b[k].first || a[k].end != b[k].end ||
          std::memcmp(&a[k].intercept, &b[k].intercept, sizeof(double)) != 0 ||
          std::memcmp(&a[k].slope, &b[k].slope, sizeof(double)) != 0)
        return false;
    return true;
  };
  // The kernel for a stride: the widest width whose lanes divide it, as the batched step chooses its groups'
  // (batched::width_dividing); 1 full, 2 four, 3 two, 0 none.
  const auto kernel_of = [](std::size_t stride) {
    batched::Width width = batched::Width::full;
    if (!batched::width_dividing(stride, width)) return 0;
    return width == batched::Width::full ? 1 : width == batched::Width::four ? 2 : 3;
  };
  // A run of the closed form on a uniform mesh: its affine runs and contact values are taken from a run
  // at the same instants (runs_of, contact_values), whatever its layout; summed in one pass with others
  // if it lies in lanes of a width the vectors divide (in_vectors).
  const auto takes = [&](const Lane& r) {
    return r.errors->closed_form_ && !r.errors->general_ && r.lanes.stride >= 1 && r.lanes.lane < r.lanes.stride;
  };
  const auto in_vectors = [&](const Lane& r) { return r.lanes.stride >= 2 && kernel_of(r.lanes.stride) != 0; };
  // A run against another reference (the characteristic solution, tabulated or not, ...) on a uniform
  // mesh, in lanes as above: its interpolants are evaluated once for the runs of the same reference,
  // nodes and instants.
  const auto evaluates = [&](const Lane& r) {
    return !r.errors->closed_form_ && !r.errors->general_ && r.lanes.stride >= 2 && r.lanes.lane < r.lanes.stride &&
           kernel_of(r.lanes.stride) != 0;
  };
  const auto interpolant_sums_of = [&](const double* w, std::size_t W, const double* wi, long n, double* out) {
    switch (kernel_of(W)) {
      case 1:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneInterpolantSums)(w, W, wi, n, out, out + W, out + 2 * W,
                                                                      out + 3 * W);
      case 2:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneInterpolantSums4)(w, W, wi, n, out, out + W, out + 2 * W,
                                                                       out + 3 * W);
      default:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneInterpolantSums2)(w, W, wi, n, out, out + W, out + 2 * W,
                                                                       out + 3 * W);
    }
  };
  const auto run_sums_of = [&](const double* w, std::size_t W, const double* x, const Run* r, int count, double* out) {
    switch (kernel_of(W)) {
      case 1:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneRunSums)(w, W, x, r, count, out, out + W, out + 2 * W,
                                                              out + 3 * W);
      case 2:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneRunSums4)(w, W, x, r, count, out, out + W, out + 2 * W,
                                                               out + 3 * W);
      default:
        return HWY_DYNAMIC_DISPATCH(error_lanes::LaneRunSums2)(w, W, x, r, count, out, out + W, out + 2 * W,
                                                               out + 3 * W);
    }
  };
  const auto same_bits = [](double p, double q) { return std::memcmp(&p, &q, sizeof p) == 0; };
  // The scratch of a level, this thread's, kept from call to call (a sweep calls once per level and batch).
  thread_local std::vector<Runs> runs;
  thread_local std::vector<char> done;
  thread_local std::vector<std::size_t> set, source, evaluated;
  thread_local std::vector<double> sums;
  runs.resize(count);
  done.assign(count, 0), source.assign(count, count);
  evaluated.clear();
  std::size_t together = 0;
  // Run k's affine runs, computed once per level: the runs of an earlier lane of the level whose closed
  // form is the same object, asked at the same instants (their bits) on the same uniform mesh (so the
  // same nodes, as for the sets below), are the same function of the same arguments, so they are taken
  // from it (the lanes of one Δt in a batch).
  const auto runs_of = [&](std::size_t k) -> const Runs& {
    if (source[k] == count) {
      const ErrorAccumulator& e = *level[k].errors;
      const Sample& s = *level[k].sample;
      const double* x = e.nodes_.data();
      const long n = static_cast<long>(e.mesh_.unknowns());
      for (std::size_t m : evaluated) {
        const ErrorAccumulator& f = *level[m].errors;
        const Sample& t = *level[m].sample;
        if (f.closed_form_ == e.closed_form_ && same_bits(t.time, s.time) &&
            same_bits(t.velocity_time, s.velocity_time) && f.mesh_.unknowns() == e.mesh_.unknowns() &&
            f.mesh_.length == e.mesh_.length && f.mesh_.h() == e.mesh_.h()) {
          source[k] = m;
          return runs[m];
        }
      }
      Runs& r = runs[k];
      r.has_interpolant = false;
      r.u_count = e.closed_form_->displacement_runs(s.time, x, n, r.u, 32);
      r.v_count = e.closed_form_->velocity_runs(s.velocity_time, x, n, r.v, 32);
      source[k] = k;
      evaluated.push_back(k);
    }
    return runs[source[k]];
  };
  // The interpolant's sums of run k's affine runs: formed once for the runs that share them.
  const auto interpolant_of = [&](std::size_t k) -> const Runs& {
    Runs& r = runs[source[k]];
    if (!r.has_interpolant) {
      const ErrorAccumulator& e = *level[k].errors;
      const double h = e.mesh_.h();
      r.zu = interpolant_run_sums(e.nodes_.data(), h, r.u, r.u_count);
      r.zv = interpolant_run_sums(e.nodes_.data(), h, r.v, r.v_count);
      r.has_interpolant = true;
    }
    return r;
  };
  // u₀(t) and λ(t) once per reference object and instant (the runs of one Δt share both).
  const ReferenceSolution* u0_of = nullptr;
  const ReferenceSolution* lambda_of = nullptr;
  double u0 = 0, u0_time = 0, lambda = 0, lambda_time = 0;
  const auto contact_values = [&](std::size_t k) {
    const Sample& sample = *level[k].sample;
    const ReferenceSolution* exact = level[k].errors->exact_.get();
    if (!(u0_of == exact && same_bits(sample.time, u0_time))) {
      u0 = exact->contact_displacement(sample.time);
      u0_of = exact, u0_time = sample.time;
    }
    if (sample.has_multiplier && !(lambda_of == exact && same_bits(sample.multiplier_time, lambda_time))) {
      lambda = exact->contact_multiplier(sample.multiplier_time);
      lambda_of = exact, lambda_time = sample.multiplier_time;
    }
  };
  for (std::size_t a = 0; a < count; ++a) {
    if (done[a]) continue;
    const Lane& first = level[a];
    ErrorAccumulator& lead = *first.errors;
    if (!takes(first) && evaluates(first)) {
      // The runs of the same reference, nodes and instants in the lanes of the same vectors: u_I and
      // (u_t)_I evaluated once (the lead's buffers), the interpolant's sums and the contact values once,
      // the error's sums of every lane in one pass (LaneInterpolantSums: each lane add_vectors' bits).
      const Sample& at = *first.sample;
      const Index n = lead.mesh_.unknowns();
      const std::size_t W = first.lanes.stride;
      const double* u_base = first.lanes.displacement - first.lanes.lane;
      const double* v_base = first.lanes.velocity - first.lanes.lane;
      set.assign(1, a);
      for (std::size_t b = a + 1; b < count; ++b) {
        const Lane& other = level[b];
        const ErrorAccumulator& e = *other.errors;
        if (!done[b] && evaluates(other) && e.exact_ == lead.exact_ && other.lanes.stride == W &&
            other.lanes.displacement - other.lanes.lane == u_base &&
            other.lanes.velocity - other.lanes.lane == v_base && same_bits(other.sample->time, at.time) &&
            same_bits(other.sample->velocity_time, at.velocity_time) && e.mesh_.unknowns() == n &&
            std::memcmp(e.nodes_.data(), lead.nodes_.data(), static_cast<std::size_t>(n) * sizeof(double)) == 0)
          set.push_back(b);
      }
      if (set.size() == 1) {
        lead.add(at, first.lanes);
        continue;
      }
      const double* x = lead.nodes_.data();
      double* ui = lead.interpolant_.data();
      double* vi = lead.velocity_interpolant_.data();
      lead.exact_->displacement_at_points(at.time, x, static_cast<long>(n), ui);
      lead.exact_->velocity_at_points(at.velocity_time, x, static_cast<long>(n), vi);
      sums.assign(8 * W, 0.0);
      double* s = sums.data();
      interpolant_sums_of(u_base, W, ui, static_cast<long>(n), s);
      interpolant_sums_of(v_base, W, vi, static_cast<long>(n), s + 4 * W);
      const InterpolantSums zu = interpolant_sums(ui, static_cast<long>(n));
      const InterpolantSums zv = interpolant_sums(vi, static_cast<long>(n));
      for (std::size_t k : set) {
        const Sample& sample = *level[k].sample;
        const std::size_t j = level[k].lanes.lane;
        const Sums su{s[j], s[W + j], s[2 * W + j], s[3 * W + j], zu.z0, zu.z_last, zu.differences, zu.squares};
        const Sums sv{s[4 * W + j], s[5 * W + j], s[6 * W + j],   s[7 * W + j],
                      zv.z0,        zv.z_last,    zv.differences, zv.squares};
        contact_values(k);
        level[k].errors->add_sums(sample, level[k].lanes.displacement[0], su, sv, u0,
                                  sample.has_multiplier ? lambda : 0.0);
        done[k] = 1;
      }
      together += set.size();
      continue;
    }
    if (!takes(first)) {
      // The other runs against a reference other than the closed form (on their own vectors, stepped
      // alone in a batch; in lanes of a width without a kernel; on a mesh whose matrices are not
      // Toeplitz): those of the same reference object, instants and nodes have u_I and (u_t)_I evaluated
      // once (the lead's buffers, copied into each run's), and each adds its level from them
      // (add_vectors with the stride add(sample, lanes) passes, so add's bits).
      const Sample& at = *first.sample;
      const Index n = lead.mesh_.unknowns();
      set.assign(1, a);
      for (std::size_t b = a + 1; b < count; ++b) {
        const Lane& other = level[b];
        const ErrorAccumulator& e = *other.errors;
        if (!done[b] && !takes(other) && !evaluates(other) && e.exact_ == lead.exact_ && other.lanes.stride >= 1 &&
            same_bits(other.sample->time, at.time) && same_bits(other.sample->velocity_time, at.velocity_time) &&
            e.mesh_.unknowns() == n &&
            std::memcmp(e.nodes_.data(), lead.nodes_.data(), static_cast<std::size_t>(n) * sizeof(double)) == 0)
          set.push_back(b);
      }
      if (set.size() == 1 || first.lanes.stride < 1) {
        lead.add(at, first.lanes);
        continue;
      }
      const double* x = lead.nodes_.data();
      lead.exact_->displacement_at_points(at.time, x, static_cast<long>(n), lead.interpolant_.data());
      lead.exact_->velocity_at_points(at.velocity_time, x, static_cast<long>(n), lead.velocity_interpolant_.data());
      for (std::size_t k : set) {
        ErrorAccumulator& e = *level[k].errors;
        if (k != a) e.interpolant_ = lead.interpolant_, e.velocity_interpolant_ = lead.velocity_interpolant_;
        const LaneVectors& lanes = level[k].lanes;
        e.add_vectors(*level[k].sample, lanes.displacement, lanes.velocity, static_cast<long>(lanes.stride), true);
        done[k] = 1;
      }
      continue;  // evaluated together, summed one by one: not counted
    }
    const Index n = lead.mesh_.unknowns();
    const double* x = lead.nodes_.data();
    const std::size_t W = first.lanes.stride;
    const double* u_base = first.lanes.displacement - first.lanes.lane;
    const double* v_base = first.lanes.velocity - first.lanes.lane;
    const Runs& mine = runs_of(a);
    set.assign(1, a);
    for (std::size_t b = a + 1; in_vectors(first) && b < count; ++b) {
      const Lane& other = level[b];
      const ErrorAccumulator& e = *other.errors;
      if (done[b] || !takes(other) || other.lanes.stride != W ||
          other.lanes.displacement - other.lanes.lane != u_base || other.lanes.velocity - other.lanes.lane != v_base ||
          e.mesh_.unknowns() != n || e.mesh_.length != lead.mesh_.length || e.mesh_.h() != lead.mesh_.h())
        continue;
      const Runs& theirs = runs_of(b);
      if (&theirs == &mine || (same(mine.u, mine.u_count, theirs.u, theirs.u_count) &&
                               same(mine.v, mine.v_count, theirs.v, theirs.v_count)))
        set.push_back(b);
    }
    if (set.size() == 1) {  // alone: add's sums (add_vectors), from the runs and contact values found above
      const auto sums_of = [&](const double* w, const Run* r, int c) {
        return W == 1 ? error_run_sums(w, std::integral_constant<long, 1>(), x, r, c)
                      : error_run_sums(w, static_cast<long>(W), x, r, c);
      };
      const ErrorRunSums eu = sums_of(first.lanes.displacement, mine.u, mine.u_count);
      const ErrorRunSums ev = sums_of(first.lanes.velocity, mine.v, mine.v_count);
      const Runs& z = interpolant_of(a);
      const InterpolantSums &zu = z.zu, &zv = z.zv;
      contact_values(a);
      lead.add_sums(*first.sample, first.lanes.displacement[0],
                    {eu.e0, eu.e_last, eu.differences, eu.squares, zu.z0, zu.z_last, zu.differences, zu.squares},
                    {ev.e0, ev.e_last, ev.differences, ev.squares, zv.z0, zv.z_last, zv.differences, zv.squares}, u0,
                    first.sample->has_multiplier ? lambda : 0.0);
      continue;
    }
    // Eight arrays of W: e₀, e_{n−1}, D, Q of u, then of v.
    sums.assign(8 * W, 0.0);
    double* s = sums.data();
    run_sums_of(u_base, W, x, mine.u, mine.u_count, s);
    run_sums_of(v_base, W, x, mine.v, mine.v_count, s + 4 * W);
    const Runs& z = interpolant_of(a);
    const InterpolantSums &zu = z.zu, &zv = z.zv;
    for (std::size_t k : set) {
      const std::size_t j = level[k].lanes.lane;
      const Sums su{s[j], s[W + j], s[2 * W + j], s[3 * W + j], zu.z0, zu.z_last, zu.differences, zu.squares};
      const Sums sv{s[4 * W + j], s[5 * W + j], s[6 * W + j],   s[7 * W + j],
                    zv.z0,        zv.z_last,    zv.differences, zv.squares};
      const Sample& sample = *level[k].sample;
      contact_values(k);
      level[k].errors->add_sums(sample, level[k].lanes.displacement[0], su, sv, u0,
                                sample.has_multiplier ? lambda : 0.0);
      done[k] = 1;
    }
    together += set.size();
  }
  return together;
}

}  // namespace mrm
#endif  // HWY_ONCE

#if HWY_ONCE
namespace mrm {

namespace {

// Every lane's eight measures against its run alone: the same bits, and positive (not vacuous).
void check_lanes_match(const std::vector<ErrorAccumulator>& alone, const std::vector<ErrorAccumulator>& together) {
  for (std::size_t j = 0; j < alone.size(); ++j) {
    const auto a = ErrorAccumulator::values(alone[j].relative());
    [[maybe_unused]] const auto b = ErrorAccumulator::values(together[j].relative());  // (checks compiled out: mrm)
    for (std::size_t k = 0; k < a.size(); ++k) {
      CAPTURE(j);
      CAPTURE(ErrorAccumulator::names[k]);
      CHECK(a[k] > 0);
      CHECK(std::memcmp(&a[k], &b[k], sizeof(double)) == 0);
    }
  }
}

// The lanes of add_lanes for runs 0 … runs−1 of a batch of W lanes: run j's displacement and velocity
// (own_u[j], own_v[j]) put in lane j of the interleaved vectors u and v, the lanes past the runs filled
// with 1e300 (padding, which no run's sums may read).
std::vector<ErrorAccumulator::Lane> interleaved_lanes(const std::vector<Eigen::VectorXd>& own_u,
                                                      const std::vector<Eigen::VectorXd>& own_v, std::size_t W,
                                                      std::vector<double>& u, std::vector<double>& v,
                                                      std::vector<ErrorAccumulator>& together,
                                                      std::vector<Sample>& samples) {
  const std::size_t runs = own_u.size(), n = static_cast<std::size_t>(own_u.front().size());
  for (std::size_t j = 0; j < W; ++j)
    for (std::size_t i = 0; i < n; ++i) {
      u[i * W + j] = j < runs ? own_u[j][static_cast<Index>(i)] : 1e300;
      v[i * W + j] = j < runs ? own_v[j][static_cast<Index>(i)] : 1e300;
    }
  std::vector<ErrorAccumulator::Lane> lanes;
  for (std::size_t j = 0; j < runs; ++j) lanes.push_back({&together[j], &samples[j], LaneVectors{&u[j], &v[j], W, j}});
  return lanes;
}

// Whether add_lanes' one pass takes lanes of stride W on the current target: one of its widths (its
// lanes, 4 and 2, each at most its lanes) divides W.
bool one_pass_takes(std::size_t W) {
  const std::size_t full = current_batch_target().lanes;
  return W % full == 0 || W % std::min<std::size_t>(4, full) == 0 || W % std::min<std::size_t>(2, full) == 0;
}
}  // namespace

TEST_CASE("the error sums of a batch's lanes in one pass are each lane's own, bit for bit, on every vector target") {
  // Prediction: add_lanes forms each lane's sums with error_run_sums' operations in its order, lane-wise
  // (LaneRunSums), and the interpolant's with the same function as add: so every measure of every lane
  // has the bits of add(sample) on that lane's own contiguous vectors. W lanes (2, 4, 8, 16: one or
  // several vectors of each target, at its full width or a capped one of 4 or 2 lanes, as a batch's
  // narrow groups; 6: vectors of 2 lanes on a wider target; 3: no width divides it, each run alone), on a
  // mesh of an odd and an even number of nodes, at instants where u's runs are affine (b ≠ 0) and
  // constant (b = 0, and every run of u_t), on the kinks (t a multiple of h) and off them; most lanes
  // share their instants, one lane has instants of its own (it is added alone), and one lane of the
  // vectors is no run at all (padding).
  std::vector<std::int64_t> targets{0};
  for (const BatchTarget& t : batch_targets()) targets.push_back(t.bit);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> wiggle(-0.01, 0.01);
  for (const std::int64_t bit : targets) {
    use_batch_target(bit);
    for (const Index elements : {36, 37}) {
      const UniformMesh mesh(1.0, elements);
      const Index n = mesh.unknowns();
      const ExactSolution exact;
      for (const std::size_t W : {2, 3, 4, 6, 8, 16}) {
        const std::size_t runs = W == 2 ? 2 : W - 1;  // from W = 4, lane W − 1 is padding
        std::vector<ErrorAccumulator> together, alone;
        for (std::size_t j = 0; j < runs; ++j) together.emplace_back(mesh, exact), alone.emplace_back(mesh, exact);
        std::vector<double> u(static_cast<std::size_t>(n) * W), v(u.size());
        std::vector<Eigen::VectorXd> own_u(runs, Eigen::VectorXd(n)), own_v(runs, Eigen::VectorXd(n));
        int apart = 0;  // the levels at which lane 1 was added alone
        for (int level = 0; level <= 40; ++level) {
          std::vector<Sample> samples(runs);
          for (std::size_t j = 0; j < runs; ++j) {
            // The instants: a step of h/2 (every other level on a kink), lane 1's 0.37 h (its own).
            const double dt = (j == 1 && runs > 2 ? 0.37 : 0.5) * mesh.h(), t = level * dt, tv = t - 0.5 * dt;
            for (Index i = 0; i < n; ++i) {
              own_u[j][i] = exact.displacement(mesh.x(i), t) + wiggle(random);
              own_v[j][i] = exact.velocity(mesh.x(i), tv) + wiggle(random);
            }
            samples[j] = {level, t,  &own_u[j], tv, &own_v[j], true, t, exact.contact_multiplier(t) + wiggle(random),
                          t,     0.0};
            alone[j].add(samples[j]);
          }
          std::vector<ErrorAccumulator::Lane> lanes = interleaved_lanes(own_u, own_v, W, u, v, together, samples);
          // The runs of one pass, if the vectors divide W: all, but lane 1 from W = 4 at the levels where
          // its instants give other runs of the closed form.
          const std::size_t got = ErrorAccumulator::add_lanes(lanes.data(), lanes.size());
          if (!one_pass_takes(W)) {
            CHECK(got == 0);
          } else {
            CHECK((got == runs || (runs > 2 && got == runs - 1)));
            apart += got < runs;
          }
        }
        if (runs > 2 && one_pass_takes(W)) CHECK(apart > 20);
        CAPTURE(current_batch_target().name);
        CAPTURE(elements);
        CAPTURE(W);
        check_lanes_match(alone, together);
      }
    }
  }
  use_batch_target(0);
}

TEST_CASE("runs on their own vectors at the same instants share the closed form's runs, each its own bits") {
  // Prediction: add_lanes takes the closed form's affine runs, the interpolant's sums and u₀, λ of a run
  // stepped alone (its own vectors, stride 1) from an earlier run at the same instants (runs of different
  // schemes with one Δt, repro/sweep.hpp's caller keys), and forms its error sums with error_run_sums
  // alone: every measure has the bits of add(sample). Three runs, two at the instants of a step h/2
  // and one at 0.37 h; none is summed with another (no lanes of one vector).
  const UniformMesh mesh(1.0, 37);
  const Index n = mesh.unknowns();
  const ExactSolution exact;
  std::mt19937 random(5);
  std::uniform_real_distribution<double> wiggle(-0.01, 0.01);
  std::vector<ErrorAccumulator> together, alone;
  for (int j = 0; j < 3; ++j) together.emplace_back(mesh, exact), alone.emplace_back(mesh, exact);
  std::vector<Eigen::VectorXd> u(3, Eigen::VectorXd(n)), v(3, Eigen::VectorXd(n));
  for (int level = 0; level <= 40; ++level) {
    std::vector<Sample> samples(3);
    std::vector<ErrorAccumulator::Lane> lanes;
    for (std::size_t j = 0; j < 3; ++j) {
      const double dt = (j == 2 ? 0.37 : 0.5) * mesh.h(), t = level * dt, tv = t - 0.5 * dt;
      for (Index i = 0; i < n; ++i) {
        u[j][i] = exact.displacement(mesh.x(i), t) + wiggle(random);
        v[j][i] = exact.velocity(mesh.x(i), tv) + wiggle(random);
      }
      samples[j] = {level, t, &u[j], tv, &v[j], true, t, exact.contact_multiplier(t) + wiggle(random), t, 0.0};
      alone[j].add(samples[j]);
      lanes.push_back({&together[j], &samples[j], LaneVectors{u[j].data(), v[j].data(), 1, 0}});
    }
    CHECK(ErrorAccumulator::add_lanes(lanes.data(), lanes.size()) == 0);
  }
  check_lanes_match(alone, together);
}

TEST_CASE("runs on their own vectors against one reference object at the same instants share its evaluation") {
  // Prediction: add_lanes evaluates a reference other than the closed form once per level for the runs
  // on their own vectors (stride 1: stepped alone in a batch) that ask the same object at the same
  // instants on the same nodes, on a uniform mesh and on a graded one (whose matrices are not Toeplitz:
  // the forms by Tridiagonal::bilinear), and each run adds its level from those values with add's
  // arithmetic: every measure has the bits of add(sample). Four runs: three at the instants of a step
  // h/2, one at 0.37 h (its own evaluation). So two evaluations of u_I and two of (u_t)_I per level,
  // against eight alone; none is summed in one pass with another (no lanes of one vector).
  const CharacteristicSolution solution(benchmark_initial_data(1.0, 0.5), 2.0);
  for (const double ratio : {1.0, 1.01}) {
    const UniformMesh mesh = graded_mesh(1.0, 20, ratio);
    const Index n = mesh.unknowns();
    const auto shared = std::make_shared<const error_sums::ForwardedSolution>(solution);
    const auto own = std::make_shared<const error_sums::ForwardedSolution>(solution);
    std::mt19937 random(7);
    std::uniform_real_distribution<double> wiggle(-0.01, 0.01);
    std::vector<ErrorAccumulator> together, alone;
    for (int j = 0; j < 4; ++j) together.emplace_back(mesh, shared), alone.emplace_back(mesh, own);
    std::vector<Eigen::VectorXd> u(4, Eigen::VectorXd(n)), v(4, Eigen::VectorXd(n));
    for (int level = 0; level <= 30; ++level) {
      std::vector<Sample> samples(4);
      std::vector<ErrorAccumulator::Lane> lanes;
      for (std::size_t j = 0; j < 4; ++j) {
        const double dt = (j == 1 ? 0.37 : 0.5) * mesh.h(0), t = level * dt;
        for (Index i = 0; i < n; ++i) {
          u[j][i] = solution.displacement(mesh.x(i), t) + wiggle(random);
          v[j][i] = solution.velocity(mesh.x(i), t) + wiggle(random);
        }
        samples[j] = {level, t, &u[j], t, &v[j], level > 0, t, solution.contact_multiplier(t) + wiggle(random), t, 0.0};
        alone[j].add(samples[j]);
        lanes.push_back({&together[j], &samples[j], LaneVectors{u[j].data(), v[j].data(), 1, 0}});
      }
      const long before = shared->evaluations;
      CHECK(ErrorAccumulator::add_lanes(lanes.data(), lanes.size()) == 0);
      CAPTURE(level);
      CHECK(shared->evaluations - before == (level == 0 ? 2 : 4));  // level 0: t = 0 for all four
    }
    CAPTURE(ratio);
    check_lanes_match(alone, together);
  }
}

TEST_CASE("runs against one reference object at the same instants share its evaluation, each lane's bits its own") {
  // Prediction: add_lanes evaluates a reference other than the closed form once for the lanes that ask
  // the same object at the same instants on the same nodes, forms the interpolant's sums once and each
  // lane's error sums lane-wise in add_vectors' order (LaneInterpolantSums): every measure of every lane
  // has the bits of add(sample) on its own vectors. The references: the characteristic solution of the
  // benchmark's data, tabulated on the lattice δ = h/2 (the straight loop) and not tabulated (evaluated
  // at each point). The lanes: most at Δt = h/2 against reference A; lane 1 at Δt = 0.37 h (instants of
  // its own, off the lattice: alone); from W = 8, lanes 2 and 3 against B, another object of the same
  // solution (a set of their own); from W = 4, lane W − 1 padding. `got` counts the runs of the shared
  // passes, so the comparison cannot pass by adding every run alone.
  std::vector<std::int64_t> targets{0};
  for (const BatchTarget& t : batch_targets()) targets.push_back(t.bit);
  std::mt19937 random(12);
  std::uniform_real_distribution<double> wiggle(-0.01, 0.01);
  const CharacteristicSolution solution(benchmark_initial_data(1.0, 0.5), 2.0);
  for (const bool tabulate : {true, false}) {
    for (const std::int64_t bit : targets) {
      use_batch_target(bit);
      for (const Index elements : {36, 37}) {
        const UniformMesh mesh(1.0, elements);
        const Index n = mesh.unknowns();
        const auto make = [&]() -> std::shared_ptr<const ReferenceSolution> {
          if (tabulate) return std::make_shared<const TabulatedSolution>(solution, 0.5 * mesh.h());
          return std::make_shared<const CharacteristicSolution>(solution);
        };
        const std::shared_ptr<const ReferenceSolution> a_ref = make(), b_ref = make();
        for (const std::size_t W : {2, 3, 4, 6, 8, 16}) {
          const std::size_t runs = W == 2 ? 2 : W - 1;
          const auto reference_of = [&](std::size_t j) { return W >= 8 && (j == 2 || j == 3) ? b_ref : a_ref; };
          const auto own_instants = [&](std::size_t j) { return j == 1 && runs > 2; };
          // The runs of the shared passes at a level (at level 0, t = 0, lane 1 asks A at the same instant).
          const auto shared = [&](int level) {
            std::size_t in_a = 0, in_b = 0;
            for (std::size_t j = 0; j < runs; ++j)
              if (level == 0 || !own_instants(j)) (reference_of(j) == a_ref ? in_a : in_b) += 1;
            return (in_a >= 2 ? in_a : 0) + (in_b >= 2 ? in_b : 0);
          };
          std::vector<ErrorAccumulator> together, alone;
          for (std::size_t j = 0; j < runs; ++j)
            together.emplace_back(mesh, reference_of(j)), alone.emplace_back(mesh, reference_of(j));
          std::vector<double> u(static_cast<std::size_t>(n) * W), v(u.size());
          std::vector<Eigen::VectorXd> own_u(runs, Eigen::VectorXd(n)), own_v(runs, Eigen::VectorXd(n));
          for (int level = 0; level <= 40; ++level) {
            std::vector<Sample> samples(runs);
            for (std::size_t j = 0; j < runs; ++j) {
              const double dt = (own_instants(j) ? 0.37 : 0.5) * mesh.h(), t = level * dt;
              for (Index i = 0; i < n; ++i) {
                own_u[j][i] = solution.displacement(mesh.x(i), t) + wiggle(random);
                own_v[j][i] = solution.velocity(mesh.x(i), t) + wiggle(random);
              }
              samples[j] = {level,     t,         &own_u[j], t,
                            &own_v[j], level > 0, t,         solution.contact_multiplier(t) + wiggle(random),
                            t,         0.0};
              alone[j].add(samples[j]);
            }
            std::vector<ErrorAccumulator::Lane> lanes = interleaved_lanes(own_u, own_v, W, u, v, together, samples);
            const std::size_t got = ErrorAccumulator::add_lanes(lanes.data(), lanes.size());
            CAPTURE(current_batch_target().name);
            CAPTURE(W);
            CHECK(got == (one_pass_takes(W) ? shared(level) : 0));
          }
          CAPTURE(tabulate);
          CAPTURE(current_batch_target().name);
          CAPTURE(elements);
          CAPTURE(W);
          check_lanes_match(alone, together);
        }
      }
    }
  }
  use_batch_target(0);
}

}  // namespace mrm
#endif  // HWY_ONCE
