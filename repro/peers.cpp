/// @file peers.cpp
/// @brief GetFEM's demo_dynamic_contact_1D.py (interface/tests/python, GetFEM 5.4) as bar1d presets.
///
/// The demo's defaults: NX = 20, T = 12, dt = 0.002, Newmark β = 0 (explicit: the step solves with the
/// mass), γ = ½, γ₀_N = 5, θ_N = 0, γ₀_P = 1, e_PS = 0, the standard (consistent) mass. Per version, the
/// formulation of this library that reproduces its displacement measures (tests/getfem_peer.sh compares
/// them with the demo's printed values, tests/data/getfem/measures.dat):
///   v0, Signorini with a multiplier: `newmark`; the demo has no explicit step with the standard mass
///       (it stops on `assert(false)`), and so does the library (refused, exit 2): run it with
///       --newmark-beta 0.25 (implicit, the demo's blowing-up run) or a massless contact node.
///   v1, Paoli–Schatzman: `ps` with β = 0, e = e_PS and the literal row: the demo's explicit Newmark with
///       γ = ½ and the impulse (U − U_pred)/Δt added to V is, with V eliminated, the three-level scheme
///       M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹) + Δt² SUⁿ = −Δt²λⁿe₀ with (u₀ⁿ⁺¹ + e u₀ⁿ⁻¹)/(1 + e) ≥ 0 (contact_classes.cpp's
///       derivation for the penalty, with the impulse in place of the force), started as the demo starts:
///       by the explicit Newmark step U¹ = U⁰ + ΔtV⁰ + ½Δt²M⁻¹(−SU⁰) (--ps-start explicit; the library's
///       Crank–Nicolson start differs by 5e-5 relative at T = 0.1, 8e-6 at T = 12). Its β is --beta.
///   v2, penalty: `penalty` with Newmark (0, ½) and γ₀ = γ₀_P.
///   v3, Nitsche: `nitsche` with Newmark (0, ½), γ₀ = γ₀_N, θ = θ_N.
///   v4, Taylor–Flanagan: `taylor-flanagan` with the consistent mass solved at every step (--lumping none:
///       the demo's lump_mass_matrix = 0) and the interpolant as the contact node's initial value; what
///       the match required is getfem_demo_v4.hpp's (the scheme's (E1) is the demo's step).
#include "peers.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

#include "getfem_demo_v4.hpp"
#include "exact/exact_solution.hpp"
#include "fem/mass_redistribution.hpp"

