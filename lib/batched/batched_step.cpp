/// @file batched_step.cpp
/// @brief The fused step of fast_step.cpp, one run per vector lane (Google Highway, the widest target
/// of the processor chosen at run time: AVX-512, AVX2, SSE4, NEON, ... or a portable 128-bit emulation);
/// and the steps of the field's contact classes the same way: the Newmark type (newmark, penalty, nitsche: four
/// passes), Moreau–Jean and DKE (one solve each; contact_classes.cpp) and the explicit classes
/// (taylor-flanagan, explicit: a kick and drift, then a kick; explicit_schemes.cpp), their passes and the
/// energy's forms in vectors, their contact decisions and ends of step each lane's own (NewmarkTypeStep,
/// OneSolveStep, ExplicitStep::contact).
///
/// A step of one run is two long chains of dependent operations (the sweeps of the tridiagonal solve,
/// fast_step.cpp), so a run fills one lane of a vector unit. W runs with the same number of unknowns and
/// the same scheme family have the same sequence of operations, node by node, on different numbers: the
/// batched step does that sequence once on vectors of W doubles, lane j holding run j. Nothing mixes the
/// lanes (every operation is lane-wise: +, −, ×, and the per-lane contact decision between the sweeps is
/// FastStep::contact_decision itself), and the vector operations are IEEE-754 double operations with the
/// same rounding as the scalar ones, so each lane is bitwise the run stepped alone, provided that the
/// compiler neither contracts a×b + c into a fused multiply-add in one path and not the other: the
/// project compiles everything with -ffp-contract=off (CMakeLists.txt; ISO C++'s default under GCC,
/// made explicit because the vector targets enable FMA instructions). The operations below are
/// fast_step.cpp's, written in the same order, operand for operand; the doctest at the end checks the
/// identity bit for bit, lane by lane, for every scheme and every target the machine has.
///
/// Layout: the state and factor vectors of a group are interleaved, element i of lane j at i·W + j, so
/// that one aligned load gives node i of the W runs. Each lane keeps its own factors and rows (runs may
/// differ in Δt, mass, restitution, β): nothing is shared but the number of unknowns and the layout of the
/// fast step (its explicit head rows, the Toeplitz interior, the last row).
///
/// Width: a group has the target's full width W, except the remainder of a family (q < W runs left after
/// its full groups), which gets the narrowest width that holds it: 2 lanes for 2 runs, 4 for 3 or 4, W
/// for more (a run left alone is stepped alone). A padding lane costs as much as a run (bench_step times
/// the step at each width): on an AVX-512 machine, 2 runs padded to 8 lanes were slower than the same runs
/// stepped alone. The kernels are templates over
/// Highway's tag, instantiated for the full width and the capped widths of 4 and 2 doubles; the width
/// changes no bit of a lane, since no operation mixes lanes.
#include "batched/batched_step.hpp"

/// @cond MRM_INTERNAL (the Highway plumbing and the kernel: not part of the library's interface)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batched/batched_step.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

#ifndef MRM_BATCHED_STEP_ONCE
#define MRM_BATCHED_STEP_ONCE
namespace mrm::batched {

// The interleaved arrays of one group and what the two sweeps exchange with the per-lane contact
// decision between them (plain pointers: the same struct for every target).
struct Kernel {
  std::size_t n = 0, lanes = 0, head = 0;
  std::size_t flat_begin = 0, flat_end = 0;  // rows [flat_begin, flat_end) of the interior: constant factors
  bool three_level = false, keeps = false;   // keeps: a lane may be left untouched (CN-switch, step(advance))
  double *u = nullptr, *y = nullptr, *w = nullptr, *x = nullptr;
  const double *elimination = nullptr, *elimination_pair = nullptr, *inverse_pivot = nullptr, *upward = nullptr,
               *upward_pair = nullptr;
  const double *head_rows = nullptr, *interior = nullptr, *last = nullptr;  // 10 coefficients × lanes per row
  const double *rate = nullptr, *memory = nullptr, *ps_q_weight = nullptr;  // per lane; 1 − 4β for PS
  const double *u0_next = nullptr, *recurrence_d0 = nullptr, *keep = nullptr;
  double* energy = nullptr;  // per lane, written by the sweep up
};

// The same for the Newmark-type steps (contact_classes.cpp, NewmarkTypeStep): the interleaved state (U, Y =
// Uⁿ⁺¹, V, Rⁿ, Rⁿ⁺¹, T the mass solve's right-hand side), the rows of M, S and S_ℓ, the factors of A and M̃,
// z, and per lane Δt, Δt²(½ − β), 1 − γ, γ, g₀, g₁, the massless flag, the decision (u₀, λ, shift), the keep
// flag and the two forms of the energy.
struct NewmarkKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *r = nullptr, *r_next = nullptr, *t = nullptr;
  const double *m_diag = nullptr, *m_lower = nullptr, *m_upper = nullptr, *s_diag = nullptr, *s_lower = nullptr,
               *s_upper = nullptr, *l_diag = nullptr, *l_lower = nullptr, *l_upper = nullptr;
  const double *elimination = nullptr, *inverse_pivot = nullptr, *upward = nullptr, *mass_elimination = nullptr,
               *mass_inverse_pivot = nullptr, *mass_upward = nullptr, *z = nullptr;
  const double *dt = nullptr, *force_weight = nullptr, *one_minus_gamma = nullptr, *gamma = nullptr, *g0 = nullptr,
               *g1 = nullptr, *massless = nullptr, *u0 = nullptr, *lambda = nullptr, *shift = nullptr, *keep = nullptr;
  double* kinetic_strain = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level
};

// The same for Moreau–Jean and DKE (contact_classes.cpp, OneSolveStep): the interleaved state (U, Y the
// solve's unknowns, V, P DKE's projected predictor), the rows of the right-hand side's matrix (right), of M
// and S, the factors of A, DKE's M⁻¹e₀, and per lane Δt, c, θ, 1 − θ, 2/Δt, the flag b₀ = 0, the projection
// (α, its flag, −g₀), the decision's first unknown x₀, the keep flag and the two forms of the energy.
struct OneSolveKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false, dke = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *p = nullptr;
  const double *right_diag = nullptr, *right_lower = nullptr, *right_upper = nullptr, *m_diag = nullptr,
               *m_lower = nullptr, *m_upper = nullptr, *s_diag = nullptr, *s_lower = nullptr, *s_upper = nullptr;
  const double *elimination = nullptr, *inverse_pivot = nullptr, *upward = nullptr, *column = nullptr;
  const double *dt = nullptr, *weight = nullptr, *theta = nullptr, *one_minus_theta = nullptr, *two_over_dt = nullptr,
               *row0_zero = nullptr, *alpha = nullptr, *projected = nullptr, *minus_gap = nullptr, *x0 = nullptr,
               *keep = nullptr;
  double* kinetic_strain = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level
};

// The same for the explicit classes (explicit_schemes.cpp, ExplicitStep): the interleaved state (U, Y the
// drift's Ũ and then Uⁿ⁺¹, V, A the consistent mass's solve), the rows of S and M, the lumped inverse mass or
// the consistent mass's LDLᵀ (pivots, factors), r = M⁻¹e₀, and per lane Δt, Δt/2, h, whether the bar is
// clamped at its far end, Taylor–Flanagan's correction (its flag, Δtμ, Δt²μ), the keep flag and the energy.
struct ExplicitKernel {
  std::size_t n = 0, lanes = 0;
  bool keeps = false, lumped = true, corrects = false;
  double *u = nullptr, *y = nullptr, *w = nullptr, *a = nullptr;
  const double *s_diag = nullptr, *s_lower = nullptr, *s_upper = nullptr, *m_diag = nullptr, *m_lower = nullptr,
               *m_upper = nullptr, *inverse_mass = nullptr, *pivot = nullptr, *factor = nullptr,
               *impulse_response = nullptr;
  const double *dt = nullptr, *half_dt = nullptr, *h = nullptr, *clamped = nullptr, *correct = nullptr,
               *dt_mu = nullptr, *dt2_mu = nullptr, *keep = nullptr;
  double* energy = nullptr;  // per lane: ½VᵀMV + ½UᵀSU of the new level (BarSimulation's)
};

}  // namespace mrm::batched
#endif

HWY_BEFORE_NAMESPACE();
namespace mrm::batched {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// The kernels are templates over the vector tag D: the full width of the target (ScalableTag) and the
// capped widths of 4 and 2 doubles, for a group narrower than the target (the remainder of a batch, see
// BatchedSimulation's constructor). The same operations in the same order at every width: the width only
// says how many lanes one instruction holds.
using Full = hn::ScalableTag<double>;
using Four = hn::CappedTag<double, 4>;
using Two = hn::CappedTag<double, 2>;

std::size_t LaneCount() { return hn::Lanes(Full()); }
std::size_t LaneCount4() { return hn::Lanes(Four()); }
std::size_t LaneCount2() { return hn::Lanes(Two()); }

// The row coefficients in the order of FastStep::Row: c1l, c1d, c1u, c2l, c2d, c2u, md, ml2, sd, sl2.
template <class D>
struct RowV {
  hn::Vec<D> c1l, c1d, c1u, c2l, c2d, c2u, md, ml2, sd, sl2;
};
template <class D>
inline RowV<D> LoadRow(D d, const double* row, std::size_t lanes) {
  const auto at = [&](std::size_t k) { return hn::Load(d, row + k * lanes); };
  return {at(0), at(1), at(2), at(3), at(4), at(5), at(6), at(7), at(8), at(9)};
}

// The sweep down of FastStep::fused_step (no load), on W lanes.
template <class D>
void SweepDownT(D d, const Kernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n), head = static_cast<std::ptrdiff_t>(k.head);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const double* u = k.u;
  const double* w = k.w;
  const auto rhs = [&](const RowV<D>& r, std::ptrdiff_t i, V u_up, V w_up) {
    return r.c1l * at(u, i - 1) + r.c1d * at(u, i) + r.c1u * u_up + r.c2l * at(w, i - 1) + r.c2d * at(w, i) +
           r.c2u * w_up;
  };
  const auto rhs_interior = [&](const RowV<D>& r, std::ptrdiff_t i) {
    return r.c1l * (at(u, i - 1) + at(u, i + 1)) + r.c1d * at(u, i) + r.c2l * (at(w, i - 1) + at(w, i + 1)) +
           r.c2d * at(w, i);
  };
  V b_up = hn::Zero(d), y_up = hn::Zero(d), y_up2 = hn::Zero(d);
  const auto eliminate_by = [&](std::ptrdiff_t i, V b, V elimination, V elimination_pair) {
    const V yi = (b - elimination * b_up) + elimination_pair * y_up2;
    hn::Store(yi, d, k.y + static_cast<std::size_t>(i) * W);
    b_up = b, y_up2 = y_up, y_up = yi;
  };
  const auto eliminate = [&](std::ptrdiff_t i, V b) {
    eliminate_by(i, b, at(k.elimination, i), at(k.elimination_pair, i));
  };
  eliminate(n - 1, rhs(LoadRow(d, k.last, W), n - 1, hn::Zero(d), hn::Zero(d)));
  {
    // The interior rows, bottom up; on the plateau [a, b) the factors are the same numbers row after row
    // (Kernel::flat_begin), held in registers instead of loaded.
    const RowV<D> r = LoadRow(d, k.interior, W);
    const std::ptrdiff_t a = static_cast<std::ptrdiff_t>(k.flat_begin), b = static_cast<std::ptrdiff_t>(k.flat_end);
    std::ptrdiff_t i = n - 2;
    for (; i >= std::max(b, head); --i) eliminate(i, rhs_interior(r, i));
    if (a < b) {
      const V elimination = at(k.elimination, a), elimination_pair = at(k.elimination_pair, a);
      for (; i >= a; --i) eliminate_by(i, rhs_interior(r, i), elimination, elimination_pair);
    }
    for (; i >= head; --i) eliminate(i, rhs_interior(r, i));
  }
  for (std::ptrdiff_t i = std::min(head, n - 1) - 1; i >= 1; --i)
    eliminate(i, rhs(LoadRow(d, k.head_rows + static_cast<std::size_t>(i) * 10 * W, W), i, at(u, i + 1), at(w, i + 1)));
}

