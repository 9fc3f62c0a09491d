/// @file kernels.cpp
/// @brief The passes of the batched step on vectors of lanes (Google Highway, the widest target of the
/// processor chosen at run time: AVX-512, AVX2, SSE4, NEON, ... or a portable 128-bit emulation): the fused
/// step of fast_step.cpp, the Newmark type's four passes, Moreau–Jean's and DKE's one solve
/// (contact_classes.cpp) and the explicit classes' kick and drift, then kick (explicit_schemes.cpp), one run
/// per lane.
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
///
/// Width: the kernels are templates over Highway's tag, instantiated for the full width and the capped
/// widths of 4 and 2 doubles (a group narrower than the target, batched_step.cpp); the width changes no bit
/// of a lane, since no operation mixes lanes.
#include "batched/kernels.hpp"

#include <algorithm>
#include <cstddef>
#include <type_traits>

/// @cond MRM_INTERNAL (the Highway plumbing and the kernels: not part of the library's interface)
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "batched/kernels.cpp"
#include <hwy/foreach_target.h>  // IWYU pragma: keep
#include <hwy/highway.h>

// The sweep up's row emission is called from its hot interior loops and from a few rows where lanes differ
// (their heads, their far ends): forced inline, so that those few call sites do not make the compiler
// call it out of line in the loops (measured: 2.5 times the time per node when it did).
#if defined(__GNUC__)
#define MRM_INLINE_LAMBDA __attribute__((always_inline))
#else
#define MRM_INLINE_LAMBDA
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

