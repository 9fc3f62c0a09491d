/// @file peers.hpp
/// @brief The configurations that match a peer code's run (bar1d --peer): GetFEM's
/// demo_dynamic_contact_1D.py, versions 0–4, at its defaults (field.md §2, beyond.md §7).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "reference_solution.hpp"
#include "schemes.hpp"

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

/// The presets, GetFEM's demo versions 0–3 (4, Taylor–Flanagan, is added with its scheme).
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
class PeerMeasures {
 public:
  /// On `mesh` (the paper's: uniform, E = 1) against `exact`, which must outlive the accumulator.
  PeerMeasures(const UniformMesh& mesh, const ReferenceSolution& exact);
  /// Adds one level of a run.
  void add(const Sample& sample);
  /// The names the demo prints them under: LinfL2u, LinfH1u, L2L2u, L2H1u.
  static const std::array<const char*, 4> names;
  /// The four relative measures, in the order of `names`.
  std::array<double, 4> values() const;

 private:
  const ReferenceSolution& exact_;
  Tridiagonal mass_, h1_;
  std::vector<double> x_;
  double error_l2_max_ = 0, exact_l2_max_ = 0, error_h1_max_ = 0, exact_h1_max_ = 0;
  double error_l2_sum_ = 0, exact_l2_sum_ = 0, error_h1_sum_ = 0, exact_h1_sum_ = 0;
};

}  // namespace mrm::repro