// The sweep up of FastStep::fused_step, from the lanes' contact decisions; a lane with keep ≠ 0 is
// written back unchanged (CN-switch takes its θ-step there, alone; a lane that does not advance in a
// partial step, BatchedSimulation::step(advance), keeps its level).
template <bool three_level, bool keeps, class D>
void SweepUpT(D d, const Kernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n), head = static_cast<std::ptrdiff_t>(k.head);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto put = [&](V v, double* a, std::ptrdiff_t i) { hn::Store(v, d, a + static_cast<std::size_t>(i) * W); };
  const double* u = k.u;
  double* y = k.y;
  double* w_out = k.w;
  double* x_out = k.x;
  const V rate = hn::Load(d, k.rate), memory = hn::Load(d, k.memory);
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const V zero = hn::Zero(d);
  V kinetic = zero, potential = zero, potential_q = zero;
  V un_prev = zero, d_prev = zero, d_prev2 = zero, z_prev = zero, v_prev = zero, p_prev = zero, q_prev = zero;
  V k_d = zero, k_q = zero, p_d = zero, p_q = zero, q_d = zero, q_q = zero;
  const auto emit = [&](const RowV<D>& r, std::ptrdiff_t i, V dd, V un, auto toeplitz) {
    constexpr bool sums = decltype(toeplitz)::value;
    const V uo = at(u, i);
    if constexpr (keeps) {
      put(hn::IfThenElse(keep, uo, un), y, i);
    } else {
      put(un, y, i);
    }
    if constexpr (three_level) {
      const V xx = rate * dd, p = un + uo, q = dd;
      if constexpr (keeps) {
        put(hn::IfThenElse(keep, at(x_out, i), xx), x_out, i);
        put(hn::IfThenElse(keep, at(w_out, i), dd), w_out, i);
      } else {
        put(xx, x_out, i);
        put(dd, w_out, i);
      }
      if constexpr (sums) {
        const V dx = xx - v_prev, dp = p - p_prev, dq = q - q_prev;
        k_d = k_d + dx * dx, k_q = k_q + xx * xx;
        p_d = p_d + dp * dp, p_q = p_q + p * p;
        q_d = q_d + dq * dq, q_q = q_q + q * q;
      } else {
        kinetic = kinetic + (r.md * xx * xx + r.ml2 * v_prev * xx);
        potential = potential + (r.sd * p * p + r.sl2 * p_prev * p);
        potential_q = potential_q + (r.sd * q * q + r.sl2 * q_prev * q);
      }
      v_prev = xx, p_prev = p, q_prev = q;
    } else {
      const V wo = at(w_out, i);
      const V v = rate * dd - memory * wo;
      if constexpr (keeps) {
        put(hn::IfThenElse(keep, wo, v), w_out, i);
      } else {
        put(v, w_out, i);
      }
      if constexpr (sums) {
        const V dv = v - v_prev, du = un - un_prev;
        k_d = k_d + dv * dv, k_q = k_q + v * v;
        p_d = p_d + du * du, p_q = p_q + un * un;
      } else {
        kinetic = kinetic + (r.md * v * v + r.ml2 * v_prev * v);
        potential = potential + (r.sd * un * un + r.sl2 * un_prev * un);
      }
      v_prev = v;
    }
    un_prev = un;
    d_prev2 = d_prev, d_prev = dd;
  };
  const std::false_type explicit_row;
  const std::true_type toeplitz_row;
  const auto solve_up_by = [&](std::ptrdiff_t i, V inverse_pivot, V upward, V upward_pair) {
    const V z = inverse_pivot * at(y, i);
    const V dd = (z - upward * z_prev) + upward_pair * d_prev2;
    z_prev = z;
    return dd;
  };
  const auto emit_up = [&](const RowV<D>& r, std::ptrdiff_t i, auto toeplitz) {
    const V dd = solve_up_by(i, at(k.inverse_pivot, i), at(k.upward, i), at(k.upward_pair, i));
    emit(r, i, dd, at(u, i) + dd, toeplitz);
  };
  const V u0_next = hn::Load(d, k.u0_next), recurrence_d0 = hn::Load(d, k.recurrence_d0);
  emit(LoadRow(d, k.head_rows, W), 0, u0_next - at(u, 0), u0_next, explicit_row);
  z_prev = recurrence_d0;
  for (std::ptrdiff_t i = 1; i < std::min(head, n - 1); ++i) {
    emit_up(LoadRow(d, k.head_rows + static_cast<std::size_t>(i) * 10 * W, W), i, explicit_row);
    if (i == 1) d_prev2 = recurrence_d0;
  }
  if (head < n - 1) {
    const RowV<D> r = LoadRow(d, k.interior, W);
    const V ka = v_prev, pa = three_level ? p_prev : un_prev, qa = q_prev;
    // The interior rows, top down, with the plateau [a, b) as in SweepDown. Two levels: its factors held
    // in registers. Three levels keep three more forms' sums live, and three copies of the emission
    // would not all be inlined (measured: twice the time): one loop, the plateau's factors read from
    // row a (L1-resident) rather than streamed.
    const std::ptrdiff_t a = static_cast<std::ptrdiff_t>(k.flat_begin), b = static_cast<std::ptrdiff_t>(k.flat_end);
    if constexpr (three_level) {
      for (std::ptrdiff_t i = head; i < n - 1; ++i) {
        const std::ptrdiff_t f = i >= a && i < b ? a : i;
        const V dd = solve_up_by(i, at(k.inverse_pivot, f), at(k.upward, f), at(k.upward_pair, f));
        emit(r, i, dd, at(u, i) + dd, toeplitz_row);
      }
    } else {
      std::ptrdiff_t i = head;
      for (; i < std::min(a, n - 1); ++i) emit_up(r, i, toeplitz_row);
      if (a < b) {
        const V inverse_pivot = at(k.inverse_pivot, a), upward = at(k.upward, a), upward_pair = at(k.upward_pair, a);
        for (; i < b; ++i) {
          const V dd = solve_up_by(i, inverse_pivot, upward, upward_pair);
          emit(r, i, dd, at(u, i) + dd, toeplitz_row);
        }
      }
      for (; i < n - 1; ++i) emit_up(r, i, toeplitz_row);
    }
    const V kb = v_prev, pb = three_level ? p_prev : un_prev, qb = q_prev;
    const V half = hn::Set(d, 0.5);
    const auto form = [&](V dg, V l2, V sum_d, V sum_q, V za, V zb) {
      const V l = half * l2;
      return hn::Neg(l) * sum_d + (dg + l2) * sum_q - l * zb * zb + l * za * za;
    };
    kinetic = kinetic + form(r.md, r.ml2, k_d, k_q, ka, kb);
    potential = potential + form(r.sd, r.sl2, p_d, p_q, pa, pb);
    if constexpr (three_level) potential_q = potential_q + form(r.sd, r.sl2, q_d, q_q, qa, qb);
  }
  emit_up(LoadRow(d, k.last, W), n - 1, explicit_row);
  V energy;
  if constexpr (three_level) {
    energy = hn::Set(d, 0.5) * kinetic + hn::Set(d, 0.125) * (potential - hn::Load(d, k.ps_q_weight) * potential_q);
  } else {
    energy = hn::Set(d, 0.5) * kinetic + hn::Set(d, 0.5) * potential;
  }
  hn::Store(energy, d, k.energy);
}

template <class D>
void SweepUpD(D d, const Kernel& k) {
  if (k.three_level) return k.keeps ? SweepUpT<true, true>(d, k) : SweepUpT<true, false>(d, k);
  if (k.keeps) return SweepUpT<false, true>(d, k);
  SweepUpT<false, false>(d, k);
}

// ---- The Newmark-type step (contact_classes.cpp, NewmarkContactStep::fused_advance), on W lanes ----
// Each function is a pass of the fused step, with its operations in its order, operand for operand:
// (A x)_i as Tridiagonal::multiply sums it, (d_i x_i + l_i x_{i−1}) + u_i x_{i+1}, the terms that exist.

// 1. b_i = ((MUⁿ)_i + Δt(MVⁿ)_i) + Δt²(½ − β)Rⁿ_i inside the sweep down of A, y_i = b_i − ε_i y_{i+1}; row 0's
// b is 0 for a massless contact node.
template <class D>
void NewmarkDownT(D d, const NewmarkKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const V dt = hn::Load(d, k.dt), c_r = hn::Load(d, k.force_weight);
  const auto row = [&](const double* dg, const double* lo, const double* up, const double* x, std::ptrdiff_t i) {
    V s = at(dg, i) * at(x, i);
    if (i > 0) s = s + at(lo, i) * at(x, i - 1);
    if (i + 1 < n) s = s + at(up, i) * at(x, i + 1);
    return s;
  };
  const auto b = [&](std::ptrdiff_t i) {
    V bi = row(k.m_diag, k.m_lower, k.m_upper, k.u, i) + dt * row(k.m_diag, k.m_lower, k.m_upper, k.w, i);
    bi = bi + c_r * at(k.r, i);
    return bi;
  };
  V yi = b(n - 1);
  hn::Store(yi, d, k.y + static_cast<std::size_t>(n - 1) * W);
  for (std::ptrdiff_t i = n - 2; i > 0; --i) {
    yi = b(i) - at(k.elimination, i) * yi;
    hn::Store(yi, d, k.y + static_cast<std::size_t>(i) * W);
  }
  const V b0 = hn::IfThenElse(hn::Ne(hn::Load(d, k.massless), hn::Zero(d)), hn::Zero(d), b(0));
  hn::Store(b0 - at(k.elimination, 0) * yi, d, k.y);
}

// 2. From each lane's decision: the sweep up of A (penalty, Nitsche: of U_f, then U = U_f − λz where the lane
// shifts), and Rⁿ⁺¹_{i−1} = −(S_ℓUⁿ⁺¹)_{i−1} one row behind; rows 0 and 1 then take −λg, and row 0 of a massless
// node is 0. A kept lane's U and R are written back unchanged.
template <bool keeps, class D>
void NewmarkUpT(D d, const NewmarkKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const auto shift = hn::Ne(hn::Load(d, k.shift), hn::Zero(d));
  const V lambda = hn::Load(d, k.lambda);
  const auto put = [&](V v, double* a, const double* old, std::ptrdiff_t i) {
    if constexpr (keeps) v = hn::IfThenElse(keep, at(old, i), v);
    hn::Store(v, d, a + static_cast<std::size_t>(i) * W);
  };
  const auto shifted = [&](V free, std::ptrdiff_t i) {
    return hn::IfThenElse(shift, free - lambda * at(k.z, i), free);
  };
  V free = hn::Load(d, k.u0);
  const V y0 = shifted(free, 0);
  free = at(k.inverse_pivot, 1) * at(k.y, 1) - at(k.upward, 1) * free;
  const V y1 = shifted(free, 1);
  put(y0, k.y, k.u, 0);
  put(y1, k.y, k.u, 1);
  V r0 = at(k.l_diag, 0) * y0;
  r0 = hn::Neg(r0 + at(k.l_upper, 0) * y1);
  V before = y0, last = y1, r1 = r0;
  for (std::ptrdiff_t i = 2; i < n; ++i) {
    free = at(k.inverse_pivot, i) * at(k.y, i) - at(k.upward, i) * free;
    const V yi = shifted(free, i);
    put(yi, k.y, k.u, i);
    V s = at(k.l_diag, i - 1) * last;
    s = s + at(k.l_lower, i - 1) * before;
    s = hn::Neg(s + at(k.l_upper, i - 1) * yi);
    if (i == 2)
      r1 = s;
    else
      put(s, k.r_next, k.r, i - 1);
    before = last, last = yi;
  }
  V rl = at(k.l_diag, n - 1) * last;
  put(hn::Neg(rl + at(k.l_lower, n - 1) * before), k.r_next, k.r, n - 1);
  r0 = r0 - lambda * hn::Load(d, k.g0);
  r1 = r1 - lambda * hn::Load(d, k.g1);
  r0 = hn::IfThenElse(hn::Ne(hn::Load(d, k.massless), hn::Zero(d)), hn::Zero(d), r0);
  put(r0, k.r_next, k.r, 0);
  put(r1, k.r_next, k.r, 1);
}

// 3. Δt((1 − γ)Rⁿ_i + γRⁿ⁺¹_i) inside the sweep down of M̃; 4. its sweep up, each entry added to Vⁿ as it
// comes (a kept lane's V stays).
template <bool keeps, class D>
void NewmarkVelocityT(D d, const NewmarkKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const V dt = hn::Load(d, k.dt), a = hn::Load(d, k.one_minus_gamma), g = hn::Load(d, k.gamma);
  V ti = dt * (a * at(k.r, n - 1) + g * at(k.r_next, n - 1));
  hn::Store(ti, d, k.t + static_cast<std::size_t>(n - 1) * W);
  for (std::ptrdiff_t i = n - 2; i >= 0; --i) {
    ti = dt * (a * at(k.r, i) + g * at(k.r_next, i)) - at(k.mass_elimination, i) * ti;
    hn::Store(ti, d, k.t + static_cast<std::size_t>(i) * W);
  }
  V vi = at(k.t, 0) * at(k.mass_inverse_pivot, 0);
  for (std::ptrdiff_t i = 0; i < n; ++i) {
    if (i > 0) vi = at(k.mass_inverse_pivot, i) * at(k.t, i) - at(k.mass_upward, i) * vi;
    V wi = at(k.w, i) + vi;
    if constexpr (keeps) wi = hn::IfThenElse(keep, at(k.w, i), wi);
    hn::Store(wi, d, k.w + static_cast<std::size_t>(i) * W);
  }
}

// xᵀAx as Tridiagonal::form sums it (p1.cpp, form_of), lane by lane: the rows' terms x_i (A x)_i in four
// partial sums by i mod 4, then (s₀ + s₂) and (s₁ + s₃), the rows of a last pair, their sum, and a last odd
// row; n ≥ 4.
template <class D>
hn::Vec<D> FormT(D d, std::size_t W, std::ptrdiff_t n, const double* dg, const double* lo, const double* up,
                 const double* x) {
  using V = hn::Vec<D>;
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto row = [&](std::ptrdiff_t i) {
    const V xi = at(x, i);
    V s = at(dg, i) * xi;
    if (i > 0) s = s + at(lo, i) * at(x, i - 1);
    if (i + 1 < n) s = s + at(up, i) * at(x, i + 1);
    return xi * s;
  };
  const std::ptrdiff_t end4 = n / 4 * 4, end2 = n / 2 * 2;
  V a0 = row(0), a1 = row(1), b0 = row(2), b1 = row(3);
  std::ptrdiff_t i = 4;
  for (; i + 4 < n; i += 4) {
    a0 = a0 + row(i), a1 = a1 + row(i + 1);
    b0 = b0 + row(i + 2), b1 = b1 + row(i + 3);
  }
  if (i < end4) {
    a0 = a0 + row(i), a1 = a1 + row(i + 1);
    b0 = b0 + row(i + 2), b1 = b1 + row(i + 3);
  }
  a0 = a0 + b0, a1 = a1 + b1;
  if (end2 > end4) a0 = a0 + row(end4), a1 = a1 + row(end4 + 1);
  V sum = a0 + a1;
  if (n > end2) sum = sum + row(n - 1);
  return sum;
}

// The energy's ½VᵀMV + ½UᵀSU of the new level (kinetic_and_strain, contact_classes.cpp), U in y.
template <class D>
void NewmarkEnergyT(D d, const NewmarkKernel& k) {
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto half = hn::Set(d, 0.5);
  const auto kinetic = FormT(d, k.lanes, n, k.m_diag, k.m_lower, k.m_upper, k.w);
  const auto strain = FormT(d, k.lanes, n, k.s_diag, k.s_lower, k.s_upper, k.y);
  hn::Store(half * kinetic + half * strain, d, k.kinetic_strain);
}

template <class D>
void NewmarkStepD(D d, const NewmarkKernel& k) {
  if (k.keeps) {
    NewmarkUpT<true>(d, k);
    NewmarkVelocityT<true>(d, k);
  } else {
    NewmarkUpT<false>(d, k);
    NewmarkVelocityT<false>(d, k);
  }
  NewmarkEnergyT(d, k);
}

