/// @file explicit_schemes.cpp
/// @brief The explicit contact classes (doc/contact_treatments.md §6): `taylor-flanagan` and `explicit`.
///
/// ## Central differences (Newmark β = 0, γ = ½) in velocity-Verlet form
///
/// The semi-discrete problem is M U'' + S U = F − λe₀ (schemes.cpp), M here a diagonal (row-sum lumped)
/// mass, or the consistent one for `--lumping none`. One step, with Aⁿ = M⁻¹(Fⁿ − SUⁿ) on the rows with
/// mass:
///
///     Vⁿ⁺½ = Vⁿ + (Δt/2) Aⁿ,    Uⁿ⁺¹ = Uⁿ + Δt Vⁿ⁺½,    [contact],    Vⁿ⁺¹ = Vⁿ⁺½ + (Δt/2) Aⁿ⁺¹,      (E1)
///
/// which is GetFEM's explicit Newmark (U¹ = U⁰ + ΔtV⁰ + (Δt²/2)A⁰, V¹ = V⁰ + (Δt/2)(A⁰ + A¹)) and, with
/// V eliminated, central differences M(Uⁿ⁺¹ − 2Uⁿ + Uⁿ⁻¹)/Δt² + SUⁿ = Fⁿ on the free rows.
///
/// **Energy identity.** With D = (Uⁿ⁺¹ − Uⁿ)/Δt, multiplying the central difference by Uⁿ⁺¹ − Uⁿ⁻¹ gives
///
///     E_{n+½} − E_{n−½} = ½ Fⁿ·(Uⁿ⁺¹ − Uⁿ⁻¹) − ½ Pⁿ·(D_{n+½} + D_{n−½}),
///     E_{n+½} = ½ DᵀMD + ½ Uⁿ⁺¹ᵀSUⁿ = ½ Dᵀ(M − Δt²S/4)D + ½ ŪᵀSŪ,   Ū = (Uⁿ⁺¹ + Uⁿ)/2,          (E2)
///
/// Pⁿ the impulse of the contact over the step (M(D_{n+½} − D_{n−½}) = Δt(Fⁿ − SUⁿ) − Pⁿ). Without load
/// and contact E_{n+½} is conserved exactly (doctest), and it is a norm iff M − Δt²S/4 > 0.
///
/// ## The stability limits
///
/// (E2) is a norm iff Δt² ω² < 4 for every eigenvalue ω² of M⁻¹S: Δt < 2/ω_max. A bound Λ ≥ ω²_max
/// gives the sufficient limit Δt ≤ 2/√Λ (the bound is never attained on these meshes, so equality is
/// kept). With a diagonal mass m, M⁻¹S is similar to the symmetric M^{-½}SM^{-½}, and Gershgorin's
/// discs of M⁻¹S give Λ = max_i Σ_j |S_ij|/m_i. On the paper's mesh (S_ii = 2/h, S_{i,i±1} = −1/h,
/// S₀₀ = 1/h):
/// - taylor-flanagan, lumped consistent mass (h/2, h, …, h): row 0 (1/h + 1/h)/(h/2) = 4/h², interior
///   rows 4/h², row N−1 3/h²: Λ = 4/h², **Δt ≤ h** (c = 1, the lumped P1 limit h/c);
/// - explicit, massless node 0: rows 1..N−1 with node 0 condensed. In contact node 0 is held, S's block
///   on 1..N−1; free, node 1's stiffness is S₁₁ − S₁₀²/S₀₀ = 1/h, smaller, with the same off-diagonal:
///   the contact block bounds both. Lumped Mod 3 (0, 3h/2, h, …): row 1 (2/h + 1/h)/(3h/2) = 2/h²,
///   interior 4/h²: **Δt ≤ h**, the same limit; a lighter node 1 lowers it once 3/(h m₁) > 4/h²,
///   i.e. m₁ < 3h/4 (lumped Mod 1 has m₁ = 5h/6: still h);
/// - taylor-flanagan with the consistent mass (lumping none): Gershgorin does not apply to a
///   non-diagonal M; the element bound ω²_max ≤ max_e λ_max(M_e⁻¹S_e) (Irons–Treharne) with
///   M_e = ρh/6 [2 1; 1 2], S_e = E/h [1 −1; −1 1] gives 12E/(ρh²): **Δt ≤ h/√3** (GetFEM's demo
///   estimates h/2 and refuses above it).
/// The limit is checked before any work (ExplicitStep's constructor): "dt: … (allowed: …)".
///
/// ## taylor-flanagan: the contact by a velocity correction (GetFEM's version 4)
///
/// After the predictor (E1), if ũ₀ + gap < 0 (penetration), the impulse P e₀ = Δt μ e₀ that sets the
/// contact node's half-step velocity to zero is applied through M⁻¹, to the velocity and, as if it had
/// acted over the whole step, to the position:
///
///     r = M⁻¹e₀,   μ = ṽ₀/(Δt r₀),   Vⁿ⁺½ = Ṽ − Δtμ r,   Uⁿ⁺¹ = Ũ − Δt²μ r,   λⁿ⁺¹ = μ (≤ 0 on approach),
///
/// and λⁿ⁺¹ = 0 without penetration; the second half kick of (E1) carries no contact force. Node 0
/// moves by −Δt²μ r₀ = −Δt ṽ₀, so u₀ⁿ⁺¹ = ũ₀ − Δt ṽ₀ = u₀ⁿ whatever the mass: the node stays where it
/// was, and by induction it **never penetrates** (u₀⁰ + gap ≥ 0), but it may stop above the obstacle.
/// With a lumped mass r = e₀/m₀ and only node 0 moves; with the consistent mass r is full and the
/// impulse moves every node. By (E2) with P = Δtμe₀ the step changes the shadow energy by
/// −½ Δtμ (D₀_{n+½} + D₀_{n−½}) (doctest: to round-off at every step); lumped, D₀_{n+½} = 0 after a
/// correction and the change is −½ m₀ ṽ₀ D₀_{n−½}: ≤ 0 when the node was approaching or at rest
/// (D₀_{n−½} ≤ 0, ṽ₀ < 0), a gain when it had just left the obstacle (D₀_{n−½} > 0), which happens at
/// Δt = h (doctest: the node rattles and the energy grows).
///
/// ## explicit: a massless contact node, made algebraic by mass redistribution
///
/// With m₀ = 0 node 0 has no equation of motion: its row is the algebraic contact row (paper eq. (6))
/// S₀·Uⁿ⁺¹ = F₀ⁿ⁺¹ − λⁿ⁺¹, 0 ≤ u₀ⁿ⁺¹ + gap ⊥ λⁿ⁺¹ ≤ 0, solved in closed form after the predictor of the
/// other nodes (condense_contact_node: u₀ = max(−gap, u₁ + hF₀), λ = min(0, F₀ + (u₁ + gap)/h)). No
/// impact law is needed: Signorini's conditions hold exactly at every level (no penetration, λg = 0),
/// and eliminating u₀ leaves central differences on nodes 1..N−1 with node 1 held by a one-sided
/// spring of stiffness 1/h (in contact) or by the load (free): a Lipschitz force, whence the same limit.
///
/// ## Is the scheme "explicit" exact at the nodes at Δt = h?
///
/// For the free wave equation, lumped central differences at Δt = h are the d'Alembert diamond
/// u_iⁿ⁺¹ + u_iⁿ⁻¹ = u_{i+1}ⁿ + u_{i−1}ⁿ, exact at the nodes; a free end with the lumped half mass h/2
/// gives u₀ⁿ⁺¹ + u₀ⁿ⁻¹ = 2u₁ⁿ, the mirrored diamond, exact too (doctest: taylor-flanagan, lumped, Δt = h,
/// exact to round-off up to the first impact). With a massless contact node, node 1's row is
/// m₁(u₁ⁿ⁺¹ − 2u₁ⁿ + u₁ⁿ⁻¹)/h² = (u₂ⁿ − u₁ⁿ)/h + (u₀ⁿ − u₁ⁿ)/h, u₀ = u₁ (free) or 0 (contact):
/// - in contact the diamond needs m₁ = h; Mod 3's lumped m₁ = 3h/2 gives
///   u₁ⁿ⁺¹ + u₁ⁿ⁻¹ = (2/3)(u₂ⁿ + u₁ⁿ) + … ≠ the diamond;
/// - free, the massless node is tied to node 1 (element 0 carries no strain), while the exact solution
///   has u(0, t) ≠ u(h, t) whenever a front lies in (0, h): at t = 0 already, u(0) − u(h) = h/2, and
///   the predictor of node 1 is off by O(h) at the first step for every m₁ (m₁ = 3h/2: ū₁¹ = u₁⁰ − h/6
///   against the exact u₁⁰).
/// So the answer is **no**: the explicit scheme with a massless contact node is not exact at the nodes
/// at Δt = h, for Mod 3's lumped mass or any other m₁; the defect is local to the contact element
/// (O(h) at node 1, carried by the fronts), and the doctest measures it against the closed form.

