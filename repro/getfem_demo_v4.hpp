/// @file getfem_demo_v4.hpp
/// @brief GetFEM's demo_dynamic_contact_1D.py, version 4 (Taylor–Flanagan), as a configuration of this
/// project, and the demo's own error measures (its definitions, not this project's), so that the two
/// codes' printed numbers can be compared digit by digit (tests/getfem_demo_v4.cpp,
/// tests/data/getfem_demo_v4.txt). For `bar1d --peer getfem-v4` (doc/peer.md).
#pragma once

#include <array>
#include <string>

#include "configurations.hpp"

namespace mrm::repro {

/// The demo's version 4 with its defaults: NX = 20, dt = 0.002, T = 12, β = 0, γ = ½ (explicit Newmark,
/// i.e. central differences), the standard mass unlumped (lump_mass_matrix = 0, mass_matrix_type = 0):
/// the scheme taylor-flanagan with `lumping none` and the consistent mass. What the match required:
/// the consistent mass solved at every step (not the lumped one), the impulse spread through M⁻¹, the
/// interpolant as the initial value of the contact node (the only one for a node with inertia), and
/// nothing else: the scheme's (E1) is the demo's step (explicit_schemes.cpp).
Configuration getfem_demo_v4_configuration();

/// The demo's exact solution uExact(x, t, d) (demo_dynamic_contact_1D.py) on the paper's benchmark
/// (L = 1, a = ½, period 3), transcribed with its floating-point operations and its zones (tf < x,
/// tf ≤ 1 − x): d = 0 the displacement, 1 u_x, 2 u_t, with the demo's one-sided values where a front
/// crosses a point exactly: there this project's ReferenceSolution may take the other side (a difference
/// of ½ in u_t or u_x at that node and level), and the demo compares with its own side. The displacement
/// is continuous. Used by the demo's measures here and by the peer measures (peers.hpp).
double getfem_demo_exact(double x, double t, int d);

/// The seven relative errors the demo prints, in its order and under its names (below), computed as
/// the demo computes them: at every level t_k = k dt, k = 0..K (K = ⌈T/dt⌉), the P1 norms over all
/// nodes 0..N (the clamped node included) of the difference between the scheme's nodal values and the
/// demo's uExact at the nodes x_i = i (1/NX), with its one-sided values on the characteristics
/// (zones decided by tf < x and tf ≤ 1 − x); H¹ is GetFEM's full norm (L² and seminorm); L∞ in time is
/// the largest value over the levels, L² in time the sum of the squares (dt cancels), each divided by
/// the same measure of the exact solution; the contact stress is the scheme's λ against u_x(0, t).
struct GetfemDemoMeasures {
  /// LinfL2u, LinfH1u, LinfL2v, L2L2u, L2H1u, L2L2v, L2sn
  std::array<double, 7> values{};
  static const char* const names[7];  ///< the names above
};
/// Runs `configuration` (which must be on the paper's benchmark with L = 1, a = ½, the demo's problem)
/// and returns the demo's measures of the run.
GetfemDemoMeasures getfem_demo_measures(const Configuration& configuration);

}  // namespace mrm::repro
