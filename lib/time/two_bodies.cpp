/// @file two_bodies.cpp
/// @brief Two bars in unilateral contact (doc/benchmarks.md §6, two-bars) on the finite element side; see two_bodies.hpp.
#include "time/two_bodies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include <doctest/doctest.h>

#include "time/schemes.hpp"

namespace mrm {

/// ## Two bodies coupled by one contact multiplier (the project's derivation)
///
/// **The problem.** Two bars A (left, (0, ℓ_A)) and B (right, (ℓ_A, ℓ_A + ℓ_B)) touch at x = ℓ_A across
/// an initial gap g₀ ≥ 0; the gap z(t) = u_B(ℓ_A⁺, t) − u_A(ℓ_A⁻, t) + g₀ stays ≥ 0, the contact stress
/// λ = E u_x, the same on both sides of the junction (the balance of the massless interface), is ≤ 0 and
/// λz = 0. Each body is written in its own frame, ξ from its contact end: ξ = ℓ_A − x, w_A = −u_A for A,
/// ξ = x − ℓ_A, w_B = u_B for B. Both satisfy ρw_tt = (E w_ξ)_ξ, and w_ξ = u_x in both frames (the sign of
/// ξ and of w flip together), so at ξ = 0 each body sees the stress λ, and z = w_A(0) + w_B(0) + g₀: in its
/// own frame each body is the paper's bar with its contact at node 0, and the obstacle of one is the
/// other's contact node.
///
/// **Semi-discrete.** P1 on each body, the redistributed mass M̄ₖ (Mod 1/2/3: row and column 0 vanish),
/// the stiffness Sₖ. The weak form of body k, as the paper's eq. (5): M̄ₖWₖ'' + SₖWₖ = −λe₀. Its row 0
/// has no inertia: it is the algebraic contact row Sₖ₀·Wₖ = −λ, that is (E₀/h₀)(w₀ − w₁) = −λ,
///
///     w₀ = w₁ − cₖλ,   cₖ = h₀/E₀ (the compliance of the contact element).
///
/// **Elimination of the massless nodes.** Substituting w₀ into row 1, S₁₀w₀ + S₁₁w₁ + S₁₂w₂ =
/// (S₁₁ + S₁₀)w₁ + S₁₂w₂ + λ (since −S₁₀cₖ = 1): on the nodes 1.. each body is
///
///     M̄_II Wₖ'' + S̃ₖWₖ = −λe₁,   S̃ₖ = S_II with S̃₁₁ = S₁₁ + S₁₀,
///
/// the bar without its contact element, pushed by λ at node 1. The contact condition on the relative
/// displacement: with s = w₁ᴬ + w₁ᴮ + g₀ and c = c_A + c_B, z = s − cλ, so 0 ≤ z ⊥ λ ≤ 0 has the one
/// solution λ = min(0, s)/c, z = max(0, s): a Lipschitz force λ(s) = ψ'(s), ψ(s) = min(0, s)²/(2c). The
/// contact element's strain energy is (E₀/2h₀)(w₀ − w₁)² = cₖλ²/2, summed over the bodies cλ²/2 = ψ(s):
/// the energy on all nodes, E = Σₖ ½VₖᵀM̄ₖVₖ + ½WₖᵀSₖWₖ, is the condensed one plus ψ.
///
/// **Crank–Nicolson** (the trapezoidal rule on nodes 1.., the contact rows at every level, as the
/// library's algebraic row for one body): ΔW = (Δt/2)(Vⁿ + Vⁿ⁺¹), M̄ΔV = (Δt/2)(−S̃(Wⁿ + Wⁿ⁺¹) −
/// (λⁿ + λⁿ⁺¹)e₁). Eliminating Vⁿ⁺¹ = 2ΔW/Δt − Vⁿ and multiplying by Δt/2 (θ = Δt²/4):
///
///     (M̄_II + θS̃)ΔWₖ = Δt M̄_II Vₖⁿ − 2θS̃Wₖⁿ − θλⁿe₁ − θλⁿ⁺¹e₁.
///
/// With A = M̄_II + θS̃ (symmetric positive definite, factored once), ΔWₖ = ΔWₖ* − θλⁿ⁺¹yₖ, yₖ = A⁻¹e₁,
/// so sⁿ⁺¹ = s* − θYλⁿ⁺¹ with s* the predictor's s and Y = y_{A,1} + y_{B,1} > 0; λⁿ⁺¹ = min(0, sⁿ⁺¹)/c
/// then has the one root λⁿ⁺¹ = min(0, s*)/(c + θY) (s* ≥ 0: no force; s* < 0: sⁿ⁺¹ = s*c/(c + θY) < 0).
/// The contact nodes follow, w₀ = w₁ − cₖλ, and their velocity is the derivative of that row: ẇ₀ = ẇ₁ in
/// flight, ẇ₀ = ẇ₁ − (cₖ/c)(ẇ₁ᴬ + ẇ₁ᴮ) in contact (then ẇ₀ᴬ + ẇ₀ᴮ = 0, the contact is held).
///
/// **Energy identity.** Multiplying the momentum rows by (Vⁿ + Vⁿ⁺¹)/2 = ΔW/Δt, the symmetric S̃ terms
/// telescope: E_condensed(n+1) − E_condensed(n) = −½(λⁿ + λⁿ⁺¹)(sⁿ⁺¹ − sⁿ). Adding ψ,
///
///     Eⁿ⁺¹ − Eⁿ = ∫_{sⁿ}^{sⁿ⁺¹} λ(s) ds − ½(λⁿ + λⁿ⁺¹)(sⁿ⁺¹ − sⁿ),
///
/// the trapezoidal rule's error on λ(s), which is linear on each side of 0: the energy is conserved
/// exactly (to round-off) by every step that keeps the contact status, and a step across s = 0 changes
/// it by −sⁿsⁿ⁺¹/(2c) at a release (> 0: energy created, as for one body) and sⁿsⁿ⁺¹/(2c) at an impact
/// (< 0). **Momentum.** With free far ends 1ᵀS̃ₖ = 0 (S̃ₖ is the stiffness of a free–free bar), so
/// 1ᵀM̄ₖΔVₖ = −(Δt/2)(λⁿ + λⁿ⁺¹) for each body: equal changes in the two frames, opposite in the global
/// one, whose momentum 1ᵀM̄ᴮVᴮ − 1ᵀM̄ᴬVᴬ is conserved exactly. **Symmetry.** Two equal bodies with equal
/// data (in their frames) have s = 2w₁ + g₀ and c = 2h₀/E₀, so λ = min(0, w₁ + g₀/2)/(h₀/E₀): each is the
/// one body of the library against a rigid obstacle at the gap g₀/2, the same equations step by step.
namespace {

// The symmetric tridiagonal block of A on the indices first.. (drops the leading rows and columns).
Tridiagonal without_leading(const Tridiagonal& a, Index first) {
  const Index n = a.size() - first;
  Tridiagonal b(n);
  for (Index i = 0; i < n; ++i) {
    b.diag[i] = a.diag[first + i];
    if (i > 0) b.lower[i] = a.lower[first + i];
    if (i + 1 < n) b.upper[i] = a.upper[first + i];
  }
  return b;
}

}  // namespace

TwoBodySimulation::TwoBodySimulation(std::array<TwoBodyPart, 2> parts, double gap, double dt) : gap_(gap), dt_(dt) {
  if (!(std::isfinite(dt) && dt > 0)) throw InvalidParameter("dt", "the time step must be positive and finite");
  if (!(std::isfinite(gap) && gap >= 0)) throw InvalidParameter("gap", "the initial gap must be finite and >= 0");
  const double theta = 0.25 * dt * dt;
  for (int k = 0; k < 2; ++k) {
    Body& b = body_[k];
    TwoBodyPart& part = parts[k];
    b.mesh = part.mesh;
    const Index n = b.mesh.unknowns();
    if (part.displacement.size() != n || part.velocity.size() != n)
      throw std::invalid_argument("two bodies: the initial data of body " + std::to_string(k) + " must have " +
                                  std::to_string(n) + " values (its unknowns)");
    if (n < 3) throw std::invalid_argument("two bodies: each body needs two nodes beside its contact node");
    if (part.assembled && part.assembled->matrix.size() != n)
      throw std::invalid_argument("two bodies: the assembled mass of body " + std::to_string(k) + " must have " +
                                  std::to_string(n) + " rows (its unknowns)");
    b.mass = part.assembled ? part.assembled->matrix : modified_mass(b.mesh, part.redistribution);
    if (!contact_node_is_massless(b.mass))
      throw InvalidParameter("mass",
                             "two bodies: each contact node must be massless (allowed: a redistribution, "
                             "not the consistent mass)");
    b.stiffness = p1_stiffness(b.mesh);
    b.compliance = b.mesh.contact_compliance();
    b.interior_stiffness = without_leading(b.stiffness, 1);
    b.interior_stiffness.diag[0] += b.stiffness.lower[1];  // S̃₁₁ = S₁₁ + S₁₀
    b.interior_mass = without_leading(b.mass, 1);
    const Tridiagonal a = b.interior_mass.plus(theta, b.interior_stiffness);
    const Index m = a.size();
    b.d.resize(m);
    b.l.setZero(m);
    for (Index i = 0; i < m; ++i) {  // A = L D Lᵀ, L unit lower bidiagonal
      if (i > 0) b.l[i] = a.lower[i] / b.d[i - 1];
      b.d[i] = a.diag[i] - (i > 0 ? b.l[i] * b.l[i] * b.d[i - 1] : 0.0);
      if (!(b.d[i] > 0)) throw InvalidParameter("mass", "two bodies: the step matrix is not positive definite");
    }
    b.response = solve(b, Eigen::VectorXd::Unit(m, 0));
    b.w = part.displacement;
    b.v = part.velocity;
  }
  const double s = indicator();
  lambda_ = std::min(0.0, s) / (body_[0].compliance + body_[1].compliance);
  set_contact_nodes();
}

Eigen::VectorXd TwoBodySimulation::solve(const Body& b, Eigen::VectorXd r) const {
  const Index m = r.size();
  for (Index i = 1; i < m; ++i) r[i] -= b.l[i] * r[i - 1];
  for (Index i = 0; i < m; ++i) r[i] /= b.d[i];
  for (Index i = m - 2; i >= 0; --i) r[i] -= b.l[i + 1] * r[i + 1];
  return r;
}

void TwoBodySimulation::set_contact_nodes() {
  const double c = body_[0].compliance + body_[1].compliance, relative = body_[0].v[1] + body_[1].v[1];
  for (Body& b : body_) {
    b.w[0] = b.w[1] - b.compliance * lambda_;
    b.v[0] = lambda_ < 0 ? b.v[1] - (b.compliance / c) * relative : b.v[1];
  }
}

double TwoBodySimulation::indicator() const { return body_[0].w[1] + body_[1].w[1] + gap_; }
double TwoBodySimulation::gap() const { return body_[0].w[0] + body_[1].w[0] + gap_; }

double TwoBodySimulation::energy() const {
  double e = 0;
  for (const Body& b : body_) e += 0.5 * b.mass.bilinear(b.v, b.v) + 0.5 * b.stiffness.bilinear(b.w, b.w);
  return e;
}

double TwoBodySimulation::momentum() const {
  return (body_[1].mass * body_[1].v).sum() - (body_[0].mass * body_[0].v).sum();
}

void TwoBodySimulation::step() {
  const double theta = 0.25 * dt_ * dt_;
  std::array<Eigen::VectorXd, 2> increment;
  double s_predicted = gap_, response = 0;
  for (int k = 0; k < 2; ++k) {
    const Body& b = body_[k];
    const Index m = b.w.size() - 1;
    const Eigen::VectorXd w = b.w.tail(m), v = b.v.tail(m);
    Eigen::VectorXd rhs = dt_ * (b.interior_mass * v) - (2 * theta) * (b.interior_stiffness * w);
    rhs[0] -= theta * lambda_;
    increment[k] = solve(b, rhs);
    s_predicted += b.w[1] + increment[k][0];
    response += b.response[0];
  }
  const double c = body_[0].compliance + body_[1].compliance;
  lambda_ = s_predicted < 0 ? s_predicted / (c + theta * response) : 0.0;
  for (int k = 0; k < 2; ++k) {
    Body& b = body_[k];
    const Index m = b.w.size() - 1;
    increment[k] -= (theta * lambda_) * b.response;
    b.w.tail(m) += increment[k];
    b.v.tail(m) = (2 / dt_) * increment[k] - b.v.tail(m);
  }
  set_contact_nodes();
  ++level_;
}

TwoBodyReference::TwoBodyReference(std::shared_ptr<const ImpactSolution> chain, int body)
    : chain_(std::move(chain)), body_(body) {
  if (!chain_ || !is_two_body_chain(chain_->configuration()) || (body != 0 && body != 1))
    throw std::invalid_argument("two-body reference: a chain of two bodies in contact and body 0 or 1");
  junction_ = chain_->configuration().segments[0].length;
  sign_ = body == 0 ? -1.0 : 1.0;
  // The body's energy at t = 0, ½∫(ρu_t² + E u_x²), by 8-point Gauss–Legendre on 64 equal parts (exact
  // for data of degree ≤ 7 on each part; the two-bars data are constant).
  static const double node[4] = {0.1834346424956498, 0.5255324099163290, 0.7966664774136267, 0.9602898564975363};
  static const double weight[4] = {0.3626837833783620, 0.3137066661722023, 0.2223810344533745, 0.1012285362903763};
  const BarSegment& s = chain_->configuration().segments[static_cast<std::size_t>(body)];
  const double part = s.length / 64;
  for (int p = 0; p < 64; ++p)
    for (int q = 0; q < 4; ++q)
      for (const double side : {-1.0, 1.0}) {
        const double xi = part * (p + 0.5 + 0.5 * side * node[q]);
        const double v = velocity(xi, 0.0), e = chain_->stress(global(xi), 0.0);
        energy_ += 0.5 * weight[q] * 0.5 * part * (s.density * v * v + e * e / s.modulus);
      }
}

double TwoBodyReference::length() const {
  return chain_->configuration().segments[static_cast<std::size_t>(body_)].length;
}

double TwoBodyReference::global(double xi) const {
  if (body_ == 0) return std::max(0.0, junction_ - xi);
  if (xi == 0.0) return std::nextafter(junction_, std::numeric_limits<double>::infinity());
  return std::min(chain_->configuration().length(), junction_ + xi);
}

double TwoBodyReference::displacement(double xi, double t) const { return sign_ * chain_->displacement(global(xi), t); }
double TwoBodyReference::velocity(double xi, double t) const { return sign_ * chain_->velocity(global(xi), t); }
double TwoBodyReference::strain(double xi, double t) const {
  return chain_->stress(global(xi), t) / chain_->configuration().segments[static_cast<std::size_t>(body_)].modulus;
}
double TwoBodyReference::contact_displacement(double t) const { return displacement(0.0, t); }
void TwoBodyReference::displacement_at_points(double t, const double* xi, long count, double* w) const {
  for (long k = 0; k < count; ++k) w[k] = displacement(xi[k], t);
}
void TwoBodyReference::velocity_at_points(double t, const double* xi, long count, double* v) const {
  for (long k = 0; k < count; ++k) v[k] = velocity(xi[k], t);
}

// ---------------------------------------------------------------------------------------------------
// Checks of the derivation above.
namespace {

// Body k of length ℓ with N elements, free far end, the redistribution `mass`, data in its own frame at
// rest and undeformed with velocity ẇ = `velocity` (negative: toward the contact).
[[maybe_unused]] TwoBodyPart free_body(double length, Index elements, const MassRedistribution& mass, double velocity) {
  TwoBodyPart p;
  p.mesh = with_far_end(UniformMesh(length, elements), FarEnd::free);
  p.redistribution = mass;
  p.displacement = Eigen::VectorXd::Zero(p.mesh.unknowns());
  p.velocity = Eigen::VectorXd::Constant(p.mesh.unknowns(), velocity);
  return p;
}

[[maybe_unused]] double contact_potential(double s, double c) { return std::min(0.0, s) * std::min(0.0, s) / (2 * c); }

}  // namespace

TEST_CASE("two bodies: Crank-Nicolson's energy identity and the conservation of momentum") {
  // Unequal bodies, meshes, masses and speeds, a gap closing at t = 0.05/1.5: impact, a contact phase,
  // a release. The prediction (derivation above): Eⁿ⁺¹ − Eⁿ equals ψ(sⁿ⁺¹) − ψ(sⁿ) − ½(λⁿ + λⁿ⁺¹)Δs to
  // round-off at every step (E ~ 0.7 from sums of ~50 terms: 1e-14 relative), so E is constant on every
  // step that keeps the status; the global momentum is constant to round-off (1e-14 of Σ m|v|).
  const double gap = 0.05;
  TwoBodySimulation run({free_body(1.0, 16, mod3(), -1.0), free_body(1.5, 24, mod1(), -0.5)}, gap, 0.4 / 16);
  const double c = 1.0 / 16 + 1.5 / 24, e0 = run.energy(), p0 = run.momentum();
  const double m_a = total_mass(run.mesh(0), mod3()), m_b = total_mass(run.mesh(1), mod1()), scale = m_a + 0.5 * m_b;
  CHECK(std::abs(e0 - (0.5 * m_a + 0.5 * m_b * 0.25)) <= 1e-14);  // at rest in its own frame, undeformed
  CHECK(std::abs(p0 - (m_a * 1.0 - m_b * 0.5)) <= 1e-14);
  // The round-off of one energy: the quadratic forms round each term, (SW)ᵢwᵢ to ε(4E/h)wᵢ² and
  // (M̄V)ᵢvᵢ to ε(row sum)vᵢ², so |δE| ≤ ε Σ (4E/h wᵢ² + mᵢvᵢ²) =: ε E_abs (the bodies translate, so
  // E_abs grows with |W|² well above E); a difference of two energies, 2ε E_abs, with a factor 4 for the
  // sums' own rounding. The momentum: one ε per term and step, accumulated linearly over the 400 steps.
  const auto absolute_energy = [&] {
    double sum = 0;
    for (int k = 0; k < 2; ++k) {
      const double stiffness = 4 / run.mesh(k).h();
      const Eigen::VectorXd masses =
          modified_mass(run.mesh(k), k == 0 ? mod3() : mod1()) * Eigen::VectorXd::Ones(run.mesh(k).unknowns());
      sum += stiffness * run.displacement(k).squaredNorm() + (masses.array() * run.velocity(k).array().square()).sum();
    }
    return sum;
  };
  int changes = 0, contact_steps = 0;
  double worst_identity = 0, worst_kept = 0, worst_momentum = 0, largest_absolute = 0;
  for (int n = 0; n < 400; ++n) {
    const double s0 = run.indicator(), l0 = run.multiplier(), before = run.energy();
    run.step();
    const double s1 = run.indicator(), l1 = run.multiplier(), after = run.energy();
    const double predicted = contact_potential(s1, c) - contact_potential(s0, c) - 0.5 * (l0 + l1) * (s1 - s0);
    const double tolerance = 8 * std::numeric_limits<double>::epsilon() * absolute_energy();
    largest_absolute = std::max(largest_absolute, absolute_energy());
    worst_identity = std::max(worst_identity, std::abs(after - before - predicted) / tolerance);
    if ((s0 > 0) != (s1 > 0))
      ++changes;
    else
      worst_kept = std::max(worst_kept, std::abs(after - before) / tolerance);
    contact_steps += l1 < 0;
    worst_momentum = std::max(worst_momentum, std::abs(run.momentum() - p0));
    CHECK(run.gap() >= -1e-15);
    CHECK(std::abs(run.gap() * run.multiplier()) <= 1e-15);
  }
  CAPTURE(worst_identity);
  CAPTURE(worst_kept);
  CAPTURE(worst_momentum);
  CHECK(changes >= 2);  // the impact and the release (and the energy they change)
  CHECK(contact_steps > 10);
  CAPTURE(largest_absolute);
  CHECK(worst_identity <= 1.0);  // in units of the round-off bound
  CHECK(worst_kept <= 1.0);
  CHECK(worst_momentum <= 400 * std::numeric_limits<double>::epsilon() * scale * 4);
  CHECK(std::abs(run.energy() - e0) > 1e-6 * e0);  // the status changes did change it: the check can fail
}

TEST_CASE("two bodies: symmetric data give a symmetric motion, the one body against an obstacle at g0/2") {
  // The prediction (derivation above, "Symmetry"): equal bodies with equal data compute the same doubles
  // in the same order, so Wᴬ = Wᴮ exactly; and each is the library's one body (free far end, rigid
  // obstacle at the gap g₀/2) to the round-off of two different solvers (1e-12 of the displacement).
  for (const MassRedistribution& mass : {mod1(), mod2(), mod3()}) {
    const double gap = 0.02, dt = 0.5 / 20;
    TwoBodySimulation two({free_body(1.0, 20, mass, -1.0), free_body(1.0, 20, mass, -1.0)}, gap, dt);
    Problem one_body;
    one_body.initial_displacement = [](double) { return 0.0; };
    one_body.initial_velocity = [](double) { return -1.0; };
    one_body.gap = gap / 2;
    SchemeParameters cn;
    cn.scheme = Scheme::crank_nicolson;
    BarSimulation one(one_body, with_far_end(UniformMesh(1.0, 20), FarEnd::free), mass, cn, dt);
    double asymmetry = 0, difference = 0;
    int contact = 0;
    for (int n = 0; n < 200; ++n, two.step(), one.step()) {
      asymmetry = std::max(asymmetry, (two.displacement(0) - two.displacement(1)).cwiseAbs().maxCoeff());
      difference = std::max(difference, (two.displacement(0) - *one.sample().displacement).cwiseAbs().maxCoeff());
      difference = std::max(difference, std::abs(two.multiplier() - one.sample().multiplier));
      contact += two.multiplier() < 0;
    }
    CAPTURE(mass.name);
    CHECK(contact > 10);
    CHECK(asymmetry == 0.0);
    CHECK(difference <= 1e-12);
  }
}

TEST_CASE("two bodies: a mass assembled beforehand is the one the run assembles") {
  // The same M^mod (assemble_mass's matrix is modified_mass's), so the same doubles at every step.
  std::array<TwoBodyPart, 2> own{free_body(1.0, 12, mod3(), -1.0), free_body(1.5, 9, mod2(), 0.0)};
  std::array<TwoBodyPart, 2> given = own;
  for (TwoBodyPart& p : given)
    p.assembled = std::make_shared<const AssembledMass>(assemble_mass(p.mesh, p.redistribution));
  TwoBodySimulation a(own, 0.01, 0.02), b(given, 0.01, 0.02);
  for (int n = 0; n < 100; ++n, a.step(), b.step())
    for (int k = 0; k < 2; ++k) CHECK(a.displacement(k) == b.displacement(k));
  given[1].assembled = given[0].assembled;  // body 0's mass: the wrong size for body 1
  CHECK_THROWS_AS(TwoBodySimulation(given, 0.01, 0.02), std::invalid_argument);
}

TEST_CASE("two bodies: refusals") {
  CHECK_THROWS_AS(
      TwoBodySimulation({free_body(1.0, 8, consistent_mass(), -1.0), free_body(1.0, 8, mod3(), 0.0)}, 0.0, 0.01),
      InvalidParameter);
  CHECK_THROWS_AS(TwoBodySimulation({free_body(1.0, 8, mod3(), -1.0), free_body(1.0, 8, mod3(), 0.0)}, -1.0, 0.01),
                  InvalidParameter);
  CHECK_THROWS_AS(TwoBodySimulation({free_body(1.0, 8, mod3(), -1.0), free_body(1.0, 8, mod3(), 0.0)}, 0.0, 0.0),
                  InvalidParameter);
}

}  // namespace mrm
