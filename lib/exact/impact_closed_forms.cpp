/// @file impact_closed_forms.cpp
/// @brief The chain solver against closed forms: the impacting bar (doc/benchmarks.md §4), the
/// bouncing bar (§3), gravity on the paper's bar (§5), a static load on a layered bar, two bars in
/// contact (§6) and layered bars (§7).
///
/// Each closed form is derived in the comment of its doctest: a load by its static state or its
/// free fall, a free far end by the even reflection of the release wave, a gap by the free flight up to
/// the impact, layered bars by the reflection R = (Z_B − Z_A)/(Z_A + Z_B) at an interface, two bars by
/// the contact stress μβ with μ = Z_A Z_B/(Z_A + Z_B) (impact_chain.cpp, derivation §3).
#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

#include <doctest/doctest.h>

#include "core/problem.hpp"
#include "core/constants.hpp"
#include "exact/exact_solution.hpp"
#include "exact/impact_chain.hpp"

namespace mrm {

namespace {}  // namespace

TEST_CASE("the impacting bar (SDNV100): contact from gap/v for 2L/c at stress -rho c v, then rigid rebound") {
  // A free bar with uniform velocity −v toward the wall across a gap g₀: free flight z = g₀ − v t until
  // t₁ = g₀/v; the impact sends a compression wave σ = −Z v up the bar (u_t = 0 behind it); it reflects
  // at the free end as a release wave and brings σ = 0, u_t = +v back to the wall at t₁ + 2L/c, where
  // β = 2v > 0: the bar leaves rigidly with +v, z = v (t − t₁ − 2L/c).
  const double nu = 0.3, modulus = 2e11 * (1 - nu) / ((1 + nu) * (1 - 2 * nu)), rho = 8000, length = 0.2, speed = 100,
               gap = 2e-3;
  ImpactConfiguration config;
  config.segments = {uniform_segment(length, modulus, rho)};
  config.far_end = FarEnd::free;
  config.obstacle_gap = gap;
  InitialData data;
  data.pieces = {{0.0, length, {0.0}, {-speed}}};
  const double c = std::sqrt(modulus / rho), t1 = gap / speed, t2 = t1 + 2 * length / c;
  const ImpactSolution solution(config, data, 3 * t2);
  const auto& w = solution.contact_windows(0);
  REQUIRE(w.size() == 1);
  CHECK(std::abs(w[0].start - t1) <= 1e-12 * t2);
  CHECK(std::abs(w[0].end - t2) <= 1e-12 * t2);
  for (int n = 0; n <= 300; ++n) {
    const double t = 3 * t2 * (n + 0.5) / 301.0;
    CAPTURE(t);
    const double z = t < t1 ? gap - speed * t : t < t2 ? 0.0 : speed * (t - t2);
    const double lambda = t > t1 && t < t2 ? -rho * c * speed : 0.0;
    CHECK(std::abs(solution.gap(0, t) - z) <= 1e-12 * gap);
    CHECK(std::abs(solution.contact_stress(0, t) - lambda) <= 1e-12 * rho * c * speed);
    if (t > t2)
      for (int i = 0; i <= 10; ++i)
        CHECK(std::abs(solution.velocity(length * (i + 0.5) / 11, t) - speed) <= 1e-12 * speed);
  }
}

TEST_CASE("the bouncing bar (Doyen-Ern-Piperno): free-fall parabola, contacts of 2L/c every 8L/c") {
  // L = 10, E = 900, ρ = 1 (c = 30, τ = L/c = 1/3), g = 10, h₀ = 5: the bar falls rigidly,
  // z = h₀ − g t²/2, hits at t₁ = √(2h₀/g) = 1 = 3τ with speed g t₁. In the falling frame (α = −g, q = 0)
  // the floor rises as ℓ = −h₀ + g t²/2; held, the end emits s = ℓ, which comes back from the free top
  // after 2τ: β(t) = 2ℓ′(t − 2τ) − ℓ′(t) = g (t − 4τ) for t ≥ t₁ + 2τ, and −ℓ′ = −g t < 0 before. So the
  // contact lasts exactly 2τ = 2/3 (β = g τ > 0 at t₁ + 2τ because t₁ = 3τ) with λ = Z β = −Z g t, Z = 30.
  // After it the motion repeats: contacts every 8τ = 8/3, the state periodic with period 16τ = 16/3
  // (DEP: the motion is periodic; here the period of the state is two contact cycles, measured).
  ImpactConfiguration config;
  config.segments = {uniform_segment(10.0, 900.0, 1.0, -10.0)};
  config.far_end = FarEnd::free;
  config.obstacle_gap = 5.0;
  InitialData data;
  data.pieces = {{0.0, 10.0, {0.0}, {0.0}}};
  const double tau = 1.0 / 3.0;
  const ImpactSolution solution(config, data, 24.0);
  for (int n = 0; n <= 100; ++n) {
    const double t = n / 100.0;
    CHECK(std::abs(solution.gap(0, t) - (5.0 - 5.0 * t * t)) <= 1e-12 * 5.0);
  }
  const auto& w = solution.contact_windows(0);
  REQUIRE(w.size() == 9);
  for (std::size_t k = 0; k < w.size(); ++k) {
    CAPTURE(k);
    const double start = 3 * tau + 8 * tau * static_cast<double>(k), end = std::min(24.0, start + 2 * tau);
    CHECK(std::abs(w[k].start - start) <= 1e-12 * 24.0);
    CHECK(std::abs(w[k].end - end) <= 1e-12 * 24.0);
    for (int n = 1; n < 10 && k == 0; ++n) {
      const double t = start + (end - start) * n / 10.0;
      CHECK(std::abs(solution.contact_stress(0, t) + 30.0 * 10.0 * t) <= 1e-12 * 300.0);
    }
  }
  double du = 0, dv = 0;
  for (int n = 0; n <= 100; ++n)
    for (int i = 0; i <= 20; ++i) {
      const double t = 8.0 * n / 100.0, x = 10.0 * i / 20.0;
      du = std::max(du, std::abs(solution.displacement(x, t + 16 * tau) - solution.displacement(x, t)));
      dv = std::max(dv, std::abs(solution.velocity(x, t + 16 * tau) - solution.velocity(x, t)));
    }
  CAPTURE(du);
  CAPTURE(dv);
  CHECK(du <= 1e-12 * 5.0);
  CHECK(dv <= 1e-12 * 300.0);
}

TEST_CASE("gravity on the paper's bar: a sudden load gives a persistent contact around the static state") {
  // The paper's bar (clamped at L, obstacle at 0) at rest, undeformed and touching, loaded at t = 0 by
  // f = −b toward the obstacle. The static state −E u_s″ = f, u_s(0) = u_s(L) = 0 is
  // u_s = (b/2E)(x² − Lx), with λ_s = E u_s′(0) = −bL/2. If the end stays held, u − u_s is the free
  // vibration of the clamped–clamped bar from −u_s at rest: u = u_s − ½(ũ(x − ct) + ũ(x + ct)), ũ the odd
  // 2L-periodic extension of u_s, and λ(t) = λ_s − E ũ′(ct) = −b · dist(ct, 2LZ) ≤ 0 (ũ′ is even): held
  // throughout, grazing (λ = 0) at ct ∈ 2LZ; the time mean of λ over a period 2L/c is the static λ_s.
  // And the paper's data u⁰ = (1 − x)/2 under the same load: the end moves as u(0, t) = (1 − t)/2 − b t²/2
  // until the first reflection (t < L), so the first impact is at t* = (√(1 + 4b) − 1)/(2b).
  for (const auto& [length, modulus, b] : {std::tuple<double, double, double>{1.0, 1.0, 1.0}, {2.0, 4.0, 0.3}}) {
    CAPTURE(length);
    ImpactConfiguration config;
    config.segments = {uniform_segment(length, modulus, 1.0, -b)};
    InitialData data;
    data.pieces = {{0.0, length, {0.0}, {0.0}}};
    const double c = std::sqrt(modulus), period = 2 * length / c, horizon = 5 * period;
    const ImpactSolution solution(config, data, horizon);
    const auto static_u = [&](double x) { return b / (2 * modulus) * (x * x - length * x); };
    const auto extended = [&](double xi) {
      xi = std::fmod(xi, 2 * length);
      if (xi < 0) xi += 2 * length;
      return xi <= length ? static_u(xi) : -static_u(2 * length - xi);
    };
    REQUIRE(solution.contact_windows(0).size() == 1);
    CHECK(solution.contact_windows(0)[0].start == 0.0);
    CHECK(solution.contact_windows(0)[0].open);
    double du = 0, dl = 0, mean = 0;
    const int samples = 4000;
    for (int n = 0; n < samples; ++n) {
      const double t = horizon * (n + 0.5) / samples;
      for (int i = 0; i <= 20; ++i) {
        const double x = length * i / 20.0;
        du = std::max(du, std::abs(solution.displacement(x, t) -
                                   (static_u(x) - 0.5 * (extended(x - c * t) + extended(x + c * t)))));
      }
      const double ct = std::fmod(c * t, 2 * length);
      dl = std::max(dl, std::abs(solution.contact_stress(0, t) + b * std::min(ct, 2 * length - ct)));
      mean += solution.contact_stress(0, t) / samples;  // the midpoint rule is exact for the piecewise-linear λ
      CHECK(std::abs(solution.gap(0, t)) <= 1e-14 * b * length * length);
    }
    CAPTURE(du);
    CAPTURE(dl);
    CHECK(du <= 1e-12 * b * length * length / modulus);
    CHECK(dl <= 1e-12 * b * length);
    CHECK(std::abs(mean + b * length / 2) <= 1e-12 * b * length);
  }
  for (const double b : {0.25, 1.0, 4.0}) {
    ImpactConfiguration config;
    config.segments = {uniform_segment(1.0, 1.0, 1.0, -b)};
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.25, -0.25}, {0.0}}};
    const ImpactSolution solution(config, data, 3.0);
    CAPTURE(b);
    CHECK(std::abs(solution.contact_windows(0).at(0).start - (std::sqrt(1 + 4 * b) - 1) / (2 * b)) <= 1e-12);
  }
}

