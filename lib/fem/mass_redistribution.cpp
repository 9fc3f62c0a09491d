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
/// | member | weight                        | the mass 2h/3 of row and column 0           | total mass |
/// |--------|-------------------------------|---------------------------------------------|------------|
/// | Mod 1  | w = 1 for i, j ≥ 1            | dropped                                     | L − 2h/3   |
/// | Mod 2  | w = L/(L − 2h/3) for i, j ≥ 1 | spread uniformly                            | L again    |
/// | Mod 3  | w_11 = 2, w = 1 otherwise     | moved to node 1 (M̄_11 = 2h/3 + 2h/3 = 4h/3) | L          |
///
/// Removing row and column 0 removes M_00 + 2 M_01 = h/3 + 2 h/6 = 2h/3 of the total mass 1ᵀM1 = L. The
/// total mass counts every node 0..N, the clamped one included, so the matrices are built on all nodes
/// first and node N is eliminated afterwards. The uniform weight is w = 1/(1 − 2h/(3L)) =
/// 1 + 2h/(3L) + O(h²), of the form 1 + O(h) the analysis asks for (the OCR of the paper reads "o(h)").
#include "fem/mass_redistribution.hpp"

#include <charconv>
#include <cmath>
#include <stdexcept>
#include <system_error>

#include <doctest/doctest.h>