#include "steps/explicit_schemes.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

#include "steps/contact.hpp"
#include "exact/exact_solution.hpp"
#include "fem/dense_eigenvalues.hpp"

namespace mrm {

namespace {
// The row sums of M^mod (all nodes) on the unknowns 0..n−1.
Eigen::VectorXd row_sums(const Tridiagonal& all, Index n) {
  Eigen::VectorXd m(n);
  for (Index i = 0; i < n; ++i) m[i] = all.lower[i] + all.diag[i] + all.upper[i];
  return m;
}
}  // namespace

Eigen::VectorXd row_sum_lumped_mass(const UniformMesh& mesh, const MassRedistribution& mass) {
  return row_sums(modified_mass_all_nodes(mesh, mass), mesh.unknowns());
}

TEST_CASE("row-sum lumping: (h/2, h, ..., h) for the consistent mass, (0, 3h/2, h, ...) for Mod 3") {
  const UniformMesh mesh(1.0, 10);
  const double h = mesh.h();
  const Eigen::VectorXd consistent = row_sum_lumped_mass(mesh, consistent_mass());
  const Eigen::VectorXd redistributed = row_sum_lumped_mass(mesh, mod3());
  CHECK(consistent[0] == doctest::Approx(h / 2).epsilon(1e-15));
  CHECK(redistributed[0] == 0.0);
  CHECK(redistributed[1] == doctest::Approx(1.5 * h).epsilon(1e-15));
  for (Index i = 2; i < 10; ++i) {
    CHECK(consistent[i] == doctest::Approx(h).epsilon(1e-15));
    CHECK(redistributed[i] == doctest::Approx(h).epsilon(1e-15));
  }
  // Lumping keeps the total mass of the nodes 0..N−1 plus what the clamped node's column gave them.
  CHECK(consistent.sum() == doctest::Approx(1.0 - h / 2).epsilon(1e-14));
  CHECK(redistributed.sum() == doctest::Approx(1.0 - h / 2).epsilon(1e-14));
}

double explicit_stability_limit(const UniformMesh& mesh, const Eigen::VectorXd* lumped) {
  const Tridiagonal s = p1_stiffness(mesh);
  double bound = 0;  // Λ ≥ ω²_max
  if (lumped) {
    const bool massless = (*lumped)[0] == 0.0;
    for (Index i = massless ? 1 : 0; i < s.size(); ++i) {
      // Gershgorin's disc of row i of M⁻¹S; with a massless node 0 the row of node 1 drops the column
      // of the held node 0 (the contact block, whose bound is the larger).
      double radius = std::abs(s.upper[i]) + ((massless && i == 1) ? 0.0 : std::abs(s.lower[i]));
      bound = std::max(bound, (s.diag[i] + radius) / (*lumped)[i]);
    }
  } else {
    for (Index e = 0; e < mesh.elements; ++e)
      bound = std::max(bound, 12 * mesh.young(e) / (mesh.density(e) * mesh.h(e) * mesh.h(e)));
  }
  return 2 / std::sqrt(bound);
}

TEST_CASE("the explicit stability limits: h (lumped P1, and lumped Mod 3 with a massless node), h/sqrt(3)") {
  for (Index n : {10, 40, 100}) {
    const UniformMesh mesh(1.0, n);
    const double h = mesh.h();
    const Eigen::VectorXd lumped = row_sum_lumped_mass(mesh, consistent_mass());
    const Eigen::VectorXd massless = row_sum_lumped_mass(mesh, mod3());
    CHECK(explicit_stability_limit(mesh, &lumped) == doctest::Approx(h).epsilon(1e-14));
    CHECK(explicit_stability_limit(mesh, &massless) == doctest::Approx(h).epsilon(1e-14));
    CHECK(explicit_stability_limit(mesh, nullptr) == doctest::Approx(h / std::sqrt(3.0)).epsilon(1e-14));
    // The limit is sufficient and not attained: ω_max from the dense eigenproblem is below 2/Δt_max.
    Eigen::MatrixXd a = p1_stiffness(mesh).to_sparse().toDense();
    for (Index i = 0; i < n; ++i)
      for (Index j = 0; j < n; ++j) a(i, j) /= std::sqrt(lumped[i] * lumped[j]);
    const double omega2 = symmetric_eigenvalues(a).maxCoeff();
    CHECK(omega2 < 4 / (h * h));
    CHECK(omega2 > 0.95 * 4 / (h * h));  // and close: the bound is the right one
  }
}

ExplicitStep::ExplicitStep(const UniformMesh& mesh, const MassRedistribution& mass, const Tridiagonal& stiffness,
                           const SchemeParameters& parameters, double dt, double gap)
    : ExplicitStep(mesh, assemble_mass(mesh, mass), stiffness, parameters, dt, gap) {}

ExplicitStep::ExplicitStep(const UniformMesh& mesh, const AssembledMass& assembled, const Tridiagonal& stiffness,
                           const SchemeParameters& parameters, double dt, double gap)
    : mesh_(mesh),
      taylor_flanagan_(parameters.scheme == Scheme::taylor_flanagan),
      lumped_(parameters.lumping == MassLumping::row_sum),
      dt_(dt),
      gap_(gap),
      compliance_(mesh.contact_compliance()),
      stiffness_(stiffness) {
  const SchemeInfo* entry = find_entry(central_difference_schemes(), parameters.scheme);
  if (!entry) {
    std::string allowed;
    for (const SchemeInfo& info : central_difference_schemes()) allowed += (allowed.empty() ? "" : ", ") + info.id;
    throw InvalidParameter("scheme", "the scheme is not an explicit scheme (allowed: " + allowed + ")");
  }
  const MassRedistribution& mass = assembled.redistribution;
  const Tridiagonal& consistent = assembled.matrix;
  massless_ = assembled.massless;
  const std::string id = entry->id;
  if (taylor_flanagan_ && massless_)
    throw InvalidParameter("mass",
                           "taylor-flanagan needs a contact node with inertia (allowed: consistent; with a "
                           "massless contact node the explicit step is the scheme explicit)");
  if (!taylor_flanagan_ && !massless_)
    throw InvalidParameter("mass",
                           "the scheme explicit needs a massless contact node (allowed: any mass but "
                           "consistent, e.g. mod3; with inertia at the contact node use taylor-flanagan)");
  if (!lumped_ && !(mass.name == consistent_mass().name && mesh.uniform() && mesh.homogeneous()))
    throw InvalidParameter("mass_lumping",
                           "none (the consistent mass solved at every step) needs the consistent "
                           "mass on the paper's mesh (allowed: row-sum)");
  const Index n = mesh.unknowns();
  Eigen::VectorXd lumped_mass;
  if (lumped_) {
    lumped_mass = row_sums(assembled.all_nodes, n);
    mass_ = Tridiagonal(n);
    mass_.diag = lumped_mass;
    inverse_mass_.resize(n);
    for (Index i = 0; i < n; ++i) inverse_mass_[i] = lumped_mass[i] > 0 ? 1 / lumped_mass[i] : 0.0;
  } else {
    mass_ = consistent;
    // LDLᵀ of the tridiagonal M: d_i = M_ii − M_{i,i−1}²/d_{i−1}, factor_i = M_{i,i−1}/d_{i−1}.
    pivot_.resize(n);
    factor_.setZero(n);
    pivot_[0] = mass_.diag[0];
    for (Index i = 1; i < n; ++i) {
      factor_[i] = mass_.lower[i] / pivot_[i - 1];
      pivot_[i] = mass_.diag[i] - factor_[i] * mass_.lower[i];
    }
  }
  limit_ = explicit_stability_limit(mesh, lumped_ ? &lumped_mass : nullptr);
  // Δt ≤ Δt_max up to the rounding of 2/√Λ and of Δt = C h (a few ulps).
  if (!(dt <= limit_ * (1 + 1e-12))) {
    const double courant = mesh.uniform() && mesh.homogeneous() ? limit_ / mesh.h() : 0.0;
    char text[160];
    std::snprintf(text, sizeof text, "dt = %.6g is above the stability limit of %s (allowed: 0 < dt <= %.6g", dt,
                  id.c_str(), limit_);
    std::string message = text;
    if (courant > 0) {
      std::snprintf(text, sizeof text, ", i.e. Courant number <= %.6g", courant);
      message += text;
    }
    throw InvalidParameter("dt", message + ")");
  }
  if (taylor_flanagan_) {
    impulse_response_ = Eigen::VectorXd::Zero(n);
    impulse_response_[0] = 1.0;
    if (lumped_)
      impulse_response_ = impulse_response_.cwiseProduct(inverse_mass_);
    else {
      for (Index i = 1; i < n; ++i) impulse_response_[i] -= factor_[i] * impulse_response_[i - 1];
      for (Index i = n - 1; i >= 0; --i)
        impulse_response_[i] =
            impulse_response_[i] / pivot_[i] - (i + 1 < n ? factor_[i + 1] * impulse_response_[i + 1] : 0.0);
    }
  }
}

// a = M⁻¹(F − SU) on the rows with mass (0 at a massless node), λ's force on node 0 not included: the
// explicit scheme's contact force is carried by u₀ through S (its algebraic row), Taylor–Flanagan's by
// its impulse.
void ExplicitStep::accelerate(const Eigen::VectorXd& u, const Eigen::VectorXd* load, double, Eigen::VectorXd& a) const {
  stiffness_.multiply(u, a);  // −SU formed in `a` (the same bits as −(S * U), without a temporary)
  a = -a;
  if (load) a += *load;
  if (lumped_) {
    a = a.cwiseProduct(inverse_mass_);
    return;
  }
  const Index n = a.size();
  for (Index i = 1; i < n; ++i) a[i] -= factor_[i] * a[i - 1];
  for (Index i = n - 1; i >= 0; --i) a[i] = a[i] / pivot_[i] - (i + 1 < n ? factor_[i + 1] * a[i + 1] : 0.0);
}

void ExplicitStep::step(StepState& state, bool has_load) const {
  Eigen::VectorXd& u = state.u;
  Eigen::VectorXd& v = state.w;  // the two-level velocity Vⁿ
  Eigen::VectorXd& a = state.u_new;
  // (E1): the half kick and the drift.
  accelerate(u, has_load ? &state.f_now : nullptr, state.lambda, a);
  v += (0.5 * dt_) * a;  // Vⁿ⁺½ (entry 0 of a massless node: 0, its velocity is set by BarSimulation)
  u += dt_ * v;          // Ũ
  // The contact.
  const Contact c = contact(u[0], u[1], v[0], has_load ? state.f_next[0] : 0.0);
  if (c.correct) {
    v -= (dt_ * c.lambda) * impulse_response_;
    u -= (dt_ * dt_ * c.lambda) * impulse_response_;
  }
  if (c.set_u0) u[0] = c.u0;
  state.active = c.active;
  // (E1): the second half kick with Fⁿ⁺¹.
  accelerate(u, has_load ? &state.f_next : nullptr, c.lambda, a);
  v += (0.5 * dt_) * a;
  state.lambda = c.lambda;
  if (has_load) state.f_now.swap(state.f_next);
}

// Taylor–Flanagan: μ = ṽ₀/(Δt r₀) where the drift penetrates, λ = μ; explicit: the algebraic row in
// closed form (condense_contact_node), u₀ and λ.
ExplicitStep::Contact ExplicitStep::contact(double u0, double u1, double v0, double load0) const {
  Contact c;
  if (taylor_flanagan_) {
    if (u0 + gap_ < 0) {
      c.lambda = v0 / (dt_ * impulse_response_[0]);
      c.correct = true;
    }
    c.active = c.lambda != 0.0;
    return c;
  }
  const CondensedContact condensed = condense_contact_node(u1, compliance_, load0, -gap_);
  c.set_u0 = true;
  c.u0 = condensed.u0;
  c.lambda = condensed.multiplier;
  c.active = condensed.multiplier < 0 || condensed.u0 == -gap_;
  return c;
}

void ExplicitStep::advance(StepState& state, Index, bool has_load) {
  step(state, has_load);
  state.energy = 0.5 * mass_.form(state.w) + 0.5 * stiffness_form(state.u, state.u, mesh_);
}

// The registry entries (time/scheme_registry.hpp). ExplicitStep's constructor makes their checks, so that
// a step built by hand (the doctests) makes them too.
const std::vector<SchemeInfo>& central_difference_schemes() {
  const auto validate = [](const StepContext&) {};
  const auto make = [](const StepContext& c) -> std::unique_ptr<Step> {
    return std::make_unique<ExplicitStep>(c.mesh, c.assembled, c.stiffness, c.parameters, c.dt, c.gap);
  };
  static const std::vector<SchemeInfo> entries = {
      {Scheme::taylor_flanagan,
       "taylor-flanagan",
       "central differences, lumped mass, contact by Taylor–Flanagan's velocity correction (GetFEM's version 4)",
       {SchemeParameter::mass_lumping},
       validate,
       make,
       7,
       "Taylor–Flanagan",
       "Taylor--Flanagan (central differences)",
       "TF"},
      {Scheme::explicit_central,
       "explicit",
       "central differences, lumped mass, massless contact node on its algebraic row (no impact law)",
       {},
       validate,
       make,
       7,
       "explicit, massless contact node",
       "central differences with a massless contact node",
       "CD"},
  };
  return entries;
}

ExplicitStep::Lanes ExplicitStep::lanes() const {
  return {&stiffness_, &inverse_mass_, &pivot_, &factor_, &impulse_response_, dt_, lumped_};
}

}  // namespace mrm