// The sweep down of FastStep::fused_step, on W lanes; with `loaded`, each row's right-hand side b_i plus
// the lane's steady load term (Kernel::load: g_now F_i + g_next F_i, formed once, batched_step.cpp).
template <bool loaded, class D>
void SweepDownT(D d, const Kernel& k) {
  using V = hn::Vec<D>;
  const std::size_t W = k.lanes;
  const std::ptrdiff_t n = static_cast<std::ptrdiff_t>(k.n), head = static_cast<std::ptrdiff_t>(k.head);
  const auto at = [&](const double* a, std::ptrdiff_t i) { return hn::Load(d, a + static_cast<std::size_t>(i) * W); };
  const double* u = k.u;
  const double* w = k.w;
  const auto with_load = [&](V b, std::ptrdiff_t i) {
    if constexpr (loaded) b = b + at(k.load, i);
    return b;
  };
  const auto rhs = [&](const RowV<D>& r, std::ptrdiff_t i, V u_up, V w_up) {
    return with_load(
        r.c1l * at(u, i - 1) + r.c1d * at(u, i) + r.c1u * u_up + r.c2l * at(w, i - 1) + r.c2d * at(w, i) + r.c2u * w_up,
        i);
  };
  const auto rhs_interior = [&](const RowV<D>& r, std::ptrdiff_t i) {
    return with_load(r.c1l * (at(u, i - 1) + at(u, i + 1)) + r.c1d * at(u, i) + r.c2l * (at(w, i - 1) + at(w, i + 1)) +
                         r.c2d * at(w, i),
                     i);
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
  const RowV<D> r = LoadRow(d, k.interior, W);
  std::ptrdiff_t top = n - 2;  // the first row of the interior loop below
  if (k.short_lanes) {
    // The lanes of n − 1 unknowns have no row n − 1: their elimination starts at row n − 2, their last row,
    // from zero as every run's does; the others' row n − 2 is an interior row.
    const auto short_lane = hn::Ne(hn::Load(d, k.short_lanes), hn::Zero(d));
    b_up = hn::IfThenElse(short_lane, hn::Zero(d), b_up);
    y_up = hn::IfThenElse(short_lane, hn::Zero(d), y_up);
    y_up2 = hn::IfThenElse(short_lane, hn::Zero(d), y_up2);
    eliminate(n - 2, hn::IfThenElse(short_lane, rhs(LoadRow(d, k.last, W), n - 2, hn::Zero(d), hn::Zero(d)),
                                    rhs_interior(r, n - 2)));
    top = n - 3;
  }
  {
    // The interior rows, bottom up; on the plateau [a, b) the factors are the same numbers row after row
    // (Kernel::flat_begin), held in registers instead of loaded.
    const std::ptrdiff_t a = static_cast<std::ptrdiff_t>(k.flat_begin), b = static_cast<std::ptrdiff_t>(k.flat_end);
    std::ptrdiff_t i = top;
    for (; i >= std::max(b, head); --i) eliminate(i, rhs_interior(r, i));
    if (a < b) {
      const V elimination = at(k.elimination, a), elimination_pair = at(k.elimination_pair, a);
      for (; i >= a; --i) eliminate_by(i, rhs_interior(r, i), elimination, elimination_pair);
    }
    for (; i >= head; --i) eliminate(i, rhs_interior(r, i));
  }
  const auto head_row = [&](std::ptrdiff_t i) {
    return rhs(LoadRow(d, k.head_rows + static_cast<std::size_t>(i) * 10 * W, W), i, at(u, i + 1), at(w, i + 1));
  };
  // Rows head_min … head − 1: each lane's own row, explicit where the row is in its head, Toeplitz where it
  // is in its interior (both formed, the lane's taken: its operations are those of its run alone).
  const std::ptrdiff_t head_min = k.heads ? static_cast<std::ptrdiff_t>(k.head_min) : head;  // no heads: all alike
  for (std::ptrdiff_t i = std::min(head, n - 1) - 1; i >= std::max<std::ptrdiff_t>(head_min, 1); --i) {
    const auto in_head = hn::Lt(hn::Set(d, static_cast<double>(i)), hn::Load(d, k.heads));
    eliminate(i, hn::IfThenElse(in_head, head_row(i), rhs_interior(r, i)));
  }
  for (std::ptrdiff_t i = std::min(std::min(head_min, head), n - 1) - 1; i >= 1; --i) eliminate(i, head_row(i));
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
  // A row's sums of the energy: a Toeplitz row's (toeplitz_sums, into k_d … q_q) or an explicit row's
  // (explicit_sums, into kinetic, potential, potential_q), by `mode`: std::true_type, std::false_type, or
  // a mask, true in the lanes where the row is explicit, where each lane takes its own (both are formed,
  // into disjoint sums, and each lane keeps the sums of its kind of row only).
  const auto sum_by = [&](auto mode, const auto& toeplitz_sums, const auto& explicit_sums) MRM_INLINE_LAMBDA {
    using Mode = decltype(mode);
    if constexpr (std::is_same_v<Mode, std::true_type>) {
      toeplitz_sums();
    } else if constexpr (std::is_same_v<Mode, std::false_type>) {
      explicit_sums();
    } else {
      const V k0 = kinetic, p0 = potential, q0 = potential_q, kd = k_d, kq = k_q, pd = p_d, pq = p_q, qd = q_d,
              qq = q_q;
      toeplitz_sums();
      explicit_sums();
      kinetic = hn::IfThenElse(mode, kinetic, k0), potential = hn::IfThenElse(mode, potential, p0);
      potential_q = hn::IfThenElse(mode, potential_q, q0);
      k_d = hn::IfThenElse(mode, kd, k_d), k_q = hn::IfThenElse(mode, kq, k_q);
      p_d = hn::IfThenElse(mode, pd, p_d), p_q = hn::IfThenElse(mode, pq, p_q);
      q_d = hn::IfThenElse(mode, qd, q_d), q_q = hn::IfThenElse(mode, qq, q_q);
    }
  };
  const auto emit = [&](const RowV<D>& r, std::ptrdiff_t i, V dd, V un, auto mode) MRM_INLINE_LAMBDA {
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
      sum_by(
          mode,
          [&] {
            const V dx = xx - v_prev, dp = p - p_prev, dq = q - q_prev;
            k_d = k_d + dx * dx, k_q = k_q + xx * xx;
            p_d = p_d + dp * dp, p_q = p_q + p * p;
            q_d = q_d + dq * dq, q_q = q_q + q * q;
          },
          [&] {
            kinetic = kinetic + (r.md * xx * xx + r.ml2 * v_prev * xx);
            potential = potential + (r.sd * p * p + r.sl2 * p_prev * p);
            potential_q = potential_q + (r.sd * q * q + r.sl2 * q_prev * q);
          });
      v_prev = xx, p_prev = p, q_prev = q;
    } else {
      const V wo = at(w_out, i);
      const V v = rate * dd - memory * wo;
      if constexpr (keeps) {
        put(hn::IfThenElse(keep, wo, v), w_out, i);
      } else {
        put(v, w_out, i);
      }
      sum_by(
          mode,
          [&] {
            const V dv = v - v_prev, du = un - un_prev;
            k_d = k_d + dv * dv, k_q = k_q + v * v;
            p_d = p_d + du * du, p_q = p_q + un * un;
          },
          [&] {
            kinetic = kinetic + (r.md * v * v + r.ml2 * v_prev * v);
            potential = potential + (r.sd * un * un + r.sl2 * un_prev * un);
          });
      v_prev = v;
    }
    un_prev = un;
    d_prev2 = d_prev, d_prev = dd;
  };
  const std::false_type explicit_row;
  const std::true_type toeplitz_row;
  const auto solve_up_by = [&](std::ptrdiff_t i, V inverse_pivot, V upward, V upward_pair) MRM_INLINE_LAMBDA {
    const V z = inverse_pivot * at(y, i);
    const V dd = (z - upward * z_prev) + upward_pair * d_prev2;
    z_prev = z;
    return dd;
  };
  const auto emit_up = [&](const RowV<D>& r, std::ptrdiff_t i, auto mode) MRM_INLINE_LAMBDA {
    const V dd = solve_up_by(i, at(k.inverse_pivot, i), at(k.upward, i), at(k.upward_pair, i));
    emit(r, i, dd, at(u, i) + dd, mode);
  };
  const V u0_next = hn::Load(d, k.u0_next), recurrence_d0 = hn::Load(d, k.recurrence_d0);
  emit(LoadRow(d, k.head_rows, W), 0, u0_next - at(u, 0), u0_next, explicit_row);
  z_prev = recurrence_d0;
  const auto head_row = [&](std::ptrdiff_t i) {
    return LoadRow(d, k.head_rows + static_cast<std::size_t>(i) * 10 * W, W);
  };
  // Rows 1 … head_min − 1 are explicit in every lane; rows head_min … head − 1 in the lanes whose head is
  // longer (the others' interior starts there: the sums' first values ka, pa, qa are taken lane by lane,
  // and row 1's d_{i−2} is set as each lane's run sets it).
  const std::ptrdiff_t head_min = k.heads ? static_cast<std::ptrdiff_t>(k.head_min) : head;  // no heads: all alike
  const std::ptrdiff_t all_explicit = std::min(head_min, n - 1);
  for (std::ptrdiff_t i = 1; i < all_explicit; ++i) {
    emit_up(head_row(i), i, explicit_row);
    if (i == 1) d_prev2 = recurrence_d0;
  }
  const RowV<D> r = LoadRow(d, k.interior, W);
  V ka = v_prev, pa = three_level ? p_prev : un_prev, qa = q_prev;
  const auto interior_starts = [&](std::ptrdiff_t i) {  // the lanes whose first interior row is i
    const auto starts = hn::Eq(hn::Set(d, static_cast<double>(i)), hn::Load(d, k.heads));
    ka = hn::IfThenElse(starts, v_prev, ka);
    pa = hn::IfThenElse(starts, three_level ? p_prev : un_prev, pa);
    qa = hn::IfThenElse(starts, q_prev, qa);
  };
  for (std::ptrdiff_t i = std::max<std::ptrdiff_t>(all_explicit, 1); i < std::min(head, n - 1); ++i) {
    interior_starts(i);
    const auto in_head = hn::Lt(hn::Set(d, static_cast<double>(i)), hn::Load(d, k.heads));
    const V dd = solve_up_by(i, at(k.inverse_pivot, i), at(k.upward, i), at(k.upward_pair, i));
    const RowV<D> rh = head_row(i);
    // A row's coefficients enter only its explicit sums (the Toeplitz sums take the interior's at the end).
    emit(rh, i, dd, at(u, i) + dd, in_head);
    if (i == 1) d_prev2 = hn::IfThenElse(in_head, recurrence_d0, d_prev2);
  }
  if (head < n - 1) {
    if (head_min < head)
      interior_starts(head);
    else
      ka = v_prev, pa = three_level ? p_prev : un_prev, qa = q_prev;
    // The interior rows, top down, with the plateau [a, b) as in SweepDown. Two levels: its factors held
    // in registers. Three levels keep three more forms' sums live, and three copies of the emission
    // would not all be inlined (measured: twice the time): one loop, the plateau's factors read from
    // row a (L1-resident) rather than streamed.
    const std::ptrdiff_t a = static_cast<std::ptrdiff_t>(k.flat_begin), b = static_cast<std::ptrdiff_t>(k.flat_end);
    // The rows every lane takes as interior rows: head … n − 2, or n − 3 when some lanes end one row earlier.
    const std::ptrdiff_t end = k.short_lanes ? n - 2 : n - 1;
    if constexpr (three_level) {
      for (std::ptrdiff_t i = head; i < end; ++i) {
        const std::ptrdiff_t f = i >= a && i < b ? a : i;
        const V dd = solve_up_by(i, at(k.inverse_pivot, f), at(k.upward, f), at(k.upward_pair, f));
        emit(r, i, dd, at(u, i) + dd, toeplitz_row);
      }
    } else {
      std::ptrdiff_t i = head;
      for (; i < std::min(a, end); ++i) emit_up(r, i, toeplitz_row);
      if (a < b) {
        const V inverse_pivot = at(k.inverse_pivot, a), upward = at(k.upward, a), upward_pair = at(k.upward_pair, a);
        for (; i < b; ++i) {
          const V dd = solve_up_by(i, inverse_pivot, upward, upward_pair);
          emit(r, i, dd, at(u, i) + dd, toeplitz_row);
        }
      }
      for (; i < end; ++i) emit_up(r, i, toeplitz_row);
    }
    const V half = hn::Set(d, 0.5);
    const auto form = [&](V dg, V l2, V sum_d, V sum_q, V za, V zb) {
      const V l = half * l2;
      return hn::Neg(l) * sum_d + (dg + l2) * sum_q - l * zb * zb + l * za * za;
    };
    // The interior's sums closed by its end values (kb, pb, qb: those of its last row), each run's after
    // its own interior: in the lanes of `ends`, or in every lane.
    const auto close_interior = [&](auto ends) {
      const V kb = v_prev, pb = three_level ? p_prev : un_prev, qb = q_prev;
      const V kinetic_closed = kinetic + form(r.md, r.ml2, k_d, k_q, ka, kb);
      const V potential_closed = potential + form(r.sd, r.sl2, p_d, p_q, pa, pb);
      if constexpr (std::is_same_v<decltype(ends), std::true_type>) {
        kinetic = kinetic_closed, potential = potential_closed;
        if constexpr (three_level) potential_q = potential_q + form(r.sd, r.sl2, q_d, q_q, qa, qb);
      } else {
        kinetic = hn::IfThenElse(ends, kinetic_closed, kinetic);
        potential = hn::IfThenElse(ends, potential_closed, potential);
        if constexpr (three_level)
          potential_q = hn::IfThenElse(ends, potential_q + form(r.sd, r.sl2, q_d, q_q, qa, qb), potential_q);
      }
    };
    if (!k.short_lanes) {
      close_interior(std::true_type());
    } else {
      // The lanes of n − 1 unknowns: their interior ends at row n − 3, row n − 2 is their last row (explicit,
      // k.last); the others' row n − 2 is their last interior row, and their interior ends there.
      const auto short_lane = hn::Ne(hn::Load(d, k.short_lanes), hn::Zero(d));
      close_interior(short_lane);
      emit_up(LoadRow(d, k.last, W), n - 2, short_lane);
      close_interior(hn::Not(short_lane));
    }
  }
  if (!k.short_lanes) {
    emit_up(LoadRow(d, k.last, W), n - 1, explicit_row);
  } else {
    // Row n − 1, the last row of the lanes of n unknowns; the others have none: their sums are kept as they
    // are (their Toeplitz sums, which this row's mode touches in them, are closed already), and what it
    // writes in their lanes is never read.
    emit_up(LoadRow(d, k.last, W), n - 1, hn::Eq(hn::Load(d, k.short_lanes), hn::Zero(d)));
  }
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
template <class D>
void SweepDownD(D d, const Kernel& k) {
  if (k.load)
    SweepDownT<true>(d, k);
  else
    SweepDownT<false>(d, k);
}
void SweepDown(const Kernel& k) { SweepDownD(Full(), k); }
void SweepDown4(const Kernel& k) { SweepDownD(Four(), k); }
void SweepDown2(const Kernel& k) { SweepDownD(Two(), k); }
void SweepUp(const Kernel& k) { SweepUpD(Full(), k); }
void SweepUp4(const Kernel& k) { SweepUpD(Four(), k); }
void SweepUp2(const Kernel& k) { SweepUpD(Two(), k); }

}  // namespace HWY_NAMESPACE
}  // namespace mrm::batched
HWY_AFTER_NAMESPACE();

