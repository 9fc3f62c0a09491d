/// @file configurations/scaling.cpp
/// @brief The scaling law: a configuration at any length and amplitude run on the unit bar and scaled back.
#include "configurations/scaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <thread>

#include <doctest/doctest.h>

#include "exact/exact_solution.hpp"
#include "exact/impact_solution.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "parallel.hpp"
#include "time/two_bodies.hpp"
#include "configurations.hpp"

namespace mrm::repro {

// ---------------------------------------------------------------------------------------------------
// The scaling law. The problem (mathematics.md §1) is u_tt = u_xx on (0, L) (unit wave speed),
// u(L, t) = 0, 0 ≤ u(0, t) ⊥ λ(t) = u_x(0, t) ≤ 0, with data u⁰, v⁰ (f = 0 for every data of the
// harness). Put x = Lξ, t = Lτ and u(x, t) = σL û(ξ, τ) for a number σ > 0. Then
//
//     u_t = σ û_τ,   u_x = σ û_ξ,   u_tt − u_xx = (σ/L)(û_ττ − û_ξξ),
//
// so u solves the problem on (0, L) iff û solves it on (0, 1) with the data û⁰(ξ) = u⁰(Lξ)/(σL),
// v̂⁰(ξ) = v⁰(Lξ)/σ: the contact condition keeps its form (u(0, t) ≥ 0 iff û(0, τ) ≥ 0, λ = σ λ̂), and
// the energy E = ½∫₀ᴸ (u_t² + u_x²) dx = σ²L Ê. The discretisation obeys the same law: on the mesh of
// N elements h = Lĥ, Δt = LΔτ, M = L M̂, S = Ŝ/L, so every term of M U'' + S U = −λe₀ (paper eq. (5))
// is σ times the unit one, for every scheme, mass and Δt/h; the discrete energy is σ²L Ê and the
// relative error measures, ratios of two norms of the same kind, do not change.
//
// The harness runs the unit problem (the library's: L = 1, data of order one) and scales back: times
// by L, displacements by σL, velocities and λ by σ, energies by σ²L. σ is a power of two, 2^e for the
// data's amplitude a = m 2^e with m ∈ [½, 1) (the paper's a; for other data, S1, S2 and --initial-data
// files, the largest of |u⁰|/L and |v⁰| at the breakpoints), not a itself: a product by a power of two
// is exact in floating point wherever nothing over- or underflows (a subnormal is rounded on a fixed
// grid), so it commutes with every rounding of the run, and a run with L a power of two gives the same
// doubles as the same run taken at its own scale. The paper's a = ½ is its own unit amplitude (σ = 1):
// with L = 1, every run of `make all` is not scaled at all, and its data files are unchanged, byte for
// byte, down to the energies of backward Euler after 1000 periods, which decay into the subnormals.
// With L not a power of two, h = L/N, Δt and the nodes are rounded differently than at the unit scale,
// and the results may change in the last bits. The doctests below check the law on whole runs.
namespace {

// σ = 2^e for a = m 2^e, m ∈ [½, 1) (std::frexp): a/σ = m; 1 for a = 0.
double amplitude_normaliser(double a) {
  if (!(std::isfinite(a) && a > 0)) return 1.0;
  int exponent = 0;
  std::frexp(a, &exponent);
  return std::ldexp(1.0, exponent);
}

// The data divided by the scaling: breakpoints by L, u⁰ by σL, v⁰ by σ (the polynomials are in the
// piece's local variable, which does not change).
InitialData unit_data(const InitialData& data, const Scaling& scaling) {
  InitialData unit = data;
  const double u_factor = scaling.amplitude * scaling.length;
  for (InitialDataPiece& piece : unit.pieces) {
    piece.a /= scaling.length;
    piece.b /= scaling.length;
    for (double& c : piece.displacement) c /= u_factor;
    for (double& c : piece.velocity) c /= scaling.amplitude;
  }
  return unit;
}

// A reference solution seen at another scale: values of `unit` at (x/L, t/L), scaled by the law.
class ScaledSolution : public ReferenceSolution {
 public:
  ScaledSolution(std::shared_ptr<const ReferenceSolution> unit, const Scaling& scaling)
      : unit_(std::move(unit)), scaling_(scaling) {}
  const std::shared_ptr<const ReferenceSolution>& unit() const { return unit_; }
  const Scaling& scaling() const { return scaling_; }
  double length() const override { return scaling_.length * unit_->length(); }
  double displacement(double x, double t) const override {
    return scaling_.displacement(unit_->displacement(x / scaling_.length, t / scaling_.time_scale()));
  }
  double strain(double x, double t) const override {
    return scaling_.strain(unit_->strain(x / scaling_.length, t / scaling_.time_scale()));
  }
  double velocity(double x, double t) const override {
    return scaling_.velocity(unit_->velocity(x / scaling_.length, t / scaling_.time_scale()));
  }
  double contact_displacement(double t) const override {
    return scaling_.displacement(unit_->contact_displacement(t / scaling_.time_scale()));
  }
  double contact_multiplier(double t) const override {
    return scaling_.stress(unit_->contact_multiplier(t / scaling_.time_scale()));
  }
  double energy() const override { return scaling_.energy(unit_->energy()); }
  void displacement_at_points(double t, const double* x, long count, double* u) const override {
    const std::vector<double> xi = unit_points(x, count);
    unit_->displacement_at_points(t / scaling_.time_scale(), xi.data(), count, u);
    for (long k = 0; k < count; ++k) u[k] = scaling_.displacement(u[k]);
  }
  void velocity_at_points(double t, const double* x, long count, double* v) const override {
    const std::vector<double> xi = unit_points(x, count);
    unit_->velocity_at_points(t / scaling_.time_scale(), xi.data(), count, v);
    for (long k = 0; k < count; ++k) v[k] = scaling_.velocity(v[k]);
  }

