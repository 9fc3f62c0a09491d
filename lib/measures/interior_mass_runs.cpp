/// @file interior_mass_runs.cpp
/// @brief The blended interior mass (interior_mass.hpp) checked through the schemes: Crank–Nicolson keeps
/// and the energy-conserving scheme conserves the energy on the blend (interior_mass.cpp §3: the identities
/// need only a symmetric positive definite mass), and the fast kernel agrees with the reference step.
#include <algorithm>
#include <cmath>

#include <doctest/doctest.h>

#include "fem/interior_mass.hpp"
#include "fem/mass_redistribution.hpp"
#include "time/schemes.hpp"

namespace mrm {

namespace {

[[maybe_unused]] SchemeParameters scheme_with(Scheme scheme, StepKernel kernel) {
  SchemeParameters p;
  p.scheme = scheme;
  p.kernel = kernel;
  return p;
}

}  // namespace

TEST_CASE("CN keeps and EC conserves the energy on the blend, and the fast kernel agrees with the reference step") {
  // interior_mass.cpp §3: the identities need only a symmetric positive definite mass. CN: |E_k − E₀| ≤ 1e-14 + k·1e-15 over
  // the first free flight (t < 0.9, no status change); EC: the same bound at every step over 3 periods
  // (status changes included); both kernels, the blends 0.25 and 1, Mod 3 and Mod 1 on them. The two
  // kernels' displacements agree to 1e-12 (their sums are ordered differently).
  for (double a : {0.25, 1.0}) {
    for (const MassRedistribution& mass : {mod3(a), mod1(a)}) {
      const UniformMesh mesh(1.0, 40);
      const double dt = 0.5 * mesh.h();
      for (Scheme scheme : {Scheme::crank_nicolson, Scheme::energy_conserving}) {
        BarSimulation fast(benchmark_problem(), mesh, mass, scheme_with(scheme, StepKernel::fast), dt);
        BarSimulation reference(benchmark_problem(), mesh, mass, scheme_with(scheme, StepKernel::reference), dt);
        const double horizon = scheme == Scheme::crank_nicolson ? 0.9 : 9.0;
        const double e0 = fast.sample().energy;
        double drift = 0.0, gap = 0.0;
        Index k = 0;
        for (; fast.time() < horizon; ++k) {
          fast.step();
          reference.step();
          drift = std::max(drift, std::abs(fast.sample().energy - e0) - static_cast<double>(k + 1) * 1e-15);
          gap = std::max(gap, (*fast.sample().displacement - *reference.sample().displacement).cwiseAbs().maxCoeff());
        }
        CAPTURE(a);
        CAPTURE(mass.name);
        CAPTURE(to_string(scheme));
        CHECK(drift <= 1e-14);
        CHECK(gap <= 1e-12);
        CHECK(fast.mass().diag[1] == doctest::Approx(modified_mass(mesh, mass).diag[1]));
      }
    }
  }
}

}  // namespace mrm
