/// @file peers.hpp
/// @brief The configurations that match a peer code's run (bar1d --peer): GetFEM's
/// demo_dynamic_contact_1D.py, versions 0–4, at its defaults (doc/peer.md, mathematics.md §13).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "exact/reference_solution.hpp"
#include "fem/mass_redistribution.hpp"
#include "time/schemes.hpp"

namespace mrm::repro {

/// Every parameter of a bar1d run that a peer's defaults set; the usual options override each of them.
struct PeerPreset {
  std::string id;                       ///< the --peer value ("getfem-v2")
  std::string summary;                  ///< one line for the help text
  std::string formulation;              ///< what the match required (printed by bar1d as peer_formulation)
  long elements = 20;                   ///< NX
  double dt = 0.002;                    ///< dt
  double final_time = 12;               ///< T
  std::string mass = "consistent";      ///< the demo's mass_matrix_type 0 (standard)
  SchemeParameters scheme;              ///< the scheme with the demo's parameters
  std::string initial = "interpolant";  ///< u₀(0) = u⁰(0), as the demo (a massless node only)
  std::string contact_velocity = "backward-difference";  ///< V₀ as the demo (a massless node only)
};

/// The presets, GetFEM's demo versions 0–4.
const std::vector<PeerPreset>& peer_presets();
/// The ids of peer_presets(), in order.
std::vector<std::string> peer_names();
/// The preset named `id`; throws std::invalid_argument listing the allowed ids.
const PeerPreset& peer_preset(const std::string& id);

/// GetFEM's demo's four displacement measures, with its definitions (demo_dynamic_contact_1D.py, the end):
/// at every level t_n (t = 0 included) the P1 function e with nodal values Uⁿ − u(x_i, t_n) (the exact
/// solution at the nodes), its L² norm (eᵀMe, M the consistent mass, exact for P1) and its full H¹ norm
/// (eᵀ(M + S)e: GetFEM's compute_H1_norm is L² plus the seminorm, where this project's measures take the
/// seminorm alone); L∞ in time: the largest over the levels, relative to the largest of the same norm of
/// the exact nodal values; L² in time: the plain sum over the levels (dt Σ, the demo's rule, where this
/// project integrates by the trapezoidal rule), relative to the same sum for the exact nodal values.
///
/// Its velocity and stress measures, with its definitions as well: LinfL2v and L2L2v the same norms
/// (L², max and plain sum over the levels) of the P1 function with nodal values Vⁿ − v(x_i, t_n), Vⁿ the
/// scheme's velocity at level n (the sample's; with a massless contact node the demo replaces node 0's by
/// the backward difference (u₀ⁿ − u₀ⁿ⁻¹)/Δt, 0 at n = 0, and so does this accumulator); L2sn the plain sum
/// over the levels of (sⁿ − u_x(0, t_n))², sⁿ the scheme's contact stress at level n (the sample's
/// multiplier, 0 where the level has none), relative to the same sum of the exact u_x(0, t_n). Whether a
/// scheme's velocity and stress are the demo's is a property of the formulation (bar1d's peer_formulation
/// and tools/getfem_peer.sh say per version which match).
class PeerMeasures {
 public:
  /// On `mesh` (the paper's: uniform, E = 1) against `exact`, which must outlive the accumulator;
  /// `massless_contact_node`: node 0's velocity is the backward difference, as in the demo.
  PeerMeasures(const UniformMesh& mesh, const ReferenceSolution& exact, bool massless_contact_node = false);
  /// The same, its norms read from `consistent`, the consistent mass already assembled on `mesh`
  /// (assemble_mass(mesh, consistent_mass()): the run's own when it takes the consistent mass, the
  /// demo's); std::invalid_argument for another mass or another mesh's.
  PeerMeasures(const UniformMesh& mesh, const ReferenceSolution& exact, const AssembledMass& consistent,
               bool massless_contact_node);
  /// Adds one level of a run.
  void add(const Sample& sample);
  /// The names the demo prints them under, in its order: LinfL2u, LinfH1u, LinfL2v, L2L2u, L2H1u, L2L2v, L2sn.
  static const std::array<const char*, 7> names;
  /// The seven relative measures, in the order of `names`.
  std::array<double, 7> values() const;

 private:
  const ReferenceSolution& exact_;
  Tridiagonal mass_, h1_;
  std::vector<double> x_;
  Tridiagonal all_mass_;  // the consistent mass on the nodes 0..N, the clamped one included
  double length_ = 1;
  bool massless_ = false, first_ = true;
  double previous_u0_ = 0, previous_time_ = 0;
  double error_l2_max_ = 0, exact_l2_max_ = 0, error_h1_max_ = 0, exact_h1_max_ = 0;
  double error_l2_sum_ = 0, exact_l2_sum_ = 0, error_h1_sum_ = 0, exact_h1_sum_ = 0;
  double error_v_max_ = 0, exact_v_max_ = 0, error_v_sum_ = 0, exact_v_sum_ = 0;
  double error_s_sum_ = 0, exact_s_sum_ = 0;
};

}  // namespace mrm::repro
