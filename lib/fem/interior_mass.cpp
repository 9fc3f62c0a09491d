/// @file interior_mass.cpp
/// @brief The blended interior mass and its phase-matched choice: derivation and checks.
///
/// 1. The dispersion symbols. On the uniform mesh x_j = jh of a homogeneous bar (unit wave speed) a
/// mode U_j = e^{i(kjh − ωt)} sees the P1 stiffness and the blended mass M^A = (1 − A) M + A M_L
/// (p1.cpp: per element h/6 [2 + A, 1 − A; 1 − A, 2 + A]) through their symbols, with ξ = kh,
///
///     s(ξ) = (2/h)(1 − cos ξ),       m_A(ξ) = h [(2 + A)/3 + (1 − A)/3 cos ξ] = h [1 − (1 − A)(1 − cos ξ)/3],
///
/// so the semi-discrete frequency is ω_h² = s/m_A = 6(1 − cos ξ) / (h² [3 − (1 − A)(1 − cos ξ)]).
/// With 1 − cos ξ = ξ²/2 − ξ⁴/24 + …, (ω_h/k)² = 1 + ξ²(1 − A)/6 − ξ²/12 + O(ξ⁴), so
///
///     ω_h/k = 1 + (1 − 2A) ξ²/24 + O(ξ⁴):
///
/// the consistent mass (A = 0) is too fast by ξ²/24, the lumped one (A = 1) too slow by as much.
///
/// 2. Crank–Nicolson. The trapezoidal rule on Ü = −ω_h² U (Newmark β = ¼, γ = ½, the step of
/// schemes.cpp away from the contact) has the amplification of tan(ω̃Δt/2) = ω_hΔt/2, hence
///
///     ω̃ = (2/Δt) atan(ω_hΔt/2) = ω_h (1 − (ω_hΔt)²/12 + O((ω_hΔt)⁴)),
///
/// too slow by (kΔt)²/12 = c²ξ²/12 (c = Δt/h). The phase-speed error ω̃/k − 1 is therefore
///
///     e(ξ) = [(1 − 2A)/24 − c²/12] ξ² + e₄ ξ⁴ + O(ξ⁶),
///
/// and the ξ² term vanishes when 1 − 2A = 2c²: **A = ½ − c²** (¼ at c = ½; 0 at c = 1/√2, where the
/// consistent mass is already matched; no blend in [0, 1] for c > 1/√2). A series expansion (done with
/// a computer algebra system, and checked below by the measured slope) gives e₄ = (20A² + 40Ac² − 20A +
/// 24c⁴ − 20c² + 1)/1920, which at the matched A is −(1 − c⁴)/480: −1/512 at c = ½, −1/640 at c = 1/√2.
/// EC and CN-switch are Crank–Nicolson on every step without a change of the contact status
/// (energy_step.cpp), so they have the same dispersion in the bar.
///
/// This is the known construction of blended spectral/finite element schemes for the wave equation
/// (Ainsworth and Wajid: a blend of the Gauss–Lobatto (lumped) and exact (consistent) mass matrices
/// raises the dispersion order by two, and a blend with the time step's error cancels the leading
/// term of the fully discrete one); what is new here is its use with the redistributed mass and impact
/// (mass_redistribution.cpp, "the family on the blended interior mass", and the period law below).
///
/// 3. Stability and energy. For 0 ≤ A ≤ 1 every element matrix of M^A is positive definite (p1.cpp), so
/// M^A and every redistribution of it are, and nothing in the energy identities of Crank–Nicolson,
/// EC and the θ-steps (energy_step.cpp) uses more than a symmetric positive definite mass: CN keeps
/// E = ½VᵀM̄V + ½UᵀSU while the contact status does not change, EC at every step, and the fast kernel
/// (fast_step.cpp) reads M as an arbitrary symmetric tridiagonal matrix. Checked below.
///
/// 4. The period law on the blend. The law reads the drift off the row sums (lumped masses) of
/// M̄ − M̄_Mod3 (period_law.cpp; ΔP = 2 δm_loc + (3/2) δm_glob on the uniform mesh). The blend keeps the
/// row sums of every element it touches, and the free end of the free-flight bar [h, L] carries its
/// natural blended end mass (1 + A/2)h/3 (a consistent-order P1 end, no O(h) shift). So the member with
/// zero drift is the one whose node 1 carries the whole removed element beyond that end mass: Mod 3
/// defined on M^A as the Galerkin mass PᵀM^AP of u₀ := u₁, M̄₁₁ = (4/3 + A/6)h (mass_redistribution.cpp),
/// with the same row sums as the paper's Mod 3. The other members, on M^A:
///
/// | member         | the lost mass m_lost(A) = (2/3 − A/6)h                | ΔP                            |
/// |----------------|-------------------------------------------------------|-------------------------------|
/// | Mod 1          | dropped                                               | −2 m_lost(A) = −(4/3 − A/3)h  |
/// | Mod 2          | spread uniformly (δm_loc = −m_lost, δm_glob = m_lost) | −m_lost(A)/2 = −(1/3 − A/12)h |
/// | w₁₁ = 2 on M^A | M̄₁₁ = (4/3 + 2A/3)h: Ah/2 beyond Mod 3                | +A h                          |
///
/// The last one, the literal weight, is why the family must be defined by what it does with the lost
/// mass, not by its weights.
#include "fem/interior_mass.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>
#include <vector>