// ---- Moreau–Jean and DKE (contact_classes.cpp, MoreauJeanStep and DkeStep::fused_advance), on W lanes ----
// The passes of the fused steps, with their operations in their order, operand for operand.

// 1. DKE: the predictor P_i = Uⁿ_i + ΔtVⁿ_i, plus αM⁻¹e₀ in the lanes that project (and there P₀ = −g₀).
// Then, for both, b_i = (R x)_i − c(SUⁿ)_i inside the sweep down of A (R = M − θ(1 − θ)Δt²S, x = Vⁿ, c = Δt for
// Moreau–Jean; R = M, x = P, c = Δt²/4 for DKE), y_i = b_i − ε_i y_{i+1}; row 0's b is 0 on DKE's algebraic row.
template <class D>
void OneSolveDownT(D d, const OneSolveKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const V dt = hn::Load(d, k.dt), c = hn::Load(d, k.weight);
  if (k.dke) {
    const auto projects = hn::Ne(hn::Load(d, k.projected), hn::Zero(d));
    const V alpha = hn::Load(d, k.alpha);
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const V pi = at(k.u, i) + dt * at(k.w, i);
      hn::Store(hn::IfThenElse(projects, pi + alpha * at(k.column, i), pi), d, k.p + static_cast<std::size_t>(i) * W);
    }
    hn::Store(hn::IfThenElse(projects, hn::Load(d, k.minus_gap), at(k.p, 0)), d, k.p);
  }
  const double* x = k.dke ? k.p : k.w;
  const auto row = [&](const double* dg, const double* lo, const double* up, const double* v, std::ptrdiff_t i) {
    V s = at(dg, i) * at(v, i);
    if (i > 0) s = s + at(lo, i) * at(v, i - 1);
    if (i + 1 < n) s = s + at(up, i) * at(v, i + 1);
    return s;
  };
  const auto b = [&](std::ptrdiff_t i) {
    return row(k.right_diag, k.right_lower, k.right_upper, x, i) - c * row(k.s_diag, k.s_lower, k.s_upper, k.u, i);
  };
  V yi = b(n - 1);
  hn::Store(yi, d, k.y + static_cast<std::size_t>(n - 1) * W);
  for (std::ptrdiff_t i = n - 2; i > 0; --i) {
    yi = b(i) - at(k.elimination, i) * yi;
    hn::Store(yi, d, k.y + static_cast<std::size_t>(i) * W);
  }
  const V b0 = hn::IfThenElse(hn::Ne(hn::Load(d, k.row0_zero), hn::Zero(d)), hn::Zero(d), b(0));
  hn::Store(b0 - at(k.elimination, 0) * yi, d, k.y);
}

// 2. The sweep up of A from each lane's x₀ (the contact step's), and node by node the other vector: Moreau–Jean
// Uⁿ⁺¹_i = Uⁿ_i + Δt(θVⁿ⁺¹_i + (1 − θ)Vⁿ_i) with Vⁿ⁺¹ in y; DKE Vⁿ⁺¹_i = (P_i − Uⁿ_i)/Δt + (2/Δt)(Uⁿ⁺¹_i − P_i)
// with Uⁿ⁺¹ in y. A kept lane's y takes its old V (Moreau–Jean) or U (DKE) and its other vector stays, so that
// the swap after the step leaves it as it was. Then the energy's two forms of the new level.
template <bool dke, bool keeps, class D>
void OneSolveUpT(D d, const OneSolveKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const auto put = [&](V v, double* a, std::ptrdiff_t i) { hn::Store(v, d, a + static_cast<std::size_t>(i) * W); };
  const V dt = hn::Load(d, k.dt), theta = hn::Load(d, k.theta), a = hn::Load(d, k.one_minus_theta);
  const V two = hn::Load(d, k.two_over_dt);
  const auto emit = [&](std::ptrdiff_t i, V xi) {
    if constexpr (dke) {
      const V ui = at(k.u, i), pi = at(k.p, i);
      const V vi = (pi - ui) / dt + two * (xi - pi);
      if constexpr (keeps) {
        put(hn::IfThenElse(keep, ui, xi), k.y, i);
        put(hn::IfThenElse(keep, at(k.w, i), vi), k.w, i);
      } else {
        put(xi, k.y, i);
        put(vi, k.w, i);
      }
    } else {
      const V wi = at(k.w, i), ui = at(k.u, i);
      const V un = ui + dt * (theta * xi + a * wi);
      if constexpr (keeps) {
        put(hn::IfThenElse(keep, wi, xi), k.y, i);
        put(hn::IfThenElse(keep, ui, un), k.u, i);
      } else {
        put(xi, k.y, i);
        put(un, k.u, i);
      }
    }
  };
  V xi = hn::Load(d, k.x0);
  emit(0, xi);
  for (std::ptrdiff_t i = 1; i < n; ++i) {
    xi = at(k.inverse_pivot, i) * at(k.y, i) - at(k.upward, i) * xi;
    emit(i, xi);
  }
  // ½VᵀMV + ½UᵀSU (kinetic_and_strain): Moreau–Jean's Vⁿ⁺¹ is in y, DKE's Uⁿ⁺¹.
  const auto half = hn::Set(d, 0.5);
  const auto kinetic = FormT(d, W, n, k.m_diag, k.m_lower, k.m_upper, dke ? k.w : k.y);
  const auto strain = FormT(d, W, n, k.s_diag, k.s_lower, k.s_upper, dke ? k.y : k.u);
  hn::Store(half * kinetic + half * strain, d, k.kinetic_strain);
}

template <class D>
void OneSolveUpD(D d, const OneSolveKernel& k) {
  if (k.dke) return k.keeps ? OneSolveUpT<true, true>(d, k) : OneSolveUpT<true, false>(d, k);
  if (k.keeps) return OneSolveUpT<false, true>(d, k);
  OneSolveUpT<false, false>(d, k);
}

// ---- The explicit classes (explicit_schemes.cpp, ExplicitStep::step), on W lanes ----
// The passes of the step, with its operations in its order, operand for operand.

// The acceleration M⁻¹(−SX) (ExplicitStep::accelerate: −(SX) by Tridiagonal::multiply's rows, then times 1/m_i,
// or the consistent mass's LDLᵀ solve: ℓ forward, then d and ℓ backward), handed to take(i, a_i) node by node
// (lumped: in any order, each node its own; consistent: from the last row up).
template <bool lumped, class D, class Take>
void AccelerateT(D d, const ExplicitKernel& k, const double* x, const Take& take) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto row = [&](std::ptrdiff_t i) {
    V s = at(k.s_diag, i) * at(x, i);
    if (i > 0) s = s + at(k.s_lower, i) * at(x, i - 1);
    if (i + 1 < n) s = s + at(k.s_upper, i) * at(x, i + 1);
    return hn::Neg(s);
  };
  if constexpr (lumped) {
    for (std::ptrdiff_t i = 0; i < n; ++i) take(i, row(i) * at(k.inverse_mass, i));
  } else {
    V a = row(0);
    hn::Store(a, d, k.a);
    for (std::ptrdiff_t i = 1; i < n; ++i) {
      a = row(i) - at(k.factor, i) * a;
      hn::Store(a, d, k.a + static_cast<std::size_t>(i) * W);
    }
    a = at(k.a, n - 1) / at(k.pivot, n - 1) - hn::Zero(d);
    take(n - 1, a);
    for (std::ptrdiff_t i = n - 2; i >= 0; --i) {
      a = at(k.a, i) / at(k.pivot, i) - at(k.factor, i + 1) * a;
      take(i, a);
    }
  }
}

// 1. The half kick and the drift: Vⁿ⁺½ = Vⁿ + (Δt/2)Aⁿ, Ũ = Uⁿ + ΔtVⁿ⁺½ into y (a kept lane: V and U as they were).
template <bool lumped, bool keeps, class D>
void ExplicitDriftT(D d, const ExplicitKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const V dt = hn::Load(d, k.dt), half = hn::Load(d, k.half_dt);
  AccelerateT<lumped>(d, k, k.u, [&](std::ptrdiff_t i, V a) {
    const V wo = at(k.w, i), ui = at(k.u, i);
    V v = wo + half * a, y = ui + dt * v;
    if constexpr (keeps) v = hn::IfThenElse(keep, wo, v), y = hn::IfThenElse(keep, ui, y);
    hn::Store(v, d, k.w + static_cast<std::size_t>(i) * W);
    hn::Store(y, d, k.y + static_cast<std::size_t>(i) * W);
  });
}

// 2. Taylor–Flanagan's correction in the lanes that make it (V −= Δtμ r, Ũ −= Δt²μ r), the second half kick
// Vⁿ⁺¹ = Vⁿ⁺½ + (Δt/2)Aⁿ⁺¹ (a kept lane's V stays), then the energy ½VᵀMV + ½ Σ_e (Δ_e U)²/h, the elements'
// differences in order, the last one (0 − u_{n−1}) only on a bar clamped at its far end (stiffness_form).
template <bool lumped, bool keeps, class D>
void ExplicitKickT(D d, const ExplicitKernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const auto keep = hn::Ne(hn::Load(d, k.keep), hn::Zero(d));
  const V half = hn::Load(d, k.half_dt);
  if (k.corrects) {
    const auto correct = hn::Ne(hn::Load(d, k.correct), hn::Zero(d));
    const V dt_mu = hn::Load(d, k.dt_mu), dt2_mu = hn::Load(d, k.dt2_mu);
    for (std::ptrdiff_t i = 0; i < n; ++i) {
      const V r = at(k.impulse_response, i), v = at(k.w, i), y = at(k.y, i);
      hn::Store(hn::IfThenElse(correct, v - dt_mu * r, v), d, k.w + static_cast<std::size_t>(i) * W);
      hn::Store(hn::IfThenElse(correct, y - dt2_mu * r, y), d, k.y + static_cast<std::size_t>(i) * W);
    }
  }
  AccelerateT<lumped>(d, k, k.y, [&](std::ptrdiff_t i, V a) {
    const V wo = at(k.w, i);
    V v = wo + half * a;
    if constexpr (keeps) v = hn::IfThenElse(keep, wo, v);
    hn::Store(v, d, k.w + static_cast<std::size_t>(i) * W);
  });
  const V kinetic = FormT(d, W, n, k.m_diag, k.m_lower, k.m_upper, k.w);
  V strain = hn::Zero(d);
  for (std::ptrdiff_t e = 0; e + 1 < n; ++e) {
    const V du = at(k.y, e + 1) - at(k.y, e);
    strain = strain + du * du;
  }
  const V last = hn::Zero(d) - at(k.y, n - 1);
  strain = hn::IfThenElse(hn::Ne(hn::Load(d, k.clamped), hn::Zero(d)), strain + last * last, strain);
  const V point_five = hn::Set(d, 0.5);
  hn::Store(point_five * kinetic + point_five * (strain / hn::Load(d, k.h)), d, k.energy);
}

template <class D>
void ExplicitDriftD(D d, const ExplicitKernel& k) {
  if (k.lumped) return k.keeps ? ExplicitDriftT<true, true>(d, k) : ExplicitDriftT<true, false>(d, k);
  if (k.keeps) return ExplicitDriftT<false, true>(d, k);
  ExplicitDriftT<false, false>(d, k);
}

template <class D>
void ExplicitKickD(D d, const ExplicitKernel& k) {
  if (k.lumped) return k.keeps ? ExplicitKickT<true, true>(d, k) : ExplicitKickT<true, false>(d, k);
  if (k.keeps) return ExplicitKickT<false, true>(d, k);
  ExplicitKickT<false, false>(d, k);
}

// The entry points, one per width (where a capped width is the full one, the same code twice).
void ExplicitDrift(const ExplicitKernel& k) { ExplicitDriftD(Full(), k); }
void ExplicitDrift4(const ExplicitKernel& k) { ExplicitDriftD(Four(), k); }
void ExplicitDrift2(const ExplicitKernel& k) { ExplicitDriftD(Two(), k); }
void ExplicitKick(const ExplicitKernel& k) { ExplicitKickD(Full(), k); }
void ExplicitKick4(const ExplicitKernel& k) { ExplicitKickD(Four(), k); }
void ExplicitKick2(const ExplicitKernel& k) { ExplicitKickD(Two(), k); }
void OneSolveDown(const OneSolveKernel& k) { OneSolveDownT(Full(), k); }
void OneSolveDown4(const OneSolveKernel& k) { OneSolveDownT(Four(), k); }
void OneSolveDown2(const OneSolveKernel& k) { OneSolveDownT(Two(), k); }
void OneSolveUp(const OneSolveKernel& k) { OneSolveUpD(Full(), k); }
void OneSolveUp4(const OneSolveKernel& k) { OneSolveUpD(Four(), k); }
void OneSolveUp2(const OneSolveKernel& k) { OneSolveUpD(Two(), k); }
void NewmarkDown(const NewmarkKernel& k) { NewmarkDownT(Full(), k); }
void NewmarkDown4(const NewmarkKernel& k) { NewmarkDownT(Four(), k); }
void NewmarkDown2(const NewmarkKernel& k) { NewmarkDownT(Two(), k); }
void NewmarkUp(const NewmarkKernel& k) { NewmarkStepD(Full(), k); }
void NewmarkUp4(const NewmarkKernel& k) { NewmarkStepD(Four(), k); }
void NewmarkUp2(const NewmarkKernel& k) { NewmarkStepD(Two(), k); }
void SweepDown(const Kernel& k) { SweepDownT(Full(), k); }
void SweepDown4(const Kernel& k) { SweepDownT(Four(), k); }
void SweepDown2(const Kernel& k) { SweepDownT(Two(), k); }
void SweepUp(const Kernel& k) { SweepUpD(Full(), k); }
void SweepUp4(const Kernel& k) { SweepUpD(Four(), k); }
void SweepUp2(const Kernel& k) { SweepUpD(Two(), k); }

}  // namespace HWY_NAMESPACE
}  // namespace mrm::batched
HWY_AFTER_NAMESPACE();

/// @endcond

#if HWY_ONCE

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <map>
#include <optional>
#include <string>
#include <stdexcept>
#include <tuple>
#include <utility>

#include <doctest/doctest.h>
#include <hwy/aligned_allocator.h>

