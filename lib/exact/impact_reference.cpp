/// @file impact_reference.cpp
/// @brief The exact solution of a chain with a rigid obstacle as the reference of the error measures.
///
/// The reference of the error measures. The energy ½∫(ρu_t² + E u_x²) − ∫ f u at t = 0 by the 5-point
/// Gauss rule on 64 subintervals of each segment: exact for data and loads of degree ≤ 4 on each
/// subinterval (the benchmarks' are constant or affine), a quadrature otherwise.
/// Inside a contact window u(0, t) is −g₀ exactly (the Skorokhod reflection holds z = 0 there), so the
/// contact displacement is given as that constant rather than as the sum of the waves.
#include "exact/impact_reference.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <vector>

#include <doctest/doctest.h>

#include "core/problem.hpp"
#include "exact/impact_benchmarks.hpp"

namespace mrm {

ImpactReference::ImpactReference(const ImpactConfiguration& configuration, const InitialData& data, double final_time)
    : solution_(configuration, data, final_time) {
  if (!configuration.obstacle)
    throw InvalidParameter("configuration",
                           "the reference of the error measures needs a rigid obstacle at x = 0 (allowed: a chain "
                           "with an obstacle; two bars in contact have none)");
  static const double node[5] = {-0.9061798459386640, -0.5384693101056831, 0.0, 0.5384693101056831, 0.9061798459386640};
  static const double weight[5] = {0.2369268850561891, 0.4786286704993665, 0.5688888888888889, 0.4786286704993665,
                                   0.2369268850561891};
  double x0 = 0;
  for (const BarSegment& segment : configuration.segments) {
    const int parts = 64;
    const double width = segment.length / parts;
    for (int k = 0; k < parts; ++k)
      for (int q = 0; q < 5; ++q) {
        const double x = x0 + width * (k + 0.5 * (1 + node[q]));
        const double v = solution_.velocity(x, 0.0), sigma = solution_.stress(x, 0.0);
        const double f =
            segment.load.empty() ? 0.0 : poly::evaluate(segment.load, (x - x0) / (0.5 * segment.length) - 1);
        energy_ +=
            0.5 * width * weight[q] *
            (0.5 * (segment.density * v * v + sigma * sigma / segment.modulus) - f * solution_.displacement(x, 0.0));
      }
    x0 += segment.length;
  }
}

double ImpactReference::contact_displacement(double t) const {
  const std::vector<ContactInterval>& windows = contact_windows();
  const auto after = std::upper_bound(windows.begin(), windows.end(), t,
                                      [](double s, const ContactInterval& w) { return s < w.start; });
  if (after != windows.begin() && t <= std::prev(after)->end) return -solution_.configuration().obstacle_gap;
  return solution_.displacement(0.0, t);
}

double ImpactReference::strain(double x, double t) const {
  const std::vector<BarSegment>& segments = solution_.configuration().segments;
  double x0 = 0;
  std::size_t j = 0;
  while (j + 1 < segments.size() && x > x0 + segments[j].length) x0 += segments[j++].length;
  return solution_.stress(x, t) / segments[j].modulus;
}

void ImpactReference::displacement_at_points(double t, const double* x, long count, double* u) const {
  solution_.at_points(t, x, count, u, nullptr);
}

void ImpactReference::velocity_at_points(double t, const double* x, long count, double* v) const {
  solution_.at_points(t, x, count, nullptr, v);
}
TEST_CASE("the reference of the error measures: the energy with the load's potential, u(0, t) held at -g0") {
  // Impacting and layered at t = 0: undeformed with uniform v⁰, E = ½∫ρv² = ½ρLv² (8e6 J/m²; 1.25); the
  // bouncing bar at rest and undeformed: 0 (u = 0, so −∫f u = 0 too). Inside a window u(0, t) is −g₀
  // exactly; λ = σ(0, t) is that of the solution.
  const ImpactBenchmark& impacting = impact_benchmark("impacting");
  const ImpactReference a(impacting.configuration, impacting.data, impacting.final_time);
  CHECK(std::abs(a.energy() - 8e6) <= 1e-12 * 8e6);
  const ContactInterval w = a.contact_windows().front();
  CHECK(a.contact_displacement(0.5 * (w.start + w.end)) == -2e-3);
  CHECK(a.contact_multiplier(0.5 * (w.start + w.end)) == a.solution().contact_stress(0, 0.5 * (w.start + w.end)));
  const ImpactBenchmark& layered = impact_benchmark("layered");
  CHECK(std::abs(ImpactReference(layered.configuration, layered.data, 1.0).energy() - 1.25) <= 1e-12);
  const ImpactBenchmark& bouncing = impact_benchmark("bouncing");
  CHECK(ImpactReference(bouncing.configuration, bouncing.data, 1.0).energy() == 0.0);
  // u_x = σ/E in each segment (layered: E = 4 then 1).
  const ImpactReference l(layered.configuration, layered.data, 2.0);
  CHECK(std::abs(l.strain(0.5, 0.3) - l.solution().stress(0.5, 0.3) / 4) <= 1e-15);
  CHECK(std::abs(l.strain(2.0, 1.9) - l.solution().stress(2.0, 1.9)) <= 1e-15);
  const ImpactBenchmark& two = impact_benchmark("two-bars");
  CHECK_THROWS_AS(ImpactReference(two.configuration, two.data, 1.0), InvalidParameter);
}

}  // namespace mrm