 private:
  std::vector<double> unit_points(const double* x, long count) const {
    std::vector<double> xi(x, x + count);
    for (double& p : xi) p /= scaling_.length;
    return xi;
  }
  std::shared_ptr<const ReferenceSolution> unit_;
  Scaling scaling_;
};

// A field benchmark's chain and data in the unit problem (see Scaling): lengths by L, E and ρ by those of
// the contact segment, the load by E_c σ/L, the gaps and u⁰ by σL, v⁰ by σc, T by L/c.
ImpactBenchmark unit_benchmark(const ImpactBenchmark& b, const Scaling& s) {
  ImpactBenchmark unit = b;
  const double density = s.modulus / (s.wave_speed * s.wave_speed), u_factor = s.amplitude * s.length;
  for (BarSegment& segment : unit.configuration.segments) {
    segment.length /= s.length;
    segment.modulus /= s.modulus;
    segment.density /= density;
    for (double& f : segment.load) f *= s.length / (s.modulus * s.amplitude);
  }
  unit.configuration.obstacle_gap /= u_factor;
  for (SegmentJunction& j : unit.configuration.junctions) j.gap /= u_factor;
  for (InitialDataPiece& piece : unit.data.pieces) {
    piece.a /= s.length;
    piece.b /= s.length;
    for (double& u : piece.displacement) u /= u_factor;
    for (double& v : piece.velocity) v /= s.amplitude * s.wave_speed;
  }
  unit.final_time /= s.time_scale();
  return unit;
}

}  // namespace

Scaling configuration_scaling(const Configuration& c) {
  Scaling s;
  s.length = c.bar_length();
  if (has_closed_form(c)) {
    s.amplitude = amplitude_normaliser(std::abs(c.amplitude));
    return s;
  }
  if (const ImpactBenchmark* b = configuration_field(c)) {
    // The contact segment's c and E; σ from the largest of |u⁰|/L, |v⁰|/c at the breakpoints, the gaps
    // over L and the load's strain |f| L/E at the segments' ends.
    const BarSegment& contact = b->configuration.segments.front();
    s.wave_speed = std::sqrt(contact.modulus / contact.density);
    s.modulus = contact.modulus;
    double amplitude = b->configuration.obstacle_gap / s.length;
    for (const SegmentJunction& j : b->configuration.junctions) amplitude = std::max(amplitude, j.gap / s.length);
    for (const InitialDataPiece& piece : b->data.pieces)
      for (const double x : {piece.a, piece.b})
        amplitude = std::max(
            {amplitude, std::abs(b->data.displacement(x)) / s.length, std::abs(b->data.velocity(x)) / s.wave_speed});
    for (const BarSegment& segment : b->configuration.segments)
      if (!segment.load.empty())
        for (const double sigma : {-1.0, 1.0})
          amplitude = std::max(amplitude, std::abs(poly::evaluate(segment.load, sigma)) * s.length / s.modulus);
    s.amplitude = amplitude_normaliser(amplitude);
    return s;
  }
  const InitialData data = configuration_data(c);
  double amplitude = 0;
  for (const InitialDataPiece& piece : data.pieces)
    for (const double x : {piece.a, piece.b})
      amplitude = std::max({amplitude, std::abs(data.displacement(x)) / s.length, std::abs(data.velocity(x))});
  s.amplitude = amplitude_normaliser(amplitude);
  return s;
}

Configuration unit_configuration(const Configuration& c, const Scaling& s) {
  Configuration unit = c;
  unit.length = 1.0;
  if (has_closed_form(c)) {
    unit.amplitude = c.amplitude / s.amplitude;
  } else if (const ImpactBenchmark* b = configuration_field(c)) {
    unit.field = std::make_shared<const ImpactBenchmark>(unit_benchmark(*b, s));
  } else if (!s.identity()) {
    unit.data = std::make_shared<const InitialData>(unit_data(configuration_data(c), s));
  }
  if (c.dt > 0) unit.dt = c.dt / s.time_scale();
  unit.final_time = c.final_time / s.time_scale();
  for (double& t : unit.horizons) t /= s.time_scale();
  return unit;
}

// The reference of a unit configuration. The lattice: δ = min(h, Δt) when max/min is a whole number
// (to 1e-9), which puts every node and level on it (characteristics.hpp: TabulatedSolution);
// otherwise the characteristic solution is evaluated directly.
std::shared_ptr<const ReferenceSolution> unit_reference(const Configuration& c, double horizon) {
  // The closed form's error sums need the uniform mesh (errors.cpp); a graded mesh takes the
  // characteristic solution of the same data (equal to the closed form: the doctests of phase.cpp).
  if (has_closed_form(c) && c.grading == 1.0)
    return configuration_benchmark(c).reference(horizon, c.length, c.amplitude);
  if (const ImpactBenchmark* b = configuration_field(c))
    return std::make_shared<const ImpactReference>(b->configuration, b->data, horizon);
  CharacteristicSolution solution(configuration_data(c), horizon);
  if (c.grading != 1.0) return std::make_shared<const CharacteristicSolution>(std::move(solution));
  const double h = UniformMesh(c.bar_length(), c.elements).h(), dt = c.step();
  const double small = std::min(h, dt), ratio = std::max(h, dt) / small;
  // The table spans [−T, L] and [0, L + T] (TabulatedSolution): a short horizon on a fine lattice is
  // still (L + T)/δ entries, so the bar's length counts as well as the horizon.
  if (std::abs(ratio - std::round(ratio)) <= 1e-9 * ratio && (c.bar_length() + horizon) / small <= 1e7)
    return std::make_shared<const TabulatedSolution>(std::move(solution), small);
  return std::make_shared<const CharacteristicSolution>(std::move(solution));
}

// A reference at the configuration's scale brought to the unit one: the closed form rebuilt at the
// unit scale (so that the error measures keep its one-pass path), a ScaledSolution of the same scaling
// unwrapped, any other seen through the inverse scaling.
std::shared_ptr<const ReferenceSolution> to_unit(std::shared_ptr<const ReferenceSolution> reference, const Scaling& s) {
  if (s.identity()) return reference;
  if (const auto* closed_form = dynamic_cast<const ExactSolution*>(reference.get()))
    return std::make_shared<const ExactSolution>(closed_form->length() / s.length,
                                                 closed_form->amplitude() / s.amplitude);
  if (const auto* scaled = dynamic_cast<const ScaledSolution*>(reference.get()))
    if (scaled->scaling().length == s.length && scaled->scaling().amplitude == s.amplitude &&
        scaled->scaling().wave_speed == s.wave_speed && scaled->scaling().modulus == s.modulus)
      return scaled->unit();
  return std::make_shared<const ScaledSolution>(
      std::move(reference), Scaling{1 / s.length, 1 / s.amplitude, 1 / s.wave_speed, 1 / s.modulus});
}

void require_reference_memory(const Configuration& c, double horizon, std::string_view option) {
  // The paper's closed form needs none; a field benchmark's solver bounds its own pieces (ImpactSolution).
  if ((has_closed_form(c) && c.grading == 1.0) || configuration_field(c)) return;
  double coefficients = 0;
  for (const InitialDataPiece& piece : configuration_data(c).pieces)
    coefficients += static_cast<double>(piece.displacement.size() + piece.velocity.size());
  const double bytes = coefficients * (400 + 128 * horizon / c.bar_length());
  cli::require_memory(option, bytes,
                      "the exact solution of " + cli::format_real(coefficients) +
                          " coefficients up to t = " + cli::format_real(horizon));
}

std::shared_ptr<const ReferenceSolution> configuration_reference(const Configuration& c, double horizon) {
  if (has_closed_form(c) && c.grading == 1.0)
    return configuration_benchmark(c).reference(horizon, c.length, c.amplitude);
  const Scaling s = configuration_scaling(c);
  std::shared_ptr<const ReferenceSolution> unit = unit_reference(unit_configuration(c, s), horizon / s.time_scale());
  if (s.identity()) return unit;
  return std::make_shared<const ScaledSolution>(std::move(unit), s);
}

TEST_CASE("the scaling law: a run at (L, a) is the unit run scaled back, bit for bit for powers of two") {
  // Every scheme on the benchmark at (L, a), taken at its own scale (the library's formulas hold for any
  // L), against the unit run with the amplitude a/σ scaled back: the same doubles when L and a are
  // powers of two (every product by a power of two is exact). Otherwise h, Δt and the data are rounded
  // differently at the two scales (ε relative each), and each of the 100 steps adds a few N ε (the
  // condition of a step, N = 20): the bound is 100 · 20 · 2⁻⁵² · 2 ≈ 1e-11 relative to each quantity's
  // size (measured: 4e-12).
  struct ScaledBar {
    double length, amplitude;
    bool exact;
  };
  SchemeParameters ps;
  ps.scheme = Scheme::paoli_schatzman;
  for (const ScaledBar& k : {ScaledBar{4.0, 0.25, true}, ScaledBar{0.5, 8.0, true}, ScaledBar{3.0, 0.3, false}})
    for (const Scheme scheme : {Scheme::crank_nicolson, Scheme::backward_euler, Scheme::paoli_schatzman,
                                Scheme::energy_conserving, Scheme::switching}) {
      SchemeParameters p;
      p.scheme = scheme;
      const Index elements = 20;
      const UniformMesh mesh(k.length, elements), unit_mesh(1.0, elements);
      Configuration c;
      c.length = k.length;
      c.amplitude = k.amplitude;
      const Scaling scaling = configuration_scaling(c);
      const double sigma = scaling.amplitude;
      BarSimulation direct(benchmark_problem(k.length, k.amplitude), mesh, mod3(), p, 0.7 * mesh.h());
      BarSimulation unit(benchmark_problem(1.0, k.amplitude / sigma), unit_mesh, mod3(), p, 0.7 * unit_mesh.h());
      double worst = 0;
      for (Index n = 0; n <= 100; ++n, direct.step(), unit.step()) {
        const Sample d = direct.sample(), u = unit.sample();
        const Eigen::VectorXd du = *d.displacement - scaling.displacement(1.0) * *u.displacement;
        const Eigen::VectorXd dv = *d.velocity - scaling.velocity(1.0) * *u.velocity;
        const double scale_u = d.displacement->cwiseAbs().maxCoeff(), scale_v = 1 + d.velocity->cwiseAbs().maxCoeff();
        worst = std::max({worst, std::abs(d.time - scaling.time(u.time)) / k.length, du.cwiseAbs().maxCoeff() / scale_u,
                          dv.cwiseAbs().maxCoeff() / (k.amplitude * scale_v),
                          std::abs(d.multiplier - scaling.velocity(u.multiplier)) / k.amplitude,
                          std::abs(d.energy - scaling.energy(u.energy)) / d.energy});
      }
      CAPTURE(k.length);
      CAPTURE(k.amplitude);
      CAPTURE(to_string(scheme));
      CAPTURE(worst);
      CHECK(worst <= (k.exact ? 0.0 : 1e-11));
    }
}

TEST_CASE("a configuration at any scale is run at the unit scale and its measures scaled back") {
  // At (L, a) = (4, 1/4) the observer sees the samples of the run taken at its own scale, bit for bit,
  // and the energy range is that run's. At the ends of bar1d's range, 1e±100, the unit run is the
  // same as at L = 1 with the same σ, so the relative errors are the same doubles and the energies
  // those times L (the squares of the data, 1e±400, are never formed).
  Configuration c = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 20, 0.5, 6.0);
  c.length = 4.0;
  c.amplitude = 0.25;
  c.final_time = 24.0;
  const UniformMesh mesh(4.0, 20);
  BarSimulation direct(benchmark_problem(4.0, 0.25), mesh, mod3(), c.scheme, 0.5 * mesh.h());
  bool same = true;
  double lowest = HUGE_VAL;
  const Measures m = run_configuration(c, [&](const Sample& s) {
    if (s.level > 0) direct.step();
    const Sample d = direct.sample();
    same = same && s.time == d.time && *s.displacement == *d.displacement && *s.velocity == *d.velocity &&
           s.multiplier == d.multiplier && s.energy == d.energy && s.energy_time == d.energy_time;
    lowest = std::min(lowest, d.energy);
  });
  CHECK(same);
  CHECK(m.energy_min == lowest);
  CHECK(m.impacts.size() == 2);  // at L + 3Lk = 4, 16
  REQUIRE(m.phase.has_value());
  CHECK(m.phase->period == 12.0);
  for (const double length : {1e-100, 1e100})
    for (const double amplitude : {1e-100, 1e100}) {
      Configuration big = paper_configuration(Scheme::crank_nicolson, "algebraic", "mod3", 20, 0.5, 6.0 * length);
      big.length = length;
      big.amplitude = amplitude;
      Configuration one = big;
      one.length = 1.0;
      one.final_time = 6.0;
      const Measures at_scale = run_configuration(big), at_one = run_configuration(one);
      CAPTURE(length);
      CAPTURE(amplitude);
      CHECK(ErrorAccumulator::values(at_scale.errors) == ErrorAccumulator::values(at_one.errors));
      CHECK(std::isfinite(at_scale.energy_max));
      CHECK(std::abs(at_scale.energy_max / length - at_one.energy_max) <= 1e-15 * at_one.energy_max);
      REQUIRE(at_scale.phase.has_value());
      CHECK(std::abs(at_scale.phase->first_impact_error / length - at_one.phase->first_impact_error) <= 1e-15);
    }
}

}  // namespace mrm::repro