namespace mrm {

// ---------------------------------------------------------------------------------------------------
// The family on the blended interior mass (the paper has the consistent mass only, this is the
// project's construction). The interior mass M^A = (1 − A) M + A M_L (p1.cpp: per element
// m/6 [2 + A, 1 − A; 1 − A, 2 + A]) replaces M before any redistribution, and each member is defined by
// what it does with the mass that removing row and column 0 takes off M^A,
//
//     m_lost(A) = M^A₀₀ + 2M^A₀₁ = ρ₀h₀ (2 + A)/6 + 2ρ₀h₀ (1 − A)/6 = (2/3 − A/6) ρ₀h₀,
//
// exactly as on M: Mod 1 drops it, Mod 2 scales the density by m_bar/(m_bar − m_lost(A)), spread:K puts
// m_lost(A)/K on the diagonal of nodes 1..K, Mod 3 = spread:1 moves it to node 1:
//
//     M̄₁₁ = M^A₁₁ + m_lost(A) = M^A₀₀ + 2M^A₀₁ + M^A₁₁ = (PᵀM^AP)₁₁   (u₀ := u₁),
//
// still the Galerkin mass of the free-flight kinematics, (4/3 + A/6) h on the uniform mesh; node1:X adds
// (X − 2/3) ρ₀h₀ beyond Mod 1's M^A₁₁ (so node1:X is M̄₁₁ = (X + A/3) h: Mod 3 is node1:(4/3 − A/6)), and
// beta:B puts the point mass B ρ₀h₀ on node 1 and the rest by the density scale (Mod 3 is
// beta:(2/3 − A/6)). The weights are w_ij = M̄_ij / M^A_ij, with the diagonal M^A_ii = (1 + A/2) M_ii.
// Why this and not the literal weight w₁₁ = 2 on M^A (M̄₁₁ = (4/3 + 2A/3) h): the period law reads the
// drift off the row sums (lumped masses) of M̄ − M̄_Mod3 (period_law.cpp), the blend keeps every row sum
// of the elements it touches, and m_lost(A) + (row sum of node 1 in M^A without node 0) = ρ₀h₀ + ρ₁h₁/2
// for every A: the Galerkin member has Mod 3's row sums, hence Mod 3's zero drift, for every A, while
// the literal weight adds A h/2 at node 1 and drifts by ΔP = 2 · A h/2 = A h per period (doctests in
// interior_mass.cpp).
double lost_mass(const UniformMesh& mesh, double blend) {
  if (!(blend >= 0.0 && blend <= 1.0))
    throw std::invalid_argument("mass redistribution: the interior mass blend A must be in [0, 1]");
  if (blend == 0.0) return lost_mass(mesh);
  return (4.0 - blend) * mesh.density(0) * mesh.h(0) / 6.0;
}

namespace {

// A member's blend, checked at construction.
double checked_blend(double blend) {
  if (!(blend >= 0.0 && blend <= 1.0))
    throw std::invalid_argument(
        "mass redistribution: the interior mass blend A must be in [0, 1] (allowed: "
        "0 consistent, 1 lumped, in between blend:A)");
  return blend;
}

// The member `r` on the blend A: its field set, its description saying so when A ≠ 0.
MassRedistribution on_blend(MassRedistribution r, double blend) {
  r.interior_blend = blend;
  if (blend != 0.0) r.description += " (on the interior mass blend A = " + std::to_string(blend) + ")";
  return r;
}

}  // namespace

MassRedistribution consistent_mass(double blend) {
  return on_blend({"consistent", "consistent P1 mass (the contact node keeps its inertia)",
                   [](Index, Index, const UniformMesh&) { return 1.0; }},
                  checked_blend(blend));
}

MassRedistribution mod1(double blend) {
  return on_blend({"mod1", "Mod 1: the contact node's mass is dropped",
                   [](Index i, Index j, const UniformMesh&) { return (i == 0 || j == 0) ? 0.0 : 1.0; }},
                  checked_blend(blend));
}

// ---------------------------------------------------------------------------------------------------
// Unequal elements and piecewise material (the paper defines the family on a uniform mesh of
// a homogeneous bar only: what follows is this project's reconstruction). With element sizes h_e and
// densities ρ_e, removing row and column 0 removes
//
//     m_lost = M₀₀ + 2M₀₁ = ρ₀h₀/3 + 2ρ₀h₀/6 = 2ρ₀h₀/3
//
// of the bar's mass m_bar = Σ ρ_e h_e (the contact element keeps ρ₀h₀/3 on node 1). The members are
// defined by what they do with m_lost, which is what the paper's words say:
//   Mod 1   drops it (w = 1 on nodes ≥ 1), as before;
//   Mod 2   "spread uniformly": the density of the whole bar scaled by w = m_bar/(m_bar − m_lost), i.e.
//           every entry of rows and columns ≥ 1 times w (on a uniform mesh the paper's L/(L − 2h/3));
//           the other reading, equal shares per node, is spread:K with K the number of free nodes;
//   Mod 3   moves it to node 1: M̄₁₁ = M₁₁ + m_lost = ρ₀h₀ + ρ₁h₁/3, the removed element's whole mass
//           on the new free end. This is the Galerkin mass PᵀMP of the free-flight kinematics u₀ := u₁
//           (M₀₀ + 2M₀₁ + M₁₁) on any mesh, the property the period law rests on (period_law.cpp);
//           the literal weight w₁₁ = 2 of the uniform case would give M̄₁₁ = 2M₁₁ = 2(ρ₀h₀ + ρ₁h₁)/3
//           instead, which is not mass-preserving when ρ₁h₁ ≠ ρ₀h₀.
//   spread:K  m_lost in equal parts m_lost/K on the diagonal of nodes 1..K: w_ii = 1 + m_lost/(K M_ii).
// On the paper's mesh every weight below is computed by its original expression (the same number:
// m_lost/(K M_ii) = 1/K there), so that the uniform results stay bit for bit what they were.
double lost_mass(const UniformMesh& mesh) {
  if (mesh.uniform() && mesh.homogeneous()) return 2.0 * mesh.h() / 3.0;
  return 2.0 * mesh.density(0) * mesh.h(0) / 3.0;
}

namespace {

// M_ii, the consistent mass of node i (0 < i < N): (ρ_{i−1}h_{i−1} + ρ_i h_i)/3; at a free far end
// i = N, ρ_{N−1}h_{N−1}/3.
double node_mass(const UniformMesh& mesh, Index i) {
  const double left = mesh.density(i - 1) * mesh.h(i - 1);
  return (i < mesh.elements ? left + mesh.density(i) * mesh.h(i) : left) / 3.0;
}

// M^A_ii = (1 + A/2) M_ii, the diagonal of the blended mass (each element's diagonal entry m(2 + A)/6).
double node_mass(const UniformMesh& mesh, Index i, double blend) {
  return blend == 0.0 ? node_mass(mesh, i) : (1.0 + 0.5 * blend) * node_mass(mesh, i);
}

// Whether a weight may take the paper's own expression (the uniform mesh of a homogeneous bar, A = 0).
bool paper_mesh(const UniformMesh& mesh, double blend) { return blend == 0.0 && mesh.uniform() && mesh.homogeneous(); }

}  // namespace

MassRedistribution mod2(double blend) {
  checked_blend(blend);
  return on_blend({"mod2", "Mod 2: the contact node's mass is spread uniformly on the other nodes",
                   [blend](Index i, Index j, const UniformMesh& mesh) {
                     if (i == 0 || j == 0) return 0.0;
                     const double m_bar = mesh.bar_mass();
                     return m_bar / (m_bar - lost_mass(mesh, blend));
                   }},
                  blend);
}

// Spreading the lost mass 2h/3 in equal parts 2h/(3k) on the diagonal entries M_ii = 2h/3 of the
// nodes i = 1..k means the weight w_ii = 1 + 1/k there (node N, clamped, is never among them); on
// any other mesh, w_ii = 1 + m_lost/(k M_ii).
MassRedistribution spread_over_first_nodes(Index k, double blend) {
  if (k < 1) throw std::invalid_argument("spread_over_first_nodes: k must be >= 1");
  checked_blend(blend);
  return on_blend(
      {"spread:" + std::to_string(k), "the contact node's mass spread on the diagonal of nodes 1.." + std::to_string(k),
       [k, blend](Index i, Index j, const UniformMesh& mesh) {
         if (i == 0 || j == 0) return 0.0;
         if (k >= mesh.elements) throw std::invalid_argument("spread_over_first_nodes: k must be < N");
         if (!(i == j && i <= k)) return 1.0;
         if (paper_mesh(mesh, blend)) return 1.0 + 1.0 / static_cast<double>(k);
         return 1.0 + lost_mass(mesh, blend) / (static_cast<double>(k) * node_mass(mesh, i, blend));
       }},
      blend);
}

MassRedistribution mod3(double blend) {
  MassRedistribution r = spread_over_first_nodes(1);
  r.name = "mod3";
  r.description = "Mod 3: the contact node's mass is moved to the neighbouring node";
  if (blend == 0.0) return r;
  r.weight = spread_over_first_nodes(1, blend).weight;
  return on_blend(r, blend);
}

// The registry of the family: the named members and the parametrised forms (the latter defined
// below: node1, spread_over_first_nodes, beta).
const std::vector<MassFormInfo>& mass_form_registry() {
  static const std::vector<MassFormInfo> registry = {
      {"consistent", "", "the consistent P1 mass: the contact node keeps its inertia"},
      {"mod1", "", "Mod 1: the contact node's mass is dropped"},
      {"mod2", "", "Mod 2: the contact node's mass is spread uniformly on the other nodes"},
      {"mod3", "", "Mod 3: the contact node's mass is moved to node 1 (M̄₁₁ = 4h/3)"},
      {"node1", "X", "M̄₁₁ = X h on node 1, every other entry as Mod 1 (Mod 1 is node1:2/3, Mod 3 node1:4/3)"},
      {"spread", "K", "the lost mass 2h/3 in equal parts on the diagonal of nodes 1..K (spread:1 is Mod 3)"},
      {"beta", "B", "a point mass B h on node 1, the rest spread uniformly (Mod 2 is beta:0, Mod 3 beta:2/3)"},
  };
  return registry;
}

std::string spelling(const MassFormInfo& form) {
  return form.parameter.empty() ? form.id : form.id + ":" + form.parameter;
}

std::vector<std::string> mass_redistribution_names() {
  std::vector<std::string> names;
  for (const MassFormInfo& form : mass_form_registry())
    if (form.parameter.empty()) names.push_back(form.id);
  return names;
}

MassRedistribution mass_redistribution_by_name(const std::string& name, double blend) {
  if (name == "consistent") return consistent_mass(blend);
  if (name == "mod1") return mod1(blend);
  if (name == "mod2") return mod2(blend);
  if (name == "mod3") return mod3(blend);
  std::string allowed;
  for (const std::string& n : mass_redistribution_names()) allowed += (allowed.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown mass choice \"" + name + "\" (allowed: " + allowed + ")");
}

TEST_CASE("the mass registry lists every named member, each built under its own name, then the forms") {
  std::vector<std::string> spellings;
  for (const MassFormInfo& form : mass_form_registry()) spellings.push_back(spelling(form));
  CHECK(spellings == std::vector<std::string>{"consistent", "mod1", "mod2", "mod3", "node1:X", "spread:K", "beta:B"});
  for (const std::string& name : mass_redistribution_names()) {
    CAPTURE(name);
    CHECK(mass_redistribution_by_name(name).name == name);
  }
  CHECK(node1(1.0).name.rfind("node1:", 0) == 0);
  CHECK(spread_over_first_nodes(2).name.rfind("spread:", 0) == 0);
  CHECK(beta(0.5).name.rfind("beta:", 0) == 0);
}

Tridiagonal modified_mass_all_nodes(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  if (!redistribution.weight)
    throw std::invalid_argument("mass redistribution \"" + redistribution.name +
                                "\": no weight function (allowed: a function w(i, j, mesh))");
  Tridiagonal m = p1_blended_mass_all_nodes(mesh, redistribution.interior_blend);
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

// M^mod on the unknowns: the leading block of the all-nodes matrix, checked positive definite on the
// nodes with inertia.
static Tridiagonal unknowns_block(const Tridiagonal& all_nodes, const UniformMesh& mesh,
                                  const MassRedistribution& redistribution) {
  const Tridiagonal m = all_nodes.leading_block(mesh.unknowns());
  const Index first = contact_node_is_massless(m) ? 1 : 0;
  if (!tridiagonal_is_positive_definite(m, first))
    throw std::invalid_argument("mass redistribution \"" + redistribution.name +
                                "\": the weights must leave a positive definite mass on the nodes with inertia");
  return m;
}

Tridiagonal modified_mass(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  return unknowns_block(modified_mass_all_nodes(mesh, redistribution), mesh, redistribution);
}

AssembledMass assemble_mass(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  AssembledMass m;
  m.redistribution = redistribution;
  m.all_nodes = modified_mass_all_nodes(mesh, redistribution);
  m.matrix = unknowns_block(m.all_nodes, mesh, redistribution);
  m.massless = contact_node_is_massless(m.matrix);
  return m;
}

double total_mass(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  return modified_mass_all_nodes(mesh, redistribution).sum();
}

// ---------------------------------------------------------------------------------------------------

TEST_CASE("Mod 1 loses exactly 2h/3 of the total mass, and Mod 2, Mod 3 and the spreads preserve it") {
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

TEST_CASE("a mass assembled once is modified_mass, modified_mass_all_nodes and total_mass, bit for bit") {
  const auto same = [](const Tridiagonal& a, const Tridiagonal& b) {
    return a.size() == b.size() && a.diag == b.diag && a.lower == b.lower && a.upper == b.upper;
  };
  const UniformMesh layered = with_material(UniformMesh(2.5, 5), {4, 4, 1, 1, 1}, {1, 1, 1, 1, 1});
  for (const UniformMesh& mesh : {UniformMesh(1.0, 20), graded_mesh(1.0, 20, 1.05), layered})
    for (const MassRedistribution& r : {consistent_mass(), mod1(), mod3(), mod3(0.5)}) {
      CAPTURE(r.name);
      const AssembledMass m = assemble_mass(mesh, r);
      CHECK(m.redistribution.name == r.name);
      CHECK(same(m.matrix, modified_mass(mesh, r)));
      CHECK(same(m.all_nodes, modified_mass_all_nodes(mesh, r)));
      CHECK(m.total() == total_mass(mesh, r));
      CHECK(m.massless == (r.name != "consistent"));
    }
  MassRedistribution broken = mod3();
  broken.weight = [](Index i, Index j, const UniformMesh&) { return i == 1 && j == 1 ? -1.0 : 1.0; };
  CHECK_THROWS_AS(assemble_mass(UniformMesh(1.0, 10), broken), std::invalid_argument);
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

// ---------------------------------------------------------------------------------------------------
// More members of the family: a chosen mass on node 1, and a fraction on node 1 with the rest uniform.
//
// node1(X): M̄_11 = X h, every other entry as Mod 1 (no renormalisation of the total mass). Since
// M_11 = 2h/3 this is the weight w_11 = 3X/2; Mod 1 is node1(2/3), Mod 3 is node1(4/3), and the total
// mass is L − 2h/3 + (X − 2/3) h. GetFEM's demo_dynamic_contact_1D.py uses X = 7/6 ("redistributed")
// and X = 7/12 ("singular dynamic"), mathematics.md §13.
//
// beta(B): M̄ = w·(Mod 1) + B h e₁e₁ᵀ, a point mass B h on node 1 and the rest of the lost mass spread
// uniformly. Mod 1's total is L − 2h/3, so keeping the total L asks w (L − 2h/3) + B h = L, i.e.
//
//     w = (L − B h) / (L − 2h/3),        w_11 = w + B h / M_11 = w + 3B/2,
//
// and w = 1 + (2/3 − B) h / L + O(h²) is of the paper's form 1 + O(h). B = 0 gives w = L/(L − 2h/3),
// which is Mod 2; B = 2/3 gives w = 1, w_11 = 2, which is Mod 3. The uniform weight multiplies every
// entry of rows and columns 1..N (node N included, as for Mod 2), so that the total mass is L exactly.
//
// Whether a member is admissible depends on the mesh: w > 0 needs B < L/h, and the matrix must be
// positive definite on nodes 1..N−1 (node1(X) needs X above a threshold that tends to
// (2 − √3)/6 ≈ 0.045 as N grows). modified_mass checks this for the mesh at hand (and the weight of
// spread_over_first_nodes(K) refuses K ≥ N); the harness's spec parser (repro/mass_spec.cpp) calls it
// when a mesh is given.

namespace {

// The shortest decimal text that reads back to the same double (std::to_chars without a precision).
std::string shortest_decimal(double value) {
  char buffer[64];
  const auto [end, error] = std::to_chars(buffer, buffer + sizeof buffer, value);
  if (error != std::errc()) throw std::logic_error("shortest_decimal: buffer too small");
  return std::string(buffer, end);
}

}  // namespace

MassRedistribution node1(double x, double blend) {
  if (!(std::isfinite(x) && x > 0.0))
    throw std::invalid_argument("node1: X must be a positive finite number (M̄_11 = X h)");
  checked_blend(blend);
  return on_blend(
      {"node1:" + shortest_decimal(x),
       "M̄_11 = " + shortest_decimal(x) + " h on node 1, every other entry as Mod 1 (total not renormalised)",
       [x, blend](Index i, Index j, const UniformMesh& mesh) {
         if (i == 0 || j == 0) return 0.0;
         if (!(i == 1 && j == 1)) return 1.0;
         if (paper_mesh(mesh, blend)) return 1.5 * x;
         // M̄₁₁ = M^A₁₁ + (X − 2/3) ρ₀h₀: X − 2/3 of the contact element's mass added beyond Mod 1.
         return 1.0 + (x - 2.0 / 3.0) * mesh.density(0) * mesh.h(0) / node_mass(mesh, 1, blend);
       }},
      blend);
}

MassRedistribution beta(double b, double blend) {
  if (!std::isfinite(b)) throw std::invalid_argument("beta: B must be a finite number");
  checked_blend(blend);
  return on_blend(
      {"beta:" + shortest_decimal(b),
       "a point mass " + shortest_decimal(b) + " h on node 1, the rest of the lost mass spread uniformly (total L)",
       [b, blend](Index i, Index j, const UniformMesh& mesh) {
         if (i == 0 || j == 0) return 0.0;
         if (paper_mesh(mesh, blend)) {
           const double h = mesh.h();
           const double w = (mesh.length - b * h) / (mesh.length - 2.0 * h / 3.0);
           return (i == 1 && j == 1) ? w + 1.5 * b : w;
         }
         // A point mass B ρ₀h₀ on node 1, the rest of m_lost(A) by the density scale w.
         const double point = b * mesh.density(0) * mesh.h(0), m_bar = mesh.bar_mass();
         const double w = (m_bar - point) / (m_bar - lost_mass(mesh, blend));
         return (i == 1 && j == 1) ? w + point / node_mass(mesh, 1, blend) : w;
       }},
      blend);
}

// ---------------------------------------------------------------------------------------------------
// The period law's prediction for any member (mathematics.md §8).
//
// In free flight the contact row gives u₀ = u₁, element (0, h) moves rigidly and the free phase is a
// bar on [h, L] whose end x = h carries a point mass; in contact, node 0 is held. Against Mod 3 (whose
// free end carries exactly the inertia of the removed element, effective lengths ℓ_f = ℓ_c = L to
// O(h²)) a redistribution changes the benchmark's period P = 2ℓ_f + ℓ_c through two kinds of mass:
//
//   δm_loc   mass added at (or next to) node 1 beyond Mod 3's: it moves the free end of the free phase
//            by δm_loc (a point mass m at a free end acts, on the low modes, like a free end moved by
//            m), and nothing in contact, where every mode is O(kh) next to the held node;
//   δm_glob  mass spread uniformly over the bar (density 1 + δm_glob/L): the wave speed drops by the
//            factor 1 − δm_glob/(2L), so both lengths grow by δm_glob/2.
//
// Hence δℓ_f = δm_loc + δm_glob/2, δℓ_c = δm_glob/2 and ΔP = 2 δm_loc + (3/2) δm_glob, to first order
// in h. The first impact of the benchmark falls at ℓ_f, so it moves by δℓ_f.
//
// Splitting a matrix into the two: the uniform part is read off the far end of the bar, where a member
// of the family is Mod 1 times a constant weight. With the lumped masses r_i = Σ_j M̄_ij (all nodes
// 0..N; r_i = h at every interior node of Mod 1), the uniform excess is ε = r_{N−1}/h − 1 and
//
//     δm_glob = ε · 1ᵀ(Mod 1)1 = ε (L − 2h/3),       δm_loc = (1ᵀM̄1 − L) − δm_glob,
//
// i.e. everything that is not uniform is counted as local to the contact node. For the members here:
//   node1:X   ε = 0:                       δm_glob = 0,          δm_loc = (X − 4/3) h, ΔP = 2(X − 4/3) h
//             (Mod 1 −4h/3; GetFEM's 7/6: −h/3; its 7/12: −3h/2);
//   beta:B    ε = w − 1, total L:          δm_glob = (2/3 − B) h, δm_loc = (B − 2/3) h, ΔP = (B − 2/3) h/2
//             exactly (Mod 2 = beta:0: −h/3; Mod 3 = beta:2/3: 0);
//   spread:K  ε = 0 for K < N − 1, total L: δm_glob = δm_loc = 0, ΔP = 0 (the lost mass stays within Kh of
//             the contact node); spread:N−1 has ε = 2/(3(N − 1)) on every free node: nearly Mod 2.
// The split is exact for node1 and beta. For spread:K it assumes that the mass on nodes 1..K acts as a
// point mass at the free end, which holds when Kh ≪ L (the low modes do not vary over Kh); spread over
// a fixed fraction of the bar (K = N/2) lies outside the derivation, and the family study measures how
// far the law carries there. The split requires the far quarter of the bar (nodes N − ⌊N/4⌋ .. N − 1)
// to carry one uniform weight, and a massless contact node.

PeriodLawMasses period_law_masses(const UniformMesh& mesh, const MassRedistribution& redistribution) {
  if (mesh.elements < 4)
    throw std::invalid_argument("period_law_masses: the split needs N >= 4 (allowed: a mesh of 4 elements or more)");
  const Tridiagonal m = modified_mass_all_nodes(mesh, redistribution);
  if (!contact_node_is_massless(m))
    throw std::invalid_argument("period_law_masses: \"" + redistribution.name +
                                "\" keeps the inertia of the contact node (allowed: a redistribution)");
  const Index n = mesh.elements;
  const double h = mesh.h();
  auto lumped = [&m](Index i) { return m.lower[i] + m.diag[i] + m.upper[i]; };
  const double excess = lumped(n - 1) / h - 1.0;
  for (Index i = n - n / 4; i < n; ++i)
    if (std::abs(lumped(i) / h - 1.0 - excess) > 1e-12 * (1.0 + std::abs(excess)))
      throw std::invalid_argument("period_law_masses: \"" + redistribution.name +
                                  "\" is not uniform on the far quarter of the bar (allowed: a member that is "
                                  "Mod 1 times a constant weight away from the contact node)");
  PeriodLawMasses masses;
  masses.uniform = excess * (mesh.length - 2.0 * h / 3.0);
  masses.local = (m.sum() - mesh.length) - masses.uniform;
  return masses;
}

// ---------------------------------------------------------------------------------------------------

namespace {

// max over all entries of |A − B|, on all nodes 0..N.
[[maybe_unused]] double max_entry_difference(const UniformMesh& mesh, const MassRedistribution& a,
                                             const MassRedistribution& b) {
  const Tridiagonal ma = modified_mass_all_nodes(mesh, a), mb = modified_mass_all_nodes(mesh, b);
  return std::max({(ma.diag - mb.diag).cwiseAbs().maxCoeff(), (ma.upper - mb.upper).cwiseAbs().maxCoeff(),
                   (ma.lower - mb.lower).cwiseAbs().maxCoeff()});
}

}  // namespace

TEST_CASE("node1(2/3) is Mod 1 and node1(4/3) is Mod 3, entry by entry") {
  for (Index n : {4, 10, 101, 1000}) {
    const UniformMesh mesh(1.5, n);
    const double h = mesh.h();
    CAPTURE(n);
    CHECK(max_entry_difference(mesh, node1(2.0 / 3.0), mod1()) <= 4e-16 * h);
    CHECK(max_entry_difference(mesh, node1(4.0 / 3.0), mod3()) <= 4e-16 * h);
    // and a different X is a different matrix, on node 1 only
    CHECK(std::abs(modified_mass(mesh, node1(7.0 / 6.0)).diag[1] - 7.0 * h / 6.0) <= 4e-16 * h);
    CHECK(max_entry_difference(mesh, node1(7.0 / 6.0), mod3()) > 0.1 * h);
  }
}

TEST_CASE("beta(0) is Mod 2 and beta(2/3) is Mod 3 to round-off") {
  for (Index n : {4, 10, 101, 1000}) {
    const UniformMesh mesh(1.5, n);
    const double h = mesh.h();
    CAPTURE(n);
    CHECK(max_entry_difference(mesh, beta(0.0), mod2()) <= 4e-16 * h);
    CHECK(max_entry_difference(mesh, beta(2.0 / 3.0), mod3()) <= 4e-16 * h);
    CHECK(max_entry_difference(mesh, beta(1.0 / 3.0), mod3()) > 0.1 * h);
  }
}

TEST_CASE("total masses: node1(X) is L - 2h/3 + (X - 2/3)h, every beta(B) keeps L") {
  for (double length : {1.0, 2.5}) {
    for (Index n : {5, 64, 1000}) {
      const UniformMesh mesh(length, n);
      const double h = mesh.h();
      CAPTURE(length);
      CAPTURE(n);
      for (double x : {1.0 / 3.0, 7.0 / 12.0, 7.0 / 6.0, 2.0}) {
        CAPTURE(x);
        CHECK(std::abs(total_mass(mesh, node1(x)) - (length - 2 * h / 3 + (x - 2.0 / 3.0) * h)) < 1e-13 * length);
      }
      for (double b : {-0.1, 1.0 / 6.0, 1.0 / 3.0, 1.0, 4.0 / 3.0}) {
        CAPTURE(b);
        CHECK(std::abs(total_mass(mesh, beta(b)) - length) < 1e-13 * length);
      }
    }
  }
}

TEST_CASE("the period law's split refuses the consistent mass and a weight that varies along the bar") {
  const UniformMesh mesh(1.0, 20);
  CHECK_THROWS_WITH_AS(period_law_masses(mesh, consistent_mass()), doctest::Contains("keeps the inertia"),
                       std::invalid_argument);
  const MassRedistribution graded{"graded", "", [](Index i, Index j, const UniformMesh& m) {
                                    return (i == 0 || j == 0) ? 0.0 : 1.0 + 0.01 * m.x(i + j) / m.length;
                                  }};
  CHECK_THROWS_WITH_AS(period_law_masses(mesh, graded), doctest::Contains("not uniform"), std::invalid_argument);
  CHECK_THROWS_AS(period_law_masses(UniformMesh(1.0, 3), mod3()), std::invalid_argument);
}

// ---------------------------------------------------------------------------------------------------
// The family on unequal elements and piecewise material (the reconstruction above).

TEST_CASE("on graded layered meshes Mod 3 is P^T M P, Mod 1 loses 2 rho0 h0/3, the others keep the bar's mass") {
  std::vector<double> young(16, 1.0), density(16, 1.0);
  for (int e = 0; e < 5; ++e) young[e] = 3.0, density[e] = 2.5;
  for (const double r : {1.0, 1.08, 0.95}) {
    for (const bool layered : {false, true}) {
      const UniformMesh mesh =
          layered ? with_material(graded_mesh(1.0, 16, r), young, density) : graded_mesh(1.0, 16, r);
      const double m_bar = mesh.bar_mass(), lost = 2 * mesh.density(0) * mesh.h(0) / 3;
      CAPTURE(r);
      CAPTURE(layered);
      CHECK(std::abs(lost_mass(mesh) - lost) < 1e-16);
      CHECK(std::abs(total_mass(mesh, mod1()) - (m_bar - lost)) < 1e-14);
      for (const MassRedistribution& m :
           {mod2(), mod3(), spread_over_first_nodes(4), spread_over_first_nodes(15), beta(1.0 / 3)}) {
        CAPTURE(m.name);
        CHECK(std::abs(total_mass(mesh, m) - m_bar) < 1e-14);
      }
      // Mod 3 = PᵀMP, P the kinematics u₀ := u₁: M̄₁₁ = M₀₀ + 2M₀₁ + M₁₁, every other entry M's.
      const Tridiagonal m = p1_mass_all_nodes(mesh), m3 = modified_mass_all_nodes(mesh, mod3());
      CHECK(std::abs(m3.diag[1] - (m.diag[0] + 2 * m.upper[0] + m.diag[1])) < 1e-16);
      CHECK(m3.diag[2] == m.diag[2]);
      CHECK(m3.upper[1] == m.upper[1]);
      // node1:X adds (X − 2/3) ρ₀h₀ beyond Mod 1; node1:4/3 is Mod 3, node1:2/3 Mod 1.
      CHECK(std::abs(modified_mass_all_nodes(mesh, node1(4.0 / 3)).diag[1] - m3.diag[1]) < 1e-16);
      CHECK(std::abs(modified_mass_all_nodes(mesh, node1(2.0 / 3)).diag[1] - m.diag[1]) < 1e-16);
      // beta:2/3 is Mod 3 and beta:0 Mod 2.
      CHECK(std::abs(modified_mass_all_nodes(mesh, beta(2.0 / 3)).diag[1] - m3.diag[1]) < 1e-15);
      CHECK(std::abs(modified_mass_all_nodes(mesh, beta(0.0)).diag[5] - modified_mass_all_nodes(mesh, mod2()).diag[5]) <
            1e-15);
    }
  }
}

}  // namespace mrm