#include "time/contact.hpp"
#include "classes/contact_classes.hpp"
#include "time/explicit_schemes.hpp"
#include "time/fast_step.hpp"
#include "fem/mass_redistribution.hpp"

namespace mrm {
/// @cond MRM_INTERNAL
namespace batched {
HWY_EXPORT(LaneCount);
HWY_EXPORT(LaneCount4);
HWY_EXPORT(LaneCount2);
HWY_EXPORT(SweepDown);
HWY_EXPORT(SweepDown4);
HWY_EXPORT(SweepDown2);
HWY_EXPORT(SweepUp);
HWY_EXPORT(SweepUp4);
HWY_EXPORT(SweepUp2);
HWY_EXPORT(NewmarkDown);
HWY_EXPORT(NewmarkDown4);
HWY_EXPORT(NewmarkDown2);
HWY_EXPORT(NewmarkUp);
HWY_EXPORT(NewmarkUp4);
HWY_EXPORT(NewmarkUp2);
HWY_EXPORT(OneSolveDown);
HWY_EXPORT(OneSolveDown4);
HWY_EXPORT(OneSolveDown2);
HWY_EXPORT(OneSolveUp);
HWY_EXPORT(OneSolveUp4);
HWY_EXPORT(OneSolveUp2);
HWY_EXPORT(ExplicitDrift);
HWY_EXPORT(ExplicitDrift4);
HWY_EXPORT(ExplicitDrift2);
HWY_EXPORT(ExplicitKick);
HWY_EXPORT(ExplicitKick4);
HWY_EXPORT(ExplicitKick2);
}  // namespace batched
/// @endcond

void use_batch_target(std::int64_t bit) {
  hwy::SetSupportedTargetsForTest(bit);
  hwy::GetChosenTarget().Update(hwy::SupportedTargets());
}

std::vector<BatchTarget> batch_targets() {
  use_batch_target(0);  // every supported target, not the one a previous use_batch_target chose
  std::vector<BatchTarget> targets;
  for (const std::int64_t bit : hwy::SupportedAndGeneratedTargets()) {
    use_batch_target(bit);
    const std::size_t lanes = HWY_DYNAMIC_DISPATCH(batched::LaneCount)();
    if (lanes >= 2) targets.push_back({hwy::TargetName(bit), lanes, bit});  // one lane is the scalar step
  }
  use_batch_target(0);
  // Widest first; among equal widths the later (more capable) target first, as Highway orders them.
  std::stable_sort(targets.begin(), targets.end(),
                   [](const BatchTarget& a, const BatchTarget& b) { return a.lanes > b.lanes; });
  return targets;
}

int batch_family(Scheme scheme) { return scheme_info(scheme).batch_family; }

BatchTarget current_batch_target() {
  const std::int64_t bit = hwy::SupportedAndGeneratedTargets().front();  // the best the dispatch chooses
  return {hwy::TargetName(bit), HWY_DYNAMIC_DISPATCH(batched::LaneCount)(), bit};
}

// One group: W lanes (a run each, or a copy of lane 0's run for the lanes left over), interleaved. W is
// the target's full width, or 4 or 2 for the remainder of a family (the constructor).
struct BatchedSimulation::Group {
  std::vector<std::size_t> runs;  // the run of each lane (W of them); padding lanes repeat lane 0's, ignored
  std::size_t used = 0;           // lanes 0 … used−1 are runs of their own
  int width = 0;                  // the kernel of W lanes: 0 the full width, 1 CappedTag 4, 2 CappedTag 2
  std::size_t n = 0, head = 0;
  std::size_t flat_begin = 0, flat_end = 0;  // the plateau of the factors (find_plateau)
  bool three_level = false, switching = false;
  hwy::AlignedFreeUniquePtr<double[]> u, y, w, x, elimination, elimination_pair, inverse_pivot, upward, upward_pair,
      head_rows, interior, last, rate, memory, ps_q_weight, u0_next, recurrence_d0, keep, energy;
  std::vector<FastStep::ContactDecision> decisions;  // the lanes' contact decisions of the current step
  // A group of Newmark-type steps (batch_family 4, batched::NewmarkKernel): u, y, w, the factors of A
  // (elimination, inverse_pivot, upward), u0_next (the decision's u₀) and keep above, and these.
  bool newmark = false;
  hwy::AlignedFreeUniquePtr<double[]> r, r_next, t, m_diag, m_lower, m_upper, s_diag, s_lower, s_upper, l_diag, l_lower,
      l_upper, mass_elimination, mass_inverse_pivot, mass_upward, z, dt, force_weight, one_minus_gamma, gamma, g0, g1,
      massless, lambda, shift, kinetic_strain;
  std::vector<NewmarkTypeStep*> steps;  // each lane's step (its decision and end of step)
  // A group of Moreau–Jean or DKE steps (batch_family 5 or 6, batched::OneSolveKernel): u, y, w, the rows of M
  // and S, the factors of A, dt, keep and kinetic_strain above, u0_next as the decision's x₀, and these.
  bool one_solve = false, dke = false;
  hwy::AlignedFreeUniquePtr<double[]> p, right_diag, right_lower, right_upper, column, weight, theta, one_minus_theta,
      two_over_dt, row0_zero, alpha, projected, minus_gap;
  std::vector<OneSolveStep*> solve_steps;               // each lane's step (its pieces)
  std::vector<OneSolveStep::Decision> solve_decisions;  // the lanes' decisions of the current step
  // A group of the explicit classes (batch_family 7, batched::ExplicitKernel): u, y, w, the rows of M and S, dt,
  // keep and energy above, and these (a: the consistent mass's solve).
  bool explicit_scheme = false, lumped = true;
  hwy::AlignedFreeUniquePtr<double[]> a, inverse_mass, pivot, factor, impulse_response, half_dt, h, clamped, correct,
      dt_mu, dt2_mu;
  std::vector<const ExplicitStep*> explicit_steps;       // each lane's step (its contact)
  std::vector<ExplicitStep::Contact> explicit_contacts;  // the lanes' contacts of the current step
};

namespace {

// The rows of a FastStep as 10 doubles (the order of batched::RowV).
template <typename Row>
std::array<double, 10> coefficients(const Row& r) {
  return {r.c1l, r.c1d, r.c1u, r.c2l, r.c2d, r.c2u, r.md, r.ml2, r.sd, r.sl2};
}

// The plateau of a group's factors. The interior rows are one Toeplitz row (d on the diagonal, l and u
// beside it), and the elimination from the last row up (contact.cpp) computes the pivots by
// p_i = d − (u/p_{i+1}) l, a contraction near its fixed point p* = d − ul/p* (|ul/p*²| < 1 for these
// diagonally dominant matrices): a few tens of rows above the last one the pivots, and with them the
// five factor vectors the sweeps read (ε_i, ε_i ε_{i+1}, 1/p_i, ℓ_i/p_i and its pair product), repeat
// the same doubles row after row. A rounding map with an attracting fixed point lands on it exactly, or
// on a cycle of neighbouring doubles; only rows checked equal are used: the plateau is the first run
// [a, b) of interior rows, from the top, whose five factors equal row a's in every lane, bit for bit.
// The sweeps hold those five vectors in registers there instead of loading them: the same numbers, so
// the same bits; only the memory traffic changes (40 of the ~104 bytes per node and lane: bench_step).
}  // namespace

void BatchedSimulation::find_plateau(Group& g) {
  const std::size_t W = g.runs.size(), end = g.n - 1;  // the interior rows: head … n − 2
  const double* factors[] = {g.elimination.get(), g.elimination_pair.get(), g.inverse_pivot.get(), g.upward.get(),
                             g.upward_pair.get()};
  const auto same_rows = [&](std::size_t i, std::size_t m) {
    for (const double* f : factors)
      if (std::memcmp(f + i * W, f + m * W, W * sizeof(double)) != 0) return false;
    return true;
  };
  std::size_t a = g.head;
  while (a + 1 < end && !same_rows(a, a + 1)) ++a;
  std::size_t b = a + 1;
  while (b < end && same_rows(b, a)) ++b;
  if (a + 1 >= end || g.head >= end) a = b = g.head;  // no two equal rows: no plateau
  g.flat_begin = a, g.flat_end = b;
}

BatchedSimulation::BatchedSimulation(std::vector<BarSimulation> runs) : runs_(std::move(runs)) {
  lanes_ = HWY_DYNAMIC_DISPATCH(batched::LaneCount)();
  // The widths a group can have, narrowest first: 2, 4 (each at most the full width; equal to it on a
  // target of 2 or 4 lanes) and the full width, with their kernels (Group::width).
  const std::array<std::pair<std::size_t, int>, 3> widths = {{{HWY_DYNAMIC_DISPATCH(batched::LaneCount2)(), 2},
                                                              {HWY_DYNAMIC_DISPATCH(batched::LaneCount4)(), 1},
                                                              {lanes_, 0}}};
  const std::size_t count = runs_.size();
  stale_.assign(count, 0);
  group_of_.assign(count, 0);
  lane_of_.assign(count, 0);
  // The key of runs that can share a group: the number of unknowns, the scheme family and the layout of
  // the fast step. A run with the reference kernel or a load is stepped alone.
  using Key = std::tuple<std::size_t, int, std::size_t>;
  std::map<Key, std::vector<std::size_t>> families;
  for (std::size_t k = 0; k < count; ++k) {
    const BarSimulation& r = runs_[k];
    const FastStep* fast = r.fast_.get();
    const std::size_t n = static_cast<std::size_t>(r.state_.u.size());
    if (!fast && r.problem_.load == nullptr && lanes_ >= 2 && r.level_ == 0 && n >= 4) {
      // A Newmark-type step (newmark, penalty, nitsche) on the fused kernel without a load: family 4.
      const auto* step = dynamic_cast<const NewmarkTypeStep*>(r.class_step_.get());
      if (step && step->batchable()) {
        families[Key{n, 4, 0}].push_back(k);
        continue;
      }
      // The explicit classes (family 7) on a uniform homogeneous mesh (the energy's stiffness_form on one h),
      // lumped or not in groups of their own.
      if (r.explicit_ && r.mesh_.uniform() && r.mesh_.homogeneous()) {
        families[Key{n, 7, r.explicit_->lanes().lumped ? 0 : 1}].push_back(k);
        continue;
      }
      // Moreau–Jean (family 5) or DKE (6) on the fused kernel without a load.
      const auto* solve = dynamic_cast<const OneSolveStep*>(r.class_step_.get());
      if (solve && solve->batchable()) {
        families[Key{n, batch_family(r.parameters_.scheme), 0}].push_back(k);
        continue;
      }
    }
    if (!fast || r.problem_.load || n < 2 || lanes_ < 2 || r.level_ != 0) {
      alone_.push_back(k);
      continue;
    }
    // batch_family's numbers (its doctest checks that they agree)
    const int family = fast->three_level_ ? 1 : fast->energy_conserving_ ? 2 : fast->switching_ ? 3 : 0;
    families[Key{n, family, fast->head_.size()}].push_back(k);
  }
  // Each family: groups of the full width, then the remainder q < W in one group of the narrowest width
  // that holds it (2 runs in 2 lanes, 3 or 4 in 4, more in the full width), or alone if q = 1. The width
  // changes no bit of a lane (every operation is lane-wise), only the cost of the padding lanes.
  for (const auto& [key, members] : families) {
    for (std::size_t first = 0; first < members.size(); first += lanes_) {
      const std::size_t used = std::min(lanes_, members.size() - first);
      if (used == 1) {  // a group of one: stepped alone
        alone_.push_back(members[first]);
        continue;
      }
      auto g = std::make_unique<Group>();
      g->used = used;
      std::size_t width = lanes_;
      for (const auto& [w, kernel] : widths)
        if (w >= used) {
          width = w, g->width = kernel;
          break;
        }
      for (std::size_t j = 0; j < width; ++j) g->runs.push_back(members[first + (j < used ? j : 0)]);
      for (std::size_t j = 0; j < used; ++j) {
        group_of_[g->runs[j]] = groups_.size();
        lane_of_[g->runs[j]] = j;
      }
      if (std::get<1>(key) == 4) {
        g->n = std::get<0>(key);
        fill_newmark(*g, runs_);
        groups_.push_back(std::move(g));
        continue;
      }
      if (std::get<1>(key) == 7) {
        g->n = std::get<0>(key);
        fill_explicit(*g, runs_);
        groups_.push_back(std::move(g));
        continue;
      }
      if (std::get<1>(key) == 5 || std::get<1>(key) == 6) {
        g->n = std::get<0>(key);
        fill_one_solve(*g, runs_, std::get<1>(key) == 6);
        groups_.push_back(std::move(g));
        continue;
      }
      const BarSimulation& r0 = runs_[g->runs[0]];
      g->n = std::get<0>(key);
      g->head = std::get<2>(key);
      g->three_level = r0.fast_->three_level_;
      g->switching = r0.fast_->switching_;
      const std::size_t nw = g->n * width;
      for (auto* a : {&g->u, &g->y, &g->w, &g->x, &g->elimination, &g->elimination_pair, &g->inverse_pivot, &g->upward,
                      &g->upward_pair})
        *a = hwy::AllocateAligned<double>(nw);
      g->head_rows = hwy::AllocateAligned<double>(g->head * 10 * width);
      g->interior = hwy::AllocateAligned<double>(10 * width);
      g->last = hwy::AllocateAligned<double>(10 * width);
      for (auto* a : {&g->rate, &g->memory, &g->ps_q_weight, &g->u0_next, &g->recurrence_d0, &g->keep, &g->energy})
        *a = hwy::AllocateAligned<double>(width);
      g->decisions.resize(width);
      for (std::size_t j = 0; j < width; ++j) {
        const BarSimulation& r = runs_[g->runs[j]];
        const FastStep& f = *r.fast_;
        const ContactSolver& s = r.solver_;
        for (std::size_t i = 0; i < g->n; ++i) {
          const auto e = static_cast<Index>(i);
          g->elimination[i * width + j] = s.elimination()[e];
          g->elimination_pair[i * width + j] = s.elimination_pair()[e];
          g->inverse_pivot[i * width + j] = s.inverse_pivot()[e];
          g->upward[i * width + j] = s.upward()[e];
          g->upward_pair[i * width + j] = s.upward_pair()[e];
        }
        for (std::size_t h = 0; h < g->head; ++h) {
          const auto c = coefficients(f.head_[h]);
          for (std::size_t m = 0; m < 10; ++m) g->head_rows[(h * 10 + m) * width + j] = c[m];
        }
        const auto ci = coefficients(f.interior_), cl = coefficients(f.last_);
        for (std::size_t m = 0; m < 10; ++m) {
          g->interior[m * width + j] = ci[m];
          g->last[m * width + j] = cl[m];
        }
        g->rate[j] = f.coefficients_.velocity_rate;
        g->memory[j] = f.coefficients_.velocity_memory;
        g->ps_q_weight[j] = 1 - 4 * f.beta_;  // as fused_step writes it: (1 − 4β)
        g->keep[j] = 0;
      }
      for (std::size_t j = 0; j < width; ++j) load_lane(*g, j, runs_[g->runs[j]]);
      find_plateau(*g);
      groups_.push_back(std::move(g));
    }
  }
}

BatchedSimulation::~BatchedSimulation() = default;
BatchedSimulation::BatchedSimulation(BatchedSimulation&&) noexcept = default;
BatchedSimulation& BatchedSimulation::operator=(BatchedSimulation&&) noexcept = default;

namespace {

// Lane j of a group's interleaved array (element i at i·W + j) from a run's vector of the group's n entries,
// or zeros from an empty one (a vector the run's step does not have: Newmark's z, DKE's M⁻¹e₀ on a massless
// node, the other mass's arrays of an explicit step).
void interleave(double* to, const Eigen::VectorXd& from, std::size_t n, std::size_t W, std::size_t j) {
  for (std::size_t i = 0; i < n; ++i) to[i * W + j] = from.size() == 0 ? 0.0 : from[static_cast<Index>(i)];
}
// The three diagonals of a tridiagonal matrix.
void interleave(const std::array<double*, 3>& to, const Tridiagonal& a, std::size_t n, std::size_t W, std::size_t j) {
  interleave(to[0], a.diag, n, W, j), interleave(to[1], a.lower, n, W, j), interleave(to[2], a.upper, n, W, j);
}
// The three factors of a solver that its two sweeps read (ε, 1/p, ℓ/p).
void interleave(const std::array<double*, 3>& to, const ContactSolver& a, std::size_t n, std::size_t W, std::size_t j) {
  interleave(to[0], a.elimination(), n, W, j), interleave(to[1], a.inverse_pivot(), n, W, j);
  interleave(to[2], a.upward(), n, W, j);
}

}  // namespace

// A Newmark-type run's step (its lanes' rows, factors and Rⁿ).
NewmarkTypeStep& BatchedSimulation::newmark_step(const BarSimulation& run) {
  return dynamic_cast<NewmarkTypeStep&>(*run.class_step_);
}

void BatchedSimulation::fill_newmark(Group& g, const std::vector<BarSimulation>& runs) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.newmark = true;
  for (auto* a : {&g.u,
                  &g.y,
                  &g.w,
                  &g.elimination,
                  &g.inverse_pivot,
                  &g.upward,
                  &g.r,
                  &g.r_next,
                  &g.t,
                  &g.m_diag,
                  &g.m_lower,
                  &g.m_upper,
                  &g.s_diag,
                  &g.s_lower,
                  &g.s_upper,
                  &g.l_diag,
                  &g.l_lower,
                  &g.l_upper,
                  &g.mass_elimination,
                  &g.mass_inverse_pivot,
                  &g.mass_upward,
                  &g.z})
    *a = hwy::AllocateAligned<double>(nw);
  for (auto* a : {&g.dt, &g.force_weight, &g.one_minus_gamma, &g.gamma, &g.g0, &g.g1, &g.massless, &g.lambda, &g.shift,
                  &g.kinetic_strain, &g.u0_next, &g.keep})
    *a = hwy::AllocateAligned<double>(W);
  for (std::size_t j = 0; j < W; ++j) {
    NewmarkTypeStep& step = newmark_step(runs[g.runs[j]]);
    g.steps.push_back(&step);
    const NewmarkTypeStep::Lanes l = step.lanes();
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, *l.mass, g.n, W, j);
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.l_diag.get(), g.l_lower.get(), g.l_upper.get()}, *l.linear, g.n, W, j);
    interleave({g.elimination.get(), g.inverse_pivot.get(), g.upward.get()}, *l.solver, g.n, W, j);
    interleave({g.mass_elimination.get(), g.mass_inverse_pivot.get(), g.mass_upward.get()}, *l.mass_solver, g.n, W, j);
    interleave(g.z.get(), *l.z, g.n, W, j);  // newmark: no z, zeros (never shifted)
    // As the fused step computes them: Δt²(½ − β) and 1 − γ.
    g.dt[j] = l.dt;
    g.force_weight[j] = l.dt * l.dt * (0.5 - l.beta);
    g.one_minus_gamma[j] = 1 - l.gamma;
    g.gamma[j] = l.gamma;
    g.g0[j] = l.g[0];
    g.g1[j] = l.g[1];
    g.massless[j] = l.massless ? 1.0 : 0.0;
    g.keep[j] = 0.0;
    load_lane(g, j, runs[g.runs[j]]);
  }
}

