// GetFEM's demo, version 4, as a configuration, and the demo's measures: see getfem_demo_v4.hpp.
#include "getfem_demo_v4.hpp"

#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm::repro {

const char* const GetfemDemoMeasures::names[7] = {"LinfL2u", "LinfH1u", "LinfL2v", "L2L2u", "L2H1u", "L2L2v", "L2sn"};

Configuration getfem_demo_v4_configuration() {
  Configuration c;
  c.scheme.scheme = mrm::Scheme::taylor_flanagan;
  c.scheme.lumping = mrm::MassLumping::none;
  c.mass = mrm::consistent_mass();
  c.elements = 20;
  c.dt = 0.002;
  c.final_time = 12;
  c.initial = mrm::InitialContactNode::interpolant;
  return c;
}

// The demo's uExact(x, t, d): d = 0 the displacement, 1 the x derivative, 2 the time derivative, with
// its zones and its one-sided values on the characteristics (reconstructed line by line from the demo).
double getfem_demo_exact(double x, double t, int d) {
  const double tp = std::fmod(t, 3.0), tf = std::fmod(tp, 1.0), nf = std::floor(tp);
  int zone;
  if (tf < x)
    zone = tf <= 1 - x ? 1 : 3;
  else
    zone = tf <= 1 - x ? 2 : 4;
  double u = 0, dxu = 0, dtu = 0;
  if (nf == 0) {
    if (zone == 1 || zone == 3)
      u = 0.5 - x / 2, dxu = -0.5, dtu = 0;
    else
      u = 0.5 - tf / 2, dxu = 0, dtu = -0.5;
  } else if (nf == 1) {
    if (zone == 1)
      u = -tf / 2, dxu = 0, dtu = -0.5;
    else if (zone == 2)
      u = -x / 2, dxu = -0.5, dtu = 0;
    else if (zone == 3)
      u = -0.5 + x / 2, dxu = 0.5, dtu = 0;
    else
      u = -0.5 + tf / 2, dxu = 0, dtu = 0.5;
  } else {
    if (zone == 1 || zone == 2)
      u = tf / 2, dxu = 0, dtu = 0.5;
    else
      u = 0.5 - x / 2, dxu = -0.5, dtu = 0;
  }
  return d == 0 ? u : (d == 1 ? dxu : dtu);
}

namespace {}  // namespace

GetfemDemoMeasures getfem_demo_measures(const Configuration& configuration) {
  if (!has_closed_form(configuration) || configuration.length != 1.0 || configuration.amplitude != 0.5)
    throw std::invalid_argument("getfem_demo_measures: the demo's problem is the paper's benchmark, L = 1, a = 1/2");
  const Index n = configuration.elements;
  const double h = 1.0 / static_cast<double>(n), dt = configuration.step();
  // The P1 mass and stiffness over all nodes 0..N (GetFEM's norms of the P1 functions, exact with its
  // integration method of order 4).
  const UniformMesh mesh(1.0, n);
  const Tridiagonal mass = p1_mass_all_nodes(mesh), stiffness = p1_stiffness_all_nodes(mesh);
  Eigen::VectorXd x(n + 1), e_u(n + 1), e_v(n + 1), ex_u(n + 1), ex_v(n + 1);
  for (Index i = 0; i <= n; ++i) x[i] = static_cast<double>(i) * h;  // np.arange(0, 1 + 1/NX, 1/NX)
  double max_ul2 = 0, max_ul2_ex = 0, max_uh1 = 0, max_uh1_ex = 0, max_vl2 = 0, max_vl2_ex = 0;
  double sum_ul2 = 0, sum_ul2_ex = 0, sum_uh1 = 0, sum_uh1_ex = 0, sum_vl2 = 0, sum_vl2_ex = 0, sum_s = 0, sum_s_ex = 0;
  Configuration run = configuration;
  run_configuration(run, [&](const Sample& s) {
    const double t = static_cast<double>(s.level) * dt;  // np.arange's t_k = k dt
    for (Index i = 0; i <= n; ++i) {
      const double u = i < n ? (*s.displacement)[i] : 0.0, v = i < n ? (*s.velocity)[i] : 0.0;
      ex_u[i] = getfem_demo_exact(x[i], t, 0);
      ex_v[i] = getfem_demo_exact(x[i], t, 2);
      e_u[i] = u - ex_u[i];
      e_v[i] = v - ex_v[i];
    }
    const double ul2 = mass.bilinear(e_u, e_u), ul2_ex = mass.bilinear(ex_u, ex_u);
    const double uh1 = ul2 + stiffness.bilinear(e_u, e_u), uh1_ex = ul2_ex + stiffness.bilinear(ex_u, ex_u);
    const double vl2 = mass.bilinear(e_v, e_v), vl2_ex = mass.bilinear(ex_v, ex_v);
    max_ul2 = std::max(max_ul2, ul2), max_ul2_ex = std::max(max_ul2_ex, ul2_ex);
    max_uh1 = std::max(max_uh1, uh1), max_uh1_ex = std::max(max_uh1_ex, uh1_ex);
    max_vl2 = std::max(max_vl2, vl2), max_vl2_ex = std::max(max_vl2_ex, vl2_ex);
    sum_ul2 += ul2, sum_ul2_ex += ul2_ex, sum_uh1 += uh1, sum_uh1_ex += uh1_ex, sum_vl2 += vl2, sum_vl2_ex += vl2_ex;
    const double lambda = s.level == 0 ? 0.0 : s.multiplier, lambda_exact = getfem_demo_exact(0.0, t, 1);
    sum_s += (lambda - lambda_exact) * (lambda - lambda_exact), sum_s_ex += lambda_exact * lambda_exact;
  });
  GetfemDemoMeasures m;
  m.values = {std::sqrt(max_ul2 / max_ul2_ex), std::sqrt(max_uh1 / max_uh1_ex), std::sqrt(max_vl2 / max_vl2_ex),
              std::sqrt(sum_ul2 / sum_ul2_ex), std::sqrt(sum_uh1 / sum_uh1_ex), std::sqrt(sum_vl2 / sum_vl2_ex),
              std::sqrt(sum_s / sum_s_ex)};
  return m;
}

TEST_CASE("the demo's uExact: its zones and one-sided values on the characteristics") {
  CHECK(getfem_demo_exact(0.3, 0.1, 0) == doctest::Approx(0.35));  // zone I, phase 0: u = 1/2 − x/2
  CHECK(getfem_demo_exact(0.0, 1.5, 0) == 0.0);                    // in contact
  CHECK(getfem_demo_exact(1.0, 1.0, 2) == -0.5);                   // at the clamp at t = 1: the zone-I value
  CHECK(getfem_demo_exact(0.0, 1.5, 1) == -0.5);                   // the contact stress
}

}  // namespace mrm::repro
