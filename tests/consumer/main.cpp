// A consumer of the installed library: assembles the Mod 3 mass matrix on all nodes of a mesh of
// (0, L) and prints L and the matrix's total 1ᵀ M^mod 1 (mathematics.md §3: Mod 3 moves the contact
// node's mass 2h/3 onto node 1, so the total stays L). tests/consumer/run.sh compares the two.
#include <cstdio>

#include "fem/mass_redistribution.hpp"
#include "fem/p1.hpp"

int main() {
  const double length = 2.5;
  const mrm::UniformMesh mesh(length, 40);
  const mrm::Tridiagonal mass = mrm::modified_mass_all_nodes(mesh, mrm::mod3());
  std::printf("length = %.17g\ntotal = %.17g\n", length, mass.sum());
  return 0;
}
