// The mass option's text: a spec string names a member of the weighted redistribution family
// (lib/fem/mass_redistribution.hpp: mrm::node1, mrm::beta, mrm::spread_over_first_nodes and the named Mod 1/2/3
// and consistent masses). The library constructs the members and checks them on a mesh; reading them
// from a command line is the harness's.
#pragma once

#include <string>

#include "fem/mass_redistribution.hpp"

namespace mrm::repro {

/// The spec strings accepted by mass_redistribution_from_spec, in words (for messages and help texts).
std::string mass_redistribution_forms();
/// The help text of a program's mass option: `what`, then the forms of the library's registry
/// (mrm::mass_form_registry).
std::string mass_option_help(const std::string& what);
/// The member named by a spec string: consistent | mod1 | mod2 | mod3 | node1:X | spread:K | beta:B,
/// X and B decimals or fractions ("7/6"); its name is the spec. Throws std::invalid_argument, with a
/// message starting with the quoted spec and ending with the allowed forms, for what is wrong on any
/// mesh (unparseable, X <= 0, K < 1).
MassRedistribution mass_redistribution_from_spec(const std::string& spec, double blend = 0.0);
/// The same, checked on the mesh at hand: also K <= N - 1 and a mass that is positive definite on
/// the nodes that keep inertia (mrm::modified_mass).
MassRedistribution mass_redistribution_from_spec(const std::string& spec, const UniformMesh& mesh, double blend = 0.0);
/// The same, with M^mod as the check assembled it on the mesh (mrm::assemble_mass), for a run that reads
/// it rather than assembling it again.
AssembledMass assembled_mass_from_spec(const std::string& spec, const UniformMesh& mesh, double blend = 0.0);

/// The interior mass forms, in words: "consistent, lumped, blend:A with A a decimal or a fraction in [0, 1]".
std::string interior_mass_forms();
/// The blend A of an interior mass spec (lib/fem/interior_mass.hpp): consistent (0), lumped (1) or
/// blend:A, A a decimal or a fraction such as 1/4 in [0, 1]. Throws std::invalid_argument starting with
/// the quoted spec and ending with the allowed forms otherwise. (`blend` in the two functions above is
/// this A: each member is then defined on the blended mass, mrm::mass_redistribution.)
double interior_blend_from_spec(const std::string& spec);

}  // namespace mrm::repro