#include <doctest/doctest.h>

#include "core/constants.hpp"
#include "fem/mass_redistribution.hpp"
#include "fem/period_law.hpp"

namespace mrm {

namespace {

void check_blend(double blend, const char* where) {
  if (!(blend >= 0.0 && blend <= 1.0))
    throw std::invalid_argument(std::string(where) + ": the blend A must be in [0, 1] (allowed: 0 <= A <= 1)");
}
}  // namespace

double phase_speed_error(double xi, double courant, double blend) {
  if (!(xi > 0.0 && xi <= pi)) throw std::invalid_argument("phase_speed_error: xi = kh must be in (0, pi]");
  if (!(std::isfinite(courant) && courant >= 0.0))
    throw std::invalid_argument("phase_speed_error: the Courant number must be finite and >= 0");
  check_blend(blend, "phase_speed_error");
  // 1 − cos ξ = 2 sin²(ξ/2), without the cancellation of 1 − cos ξ at small ξ.
  const double one_minus_cos = 2.0 * std::sin(0.5 * xi) * std::sin(0.5 * xi);
  const double omega_h = std::sqrt(6.0 * one_minus_cos / (3.0 - (1.0 - blend) * one_minus_cos));  // ω_h h
  // ω̃h = (2/c) atan(c ω_h h/2) (ω_h h itself as c → 0); e = ω̃/k − 1 = ω̃h/ξ − 1.
  const double omega = courant == 0.0 ? omega_h : 2.0 / courant * std::atan(0.5 * courant * omega_h);
  return omega / xi - 1.0;
}

double phase_speed_error_leading(double xi, double courant, double blend) {
  return ((1.0 - 2.0 * blend) / 24.0 - courant * courant / 12.0) * xi * xi;
}

double largest_phase_matched_courant() { return 1.0 / std::sqrt(2.0); }

double phase_matched_blend(double courant) {
  if (!(std::isfinite(courant) && courant > 0.0))
    throw std::invalid_argument(
        "phase-matched blend: dt/h must be positive and finite (allowed: 0 < dt/h <= 1/sqrt(2))");
  double a = 0.5 - courant * courant;
  if (a < 0.0 && a >= -1e-12) a = 0.0;
  if (a < 0.0)
    throw std::invalid_argument("phase-matched blend: dt/h = " + std::to_string(courant) +
                                " > 1/sqrt(2) would need A = 1/2 - (dt/h)^2 < 0 (allowed: 0 < dt/h <= 1/sqrt(2))");
  return a;
}

double interior_blend_from_value(double value) {
  check_blend(value, "--interior-mass blend:A");
  return value;
}

std::string interior_mass_name(double blend) {
  check_blend(blend, "interior_mass_name");
  if (blend == 0.0) return "consistent";
  if (blend == 1.0) return "lumped";
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, blend);
  if (error != std::errc()) throw std::logic_error("interior_mass_name: buffer too small");
  return "blend:" + std::string(buffer, end);
}

// ---------------------------------------------------------------------------------------------------

namespace {

// The slope of log|e| against log ξ between ξ and ξ/2.
[[maybe_unused]] double measured_order(double xi, double courant, double blend) {
  return std::log2(std::abs(phase_speed_error(xi, courant, blend) / phase_speed_error(0.5 * xi, courant, blend)));
}

}  // namespace

