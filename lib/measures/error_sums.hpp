/// @file error_sums.hpp
/// @brief The sums of the error measures' quadratic forms over one level of a run (errors.cpp), shared by
/// the error accumulator and the one-pass sums of a batch's lanes (batched/lane_errors.cpp).
#pragma once

#include <algorithm>
#include <utility>

#include "exact/exact_solution.hpp"
#include "exact/reference_solution.hpp"

/// @cond MRM_INTERNAL (the arithmetic of ErrorAccumulator: not part of the library's interface)
namespace mrm::error_sums {

// The two sums of one run of nodes first … end−1 (entries w[i·stride]) in a fixed order: two partial
// sums, one over the even offsets from `first` and one over the odd ones, each in increasing i, added at
// the end (even + odd). The order is written out so that it is the source's and not a compiler's, and
// so that a run read from the lane layout of a batch (LaneVectors) sums in the same order as a run
// alone: it is the order of the loop this replaces (an `omp simd` reduction that GCC 12 vectorised with
// two lanes of SSE2, unaligned, and the odd element last into the even lane), so the measures keep
// their bits. `term(x_i, x_{i−1}, w_i, w_{i−1})` gives (de, e) at node i, on doubles or, for the nodes
// i and i + 1 at once, on pairs of them: the even offset in lane 0, the odd one in lane 1 (GCC's vector
// extension: each lane's operations are the scalar ones, in the same order, as in Tridiagonal::form), so
// that the two partial sums are the two lanes of one pair.
typedef double Pair __attribute__((vector_size(16)));
template <typename Stride, typename Term>
inline void pair_sums(const double* w, const double* x, long first, long end, Stride stride, const Term& term,
                      double& differences, double& squares) {
  Pair d{0, 0}, s{0, 0};
  long i = first;
  for (; i + 1 < end; i += 2) {
    const Pair wi{w[i * stride], w[(i + 1) * stride]}, wp{w[(i - 1) * stride], w[i * stride]};
    const Pair xi{x[i], x[i + 1]}, xp{x[i - 1], x[i]};
    const auto [de, e] = term(xi, xp, wi, wp);
    d += de * de, s += e * e;
  }
  double d0 = d[0], d1 = d[1], s0 = s[0], s1 = s[1];
  if (i < end) {
    const auto [de, e] = term(x[i], x[i - 1], w[i * stride], w[(i - 1) * stride]);
    d0 += de * de, s0 += e * e;
  }
  differences = d0 + d1, squares = s0 + s1;
}

// The error's sums over the closed form's runs (see above): e₀, e_{n−1}, D and Q of e = W − w_I, the
// interpolant w_I = a + b x_i on each run. Per run: its first node against the last of the previous
// run, then pair_sums over the rest, added to the totals. The interpolant's own sums do not depend on
// W (interpolant_run_sums).
struct ErrorRunSums {
  double e0, e_last, differences, squares;
};
template <typename Stride>
ErrorRunSums error_run_sums(const double* w, Stride stride, const double* x, const ExactSolution::AffineRun* runs,
                            int count) {
  const double z0 = runs[0].intercept + runs[0].slope * x[0];
  const double e0 = w[0] - z0;
  double ed = 0, es = 0, e_prev = e0;
  for (int k = 0; k < count; ++k) {
    const double a = runs[k].intercept, b = runs[k].slope;
    const long first = std::max(runs[k].first, 1L), end = runs[k].end;
    if (first >= end) continue;
    {  // the first node of the run, against the last of the previous one
      const double wf = w[first * stride];
      const double z = a + b * x[first], e = wf - z, de = e - e_prev;
      ed += de * de, es += e * e;
    }
    double red = 0, res = 0;
    if (b == 0)  // a constant interpolant (every run of u_t, some of u): no node positions needed
      pair_sums(
          w, x, first + 1, end, stride, [a](auto, auto, auto wi, auto wp) { return std::pair(wi - wp, wi - a); }, red,
          res);
    else
      pair_sums(
          w, x, first + 1, end, stride,
          [a, b](auto xi, auto xp, auto wi, auto wp) {
            return std::pair((wi - wp) - b * (xi - xp), wi - (a + b * xi));
          },
          red, res);
    ed += red, es += res;
    e_prev = w[(end - 1) * stride] - (a + b * x[end - 1]);
  }
  return {e0, e_prev, ed, es};
}

// The interpolant's sums over the runs: z₀, z_{n−1}, D and Q, the first node of each run term by term
// and the rest in closed form (see above).
struct InterpolantSums {
  double z0, z_last, differences, squares;
};
inline InterpolantSums interpolant_run_sums(const double* x, double h, const ExactSolution::AffineRun* runs,
                                            int count) {
  const double z0 = runs[0].intercept + runs[0].slope * x[0];
  double id = 0, is = 0, z_prev = z0;
  for (int k = 0; k < count; ++k) {
    const double a = runs[k].intercept, b = runs[k].slope;
    const long first = std::max(runs[k].first, 1L), end = runs[k].end;
    if (first >= end) continue;
    {
      const double z = a + b * x[first], dz = z - z_prev;
      id += dz * dz, is += z * z;
    }
    const double m = static_cast<double>(end - first - 1);  // the nodes first+1 … end−1
    if (m > 0) {
      const double mean = a + b * 0.5 * (x[first + 1] + x[end - 1]), bh = b * h;
      is += m * mean * mean + bh * bh * m * (m * m - 1) / 12;
      id += m * bh * bh;
    }
    z_prev = a + b * x[end - 1];
  }
  return {z0, z_prev, id, is};
}

// The interpolant's sums from its values at the nodes (a reference other than the closed form): add_vectors'
// sums of w_I, in their order. Not inlined: inside add_lanes GCC 12 kept the two sums on the stack, a
// store and a load in each chain (34 % of fig_smooth_convergence's time against about 8 % for the lanes'
// sums).
[[gnu::noinline]] inline InterpolantSums interpolant_sums(const double* z, long n) {
  double id = 0, is = 0, z_prev = z[0];
  for (long i = 1; i < n; ++i) {
    const double dz = z[i] - z_prev;
    id += dz * dz, is += z[i] * z[i];
    z_prev = z[i];
  }
  return {z[0], z_prev, id, is};
}

/// A reference behind another face (for the doctests of errors.cpp and lane_errors.cpp), which counts its evaluations at the nodes: the accumulator cannot
/// recognise the closed form through it and takes the general path.
struct ForwardedSolution final : ReferenceSolution {
  const ReferenceSolution& inner;  // outlives this object in the doctests
  mutable long evaluations = 0;
  explicit ForwardedSolution(const ReferenceSolution& r) : inner(r) {}
  double length() const override { return inner.length(); }
  double displacement(double x, double t) const override { return inner.displacement(x, t); }
  double strain(double x, double t) const override { return inner.strain(x, t); }
  double velocity(double x, double t) const override { return inner.velocity(x, t); }
  double contact_displacement(double t) const override { return inner.contact_displacement(t); }
  double contact_multiplier(double t) const override { return inner.contact_multiplier(t); }
  double energy() const override { return inner.energy(); }
  void displacement_at_points(double t, const double* x, long count, double* u) const override {
    ++evaluations;
    inner.displacement_at_points(t, x, count, u);
  }
  void velocity_at_points(double t, const double* x, long count, double* v) const override {
    ++evaluations;
    inner.velocity_at_points(t, x, count, v);
  }
};

}  // namespace mrm::error_sums
/// @endcond