// A Moreau–Jean or DKE run's step.
OneSolveStep& BatchedSimulation::one_solve_step(const BarSimulation& run) {
  return dynamic_cast<OneSolveStep&>(*run.class_step_);
}

void BatchedSimulation::fill_one_solve(Group& g, const std::vector<BarSimulation>& runs, bool dke) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.one_solve = true, g.dke = dke;
  for (auto* a : {&g.u, &g.y, &g.w, &g.p, &g.elimination, &g.inverse_pivot, &g.upward, &g.right_diag, &g.right_lower,
                  &g.right_upper, &g.m_diag, &g.m_lower, &g.m_upper, &g.s_diag, &g.s_lower, &g.s_upper, &g.column})
    *a = hwy::AllocateAligned<double>(nw);
  for (auto* a : {&g.dt, &g.weight, &g.theta, &g.one_minus_theta, &g.two_over_dt, &g.row0_zero, &g.alpha, &g.projected,
                  &g.minus_gap, &g.u0_next, &g.keep, &g.kinetic_strain})
    *a = hwy::AllocateAligned<double>(W);
  g.solve_decisions.resize(W);
  for (std::size_t j = 0; j < W; ++j) {
    OneSolveStep& step = one_solve_step(runs[g.runs[j]]);
    g.solve_steps.push_back(&step);
    const OneSolveStep::Lanes l = step.lanes();
    interleave({g.right_diag.get(), g.right_lower.get(), g.right_upper.get()}, *l.right, g.n, W, j);
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, *l.mass, g.n, W, j);
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.elimination.get(), g.inverse_pivot.get(), g.upward.get()}, *l.solver, g.n, W, j);
    interleave(g.column.get(), *l.column, g.n, W, j);  // Moreau–Jean, a massless node: zeros (never projected)
    // As the fused steps compute them: 1 − θ, 2/Δt, −g₀.
    g.dt[j] = l.dt;
    g.weight[j] = l.weight;
    g.theta[j] = l.theta;
    g.one_minus_theta[j] = 1 - l.theta;
    g.two_over_dt[j] = 2 / l.dt;
    g.row0_zero[j] = l.row0_zero ? 1.0 : 0.0;
    g.minus_gap[j] = -l.gap;
    g.alpha[j] = 0.0, g.projected[j] = 0.0, g.keep[j] = 0.0;
    load_lane(g, j, runs[g.runs[j]]);
  }
}

void BatchedSimulation::fill_explicit(Group& g, const std::vector<BarSimulation>& runs) {
  const std::size_t W = g.runs.size(), nw = g.n * W;
  g.explicit_scheme = true;
  g.lumped = runs[g.runs[0]].explicit_->lanes().lumped;
  for (auto* a : {&g.u, &g.y, &g.w, &g.a, &g.s_diag, &g.s_lower, &g.s_upper, &g.m_diag, &g.m_lower, &g.m_upper,
                  &g.inverse_mass, &g.pivot, &g.factor, &g.impulse_response})
    *a = hwy::AllocateAligned<double>(nw);
  for (auto* a : {&g.dt, &g.half_dt, &g.h, &g.clamped, &g.correct, &g.dt_mu, &g.dt2_mu, &g.keep, &g.energy})
    *a = hwy::AllocateAligned<double>(W);
  g.explicit_contacts.resize(W);
  for (std::size_t j = 0; j < W; ++j) {
    const BarSimulation& run = runs[g.runs[j]];
    const ExplicitStep& step = *run.explicit_;
    g.explicit_steps.push_back(&step);
    const ExplicitStep::Lanes l = step.lanes();
    interleave({g.s_diag.get(), g.s_lower.get(), g.s_upper.get()}, *l.stiffness, g.n, W, j);
    interleave({g.m_diag.get(), g.m_lower.get(), g.m_upper.get()}, run.mass_, g.n, W, j);  // the energy's M
    // The other mass's arrays (lumped: pivot and factor; consistent: 1/m) and explicit's r are empty: zeros.
    interleave(g.inverse_mass.get(), *l.inverse_mass, g.n, W, j);
    interleave(g.pivot.get(), *l.pivot, g.n, W, j);
    interleave(g.factor.get(), *l.factor, g.n, W, j);
    interleave(g.impulse_response.get(), *l.impulse_response, g.n, W, j);
    // As the step and BarSimulation compute them: Δt/2 (0.5Δt) and the energy's h.
    g.dt[j] = l.dt;
    g.half_dt[j] = 0.5 * l.dt;
    g.h[j] = run.mesh_.h();
    g.clamped[j] = run.mesh_.elements == static_cast<Index>(g.n) ? 1.0 : 0.0;
    g.correct[j] = 0.0, g.dt_mu[j] = 0.0, g.dt2_mu[j] = 0.0, g.keep[j] = 0.0;
    load_lane(g, j, run);
  }
}

void BatchedSimulation::load_lane(Group& g, std::size_t j, const BarSimulation& run) {
  const std::size_t W = g.runs.size();
  if (g.one_solve || g.explicit_scheme) {
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      g.u[i * W + j] = run.state_.u[e];
      g.w[i * W + j] = run.state_.w[e];
    }
    return;
  }
  if (g.newmark) {
    const Eigen::VectorXd& r = *newmark_step(run).lanes().force;
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      g.u[i * W + j] = run.state_.u[e];
      g.w[i * W + j] = run.state_.w[e];
      g.r[i * W + j] = r[e];
    }
    return;
  }
  const bool has_x = static_cast<std::size_t>(run.state_.x.size()) == g.n;
  for (std::size_t i = 0; i < g.n; ++i) {
    const auto e = static_cast<Index>(i);
    g.u[i * W + j] = run.state_.u[e];
    g.w[i * W + j] = run.state_.w[e];
    g.x[i * W + j] = has_x ? run.state_.x[e] : 0.0;
  }
}

void BatchedSimulation::store_lane(const Group& g, std::size_t j, BarSimulation& run) {
  const std::size_t W = g.runs.size();
  if (g.one_solve || g.explicit_scheme) {
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      run.state_.u[e] = g.u[i * W + j];
      run.state_.w[e] = g.w[i * W + j];
    }
    return;
  }
  if (g.newmark) {
    Eigen::VectorXd& r = *newmark_step(run).lanes().force;
    for (std::size_t i = 0; i < g.n; ++i) {
      const auto e = static_cast<Index>(i);
      run.state_.u[e] = g.u[i * W + j];
      run.state_.w[e] = g.w[i * W + j];
      r[e] = g.r[i * W + j];
    }
    return;
  }
  const bool has_x = static_cast<std::size_t>(run.state_.x.size()) == g.n;
  for (std::size_t i = 0; i < g.n; ++i) {
    const auto e = static_cast<Index>(i);
    run.state_.u[e] = g.u[i * W + j];
    run.state_.w[e] = g.w[i * W + j];
    if (has_x) run.state_.x[e] = g.x[i * W + j];
  }
}

const BarSimulation& BatchedSimulation::run(std::size_t k) {
  if (k >= runs_.size()) throw std::out_of_range("BatchedSimulation::run: no run " + std::to_string(k));
  if (!stale_[k]) return runs_[k];
  // Every stale lane of k's group in one pass over the interleaved vectors: a driver that observes
  // every run at every step asks for all of them, and one lane alone would read every cache line of the
  // group's vectors (W passes for W lanes). Copies only: the same bits as store_lane.
  const Group& g = *groups_[group_of_[k]];
  const std::size_t W = g.runs.size();
  std::vector<std::size_t> lanes;
  for (std::size_t j = 0; j < g.used; ++j)
    if (stale_[g.runs[j]]) lanes.push_back(j);
  if (lanes.size() == 1 || g.newmark || g.one_solve ||
      g.explicit_scheme) {  // one lane, or a class group's lanes one by one
    for (std::size_t j : lanes) {
      store_lane(g, j, runs_[g.runs[j]]);
      stale_[g.runs[j]] = 0;
    }
    return runs_[k];
  }
  std::vector<double*> u, w, x;
  for (std::size_t j : lanes) {
    BarSimulation& r = runs_[g.runs[j]];
    u.push_back(r.state_.u.data());
    w.push_back(r.state_.w.data());
    x.push_back(static_cast<std::size_t>(r.state_.x.size()) == g.n ? r.state_.x.data() : nullptr);
  }
  const std::size_t count = lanes.size();
  for (std::size_t i = 0; i < g.n; ++i) {
    const double* gu = &g.u[i * W];
    const double* gw = &g.w[i * W];
    const double* gx = &g.x[i * W];
    for (std::size_t m = 0; m < count; ++m) {
      const std::size_t j = lanes[m];
      u[m][i] = gu[j];
      w[m][i] = gw[j];
      if (x[m]) x[m][i] = gx[j];
    }
  }
  for (std::size_t j : lanes) stale_[g.runs[j]] = 0;
  return runs_[k];
}

