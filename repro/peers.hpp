/// @file peers.hpp
/// @brief The configurations that match a peer code's run (bar1d --peer): GetFEM's
/// demo_dynamic_contact_1D.py, versions 0–4, at its defaults (field.md §2, beyond.md §7).
#pragma once

#include <string>
#include <vector>

#include "schemes.hpp"

namespace mrm::repro {

/// Every parameter of a bar1d run that a peer's defaults set; the usual options override each of them.
struct PeerPreset {
  std::string id;                       ///< the --peer value ("getfem-v2")
  std::string summary;                  ///< one line for the help text
  std::string formulation;              ///< what the match required (printed by bar1d as peer_formulation)
  long elements = 20;                   ///< NX
  double dt = 0.002;                    ///< dt
  double final_time = 12;               ///< T
  std::string mass = "consistent";      ///< the demo's mass_matrix_type 0 (standard)
  SchemeParameters scheme;              ///< the scheme with the demo's parameters
  std::string initial = "interpolant";  ///< u₀(0) = u⁰(0), as the demo (a massless node only)
  std::string contact_velocity = "backward-difference";  ///< V₀ as the demo (a massless node only)
};

/// The presets, GetFEM's demo versions 0–3 (4, Taylor–Flanagan, is added with its scheme).
const std::vector<PeerPreset>& peer_presets();
/// The ids of peer_presets(), in order.
std::vector<std::string> peer_names();
/// The preset named `id`; throws std::invalid_argument listing the allowed ids.
const PeerPreset& peer_preset(const std::string& id);

}  // namespace mrm::repro
