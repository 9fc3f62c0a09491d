/// @file mass_redistribution.hpp
/// @brief The weighted mass-redistribution family of the paper (§2) and its instances Mod 1/2/3.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "fem/p1.hpp"

namespace mrm {

/// A choice of the weights w_{h,ij} of the paper's weighted modified mass
/// M^mod_ij = ∫ φ_i φ_j w_{h,ij} dx = w_{h,ij} M_ij (weights constant per entry), on all nodes 0..N.
/// A redistribution removes the inertia of the contact node when w_{h,0j} = w_{h,j0} = 0 for all j.
struct MassRedistribution {
  std::string name;         ///< short name used on command lines and in data files ("mod3")
  std::string description;  ///< one line for help texts and reports
  /// w(i, j, mesh) for |i − j| ≤ 1, 0 ≤ i, j ≤ N; must be symmetric in (i, j).
  std::function<double(Index i, Index j, const UniformMesh& mesh)> weight;
  /// The interior mass blend A ∈ [0, 1] (interior_mass.hpp): the weights multiply the entries
  /// of M^A = (1 − A) M + A M_L (p1_blended_mass_all_nodes) instead of M's. 0, the paper's consistent
  /// mass, by default. Set by the constructors below (their argument `blend`), which define each member
  /// on M^A by what it does with M^A's lost mass; a weight written for A = 0 keeps A = 0.
  double interior_blend = 0.0;
};

/// The mass that removing row and column 0 takes off the bar: M₀₀ + 2M₀₁ = 2ρ₀h₀/3 (2h/3 on the
/// paper's mesh). Every member of the family is defined by what it does with it (mass_redistribution.cpp).
double lost_mass(const UniformMesh& mesh);
/// The same on the blended interior mass M^A: M^A₀₀ + 2M^A₀₁ = (2/3 − A/6) ρ₀h₀ (lost_mass for A = 0).
double lost_mass(const UniformMesh& mesh, double blend);

// Every constructor below takes the interior mass blend A (default 0: the paper's family) and defines its
// member on M^A by what it does with M^A's lost mass (mass_redistribution.cpp, "the family on the
// blended interior mass"); it throws std::invalid_argument unless 0 ≤ A ≤ 1.

/// The consistent (unmodified) P1 mass: w ≡ 1, the contact node keeps its inertia.
MassRedistribution consistent_mass(double blend = 0.0);
/// Mod 1: the contact node's mass is dropped (w_{0j} = 0, w = 1 elsewhere).
MassRedistribution mod1(double blend = 0.0);
/// Mod 2: the contact node's mass is spread uniformly: w = L/(L − 2h/3) on the other nodes.
MassRedistribution mod2(double blend = 0.0);
/// Mod 3: the contact node's mass is moved to node 1: w_11 = 2 (M̄_11 = 4h/3).
MassRedistribution mod3(double blend = 0.0);
/// The lost mass 2h/3 spread in equal parts on the diagonal of nodes 1..k (k = 1 is Mod 3).
MassRedistribution spread_over_first_nodes(Index k, double blend = 0.0);

/// One entry of the registry of the family's members: a named member (consistent, mod1, mod2, mod3) or
/// a parametrised form (node1:X, spread:K, beta:B). The harness's help texts, choice lists and spec
/// parser read it.
struct MassFormInfo {
  std::string id;         ///< the name, or the form's prefix before the colon ("node1")
  std::string parameter;  ///< the parameter's placeholder ("X"), empty for a named member
  std::string summary;    ///< one line for help texts and reports
};
/// The named members and the parametrised forms, in this order: consistent, mod1, mod2, mod3, node1:X,
/// spread:K, beta:B (mass_redistribution.cpp). Adding a member is: its weights, its doctests, one entry.
const std::vector<MassFormInfo>& mass_form_registry();
/// How a registry entry is written on a command line: the id, or "id:parameter" ("node1:X").
std::string spelling(const MassFormInfo& form);

/// The named members of the registry (those without a parameter): consistent, mod1, mod2, mod3.
std::vector<std::string> mass_redistribution_names();
/// The named member; throws std::invalid_argument listing the allowed names for an unknown name.
MassRedistribution mass_redistribution_by_name(const std::string& name, double blend = 0.0);

/// M^mod on all nodes 0..N (clamped node included; used for the total mass).
Tridiagonal modified_mass_all_nodes(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// M^mod on the unknowns 0..N-1. Throws std::invalid_argument unless the weights are symmetric and
/// finite, and M^mod is positive definite on the nodes that keep inertia (all of them, or 1..N-1
/// when row and column 0 vanish).
Tridiagonal modified_mass(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// The total mass 1ᵀ M^mod 1 over all nodes 0..N (L for the consistent mass).
double total_mass(const UniformMesh& mesh, const MassRedistribution& redistribution);
/// True when row and column 0 of the mass matrix vanish: the contact node has no inertia.
bool contact_node_is_massless(const Tridiagonal& mass);

/// The mass of a run, assembled once from its redistribution on its mesh and read by everything of the
/// run that needs it (the step, the checks, the total mass, the period law), so that M^mod is formed
/// once per run: M^mod on every node, its block on the unknowns, and whether the contact node is massless.
struct AssembledMass {
  MassRedistribution redistribution;  ///< the redistribution it was assembled from
  Tridiagonal all_nodes;              ///< M^mod on all nodes 0..N (modified_mass_all_nodes)
  Tridiagonal matrix;                 ///< M^mod on the unknowns 0..N-1 (modified_mass)
  bool massless = false;              ///< contact_node_is_massless(matrix)
  /// The total mass 1ᵀ M^mod 1 over all nodes (total_mass).
  double total() const { return all_nodes.sum(); }
};
/// M^mod of `redistribution` on `mesh`, assembled once; throws std::invalid_argument where
/// modified_mass does.
AssembledMass assemble_mass(const UniformMesh& mesh, const MassRedistribution& redistribution);

/// M̄_11 = X h on node 1 (weight w_11 = 3X/2), every other entry as Mod 1, the total not renormalised:
/// Mod 1 is node1(2/3), Mod 3 is node1(4/3). Throws std::invalid_argument unless X > 0 is finite.
MassRedistribution node1(double x, double blend = 0.0);
/// M̄ = w·(Mod 1) + B h e₁e₁ᵀ with w = (L − Bh)/(L − 2h/3) keeping the total mass L: beta(0) is Mod 2,
/// beta(2/3) is Mod 3. Throws std::invalid_argument unless B is finite.
MassRedistribution beta(double b, double blend = 0.0);

/// The two masses of the period law (mathematics.md §8), relative to Mod 3; the period changes by
/// ΔP = predicted_period_change(local, uniform) (period_law.hpp) = 2 δm_loc + (3/2) δm_glob.
struct PeriodLawMasses {
  double local = 0.0;    ///< δm_loc: the mass at the contact end beyond Mod 3's M̄_11 = 4h/3
  double uniform = 0.0;  ///< δm_glob: the mass spread uniformly over the bar
};
/// The split of a redistribution: the uniform excess read off the far end of the bar, the rest counted
/// as local (exact for node1, beta, Mod 1/2/3; for spread:K it assumes Kh << L). Throws
/// std::invalid_argument for N < 4, a massive contact node, or a far quarter without a uniform weight.
PeriodLawMasses period_law_masses(const UniformMesh& mesh, const MassRedistribution& redistribution);

}  // namespace mrm
