/// @file claims/mass.cpp
/// @brief Claim 2: Mod 2 and Mod 3 preserve the total mass, Mod 1 does not.
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

#include "batched/batched_step.hpp"
#include "claims.hpp"
#include "claims/wording.hpp"
#include "configurations.hpp"
#include "exact/exact_solution.hpp"
#include "labels.hpp"
#include "fem/period_law.hpp"
#include "regions.hpp"
#include "report_values.hpp"
#include "studies/convergence.hpp"
#include "sweep.hpp"
#include "table.hpp"
#include "steps/contact.hpp"
#include "time_family.hpp"

namespace mrm::claims {

// ---------------------------------------------------------------------------------------------------
// Claim 2: total mass (paper §2: "la masse totale du matériau est préservée").
//
// The total mass is 1ᵀM^mod1 over all nodes 0..N, L for the consistent mass. Summing the 3N + 1
// positive entries in floating point commits a relative error of at most about (3N + 1)ε, so the
// criterion is |1ᵀM^mod1 − L| ≤ 4(N + 1)εL for Mod 2 and Mod 3, and |1ᵀM^mod1 − (L − 2h/3)| ≤ 4(N + 1)εL
// for Mod 1 (it drops row and column 0, M_00 + 2M_01 = 2h/3): "exactly 2h/3" up to that round-off.
namespace {

struct MassDeviation {
  double worst_ratio = 0;     // max |deviation| / tolerance
  double worst_relative = 0;  // max |deviation| / L
  std::string worst_mesh;
};

MassDeviation mass_deviation(const MassRedistribution& mass, const std::vector<UniformMesh>& meshes, double lost) {
  MassDeviation d;
  for (const UniformMesh& mesh : meshes) {
    const double expected = mesh.length - lost * mesh.h();
    const double deviation = std::abs(total_mass(mesh, mass) - expected);
    const double tolerance =
        4.0 * static_cast<double>(mesh.elements + 1) * std::numeric_limits<double>::epsilon() * mesh.length;
    if (deviation / tolerance >= d.worst_ratio) {
      d.worst_ratio = deviation / tolerance;
      d.worst_mesh = "L = " + significant(mesh.length) + ", N = " + std::to_string(mesh.elements);
    }
    d.worst_relative = std::max(d.worst_relative, deviation / mesh.length);
  }
  return d;
}

std::string list_meshes(const std::vector<UniformMesh>& meshes) {
  std::vector<std::string> s;
  for (const UniformMesh& m : meshes)
    s.push_back("(" + significant(m.length) + ", " + std::to_string(m.elements) + ")");
  return join(s, " ");
}

}  // namespace

std::vector<ClaimResult> check_mass(const std::vector<MassRedistribution>& preserving,
                                    const std::vector<MassRedistribution>& dropping,
                                    const std::vector<UniformMesh>& meshes, Judge& judge) {
  std::vector<ClaimResult> rows;
  const std::string tolerance = "≤ 4(N + 1)εL on every mesh (L, N) of " + list_meshes(meshes) +
                                ". Basis (theory): the round-off of a sum of 3N + 1 positive terms";
  for (const auto& [masses, lost] : {std::pair{&preserving, 0.0}, std::pair{&dropping, 2.0 / 3.0}}) {
    for (const MassRedistribution& mass : *masses) {
      const MassDeviation d = mass_deviation(mass, meshes, lost);
      const bool preserves = lost == 0.0;
      rows.push_back(judge(
          "2/" + mass.name,
          "Mass: " + mass.name + (preserves ? " preserves the total mass L" : " loses exactly 2h/3 of the total mass"),
          "max |deviation|/L = " + significant(d.worst_relative) + ", at most " + decimals(d.worst_ratio, 3) +
              " × the tolerance (worst: " + d.worst_mesh + ")",
          (preserves ? "|1ᵀM 1 − L| " : "|1ᵀM 1 − (L − 2h/3)| ") + tolerance,
          at_most("largest |deviation|/tolerance", d.worst_ratio, 1)));
    }
  }
  return rows;
}

TEST_CASE("the mass check fails for a weight that loses mass and for a wrong claim about Mod 2") {
  const std::vector<UniformMesh> meshes = {UniformMesh(1.0, 10), UniformMesh(2.5, 1000)};
  MassRedistribution leaky = mod3();
  leaky.name = "leaky";
  leaky.weight = [](Index i, Index j, const UniformMesh&) {  // only half of the lost 2h/3 moved to node 1
    return (i == 0 || j == 0) ? 0.0 : (i == 1 && j == 1) ? 1.5 : 1.0;
  };
  Judge judge;
  for (const ClaimResult& row : check_mass({leaky}, {mod2()}, meshes, judge)) {
    CAPTURE(row.id);
    CAPTURE(row.measured);
    CHECK(row.verdict == Verdict::failed);
  }
  for (const ClaimResult& row : check_mass({mod2(), mod3()}, {mod1()}, meshes, judge)) {
    CAPTURE(row.id);
    CHECK(row.verdict == Verdict::reproduced);
  }
}

}  // namespace mrm::claims