TEST_CASE("the phase error of CN with the blended mass is O(xi^4) at A = 1/2 - c^2 and O(xi^2) elsewhere") {
  // Prediction (§2): slope 2 with the coefficient (1 − 2A)/24 − c²/12 unless it vanishes, then slope 4
  // with −(1 − c⁴)/480. Between ξ = 0.05 and 0.025 the next term changes the slope by O(ξ²) ≈ 3e-3
  // times the ratio of the coefficients (below 0.02 here): the tolerance 0.02 on the slope.
  struct Case {
    double courant, blend;
    int order;
  };
  const double root_half = largest_phase_matched_courant();
  for (const Case& c : {Case{0.5, 0.0, 2}, Case{0.5, 0.25, 4}, Case{root_half, 0.0, 4}, Case{0.5, 1.0, 2},
                        Case{0.25, 0.0, 2}, Case{0.25, 0.4375, 4}, Case{0.0, 0.5, 4}, Case{0.0, 0.0, 2}}) {
    CAPTURE(c.courant);
    CAPTURE(c.blend);
    const double slope = measured_order(0.05, c.courant, c.blend);
    CAPTURE(slope);
    CHECK(std::abs(slope - c.order) < 0.02);
    const double xi = 0.01, e = phase_speed_error(xi, c.courant, c.blend);
    if (c.order == 2) {
      CHECK(std::abs(e / phase_speed_error_leading(xi, c.courant, c.blend) - 1.0) < 1e-3);
    } else {
      CHECK(std::abs(phase_speed_error_leading(xi, c.courant, c.blend)) < 1e-16);
      const double e4 = -(1.0 - std::pow(c.courant, 4)) / 480.0;
      CHECK(std::abs(e / (e4 * std::pow(xi, 4)) - 1.0) < 1e-3);
    }
  }
  // At c = ½ the matched error is smaller than the consistent mass's by (1/512) ξ⁴ against (1/96) ξ² ...
  CHECK(std::abs(phase_speed_error(0.3, 0.5, 0.25)) < 0.05 * std::abs(phase_speed_error(0.3, 0.5, 0.0)));
  // ... and the sign of the consistent mass's error at c = ½ is (1/24 − 1/48) > 0: too fast.
  CHECK(phase_speed_error(0.1, 0.5, 0.0) > 0.0);
  CHECK(phase_speed_error(0.1, 0.5, 1.0) < 0.0);
}

TEST_CASE("the phase-matched blend is 1/2 - c^2, and does not exist above c = 1/sqrt(2)") {
  CHECK(phase_matched_blend(0.5) == 0.25);
  CHECK(std::abs(phase_matched_blend(1.0 / std::sqrt(2.0))) < 1e-15);  // c² rounds to 0.4999999999999999
  CHECK(phase_matched_blend(0.70710678118655) == 0.0);                 // c² = 0.5 + 8e-15: within 1e-12, taken as 0
  CHECK(phase_matched_blend(0.1) == doctest::Approx(0.49));
  CHECK_THROWS_WITH_AS(phase_matched_blend(0.75), doctest::Contains("1/sqrt(2)"), std::invalid_argument);
  CHECK_THROWS_AS(phase_matched_blend(1.0), std::invalid_argument);
  CHECK_THROWS_AS(phase_matched_blend(0.0), std::invalid_argument);
  CHECK_THROWS_AS(phase_matched_blend(std::nan("")), std::invalid_argument);
  CHECK(interior_mass_name(0.0) == "consistent");
  CHECK(interior_mass_name(1.0) == "lumped");
  CHECK(interior_mass_name(0.25) == "blend:0.25");
  CHECK_THROWS_AS(interior_blend_from_value(1.5), std::invalid_argument);
  CHECK_THROWS_AS(interior_blend_from_value(-0.25), std::invalid_argument);
  CHECK_THROWS_AS(mod3(-0.1), std::invalid_argument);
}