namespace mrm::repro {

namespace {

PeerPreset demo_version(int version) {
  PeerPreset p;
  p.id = "getfem-v" + std::to_string(version);
  p.scheme.newmark_beta = 0.0;
  p.scheme.newmark_gamma = 0.5;
  switch (version) {
    case 0:
      p.summary = "pure Signorini contact by a multiplier (newmark)";
      p.scheme.scheme = Scheme::newmark;
      p.formulation = "newmark: Newmark (beta, gamma), u0 >= 0 by a multiplier at the new level";
      break;
    case 1:
      p.summary = "Paoli-Schatzman with restitution e_PS = 0 (ps, beta 0, literal row)";
      p.scheme.scheme = Scheme::paoli_schatzman;
      p.scheme.newmark_beta = SchemeParameters().newmark_beta;  // ps takes --beta, not Newmark's
      p.scheme.newmark_gamma = SchemeParameters().newmark_gamma;
      p.scheme.beta = 0.0;
      p.scheme.restitution = 0.0;
      p.scheme.contact_row = ContactRow::literal;
      p.scheme.ps_explicit_start = true;
      p.formulation =
          "ps: three-level Paoli-Schatzman (beta = 0), the literal contact row, e = e_PS, started by "
          "the explicit Newmark step";
      break;
    case 2:
      p.summary = "penalty gamma0_P = 1 (penalty)";
      p.scheme.scheme = Scheme::penalty;
      p.scheme.penalty = 1.0;
      p.formulation = "penalty: Newmark (beta, gamma) with the force (gamma0/h) min(0, u0) at the new level";
      break;
    case 3:
      p.summary = "Nitsche gamma0_N = 5, theta_N = 0 (nitsche)";
      p.scheme.scheme = Scheme::nitsche;
      p.scheme.nitsche_gamma = 5.0;
      p.scheme.nitsche_theta = 0.0;
      p.formulation =
          "nitsche: Newmark (beta, gamma) with lambda = min(0, gamma u0 + u_x(0)), active set on the predictor";
      break;
    case 4: {
      // One source: the configuration getfem_demo_v4 runs (its mesh, step, horizon, mass and initial node).
      const Configuration demo = getfem_demo_v4_configuration();
      p.summary = "Taylor-Flanagan, the standard mass solved at every step (taylor-flanagan, lumping none)";
      p.scheme.scheme = demo.scheme.scheme;
      p.scheme.lumping = demo.scheme.lumping;
      p.elements = demo.elements;
      p.dt = demo.dt;
      p.final_time = demo.final_time;
      p.mass = demo.mass.name;
      p.initial = to_string(demo.initial);
      p.formulation =
          "taylor-flanagan: central differences with the consistent mass (no lumping), the contact node's "
          "velocity corrected by Taylor-Flanagan's impulse spread through M^-1";
      break;
    }
    default:
      throw std::logic_error("demo_version: no such version");
  }
  return p;
}

}  // namespace

const std::vector<PeerPreset>& peer_presets() {
  static const std::vector<PeerPreset> presets = {demo_version(0), demo_version(1), demo_version(2), demo_version(3),
                                                  demo_version(4)};
  return presets;
}

std::vector<std::string> peer_names() {
  std::vector<std::string> names;
  for (const PeerPreset& p : peer_presets()) names.push_back(p.id);
  return names;
}

const PeerPreset& peer_preset(const std::string& id) {
  std::string allowed;
  for (const PeerPreset& p : peer_presets()) {
    if (p.id == id) return p;
    allowed += (allowed.empty() ? "" : ", ") + p.id;
  }
  throw std::invalid_argument("unknown peer \"" + id + "\" (allowed: " + allowed + ")");
}

const std::array<const char*, 7> PeerMeasures::names = {"LinfL2u", "LinfH1u", "LinfL2v", "L2L2u",
                                                        "L2H1u",   "L2L2v",   "L2sn"};

PeerMeasures::PeerMeasures(const UniformMesh& mesh, const ReferenceSolution& exact, bool massless_contact_node)
    : PeerMeasures(mesh, exact, assemble_mass(mesh, consistent_mass()), massless_contact_node) {}

// The norms' matrices from the one assembly: M on the unknowns, M + S for H¹, and M on every node (the
// clamped one included) for the velocity's L².
PeerMeasures::PeerMeasures(const UniformMesh& mesh, const ReferenceSolution& exact, const AssembledMass& consistent,
                           bool massless_contact_node)
    : exact_(exact),
      mass_(consistent.matrix),
      h1_(consistent.matrix.plus(1.0, p1_stiffness(mesh))),
      all_mass_(consistent.all_nodes),
      length_(mesh.length),
      massless_(massless_contact_node) {
  if (consistent.redistribution.name != consistent_mass().name || consistent.redistribution.interior_blend != 0.0 ||
      consistent.matrix.size() != mesh.unknowns())
    throw std::invalid_argument("PeerMeasures: the norms take the consistent mass assembled on the run's mesh");
  for (Index i = 0; i < mesh.unknowns(); ++i) x_.push_back(mesh.x(i));
}

TEST_CASE("the peer's norms from the consistent mass assembled once are those of the demo's matrices") {
  // M on every node is M on the unknowns of the same mesh with a free far end (no node clamped).
  const UniformMesh mesh(1.0, 12);
  const AssembledMass consistent = assemble_mass(mesh, consistent_mass());
  const Tridiagonal free_end = modified_mass(with_far_end(mesh, FarEnd::free), consistent_mass());
  CHECK(consistent.all_nodes.diag == free_end.diag);
  CHECK(consistent.all_nodes.lower == free_end.lower);
  CHECK(consistent.all_nodes.upper == free_end.upper);
  const Tridiagonal m = modified_mass(mesh, consistent_mass());
  CHECK(consistent.matrix.diag == m.diag);
  CHECK(consistent.matrix.lower == m.lower);
  CHECK(consistent.matrix.upper == m.upper);
  const ExactSolution exact;
  CHECK_THROWS_AS(PeerMeasures(mesh, exact, assemble_mass(mesh, mod3()), false), std::invalid_argument);
  CHECK_THROWS_AS(PeerMeasures(UniformMesh(1.0, 10), exact, consistent, false), std::invalid_argument);
}

void PeerMeasures::add(const Sample& sample) {
  const Eigen::VectorXd& u = *sample.displacement;
  Eigen::VectorXd exact(u.size()), exact_v(u.size());
  for (Index i = 0; i < u.size(); ++i) {
    exact[i] = exact_.displacement(x_[static_cast<std::size_t>(i)], sample.time);
    // The demo's nodes are np.arange(0, 1 + 1/NX, 1/NX), i.e. i·(1/NX) in floating point, which differs from
    // i/NX in the last bit for some i: a front crossing such a node at a level picks its side by that bit.
    exact_v[i] = getfem_demo_exact(static_cast<double>(i) * (length_ / static_cast<double>(x_.size())), sample.time, 2);
  }
  const Eigen::VectorXd error = u - exact;
  const double e_l2 = mass_.bilinear(error, error), x_l2 = mass_.bilinear(exact, exact);
  const double e_h1 = h1_.bilinear(error, error), x_h1 = h1_.bilinear(exact, exact);
  error_l2_max_ = std::max(error_l2_max_, e_l2);
  exact_l2_max_ = std::max(exact_l2_max_, x_l2);
  error_h1_max_ = std::max(error_h1_max_, e_h1);
  exact_h1_max_ = std::max(exact_h1_max_, x_h1);
  error_l2_sum_ += e_l2;
  exact_l2_sum_ += x_l2;
  error_h1_sum_ += e_h1;
  exact_h1_sum_ += x_h1;
  // The velocity: the sample's, node 0's the backward difference with a massless node (0 at level 0); the
  // demo's vectors include the clamped node x = L, whose velocity is 0 and whose exact value uExact(1, t, 2)
  // is not 0 where t is a whole number (its zone 1): that node is added here with the mass of all nodes.
  const Index n = u.size();
  Eigen::VectorXd v(n + 1), exact_all(n + 1);
  v.head(n) = *sample.velocity;
  v[n] = 0.0;
  exact_all.head(n) = exact_v;
  exact_all[n] = getfem_demo_exact(length_, sample.time, 2);
  if (massless_) v[0] = first_ ? 0.0 : (u[0] - previous_u0_) / (sample.time - previous_time_);
  const Eigen::VectorXd error_v = v - exact_all;
  const double e_v = all_mass_.bilinear(error_v, error_v), x_v = all_mass_.bilinear(exact_all, exact_all);
  error_v_max_ = std::max(error_v_max_, e_v);
  exact_v_max_ = std::max(exact_v_max_, x_v);
  error_v_sum_ += e_v;
  exact_v_sum_ += x_v;
  // The contact stress against the exact u_x(0, t_n).
  const double s = sample.has_multiplier ? sample.multiplier : 0.0, s_exact = getfem_demo_exact(0.0, sample.time, 1);
  error_s_sum_ += (s - s_exact) * (s - s_exact);
  exact_s_sum_ += s_exact * s_exact;
  first_ = false;
  previous_u0_ = u[0];
  previous_time_ = sample.time;
}

std::array<double, 7> PeerMeasures::values() const {
  return {std::sqrt(error_l2_max_ / exact_l2_max_), std::sqrt(error_h1_max_ / exact_h1_max_),
          std::sqrt(error_v_max_ / exact_v_max_),   std::sqrt(error_l2_sum_ / exact_l2_sum_),
          std::sqrt(error_h1_sum_ / exact_h1_sum_), std::sqrt(error_v_sum_ / exact_v_sum_),
          std::sqrt(error_s_sum_ / exact_s_sum_)};
}

}  // namespace mrm::repro