TEST_CASE("a static load: a piecewise-polynomial f(x) on a layered bar in static equilibrium stays put") {
  // Two welded segments (E = 2 on [0, 1], E = 5 on [1, 1.5]), f(x) = −(1 + x) on the first and −3x² on
  // the second, clamped at 1.5, held at 0: the static state −(E u′)′ = f with u(0) = u(1.5) = 0 and
  // E u′ continuous at x = 1; started from it at rest, the solution is u(x, t) = u_s(x), λ = E u_s′(0) < 0.
  // u_s: E u′ = λ_s + ∫₀ˣ(1 + s) ds on [0, 1] = λ_s + x + x²/2, then λ_s + 3/2 + (x³ − 1) on [1, 1.5].
  const auto stress = [](double x, double ls) { return x <= 1 ? ls + x + x * x / 2 : ls + 1.5 + (x * x * x - 1); };
  const auto integral = [&](double x, double ls) {  // u_s(x) = ∫₀ˣ (E u′)/E
    if (x <= 1) return (ls * x + x * x / 2 + x * x * x / 6) / 2;
    const double first = (ls + 0.5 + 1.0 / 6) / 2, d = x - 1;
    return first + ((ls + 0.5) * d + (std::pow(x, 4) - 1) / 4) / 5;
  };
  const double ls = -(integral(1.5, 0.0)) / ((1.0 / 2) + (0.5 / 5));  // u_s(1.5) = 0 fixes λ_s (linear in it)
  REQUIRE(ls < 0);
  ImpactConfiguration config;
  config.segments = {uniform_segment(1.0, 2.0, 1.0), uniform_segment(0.5, 5.0, 3.0)};
  // f in σ: on [0, 1] x = (1 + σ)/2, on [1, 1.5] x = 1.25 + σ/4.
  config.segments[0].load = {-1.5, -0.5};
  config.segments[1].load = {-4.6875, -1.875, -0.1875};  // −3(1.25 + σ/4)²
  // u_s on each segment as a polynomial in σ: interpolate at enough points (degree ≤ 3 and 5).
  InitialData data;
  for (const auto& [a, b, degree] : {std::tuple<double, double, int>{0.0, 1.0, 3}, {1.0, 1.5, 5}}) {
    // The monomial coefficients in σ from values at Chebyshev-like points, by solving a small system.
    const int n = degree + 1;
    std::vector<double> matrix(static_cast<std::size_t>(n * n)), rhs(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) {
      const double s = std::cos(pi * (i + 0.5) / n), x = 0.5 * (a + b) + 0.5 * (b - a) * s;
      for (int k = 0; k < n; ++k) matrix[static_cast<std::size_t>(i * n + k)] = std::pow(s, k);
      rhs[static_cast<std::size_t>(i)] = integral(x, ls);
    }
    for (int col = 0; col < n; ++col)  // Gauss elimination with partial pivoting
      for (int row = col + 1; row < n; ++row) {
        int pivot = col;
        for (int r = col + 1; r < n; ++r)
          if (std::abs(matrix[static_cast<std::size_t>(r * n + col)]) >
              std::abs(matrix[static_cast<std::size_t>(pivot * n + col)]))
            pivot = r;
        if (pivot != col) {
          for (int k = 0; k < n; ++k)
            std::swap(matrix[static_cast<std::size_t>(col * n + k)], matrix[static_cast<std::size_t>(pivot * n + k)]);
          std::swap(rhs[static_cast<std::size_t>(col)], rhs[static_cast<std::size_t>(pivot)]);
        }
        const double factor =
            matrix[static_cast<std::size_t>(row * n + col)] / matrix[static_cast<std::size_t>(col * n + col)];
        for (int k = col; k < n; ++k)
          matrix[static_cast<std::size_t>(row * n + k)] -= factor * matrix[static_cast<std::size_t>(col * n + k)];
        rhs[static_cast<std::size_t>(row)] -= factor * rhs[static_cast<std::size_t>(col)];
      }
    poly::Coefficients coefficients(static_cast<std::size_t>(n));
    for (int row = n; row-- > 0;) {
      double sum = rhs[static_cast<std::size_t>(row)];
      for (int k = row + 1; k < n; ++k)
        sum -= matrix[static_cast<std::size_t>(row * n + k)] * coefficients[static_cast<std::size_t>(k)];
      coefficients[static_cast<std::size_t>(row)] = sum / matrix[static_cast<std::size_t>(row * n + row)];
    }
    data.pieces.push_back({a, b, coefficients, {0.0}});
  }
  data.pieces[0].displacement[0] -= poly::evaluate(data.pieces[0].displacement, -1.0);  // u_s(0) = 0 exactly
  data.pieces[1].displacement[0] -= poly::evaluate(data.pieces[1].displacement, 1.0);   // u_s(1.5) = 0 exactly
  data.pieces[1].displacement[0] += poly::evaluate(data.pieces[0].displacement, 1.0) -
                                    poly::evaluate(data.pieces[1].displacement, -1.0);  // continuity (to round-off)
  const ImpactSolution solution(config, data, 6.0);
  REQUIRE(solution.contact_windows(0).size() == 1);
  CHECK(solution.contact_windows(0)[0].start == 0.0);
  CHECK(solution.contact_windows(0)[0].open);
  double du = 0, ds = 0;
  for (int n = 0; n <= 300; ++n)
    for (int i = 0; i <= 30; ++i) {
      const double t = 6.0 * n / 300.0, x = 1.5 * (i + 0.5) / 31.0;
      du = std::max(du, std::abs(solution.displacement(x, t) - integral(x, ls)));
      ds = std::max(ds, std::abs(solution.stress(x, t) - stress(x, ls)));
    }
  CAPTURE(du);
  CAPTURE(ds);
  CHECK(du <= 1e-12);
  CHECK(ds <= 1e-12);
  CHECK(std::abs(solution.contact_stress(0, 3.0) - ls) <= 1e-12);
}