TEST_CASE("the family on the blend: Mod 3 is P^T M^A P and every member keeps its mass balance") {
  for (const UniformMesh& mesh : {UniformMesh(1.0, 16), graded_mesh(1.0, 16, 1.1)}) {
    for (double a : {0.25, 0.5, 1.0}) {
      CAPTURE(a);
      const Tridiagonal ma = p1_blended_mass_all_nodes(mesh, a), m3 = modified_mass_all_nodes(mesh, mod3(a));
      CHECK(std::abs(m3.diag[1] - (ma.diag[0] + 2 * ma.upper[0] + ma.diag[1])) < 1e-15);
      CHECK(m3.diag[2] == doctest::Approx(ma.diag[2]).epsilon(1e-15));
      CHECK(m3.upper[1] == doctest::Approx(ma.upper[1]).epsilon(1e-15));
      const double m_bar = mesh.bar_mass(), lost = lost_mass(mesh, a);
      CHECK(lost == doctest::Approx((2.0 / 3 - a / 6) * mesh.h(0)).epsilon(1e-14));
      CHECK(total_mass(mesh, mod3(a)) == doctest::Approx(m_bar).epsilon(1e-14));
      CHECK(total_mass(mesh, mod2(a)) == doctest::Approx(m_bar).epsilon(1e-14));
      CHECK(total_mass(mesh, spread_over_first_nodes(3, a)) == doctest::Approx(m_bar).epsilon(1e-14));
      CHECK(total_mass(mesh, mod1(a)) == doctest::Approx(m_bar - lost).epsilon(1e-14));
      CHECK(total_mass(mesh, consistent_mass(a)) == doctest::Approx(m_bar).epsilon(1e-14));
      // node1:(4/3 − A/6) and beta:(2/3 − A/6) are Mod 3 on the blend; beta:0 is Mod 2.
      CHECK(modified_mass_all_nodes(mesh, node1(4.0 / 3 - a / 6, a)).diag[1] ==
            doctest::Approx(m3.diag[1]).epsilon(1e-14));
      CHECK(modified_mass_all_nodes(mesh, beta(2.0 / 3 - a / 6, a)).diag[1] ==
            doctest::Approx(m3.diag[1]).epsilon(1e-14));
      CHECK(modified_mass_all_nodes(mesh, beta(0.0, a)).diag[5] ==
            doctest::Approx(modified_mass_all_nodes(mesh, mod2(a)).diag[5]).epsilon(1e-14));
    }
  }
  // A = 0 is the paper's family, the same doubles.
  const UniformMesh mesh(1.0, 10);
  const Tridiagonal a = modified_mass(mesh, mod3(0.0)), b = modified_mass(mesh, mod3());
  CHECK((a.diag - b.diag).cwiseAbs().maxCoeff() == 0.0);
}

TEST_CASE("the period law on the blend: Galerkin Mod 3 does not drift, the literal weight drifts by A h") {
  // Predictions (§4), against the period of the eigenvalues of the reduced pencils (period_law.cpp):
  // ΔP = 0 (Mod 3 on M^A), −(4/3 − A/3)h (Mod 1), −(1/3 − A/12)h (Mod 2), +A h (w₁₁ = 2 on M^A), each
  // up to O(h²). Checked as: the residual below 3h² at N = 50, 100, 200, and falling by more than a
  // factor 3 (second order: 4) from N = 50 to 200 in two halvings when it is not already below 1e-3 h.
  for (double a : {0.25, 0.5, 1.0}) {
    MassRedistribution literal = mod3();  // the weight w₁₁ = 2 of the paper's mesh, applied to M^A
    literal.interior_blend = a;
    literal.name = "w11=2 on the blend";
    struct Member {
      MassRedistribution mass;
      double drift;  // ΔP/h
    };
    for (const Member& m : {Member{mod3(a), 0.0}, Member{mod1(a), -(4.0 / 3 - a / 3)},
                            Member{mod2(a), -(1.0 / 3 - a / 12)}, Member{literal, a}}) {
      CAPTURE(a);
      CAPTURE(m.mass.name);
      std::vector<double> residual;
      for (Index n : {50, 100, 200}) {
        const UniformMesh mesh(1.0, n);
        const double h = mesh.h(), error = predict_period(mesh, m.mass).period_error;
        residual.push_back(std::abs(error - m.drift * h));
        CAPTURE(n);
        CAPTURE(error / h);
        CHECK(residual.back() < 3 * h * h);
        // The first-order rule of period_law.hpp on the row sums says the same.
        CHECK(std::abs(first_order_period_change(mesh, m.mass) - m.drift * h) < 3 * h * h);
      }
      if (residual[0] > 1e-3 / 50) CHECK(residual[0] / residual[2] > 3 * 3);
    }
  }
}

}  // namespace mrm