Sample BatchedSimulation::sample(std::size_t k, LaneVectors& lanes) const {
  if (k >= runs_.size()) throw std::out_of_range("BatchedSimulation::sample: no run " + std::to_string(k));
  const BarSimulation& r = runs_[k];
  const Sample s = r.sample();
  if (!stale_[k]) {
    lanes = own_lanes(s);
  } else {
    // The lanes hold what store_lane would copy: U in u, and the sample's velocity (X for the three-level
    // schemes, W for the two-level ones) in x or w.
    const Group& g = *groups_[group_of_[k]];
    const std::size_t W = g.runs.size(), j = lane_of_[k];
    lanes = {&g.u[j], r.three_level_ ? &g.x[j] : &g.w[j], W, j};
  }
  return s;
}

std::size_t BatchedSimulation::plateau_rows() const {
  std::size_t rows = 0;
  for (const auto& g : groups_) rows += g->flat_end - g->flat_begin;
  return rows;
}

std::vector<std::size_t> BatchedSimulation::group_widths() const {
  std::vector<std::size_t> widths;
  for (const auto& g : groups_) widths.push_back(g->runs.size());
  return widths;
}

std::size_t BatchedSimulation::batched_runs() const {
  std::size_t count = 0;
  for (const auto& g : groups_) count += g->used;
  return count;
}

void BatchedSimulation::step() { advance(nullptr); }

// A partial step: the runs with advance[k] = 0 are left as they are. In a group they are kept lanes (the
// sweep up writes their U, W' and X back unchanged, as for CN-switch's status changes; the state they
// were computed from is not used), and their bookkeeping is not touched; a group none of whose runs
// advances is not stepped. A padding lane follows lane 0, whose run it repeats.
void BatchedSimulation::step(const std::vector<char>& flags) {
  if (flags.size() != runs_.size())
    throw std::invalid_argument("BatchedSimulation::step: " + std::to_string(flags.size()) + " flags for " +
                                std::to_string(runs_.size()) + " runs (allowed: one per run)");
  advance(flags.data());
}

void BatchedSimulation::advance(const char* flags) {  // null: every run
  if (HWY_DYNAMIC_DISPATCH(batched::LaneCount)() != lanes_)
    throw std::logic_error("BatchedSimulation::step: the vector target changed since the batch was made");
  for (const std::size_t k : alone_)
    if (!flags || flags[k]) runs_[k].step();
  for (const auto& group : groups_) {
    Group& g = *group;
    const std::size_t W = g.runs.size();
    const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
    bool any = false, all = true;
    for (std::size_t j = 0; j < g.used; ++j) any = any || moves(j), all = all && moves(j);
    if (!any) continue;
    if (g.newmark) {
      advance_newmark(g, flags);
      continue;
    }
    if (g.one_solve) {
      advance_one_solve(g, flags);
      continue;
    }
    if (g.explicit_scheme) {
      advance_explicit(g, flags);
      continue;
    }
    // Paoli–Schatzman's first step is Crank–Nicolson's (BarSimulation::step's starter): each run alone.
    bool starting = false;
    for (std::size_t j = 0; j < g.used; ++j) starting = starting || (moves(j) && runs_[g.runs[j]].start_ != nullptr);
    if (starting) {
      for (std::size_t j = 0; j < W; ++j) {
        if (!moves(j)) continue;  // a run that stays: its lane stays too (it may be newer than its vectors)
        BarSimulation& run = runs_[g.runs[j]];
        if (j < g.used) {
          if (stale_[g.runs[j]]) store_lane(g, j, run);
          run.step();
          stale_[g.runs[j]] = 0;
        }
        load_lane(g, j, run);  // a padding lane repeats lane 0's run
      }
      continue;
    }
    batched::Kernel k;
    k.n = g.n, k.lanes = W, k.head = g.head, k.flat_begin = g.flat_begin, k.flat_end = g.flat_end;
    k.three_level = g.three_level, k.keeps = g.switching || !all;
    k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.x = g.x.get();
    k.elimination = g.elimination.get(), k.elimination_pair = g.elimination_pair.get();
    k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get(), k.upward_pair = g.upward_pair.get();
    k.head_rows = g.head_rows.get(), k.interior = g.interior.get(), k.last = g.last.get();
    k.rate = g.rate.get(), k.memory = g.memory.get(), k.ps_q_weight = g.ps_q_weight.get();
    k.u0_next = g.u0_next.get(), k.recurrence_d0 = g.recurrence_d0.get(), k.keep = g.keep.get();
    k.energy = g.energy.get();
    switch (g.width) {
      case 0:
        HWY_DYNAMIC_DISPATCH(batched::SweepDown)(k);
        break;
      case 1:
        HWY_DYNAMIC_DISPATCH(batched::SweepDown4)(k);
        break;
      default:
        HWY_DYNAMIC_DISPATCH(batched::SweepDown2)(k);
    }
    // Between the sweeps, each lane's contact decision: FastStep::contact_decision, the scalar code.
    std::vector<FastStep::ContactDecision>& decisions = g.decisions;
    for (std::size_t j = 0; j < W; ++j) {
      if (!moves(j)) {  // kept: its values are not written (the sweep up reads but discards them)
        decisions[j] = {};
        g.keep[j] = 1.0;
        g.u0_next[j] = g.u[j];
        g.recurrence_d0[j] = 0.0;
        continue;
      }
      const BarSimulation& run = runs_[g.runs[j]];
      const FastStep::ContactDecision c =
          run.fast_->contact_decision(g.u[j], g.u[W + j], g.w[j], g.w[W + j], g.y[W + j], run.state_.lambda,
                                      run.state_.active, run.solver_, false, 0.0, 0.0);
      decisions[j] = c;
      g.keep[j] = c.status_change ? 1.0 : 0.0;
      g.u0_next[j] = c.status_change ? g.u[j] : c.u0_next;  // (a kept lane's values are not written)
      g.recurrence_d0[j] = c.status_change ? 0.0 : c.recurrence_d0;
    }
    switch (g.width) {
      case 0:
        HWY_DYNAMIC_DISPATCH(batched::SweepUp)(k);
        break;
      case 1:
        HWY_DYNAMIC_DISPATCH(batched::SweepUp4)(k);
        break;
      default:
        HWY_DYNAMIC_DISPATCH(batched::SweepUp2)(k);
    }
    std::swap(g.u, g.y);  // U = Uⁿ⁺¹, as fused_step swaps u and u_new
    for (std::size_t j = 0; j < g.used; ++j) {
      if (!moves(j)) continue;
      const std::size_t r = g.runs[j];
      BarSimulation& run = runs_[r];
      if (decisions[j].status_change) {  // CN-switch's θ-step, alone, from the untouched state
        store_lane(g, j, run);
        run.switch_step(false);
        load_lane(g, j, run);
        stale_[r] = 0;
      } else {
        run.state_.lambda = decisions[j].lambda;
        run.state_.active = decisions[j].active;
        run.state_.energy = g.energy[j];
        // finish_step reads the new u₀ and V₁ (the massless node's velocity): those two are copied
        // out now, the rest of the vectors when run(k) is asked for.
        run.state_.u[0] = g.u[j];
        run.state_.w[1] = g.w[W + j];
        stale_[r] = 1;
      }
      run.finish_step();
      if (run.algebraic_row_ && !run.three_level_) g.w[j] = run.state_.w[0];  // its massless node's velocity
    }
  }
}

// The Newmark-type group's step: the sweep down of A, each lane's decision (the run's own decide()), the
// sweep up with Rⁿ⁺¹, V and the energy's forms in vectors, then each run's end of step (its finish(): λ,
// status, energy, the finiteness check) and BarSimulation's bookkeeping. A kept lane (flags) is written back
// unchanged and its run is not touched.
void BatchedSimulation::advance_newmark(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
  bool all = true;
  for (std::size_t j = 0; j < g.used; ++j) all = all && moves(j);
  batched::NewmarkKernel k;
  k.n = g.n, k.lanes = W, k.keeps = !all;
  k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.r = g.r.get(), k.r_next = g.r_next.get(), k.t = g.t.get();
  k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
  k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
  k.l_diag = g.l_diag.get(), k.l_lower = g.l_lower.get(), k.l_upper = g.l_upper.get();
  k.elimination = g.elimination.get(), k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get();
  k.mass_elimination = g.mass_elimination.get(), k.mass_inverse_pivot = g.mass_inverse_pivot.get();
  k.mass_upward = g.mass_upward.get(), k.z = g.z.get();
  k.dt = g.dt.get(), k.force_weight = g.force_weight.get(), k.one_minus_gamma = g.one_minus_gamma.get();
  k.gamma = g.gamma.get(), k.g0 = g.g0.get(), k.g1 = g.g1.get(), k.massless = g.massless.get();
  k.u0 = g.u0_next.get(), k.lambda = g.lambda.get(), k.shift = g.shift.get(), k.keep = g.keep.get();
  k.kinetic_strain = g.kinetic_strain.get();
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkDown)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkDown4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkDown2)(k);
  }
  for (std::size_t j = 0; j < W; ++j) {
    if (!moves(j)) {  // kept: its values are not written
      g.keep[j] = 1.0, g.lambda[j] = 0.0, g.shift[j] = 0.0, g.u0_next[j] = g.u[j];
      continue;
    }
    const NewmarkTypeStep::Decision c = g.steps[j]->decide(g.y[j], g.y[W + j]);
    g.keep[j] = 0.0, g.lambda[j] = c.lambda, g.shift[j] = c.shift ? 1.0 : 0.0, g.u0_next[j] = c.u0;
  }
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkUp)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkUp4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::NewmarkUp2)(k);
  }
  std::swap(g.u, g.y);  // U = Uⁿ⁺¹ and Rⁿ = Rⁿ⁺¹, as the step swaps them
  std::swap(g.r, g.r_next);
  for (std::size_t j = 0; j < g.used; ++j) {
    if (!moves(j)) continue;
    const std::size_t r = g.runs[j];
    BarSimulation& run = runs_[r];
    // finish() reads u₀, u₁ (Nitsche's energy) and finish_step V₁ (the massless node's velocity): those are
    // copied out now, the rest of the vectors when run(k) is asked for.
    run.state_.u[0] = g.u[j];
    run.state_.u[1] = g.u[W + j];
    run.state_.w[1] = g.w[W + j];
    stale_[r] = 1;
    g.steps[j]->finish(run.state_, g.lambda[j], g.kinetic_strain[j], run.level_);
    run.finish_step();
    if (run.algebraic_row_ && !run.three_level_) g.w[j] = run.state_.w[0];  // its massless node's velocity
  }
}

// A Moreau–Jean or DKE group's step: each lane's projection (DKE), the sweep down of A, each lane's contact
// step (the run's own decide()), the sweep up with the other vector and the energy's forms in vectors, then
// each run's end of step (its finish(): λ, status, energy, the finiteness check) and BarSimulation's
// bookkeeping. A kept lane (flags) is written back unchanged and its run is not touched.
void BatchedSimulation::advance_one_solve(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
  bool all = true;
  for (std::size_t j = 0; j < g.used; ++j) all = all && moves(j);
  batched::OneSolveKernel k;
  k.n = g.n, k.lanes = W, k.keeps = !all, k.dke = g.dke;
  k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.p = g.p.get();
  k.right_diag = g.right_diag.get(), k.right_lower = g.right_lower.get(), k.right_upper = g.right_upper.get();
  k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
  k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
  k.elimination = g.elimination.get(), k.inverse_pivot = g.inverse_pivot.get(), k.upward = g.upward.get();
  k.column = g.column.get(), k.dt = g.dt.get(), k.weight = g.weight.get(), k.theta = g.theta.get();
  k.one_minus_theta = g.one_minus_theta.get(), k.two_over_dt = g.two_over_dt.get(), k.row0_zero = g.row0_zero.get();
  k.alpha = g.alpha.get(), k.projected = g.projected.get(), k.minus_gap = g.minus_gap.get();
  k.x0 = g.u0_next.get(), k.keep = g.keep.get(), k.kinetic_strain = g.kinetic_strain.get();
  for (std::size_t j = 0; j < W; ++j) {  // DKE's projection, from u₀ⁿ and v₀ⁿ (a kept lane projects nothing)
    const std::optional<double> alpha = moves(j) ? g.solve_steps[j]->projection(g.u[j], g.w[j]) : std::nullopt;
    g.projected[j] = alpha ? 1.0 : 0.0;
    g.alpha[j] = alpha.value_or(0.0);
  }
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveDown)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveDown4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveDown2)(k);
  }
  for (std::size_t j = 0; j < W; ++j) {
    if (!moves(j)) {  // kept: its values are not written
      g.keep[j] = 1.0, g.u0_next[j] = 0.0, g.solve_decisions[j] = {};
      continue;
    }
    g.solve_decisions[j] = g.solve_steps[j]->decide(g.y[j], g.u[j], g.w[j]);
    g.keep[j] = 0.0, g.u0_next[j] = g.solve_decisions[j].x0;
  }
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveUp)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveUp4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::OneSolveUp2)(k);
  }
  // The new level: Moreau–Jean's Vⁿ⁺¹ and DKE's Uⁿ⁺¹ are in y, as each step swaps them in.
  std::swap(g.dke ? g.u : g.w, g.y);
  for (std::size_t j = 0; j < g.used; ++j) {
    if (!moves(j)) continue;
    const std::size_t r = g.runs[j];
    BarSimulation& run = runs_[r];
    // finish_step reads u₀ and V₁ (the massless node's velocity): the entries 0 and 1 are copied out now, the
    // rest of the vectors when run(k) is asked for.
    run.state_.u[0] = g.u[j], run.state_.u[1] = g.u[W + j];
    run.state_.w[0] = g.w[j], run.state_.w[1] = g.w[W + j];
    stale_[r] = 1;
    g.solve_steps[j]->finish(run.state_, g.solve_decisions[j], g.alpha[j], g.kinetic_strain[j], run.level_);
    run.finish_step();
    if (run.algebraic_row_ && !run.three_level_) g.w[j] = run.state_.w[0];  // its massless node's velocity
  }
}