TEST_CASE("two bars: equal bars meet as one bar on a wall, and unequal impedances separate after 2 transits") {
  // Two free bars touching at t = 0 with velocities v_A > v_B. Free flight would close the gap at
  // β = v_B − v_A < 0, so they stay in contact with σ = μ β, μ = Z_A Z_B/(Z_A + Z_B) (impact_chain.cpp,
  // derivation §3).
  // With equal transit times τ the free ends send back p′ = r′, q′ = s′ at t = 2τ, so that
  // β = 2(s′ − r′) = 2(p′ − q′)_{before} = −β_before > 0: release at 2τ for any impedances.
  // Equal bars (Z_A = Z_B) are symmetric about the contact plane: bar B is one bar on a rigid wall.
  {
    ImpactConfiguration config;
    config.segments = {uniform_segment(10.0, 1.0, 1.0), uniform_segment(10.0, 1.0, 1.0)};
    config.junctions = {{true, 0.0}};
    config.obstacle = false;
    config.far_end = FarEnd::free;
    InitialData data;
    data.pieces = {{0.0, 10.0, {0.0}, {0.1}}, {10.0, 20.0, {0.0}, {-0.1}}};
    const ImpactSolution solution(config, data, 60.0);
    ImpactConfiguration wall;
    wall.segments = {uniform_segment(10.0, 1.0, 1.0)};
    wall.far_end = FarEnd::free;
    InitialData one;
    one.pieces = {{0.0, 10.0, {0.0}, {-0.1}}};
    const ImpactSolution single(wall, one, 60.0);
    REQUIRE(solution.contact_windows(0).size() == 1);
    CHECK(solution.contact_windows(0)[0].start == 0.0);
    CHECK(std::abs(solution.contact_windows(0)[0].end - 20.0) <= 1e-12 * 20);
    double du = 0;
    for (int n = 0; n <= 600; ++n) {
      const double t = 60.0 * (n + 0.5) / 601.0;
      CHECK(std::abs(solution.contact_stress(0, t) - (t < 20 ? -0.1 : 0.0)) <= 1e-12 * 0.1);
      CHECK(std::abs(solution.contact_stress(0, t) - single.contact_stress(0, t)) <= 1e-12 * 0.1);
      for (int i = 1; i <= 10; ++i)
        du = std::max(du, std::abs(solution.displacement(10.0 + i, t) - single.displacement(i, t)));
      du = std::max(du, std::abs(solution.gap(0, t) - 2 * single.gap(0, t)));
      if (t > 20) {
        CHECK(std::abs(solution.velocity(5.0, t) + 0.1) <= 1e-12 * 0.1);
        CHECK(std::abs(solution.velocity(15.0, t) - 0.1) <= 1e-12 * 0.1);
        CHECK(std::abs(solution.gap(0, t) - 0.2 * (t - 20)) <= 1e-12 * 6);
      }
    }
    CHECK(du <= 1e-12 * 6);
  }
  {
    // Z_A = 1 (E = ρ = 1, ℓ = 1), Z_B = 3 (E = 9, ρ = 1, ℓ = 3): τ = 1 for both, v_A = 0.2, v_B = −0.1.
    ImpactConfiguration config;
    config.segments = {uniform_segment(1.0, 1.0, 1.0), uniform_segment(3.0, 9.0, 1.0)};
    config.junctions = {{true, 0.0}};
    config.obstacle = false;
    config.far_end = FarEnd::free;
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.0}, {0.2}}, {1.0, 4.0, {0.0}, {-0.1}}};
    const ImpactSolution solution(config, data, 6.0);
    REQUIRE(solution.contact_windows(0).size() >= 1);
    CHECK(std::abs(solution.contact_windows(0)[0].end - 2.0) <= 1e-12);
    for (int n = 1; n < 20; ++n)
      CHECK(std::abs(solution.contact_stress(0, 0.1 * n) - 0.75 * (-0.1 - 0.2)) <= 1e-12 * 0.3);
  }
}

