/// @file refinement.cpp
/// @brief The meshes of a convergence study in h and the orders observed over them; see refinement.hpp.
#include "refinement.hpp"

#include <cmath>
#include <stdexcept>

#include <doctest/doctest.h>

#include "table.hpp"

namespace mrm::repro {

MeshRefinement::MeshRefinement(Index coarsest, std::size_t levels) : coarsest_(coarsest), levels_(levels) {
  if (coarsest < 1 || levels < 1) throw std::invalid_argument("MeshRefinement: N0 and K must be at least 1");
  for (std::size_t l = 0; l < levels; ++l) mesh_sizes_.push_back(1.0 / static_cast<double>(elements(l)));
}

OrderFit MeshRefinement::fit(const std::vector<double>& errors) const { return fit_order(mesh_sizes_, errors); }

double MeshRefinement::finest_local_order(const std::vector<double>& errors) const {
  return local_orders(mesh_sizes_, errors).back();
}

TEST_CASE("a refinement doubles N from N0 and reads the orders of e = C h^p off its meshes") {
  const MeshRefinement meshes(20, 4);
  CHECK(meshes.elements(0) == 20);
  CHECK(meshes.elements(3) == 160);
  CHECK(meshes.finest() == 160);
  REQUIRE(meshes.mesh_sizes().size() == 4);
  CHECK(meshes.mesh_sizes()[1] == 1.0 / 40);
  // e = 3 h^1.5 exactly in the fit, and 2^-1.5 between two meshes.
  std::vector<double> errors;
  for (double h : meshes.mesh_sizes()) errors.push_back(3 * std::pow(h, 1.5));
  CHECK(meshes.fit(errors).order == doctest::Approx(1.5).epsilon(1e-12));
  CHECK(meshes.finest_local_order(errors) == doctest::Approx(1.5).epsilon(1e-12));
  CHECK_THROWS_AS(MeshRefinement(0, 3), std::invalid_argument);
}

}  // namespace mrm::repro