// An explicit group's step: the half kick and the drift in vectors, each lane's contact (the run's own
// ExplicitStep::contact: Taylor–Flanagan's correction, whose update of V and Ũ is then made in vectors, or the
// explicit scheme's u₀), the second half kick and the energy in vectors, then each run's end of step (λ, the
// status, the energy) and BarSimulation's bookkeeping. A kept lane (flags) is written back unchanged and its
// run is not touched.
void BatchedSimulation::advance_explicit(Group& g, const char* flags) {
  const std::size_t W = g.runs.size();
  const auto moves = [&](std::size_t j) { return !flags || flags[g.runs[j < g.used ? j : 0]] != 0; };
  bool all = true;
  for (std::size_t j = 0; j < g.used; ++j) all = all && moves(j);
  for (std::size_t j = 0; j < W; ++j) g.keep[j] = moves(j) ? 0.0 : 1.0, g.correct[j] = 0.0;
  batched::ExplicitKernel k;
  k.n = g.n, k.lanes = W, k.keeps = !all, k.lumped = g.lumped;
  k.u = g.u.get(), k.y = g.y.get(), k.w = g.w.get(), k.a = g.a.get();
  k.s_diag = g.s_diag.get(), k.s_lower = g.s_lower.get(), k.s_upper = g.s_upper.get();
  k.m_diag = g.m_diag.get(), k.m_lower = g.m_lower.get(), k.m_upper = g.m_upper.get();
  k.inverse_mass = g.inverse_mass.get(), k.pivot = g.pivot.get(), k.factor = g.factor.get();
  k.impulse_response = g.impulse_response.get(), k.dt = g.dt.get(), k.half_dt = g.half_dt.get(), k.h = g.h.get();
  k.clamped = g.clamped.get(), k.correct = g.correct.get(), k.dt_mu = g.dt_mu.get(), k.dt2_mu = g.dt2_mu.get();
  k.keep = g.keep.get(), k.energy = g.energy.get();
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitDrift)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitDrift4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitDrift2)(k);
  }
  for (std::size_t j = 0; j < W; ++j) {
    if (!moves(j)) continue;  // kept: no correction, its Ũ (its Uⁿ) untouched
    const ExplicitStep::Contact c = g.explicit_steps[j]->contact(g.y[j], g.y[W + j], g.w[j], 0.0);
    g.explicit_contacts[j] = c;
    if (c.correct) {  // as the step computes them: (Δtμ) and (Δt Δt μ)
      g.correct[j] = 1.0, g.dt_mu[j] = g.dt[j] * c.lambda, g.dt2_mu[j] = g.dt[j] * g.dt[j] * c.lambda;
      k.corrects = true;
    }
    if (c.set_u0) g.y[j] = c.u0;
  }
  switch (g.width) {
    case 0:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitKick)(k);
      break;
    case 1:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitKick4)(k);
      break;
    default:
      HWY_DYNAMIC_DISPATCH(batched::ExplicitKick2)(k);
  }
  std::swap(g.u, g.y);  // U = Uⁿ⁺¹
  for (std::size_t j = 0; j < g.used; ++j) {
    if (!moves(j)) continue;
    const std::size_t r = g.runs[j];
    BarSimulation& run = runs_[r];
    // finish_step reads u₀ and V₁ (the massless node's velocity): the entries 0 and 1 are copied out now, the
    // rest of the vectors when run(k) is asked for.
    run.state_.u[0] = g.u[j], run.state_.u[1] = g.u[W + j];
    run.state_.w[0] = g.w[j], run.state_.w[1] = g.w[W + j];
    stale_[r] = 1;
    run.state_.lambda = g.explicit_contacts[j].lambda;
    run.state_.active = g.explicit_contacts[j].active;
    run.state_.energy = g.energy[j];
    run.finish_step();
    if (run.algebraic_row_ && !run.three_level_) g.w[j] = run.state_.w[0];  // its massless node's velocity
  }
}

/// @file batched_step.cpp
/// ## The batched step against the runs stepped alone
///
/// Prediction: bit for bit the same states (U, W', X, λ, the energy, the status, the instants) at every
/// step, lane by lane, for every scheme with a batched kernel (cn, be, ps with both contact rows, ec,
/// cn-switch, the Newmark-type classes newmark, penalty, nitsche, moreau-jean, dke, taylor-flanagan and
/// explicit: every scheme of the registry) and every vector target this machine has: the batched step
/// performs each lane's operations in the scalar order, and CN-switch's status changes and
/// Paoli–Schatzman's first step are the lane's own scalar step, as are the classes' contact decisions, DKE's
/// projection and the ends of step (NewmarkTypeStep::decide, finish; OneSolveStep::projection, decide,
/// finish; ExplicitStep::contact). The runs of a batch differ in Δt (Courant numbers 0.5 … 1.7; the explicit
/// classes 0.5 … 0.92 of their stability limit), mass (Mod 1, Mod 3, the consistent mass where the scheme
/// allows it; Taylor–Flanagan's lumped or not), for Paoli–Schatzman in β and e, for the Newmark type in β (0
/// at 0.9 of the stability limit, or (γ + ½)²/4), γ, the penalty and Nitsche's θ and γ₀, for Moreau–Jean in
/// θ and e, and for Moreau–Jean, DKE and the explicit classes in the initial gap (0 or h/2); their number
/// 2W + 1 leaves a group with padding lanes or a run alone. A difference of one ulp anywhere fails; so do
/// four mutations of the Newmark-type kernel (tried): the form's partial sums paired otherwise, the law's
/// force on row 0 dropped, the shift's select inverted, a kept lane's velocity not kept; four of the
/// one-solve kernel (tried): DKE's projection dropped, DKE's P₀ = −g₀ dropped, the kinetic form taken of the
/// wrong vector, a kept Moreau–Jean lane's velocity not kept (the partial step below); and four of the
/// explicit kernel (tried): Taylor–Flanagan's correction skipped, the clamped end's element dropped from the
/// energy, a kept lane's second kick not kept, the explicit scheme's u₀ not set.
namespace {

bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  return a.size() == b.size() && (a.size() == 0 || std::memcmp(a.data(), b.data(), sizeof(double) * a.size()) == 0);
}

// Every scheme with a batched kernel, Paoli–Schatzman with both contact rows.
struct BatchedCase {
  Scheme scheme;
  ContactRow row;
};
std::vector<BatchedCase> batched_cases() {
  return {{Scheme::crank_nicolson, ContactRow::algebraic},
          {Scheme::backward_euler, ContactRow::algebraic},
          {Scheme::paoli_schatzman, ContactRow::algebraic},
          {Scheme::paoli_schatzman, ContactRow::literal},
          {Scheme::energy_conserving, ContactRow::algebraic},
          {Scheme::switching, ContactRow::algebraic},
          {Scheme::newmark, ContactRow::algebraic},
          {Scheme::penalty, ContactRow::algebraic},
          {Scheme::nitsche, ContactRow::algebraic},
          {Scheme::moreau_jean, ContactRow::algebraic},
          {Scheme::dke, ContactRow::algebraic},
          {Scheme::taylor_flanagan, ContactRow::algebraic},
          {Scheme::explicit_central, ContactRow::algebraic}};
}

// Run k's lumping, mass, gap and Δt of an explicit class: Taylor–Flanagan with the consistent mass, lumped
// (row-sum) or not; explicit with Mod 1 or Mod 3, lumped; every third run with a gap of h/2; Δt the fraction
// `fraction` of the run's stability limit (explicit_stability_limit).
MassRedistribution explicit_parameters(SchemeParameters& p, std::size_t k, Problem& problem, const UniformMesh& mesh,
                                       double fraction, double& dt) {
  if (k % 3 == 2) problem.gap = 0.5 * mesh.h();
  const bool tf = p.scheme == Scheme::taylor_flanagan;
  const MassRedistribution mass = tf ? consistent_mass() : k % 2 == 0 ? mod1() : mod3();
  p.lumping = tf && k % 2 == 1 ? MassLumping::none : MassLumping::row_sum;
  const Eigen::VectorXd lumped = row_sum_lumped_mass(mesh, mass);
  dt = fraction * explicit_stability_limit(mesh, p.lumping == MassLumping::row_sum ? &lumped : nullptr);
  return mass;
}

// Run k's parameters, mass and gap of Moreau–Jean (θ = ½, ¾, 1; e = 1, ½, 0; the consistent mass, the one it
// allows) or DKE (Mod 1, Mod 3, the consistent mass); every other run of the two with an initial gap of h/2
// (the obstacle at −g₀ in the decision and in DKE's projection).
MassRedistribution one_solve_parameters(SchemeParameters& p, std::size_t k, Problem& problem, double h) {
  if (k % 2 == 1) problem.gap = 0.5 * h;
  if (p.scheme == Scheme::dke) return k % 3 == 0 ? mod1() : k % 3 == 1 ? mod3() : consistent_mass();
  p.moreau_theta = k % 3 == 0 ? 0.5 : k % 3 == 1 ? 0.75 : 1.0;
  p.restitution = k % 4 == 0 ? 1.0 : k % 4 == 1 ? 0.5 : 0.0;
  return consistent_mass();
}

// Run k's parameters of a Newmark-type class: γ = ½ or 0.6; β = (γ + ½)²/4 (stable at any Δt) or, where
// `explicit_step` allows and the class does (exact enforcement needs a massless node for β = 0), β = 0 at 0.9
// of its stability limit, which then replaces `dt`; penalty γ₀ = 1 or 100; Nitsche θ = 0, 1 or −1, γ₀ = 5
// or 50.
void class_parameters(SchemeParameters& p, std::size_t k, const UniformMesh& mesh, const MassRedistribution& mass,
                      bool explicit_step, double& dt) {
  p.newmark_gamma = k % 4 == 3 ? 0.6 : 0.5;
  if (p.scheme == Scheme::penalty) p.penalty = k % 3 == 1 ? 100.0 : 1.0;
  if (p.scheme == Scheme::nitsche) {
    p.nitsche_theta = k % 3 == 0 ? 0.0 : k % 3 == 1 ? 1.0 : -1.0;
    p.nitsche_gamma = k % 4 < 2 ? 5.0 : 50.0;
  }
  const bool massless = contact_node_is_massless(modified_mass(mesh, mass));
  const double implicit = 0.25 * (p.newmark_gamma + 0.5) * (p.newmark_gamma + 0.5);  // β ≥ γ/2: any Δt
  p.newmark_beta = explicit_step && k % 2 == 1 && (p.scheme != Scheme::newmark || massless) ? 0.0 : implicit;
  if (p.newmark_beta == 0.0)
    dt = 0.9 * newmark_stability_limit(modified_mass(mesh, mass), p1_stiffness(mesh), p, mesh.contact_compliance());
}

}  // namespace

TEST_CASE("the batched step is bitwise each run stepped alone, lane by lane, for every scheme and target") {
  const std::vector<BatchedCase> cases = batched_cases();
  const UniformMesh mesh(1.0, 24);
  const Index steps = 150;  // past the first impact (t = 1) at every Δt below
  const std::vector<BatchTarget> targets = batch_targets();
  REQUIRE(!targets.empty());
  int batched_cases = 0, status_changes = 0;
  for (const BatchTarget& target : targets) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const BatchedCase& c : cases) {
      CAPTURE(to_string(c.scheme));
      CAPTURE(to_string(c.row));
      std::vector<BarSimulation> batch, alone;
      const std::size_t count = 2 * target.lanes + 1;
      for (std::size_t k = 0; k < count; ++k) {
        const bool inertia_allowed = c.scheme != Scheme::energy_conserving &&
                                     !(c.scheme == Scheme::paoli_schatzman && c.row == ContactRow::algebraic);
        MassRedistribution mass = k % 3 == 0        ? mod1()
                                  : k % 3 == 1      ? mod3()
                                  : inertia_allowed ? consistent_mass()
                                                    : mod2();
        SchemeParameters p;
        p.scheme = c.scheme;
        p.contact_row = c.row;
        Problem problem = benchmark_problem();
        // A restitution e > 0 with the literal row needs a contact node with inertia (schemes.cpp refuses
        // it on a massless node): the consistent mass of k % 3 == 2 only.
        const bool massless = !(k % 3 == 2 && inertia_allowed);
        if (c.scheme == Scheme::paoli_schatzman && k % 2 == 1)
          p.beta = 0.3, p.restitution = c.row == ContactRow::literal && massless ? 0.0 : 0.5;
        double dt = (0.5 + 0.1 * static_cast<double>(k % 13)) * mesh.h();
        if (batch_family(c.scheme) == 4) class_parameters(p, k, mesh, mass, true, dt);
        if (c.scheme == Scheme::moreau_jean || c.scheme == Scheme::dke)
          mass = one_solve_parameters(p, k, problem, mesh.h());
        if ((scheme_info(c.scheme).family == StepFamily::central_differences))
          mass = explicit_parameters(p, k, problem, mesh, 0.5 + 0.035 * static_cast<double>(k % 13), dt);
        batch.emplace_back(problem, mesh, mass, p, dt);
        alone.emplace_back(problem, mesh, mass, p, dt);
      }
      BatchedSimulation batched(std::move(batch));
      CHECK(batched.lanes() == target.lanes);
      batched_cases += batched.batched_runs() > 0;
      bool identical = true;
      std::vector<bool> active(count, false);
      for (Index n = 1; n <= steps && identical; ++n) {
        batched.step();
        for (std::size_t k = 0; k < count; ++k) {
          alone[k].step();
          const Sample a = batched.run(k).sample(), b = alone[k].sample();
          const bool same = a.level == b.level && same_bits(a.time, b.time) &&
                            same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                            a.has_multiplier == b.has_multiplier && same_bits(a.multiplier, b.multiplier) &&
                            same_bits(a.multiplier_time, b.multiplier_time) && same_bits(a.energy, b.energy) &&
                            same_bits(a.energy_time, b.energy_time);
          if (!same) {
            CAPTURE(k);
            CAPTURE(n);
            const std::string parts = std::string(same_bits(*a.displacement, *b.displacement) ? "" : " U") +
                                      (same_bits(*a.velocity, *b.velocity) ? "" : " V") +
                                      (same_bits(a.multiplier, b.multiplier) ? "" : " lambda") +
                                      (same_bits(a.energy, b.energy) ? "" : " E") +
                                      (a.level == b.level ? "" : " level");
            CAPTURE(parts);
            const double du = (*a.displacement - *b.displacement).cwiseAbs().maxCoeff();
            CAPTURE(du);
            CAPTURE(a.energy - b.energy);
            CHECK(same);
            identical = false;
          }
          const bool now = b.multiplier < 0;
          status_changes += c.scheme == Scheme::switching && now != active[k];
          active[k] = now;
        }
      }
      CHECK(identical);
    }
  }
  use_batch_target(0);
  // Not vacuous: every case went through the vector lanes on every target, CN-switch changed status.
  CHECK(batched_cases == static_cast<int>(targets.size() * cases.size()));
  // Every scheme of the registry has a case here, and every case went through the lanes (above): a scheme
  // added without a batched kernel fails.
  for (const SchemeInfo& info : scheme_registry()) {
    CAPTURE(info.id);
    CHECK(std::any_of(cases.begin(), cases.end(), [&](const BatchedCase& c) { return c.scheme == info.scheme; }));
  }
  CHECK(status_changes > 0);
}