/// @endcond

#if HWY_ONCE

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

std::size_t lane_count(Width width) {
  switch (width) {
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(LaneCount4)();
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(LaneCount2)();
    case Width::full:
      break;
  }
  return HWY_DYNAMIC_DISPATCH(LaneCount)();
}
bool width_dividing(std::size_t stride, Width& width) {
  for (const Width w : {Width::full, Width::four, Width::two})
    if (stride % lane_count(w) == 0) {
      width = w;
      return true;
    }
  return false;
}
void sweep_down(Width width, const Kernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(SweepDown)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(SweepDown4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(SweepDown2)(k);
  }
}
void sweep_up(Width width, const Kernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(SweepUp)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(SweepUp4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(SweepUp2)(k);
  }
}
void newmark_down(Width width, const NewmarkKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(NewmarkDown)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(NewmarkDown4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(NewmarkDown2)(k);
  }
}
void newmark_up(Width width, const NewmarkKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(NewmarkUp)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(NewmarkUp4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(NewmarkUp2)(k);
  }
}
void one_solve_down(Width width, const OneSolveKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(OneSolveDown)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(OneSolveDown4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(OneSolveDown2)(k);
  }
}
void one_solve_up(Width width, const OneSolveKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(OneSolveUp)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(OneSolveUp4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(OneSolveUp2)(k);
  }
}
void explicit_drift(Width width, const ExplicitKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(ExplicitDrift)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(ExplicitDrift4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(ExplicitDrift2)(k);
  }
}
void explicit_kick(Width width, const ExplicitKernel& k) {
  switch (width) {
    case Width::full:
      return HWY_DYNAMIC_DISPATCH(ExplicitKick)(k);
    case Width::four:
      return HWY_DYNAMIC_DISPATCH(ExplicitKick4)(k);
    case Width::two:
      return HWY_DYNAMIC_DISPATCH(ExplicitKick2)(k);
  }
}
}  // namespace batched
/// @endcond
}  // namespace mrm

#endif  // HWY_ONCE