TEST_CASE("layered bars: reflection at an interface, and equal impedances are transparent") {
  // A bar of two welded layers hits the wall with speed v: Z₁ = 2 (E = 4, ρ = 1, c = 2, ℓ = 1, τ₁ = ½),
  // Z₂ = 1 (E = ρ = 1, ℓ = 1.5, τ₂ = 1.5), free far end, gap 0.1. The impact (t₁ = 0.1) leaves σ₀ = −Z₁v
  // at the wall; the interface reflects the stress R = (Z₂ − Z₁)/(Z₁ + Z₂) of it, which doubles at the
  // rigid wall (u_t = 0 there): σ = σ₀(1 + 2R) = σ₀(3Z₂ − Z₁)/(Z₁ + Z₂) = σ₀/3 from t₁ + 2τ₁. Each round
  // trip 2τ₁ in the first layer multiplies the deviation from layer 2's stress −Z₂v by R, so on
  // [t₁ + 2kτ₁, t₁ + 2(k + 1)τ₁) the contact stress is the closed form
  //   λ_k = −Z₂v − (Z₁ − Z₂)v R^k   (here −1 − (−⅓)^k: −2, −⅔, −10/9, −26/27),
  // until the first wave that reached the free end comes back, at t₁ + 2τ₁ + 2τ₂ = 4.1. It left the
  // interface as the compression −Z₁v·2Z₂/(Z₁ + Z₂) = −4/3 at t₁ + τ₁, returns from the free end as the
  // tension 4/3, is transmitted into the first layer with 2Z₁/(Z₁ + Z₂) (16/9) and doubles at the wall
  // (32/9): λ₃ + 32/9 > 0, so the bar leaves the wall at exactly t₁ + 2τ₁ + 2τ₂, and with the wall gone the
  // far end's tension keeps it off until T = 10.
  {
    ImpactConfiguration config;
    config.segments = {uniform_segment(1.0, 4.0, 1.0), uniform_segment(1.5, 1.0, 1.0)};
    config.far_end = FarEnd::free;
    config.obstacle_gap = 0.1;
    InitialData data;
    data.pieces = {{0.0, 1.0, {0.0}, {-1.0}}, {1.0, 2.5, {0.0}, {-1.0}}};
    const ImpactSolution solution(config, data, 10.0);
    CHECK(std::abs(solution.contact_windows(0).at(0).start - 0.1) <= 1e-12);
    for (int n = 1; n < 400; ++n) {  // λ_k on [0.1 + k, 1.1 + k), k = 0..3, off its breakpoints
      const double t = 0.1 + 4.0 * n / 400.0;
      const double k = std::floor(t - 0.1);
      if (std::abs(t - 0.1 - k) < 1e-9) continue;
      CHECK(std::abs(solution.contact_stress(0, t) - (-1.0 - std::pow(-1.0 / 3, k))) <= 1e-12 * 2);
    }
    REQUIRE(solution.contact_windows(0).size() == 1);
    CHECK(std::abs(solution.contact_windows(0).at(0).end - 4.1) <= 1e-12);
  }
  {
    // Equal impedances Z = 1 with c = 4 (E = 4, ρ = ¼, ℓ = 2, τ = ½) and c = 1 (ℓ = 1.5, τ = 1.5):
    // no reflection at the interface; the contact point sees a homogeneous bar of transit time 2.
    ImpactConfiguration config;
    config.segments = {uniform_segment(2.0, 4.0, 0.25), uniform_segment(1.5, 1.0, 1.0)};
    config.far_end = FarEnd::clamped;
    InitialData data;
    // u⁰ = ½(2 − θ), θ the travel time from x = 0: 1 − x/8 on [0, 2], ½(3.5 − x) on [2, 3.5].
    data.pieces = {{0.0, 2.0, {0.875, -0.125}, {0.0}}, {2.0, 3.5, {0.375, -0.375}, {0.0}}};
    const ImpactSolution solution(config, data, 12.0);
    const ExactSolution exact(2.0, 0.5);  // u⁰ = ½(2 − θ) in the travel time θ, period 6
    double d = 0;
    for (int n = 0; n <= 1200; ++n) {
      const double t = 12.0 * (n + 0.5) / 1201.0;
      d = std::max(d, std::abs(solution.gap(0, t) - exact.contact_displacement(t)));
      d = std::max(d, std::abs(solution.contact_stress(0, t) - exact.contact_multiplier(t)));
    }
    CAPTURE(d);
    CHECK(d <= 1e-12);
    const auto& w = solution.contact_windows(0);
    REQUIRE(w.size() == 2);
    CHECK(std::abs(w[0].start - 2.0) <= 1e-12);
    CHECK(std::abs(w[0].end - 4.0) <= 1e-12);
    CHECK(std::abs(w[1].start - 8.0) <= 1e-12);
    CHECK(std::abs(w[1].end - 10.0) <= 1e-12);
  }
}

}  // namespace mrm