/// @file batched_step.cpp
/// ## Runs at their own rates: the partial step
///
/// step(advance) steps the runs with advance[k] ≠ 0 and keeps the others: a kept lane is written back
/// unchanged by the sweep up (the mask CN-switch uses for its status changes), and its run's bookkeeping
/// is not touched. So runs of Δt, 2Δt, … step together, each only at the multiples of its rate. The
/// prediction is the identity again: at every batch step, every run, advanced or kept, is bitwise its run
/// stepped alone as many times. Checked for every scheme and target with the rates 1, 2, 3, 5 (run k's
/// Δt is its rate times a common step), read without copying the lanes out (sample(k, lanes)), so that a
/// kept lane newer than its run's vectors meets another lane's Paoli–Schatzman first step (at n = 5:
/// the rate-2 lane stepped in the lanes at n = 4 and stays); a wrong flag count throws.
TEST_CASE("a partial step keeps the runs that stay, and runs at their own rates are each bitwise the run alone") {
  const std::vector<BatchedCase> cases = batched_cases();
  const UniformMesh mesh(1.0, 24);
  const std::vector<Index> rates = {1, 2, 3, 5};
  const Index batch_steps = 300;  // every run reaches t = 300 · 0.25h ≈ 3.1, past the first impact (t = 1)
  int kept_lanes = 0;
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    for (const BatchedCase& c : cases) {
      CAPTURE(to_string(c.scheme));
      CAPTURE(to_string(c.row));
      std::vector<BarSimulation> batch, alone;
      const std::size_t count = 2 * target.lanes + 1;
      for (std::size_t k = 0; k < count; ++k) {
        SchemeParameters p;
        p.scheme = c.scheme;
        p.contact_row = c.row;
        if (c.scheme == Scheme::paoli_schatzman && k % 2 == 1) p.beta = 0.3;
        double dt = 0.25 * static_cast<double>(rates[k % rates.size()]) * mesh.h();
        MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
        Problem problem = benchmark_problem();
        if (batch_family(c.scheme) == 4) class_parameters(p, k, mesh, mass, false, dt);  // implicit: any rate
        if (c.scheme == Scheme::moreau_jean || c.scheme == Scheme::dke)
          mass = one_solve_parameters(p, k, problem, mesh.h());
        if ((scheme_info(c.scheme).family ==
             StepFamily::central_differences))  // rates 1, 2, 3, 5 of 0.18 of the stability limit
          mass = explicit_parameters(p, k, problem, mesh, 0.18 * static_cast<double>(rates[k % rates.size()]), dt);
        batch.emplace_back(problem, mesh, mass, p, dt);
        alone.emplace_back(problem, mesh, mass, p, dt);
      }
      BatchedSimulation batched(std::move(batch));
      REQUIRE(batched.batched_runs() > 0);
      bool identical = true;
      for (Index n = 1; n <= batch_steps && identical; ++n) {
        std::vector<char> advance(count);
        for (std::size_t k = 0; k < count; ++k) {
          advance[k] = n % rates[k % rates.size()] == 0;
          if (advance[k]) alone[k].step();
          kept_lanes += !advance[k];
        }
        batched.step(advance);
        for (std::size_t k = 0; k < count; ++k) {
          LaneVectors where{};
          const Sample a = batched.sample(k, where), b = alone[k].sample();
          bool same = a.level == b.level && same_bits(a.time, b.time) && same_bits(a.multiplier, b.multiplier) &&
                      same_bits(a.energy, b.energy);
          for (Index i = 0; i < mesh.elements; ++i) {
            const std::size_t at = static_cast<std::size_t>(i) * where.stride;
            same = same && same_bits(where.displacement[at], (*b.displacement)[i]) &&
                   same_bits(where.velocity[at], (*b.velocity)[i]);
          }
          if (!same) {
            CAPTURE(k);
            CAPTURE(n);
            CHECK(same);
            identical = false;
          }
        }
      }
      CHECK(identical);
    }
  }
  use_batch_target(0);
  CHECK(kept_lanes > 0);
  std::vector<BarSimulation> two;
  two.emplace_back(benchmark_problem(), mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  two.emplace_back(benchmark_problem(), mesh, mod1(), SchemeParameters{}, 0.5 * mesh.h());
  BatchedSimulation batched(std::move(two));
  CHECK_THROWS_AS(batched.step(std::vector<char>(3, 1)), std::invalid_argument);
}

/// @file batched_step.cpp
/// ## One family, one group
///
/// Crank–Nicolson and backward Euler differ only in the values of their step's matrices and rates, which
/// each lane holds for itself: a group can mix them (batch_family 0), and the sweep layer batches them
/// together, so that the lanes of a batch share their Δt more often. Checked: such a mixed group is one
/// group (every run in the lanes), each lane bitwise its run alone past the first impact, on every
/// target; and two runs of two schemes share a group exactly when batch_family says so.
TEST_CASE("Crank-Nicolson and backward Euler share the lanes of a group, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 40);
  const std::vector<double> ratios = {0.5, 0.5, 1.0, 0.25};
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    std::vector<BarSimulation> batch, alone;
    Index steps = 0;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      SchemeParameters p;
      p.scheme = k % 2 == 0 ? Scheme::crank_nicolson : Scheme::backward_euler;
      const double dt = ratios[k % ratios.size()] * mesh.h();
      const MassRedistribution mass = k % 3 == 0 ? mod1() : k % 3 == 1 ? mod2() : mod3();
      batch.emplace_back(benchmark_problem(), mesh, mass, p, dt);
      alone.emplace_back(benchmark_problem(), mesh, mass, p, dt);
      steps = std::max(steps, static_cast<Index>(1.5 / dt));  // past t = 1, the first impact, for every lane
    }
    BatchedSimulation batched(std::move(batch));
    REQUIRE(batched.batched_runs() == target.lanes);
    for (Index n = 1; n <= steps; ++n) {
      batched.step();
      for (std::size_t k = 0; k < target.lanes; ++k) alone[k].step();
    }
    bool identical = true;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const Sample a = batched.run(k).sample(), b = alone[k].sample();
      identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                  same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level;
      CHECK(b.time > 1.0);
    }
    CHECK(identical);
  }
  use_batch_target(0);
  // Two runs of two schemes (mod1: allowed for every scheme with a batched kernel) are one group iff
  // their families are the same.
  const std::vector<Scheme> schemes = {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman,
                                       Scheme::energy_conserving, Scheme::switching};
  int shared = 0;
  for (Scheme a : schemes)
    for (Scheme b : schemes) {
      CAPTURE(to_string(a));
      CAPTURE(to_string(b));
      SchemeParameters pa, pb;
      pa.scheme = a, pb.scheme = b;
      std::vector<BarSimulation> two;
      two.emplace_back(benchmark_problem(), mesh, mod1(), pa, 0.5 * mesh.h());
      two.emplace_back(benchmark_problem(), mesh, mod1(), pb, 0.25 * mesh.h());
      const BatchedSimulation batched(std::move(two));
      const bool together = batched.batched_runs() == 2;
      CHECK(together == (batch_family(a) == batch_family(b)));
      shared += together && a != b;
    }
  CHECK(shared == 2);  // (CN, BE) and (BE, CN)
}

/// @file batched_step.cpp
/// ## The plateau of the factors
///
/// Prediction. Crank–Nicolson's step matrix is A = M + (Δt²/4) S; on the interior, with c = Δt²/4,
/// d = 4h/6 + 2c/h on the diagonal and l = u = h/6 − c/h beside it. The pivots from the last row up,
/// p_i = d − l²/p_{i+1}, approach p* = (d + √(d² − 4l²))/2 with the rate ρ = l²/p*² per row; at Δt = 2h,
/// the slowest lane below, d = 8h/3, l = −5h/6, p* ≈ 2.374h and ρ ≈ 0.123, so the relative distance falls
/// below ε = 2⁻⁵³ within ln ε / ln ρ ≈ 18 rows. Allowed: 40 rows off the plateau (the head rows, the
/// rounding onto the fixed point, and the factor products, which need two equal rows). And the same bits,
/// lane by lane, as each run stepped alone, past the first impact of the finest step, on every target.
TEST_CASE("the factors repeat on a plateau of the interior rows, which the sweeps hold in registers") {
  const UniformMesh mesh(1.0, 200);
  const std::vector<double> ratios = {0.25, 0.5, 1.0, 2.0};
  const Index steps = static_cast<Index>(1.2 / (ratios.front() * mesh.h()));  // past t = 1, the first impact
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    std::vector<BarSimulation> batch, alone;
    SchemeParameters cn;
    cn.scheme = Scheme::crank_nicolson;
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const double dt = ratios[k % ratios.size()] * mesh.h();
      const MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
      batch.emplace_back(benchmark_problem(), mesh, mass, cn, dt);
      alone.emplace_back(benchmark_problem(), mesh, mass, cn, dt);
    }
    BatchedSimulation batched(std::move(batch));
    REQUIRE(batched.batched_runs() == target.lanes);
    const std::size_t interior = static_cast<std::size_t>(mesh.unknowns()) - 1;  // rows 0 … n − 2
    CAPTURE(batched.plateau_rows());
    CHECK(batched.plateau_rows() + 40 >= interior);
    bool identical = true;
    for (Index n = 1; n <= steps; ++n) {
      batched.step();
      for (std::size_t k = 0; k < target.lanes; ++k) alone[k].step();
    }
    for (std::size_t k = 0; k < target.lanes; ++k) {
      const Sample a = batched.run(k).sample(), b = alone[k].sample();
      identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                  same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level;
      CHECK(alone[k].sample().time > 1.0);
    }
    CHECK(identical);
  }
  use_batch_target(0);
}

/// @file batched_step.cpp
/// ## A remainder in a narrow group
///
/// A family of W + 2 or W + 3 runs (W the target's lanes) leaves, after one full group, a remainder of 2
/// or 3 runs; the constructor puts it in one group of the narrowest width that holds it (2 lanes for 2
/// runs, 4 for 3; on a target of 4 lanes, 3 runs fill a full group; on one of 2 lanes there is no
/// remainder of two, and one of one is stepped alone). Prediction: those widths, every run of a group
/// counted by batched_runs, a lane's sample read with the stride of its group's width, and every lane
/// bitwise its run stepped alone past the first impact, for each kernel family (two-level, Paoli–Schatzman,
/// EC, CN-switch) on every target: the narrow kernels are the full one's operations on fewer lanes.
TEST_CASE("a batch's remainder is a group of the narrowest width that holds it, each lane bitwise its run alone") {
  const UniformMesh mesh(1.0, 20);
  const std::vector<Scheme> schemes = {Scheme::crank_nicolson, Scheme::paoli_schatzman, Scheme::energy_conserving,
                                       Scheme::switching};
  for (const BatchTarget& target : batch_targets()) {
    use_batch_target(target.bit);
    CAPTURE(target.name);
    const std::size_t W = target.lanes;
    for (const std::size_t extra : {std::size_t{2}, std::size_t{3}})
      for (const Scheme scheme : schemes) {
        CAPTURE(extra);
        CAPTURE(to_string(scheme));
        const std::size_t count = W + extra;
        std::vector<BarSimulation> batch, alone;
        Index steps = 0;
        for (std::size_t k = 0; k < count; ++k) {
          SchemeParameters p;
          p.scheme = scheme;
          const double dt = (0.5 + 0.1 * static_cast<double>(k % 11)) * mesh.h();
          const MassRedistribution mass = k % 2 == 0 ? mod1() : mod3();
          batch.emplace_back(benchmark_problem(), mesh, mass, p, dt);
          alone.emplace_back(benchmark_problem(), mesh, mass, p, dt);
          steps = std::max(steps, static_cast<Index>(1.5 / dt));  // past t = 1, the first impact, for every lane
        }
        BatchedSimulation batched(std::move(batch));
        CHECK(batched.lanes() == W);
        std::vector<std::size_t> expected(count / W, W);
        const std::size_t q = count % W;
        if (q >= 2) expected.push_back(q <= 2 ? 2 : q <= 4 ? 4 : W);
        CHECK(batched.group_widths() == expected);
        CHECK(batched.batched_runs() == count - (q == 1 ? 1 : 0));
        bool identical = true;
        for (Index n = 1; n <= steps; ++n) {
          batched.step();
          for (std::size_t k = 0; k < count; ++k) alone[k].step();
        }
        // The last run lies in the remainder's group: its lane's stride is the group's width (or 1 if a
        // CN-switch status change has just stepped it alone, its vectors its own).
        LaneVectors lanes{nullptr, nullptr, 0};
        batched.sample(count - 1, lanes);
        const std::size_t stride = q >= 2 ? expected.back() : q == 1 ? 1 : W;
        CHECK((lanes.stride == stride || (scheme == Scheme::switching && lanes.stride == 1)));
        for (std::size_t k = 0; k < count; ++k) {
          const Sample a = batched.run(k).sample(), b = alone[k].sample();
          identical = identical && same_bits(*a.displacement, *b.displacement) && same_bits(*a.velocity, *b.velocity) &&
                      same_bits(a.multiplier, b.multiplier) && same_bits(a.energy, b.energy) && a.level == b.level &&
                      same_bits(a.time, b.time);
          CHECK(b.time > 1.0);
        }
        CHECK(identical);
      }
  }
  use_batch_target(0);
}

}  // namespace mrm

#endif  // HWY_ONCE
