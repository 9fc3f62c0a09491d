/// @file configurations/two_bodies.hpp
/// @brief two-bars by symmetry (one bar against a wall at half the gap) and the true two-body run.
#pragma once

#include "configurations/run.hpp"

namespace mrm::repro {

/// two-bars by symmetry (configurations/two_bodies.cpp, derived there): the one-bar problem each of the two
/// identical bodies solves, a free bar (L = 10, velocity −0.1) against a rigid wall at g₀/2.
std::shared_ptr<const ImpactBenchmark> two_bars_by_symmetry();
/// Makes a two-bars configuration run as two_bars_by_symmetry's one-bar problem, with every class of the
/// registry (the two-body run takes cn with a massless contact node only): its field, and γ₀' = 2γ₀ for
/// penalty and Nitsche.
void reduce_two_bars_by_symmetry(Configuration& configuration);

/// Runs a two-bodies configuration (two-bars, Crank–Nicolson) with the measures of run_configuration.
Measures run_two_bodies(const Configuration& configuration);

}  // namespace mrm::repro
