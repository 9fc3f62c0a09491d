/// @file mass_redistribution.cpp
/// @brief The weighted mass redistribution method: paper §2 and eq. (6), mathematics.md §3.
///
/// The paper replaces the mass matrix M of (5) by a matrix M^mod whose row and column of the contact
/// node vanish, so that node 0 has no inertia and the contact condition becomes algebraic. In its
/// weighted form,
///
///     M^mod_ij = ∫₀ᴸ φ_i φ_j w_{h,ij} dx,   w_{h,0i} = w_{h,i0} = 0,   w_{h,ij} = 1 + O(h) otherwise.
///
/// With a weight that is constant on each entry this is M^mod_ij = w_{h,ij} M_ij, and every choice of
/// the paper is an instance (the matrices are this implementation's reconstruction: the paper names
/// them in words only, mathematics.md §3):
///
///   Mod 1  w = 1 for i, j ≥ 1                 the mass 2h/3 of row/column 0 is dropped: total L − 2h/3
///   Mod 2  w = L/(L − 2h/3) for i, j ≥ 1       spread uniformly: total mass L again
///   Mod 3  w_11 = 2, w = 1 otherwise           moved to node 1 (M̄_11 = 2h/3 + 2h/3 = 4h/3): total L
///
/// Removing row and column 0 removes M_00 + 2 M_01 = h/3 + 2 h/6 = 2h/3 of the total mass 1ᵀM1 = L. The
/// total mass counts every node 0..N, the clamped one included, so the matrices are built on all nodes
/// first and node N is eliminated afterwards. The uniform weight is w = 1/(1 − 2h/(3L)) =
/// 1 + 2h/(3L) + O(h²), of the form 1 + O(h) the analysis asks for (the OCR of the paper reads "o(h)").
#include "mass_redistribution.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm {

MassRedistribution consistent_mass() {
  return {"consistent", "consistent P1 mass (the contact node keeps its inertia)",
          [](Index, Index, const UniformMesh&) { return 1.0; }};
}

MassRedistribution mod1() {
  return {"mod1", "Mod 1: the contact node's mass is dropped",
          [](Index i, Index j, const UniformMesh&) { return (i == 0 || j == 0) ? 0.0 : 1.0; }};
}

MassRedistribution mod2() {
  return {"mod2", "Mod 2: the contact node's mass is spread uniformly on the other nodes",
          [](Index i, Index j, const UniformMesh& mesh) {
            if (i == 0 || j == 0) return 0.0;
            return mesh.length / (mesh.length - 2.0 * mesh.h() / 3.0);
          }};
}

// Spreading the lost mass 2h/3 in equal parts 2h/(3k) on the diagonal entries M_ii = 2h/3 of the
// nodes i = 1..k means the weight w_ii = 1 + 1/k there (node N, clamped, is never among them).
MassRedistribution spread_over_first_nodes(Index k) {
  if (k < 1) throw std::invalid_argument("spread_over_first_nodes: k must be >= 1");
  return {"spread" + std::to_string(k),
          "the contact node's mass spread on the diagonal of nodes 1.." + std::to_string(k),
          [k](Index i, Index j, const UniformMesh& mesh) {
            if (i == 0 || j == 0) return 0.0;
            if (k >= mesh.elements) throw std::invalid_argument("spread_over_first_nodes: k must be < N");
            return (i == j && i <= k) ? 1.0 + 1.0 / static_cast<double>(k) : 1.0;
          }};
}

MassRedistribution mod3() {
  MassRedistribution r = spread_over_first_nodes(1);
  r.name = "mod3";
  r.description = "Mod 3: the contact node's mass is moved to the neighbouring node";
  return r;
}

std::vector<std::string> mass_redistribution_names() { return {"consistent", "mod1", "mod2", "mod3"}; }

MassRedistribution mass_redistribution_by_name(const std::string& name) {
  if (name == "consistent") return consistent_mass();
  if (name == "mod1") return mod1();
  if (name == "mod2") return mod2();
  if (name == "mod3") return mod3();
  throw std::invalid_argument("unknown mass choice \"" + name + "\" (allowed: consistent, mod1, mod2, mod3)");
}

Tridiagonal modified_mass_all_nodes(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  if (!redistribution.weight)
    throw std::invalid_argument("mass redistribution \"" + redistribution.name +
                                "\": no weight function (allowed: a function w(i, j, mesh))");
  Tridiagonal m = p1_mass_all_nodes(mesh);
  const Index n = m.size();
  for (Index i = 0; i < n; ++i) {
    const double w = redistribution.weight(i, i, mesh);
    if (!std::isfinite(w))
      throw std::invalid_argument("mass redistribution \"" + redistribution.name + "\": non-finite weight");
    m.diag[i] *= w;
    if (i + 1 < n) {
      const double w_up = redistribution.weight(i, i + 1, mesh);
      const double w_down = redistribution.weight(i + 1, i, mesh);
      if (!(std::isfinite(w_up) && w_up == w_down))
        throw std::invalid_argument("mass redistribution \"" + redistribution.name +
                                    "\": the weights must be finite and symmetric");
      m.upper[i] *= w_up;
      m.lower[i + 1] *= w_up;
    }
  }
  return m;
}

bool contact_node_is_massless(const Tridiagonal& mass) { return mass.diag[0] == 0.0 && mass.upper[0] == 0.0; }

