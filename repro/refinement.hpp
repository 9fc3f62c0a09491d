/// @file refinement.hpp
/// @brief A study's family of meshes N₀, 2N₀, …, 2^(K−1) N₀ on the unit bar and the orders observed
/// over it: the least-squares order over every mesh and the local orders between successive meshes.
#pragma once

#include <cstddef>
#include <vector>

#include "core/problem.hpp"
#include "studies/convergence.hpp"

namespace mrm::repro {

/// The meshes of a convergence study in h: level l has N_l = 2^l N₀ elements and h_l = 1/N_l (the unit
/// bar), l = 0 … K − 1. The orders of an error measured on each level are those of e ≈ C h^p.
class MeshRefinement {
 public:
  /// The K = `levels` meshes from N₀ = `coarsest` elements on (K ≥ 1).
  MeshRefinement(Index coarsest, std::size_t levels);
  /// K, the number of meshes.
  std::size_t levels() const { return levels_; }
  /// N₀, the coarsest mesh's elements.
  Index coarsest() const { return coarsest_; }
  /// N_l = 2^l N₀.
  Index elements(std::size_t level) const { return coarsest_ << level; }
  /// N_{K−1} = 2^(K−1) N₀.
  Index finest() const { return elements(levels_ - 1); }
  /// h_l = 1/N_l for l = 0 … K − 1.
  const std::vector<double>& mesh_sizes() const { return mesh_sizes_; }
  /// The least-squares order p of e_l ≈ C h_l^p over every mesh (mrm::fit_order; its exceptions).
  OrderFit fit(const std::vector<double>& errors) const;
  /// The local order between the two finest meshes, log₂(e_{K−2}/e_{K−1}) (local_orders, repro/table).
  double finest_local_order(const std::vector<double>& errors) const;

 private:
  Index coarsest_;
  std::size_t levels_;
  std::vector<double> mesh_sizes_;
};

}  // namespace mrm::repro
