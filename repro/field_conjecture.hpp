/// @file field_conjecture.hpp
/// @brief The conjectured orders in h of Crank–Nicolson with Mod 1/2/3 on the field's benchmarks (the
/// tables of fig_benchmark_convergence and field_asymptotics), from lib/studies/smeared_orders.
#pragma once

#include <cstddef>
#include <string>

namespace mrm::repro {

/// The conjectured order in h of the error measure `measure` (the order of ErrorAccumulator::names) of
/// Crank–Nicolson at Δt = h/(2c) with the mass `mass` ("mod1", "mod2", "mod3") on the field benchmark
/// `benchmark` (bouncing, impacting, layered, two-bars: an impact then a release; gravity-paper: a
/// persistent contact: field_benchmark_releases); 0 where the measure is identically 0 (gravity-paper's
/// u(0,·)). Throws std::invalid_argument for another benchmark, mass or measure.
double field_conjectured_order(const std::string& benchmark, const std::string& mass, std::size_t measure);

/// The conjectured order in h of the error of the first release (the end of the first contact window)
/// on the benchmarks with a release, for the same runs: 2/3 (release_shift_order).
double field_release_order();

/// Whether the benchmark's first exact contact window ends within its horizon (every field benchmark
/// but gravity-paper, whose contact persists); throws for an id that is not a field benchmark.
bool field_benchmark_releases(const std::string& benchmark);

}  // namespace mrm::repro