// Positive definiteness of a symmetric tridiagonal matrix is read off its LDLᵀ pivots
// d_0 = a_0, d_i = a_i − l_i²/d_{i−1}: all of them must be positive.
static bool tridiagonal_is_positive_definite(const Tridiagonal& a, Index first) {
  double d = 0.0;
  for (Index i = first; i < a.size(); ++i) {
    d = (i == first) ? a.diag[i] : a.diag[i] - a.lower[i] * a.lower[i] / d;
    if (!(d > 0.0)) return false;
  }
  return true;
}

Tridiagonal modified_mass(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  const Tridiagonal m = modified_mass_all_nodes(mesh, redistribution).leading_block(mesh.unknowns());
  const Index first = contact_node_is_massless(m) ? 1 : 0;
  if (!tridiagonal_is_positive_definite(m, first))
    throw std::invalid_argument("mass redistribution \"" + redistribution.name +
                                "\": the weights must leave a positive definite mass on the nodes with inertia");
  return m;
}

double total_mass(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  return modified_mass_all_nodes(mesh, redistribution).sum();
}

// ---------------------------------------------------------------------------------------------------

TEST_CASE("Mod 1 loses exactly 2h/3 of the total mass; Mod 2, Mod 3 and the spreads preserve it") {
  for (double length : {1.0, 2.5}) {
    for (Index n : {2, 3, 10, 64, 1000}) {
      const UniformMesh mesh(length, n);
      const double h = mesh.h();
      CAPTURE(length);
      CAPTURE(n);
      CHECK(std::abs(total_mass(mesh, consistent_mass()) - length) < 1e-13 * length);
      CHECK(std::abs(total_mass(mesh, mod1()) - (length - 2 * h / 3)) < 1e-13 * length);
      CHECK(std::abs(total_mass(mesh, mod2()) - length) < 1e-13 * length);
      CHECK(std::abs(total_mass(mesh, mod3()) - length) < 1e-13 * length);
      if (n > 4) CHECK(std::abs(total_mass(mesh, spread_over_first_nodes(3)) - length) < 1e-13 * length);
    }
  }
}

TEST_CASE("the redistributed masses remove the inertia of the contact node and stay definite elsewhere") {
  const UniformMesh mesh(1.0, 20);
  const double h = mesh.h();
  for (const MassRedistribution& r : {mod1(), mod2(), mod3(), spread_over_first_nodes(4)}) {
    CAPTURE(r.name);
    const Tridiagonal m = modified_mass(mesh, r);
    CHECK(contact_node_is_massless(m));
    CHECK(m.lower[1] == 0.0);
    CHECK(m.size() == mesh.unknowns());
  }
  CHECK_FALSE(contact_node_is_massless(modified_mass(mesh, consistent_mass())));
  CHECK(modified_mass(mesh, mod3()).diag[1] == doctest::Approx(4 * h / 3).epsilon(1e-14));
  CHECK(modified_mass(mesh, mod3()).diag[2] == doctest::Approx(2 * h / 3).epsilon(1e-14));
  CHECK(modified_mass(mesh, mod1()).diag[1] == doctest::Approx(2 * h / 3).epsilon(1e-14));
}

TEST_CASE("the uniform weight of Mod 2 is 1 + 2h/(3L) + O(h^2)") {
  for (Index n : {10, 100, 1000}) {
    const UniformMesh mesh(2.0, n);
    const double h = mesh.h(), w = mod2().weight(1, 1, mesh);
    CAPTURE(n);
    CHECK(std::abs(w - (1 + 2 * h / (3 * mesh.length))) < 0.5 * h * h);  // remainder (2h/3L)²/(1 − 2h/3L)
    CHECK(std::abs(w - (1 + 2 * h / (3 * mesh.length))) > 0.1 * h * h);
  }
}

TEST_CASE("weights that break symmetry or definiteness are rejected with the redistribution's name") {
  const UniformMesh mesh(1.0, 10);
  MassRedistribution negative{"negative", "", [](Index i, Index j, const UniformMesh&) {
                                return (i == 0 || j == 0) ? 0.0 : (i == j && i == 3 ? -1.0 : 1.0);
                              }};
  CHECK_THROWS_WITH_AS(modified_mass(mesh, negative), doctest::Contains("\"negative\""), std::invalid_argument);
  MassRedistribution skew{"skew", "", [](Index i, Index j, const UniformMesh&) { return i < j ? 1.0 : 2.0; }};
  CHECK_THROWS_AS(modified_mass(mesh, skew), std::invalid_argument);
  // Zeroing only the diagonal entry of node 0 leaves an indefinite matrix (M_01 ≠ 0): rejected.
  MassRedistribution half{"half", "",
                          [](Index i, Index j, const UniformMesh&) { return i == 0 && j == 0 ? 0.0 : 1.0; }};
  CHECK_THROWS_AS(modified_mass(mesh, half), std::invalid_argument);
  CHECK_THROWS_WITH_AS(mass_redistribution_by_name("mod4"), doctest::Contains("allowed: consistent, mod1, mod2, mod3"),
                       std::invalid_argument);
}

TEST_CASE("a redistribution without a weight function is rejected with its name") {
  const UniformMesh mesh(1.0, 8);
  const MassRedistribution empty{"empty", "no weights", {}};
  CHECK_THROWS_WITH_AS(modified_mass(mesh, empty), doctest::Contains("\"empty\": no weight function"),
                       std::invalid_argument);
  CHECK_THROWS_AS(total_mass(mesh, empty), std::invalid_argument);
}

}  // namespace mrm
