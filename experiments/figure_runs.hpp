// What the figure programs share: the list of schemes and mass choices of the paper's Figure 1 and the
// one place where a configuration (scheme, Paoli–Schatzman contact row, mass) becomes a simulation.
#pragma once

#include <string>
#include <vector>

#include "mass_redistribution.hpp"
#include "schemes.hpp"

namespace figures {

/// The three schemes of the paper, in the order of its Figure 1 and of every data file.
inline const std::vector<std::string>& scheme_names() {
  static const std::vector<std::string> names{"cn", "be", "ps"};
  return names;
}
/// The three mass choices of the paper.
inline const std::vector<std::string>& mass_names() {
  static const std::vector<std::string> names{"mod1", "mod2", "mod3"};
  return names;
}

inline std::string scheme_label(const std::string& scheme) {
  if (scheme == "cn") return "Crank-Nicolson";
  if (scheme == "be") return "backward Euler";
  return "Paoli-Schatzman (1/4, 0)";
}

/// The scheme's parameters; Paoli–Schatzman with β = ¼, e = 0 and the given contact row (a mass that
/// keeps the contact node's inertia always takes the literal row: it has no algebraic one).
inline mrm::SchemeParameters scheme_parameters(const std::string& scheme, const std::string& ps_form,
                                               const std::string& mass) {
  mrm::SchemeParameters p;
  p.scheme = mrm::scheme_by_name(scheme);
  p.beta = 0.25;
  p.restitution = 0.0;
  p.contact_row = mass == "consistent" ? mrm::ContactRow::literal : mrm::contact_row_by_name(ps_form);
  return p;
}

}  // namespace figures
