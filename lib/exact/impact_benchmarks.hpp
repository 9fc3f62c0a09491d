/// @file impact_benchmarks.hpp
/// @brief The field's impact benchmarks as chains (doc/benchmarks.md §3–§7): bouncing, impacting,
/// gravity-paper, two-bars and layered, each with its initial data and its default horizon, and the
/// registry that names them.
#pragma once

#include <string>
#include <vector>

#include "exact/impact_chain.hpp"

namespace mrm {

/// What a configuration needs beyond the paper's problem (f = 0, clamped far end, no gap, one
/// homogeneous bar), in words: "a load f", "a free far end", "an initial gap", "segments of different
/// E or rho", "two bodies in contact", joined by ", "; empty for the paper's problem.
std::string configuration_features(const ImpactConfiguration& configuration);

/// A named benchmark of the field (doc/benchmarks.md): its chain, its initial data and its default horizon
/// (the first two periods or the first three contacts), in its own units.
struct ImpactBenchmark {
  std::string id;                     ///< the name on the command line
  std::string summary;                ///< one line: what it is
  std::string source;                 ///< where its data come from
  std::string time_unit;              ///< "s" for SI data, empty for dimensionless ones
  ImpactConfiguration configuration;  ///< the chain
  InitialData data;                   ///< u⁰, v⁰ (breakpoints at every junction)
  double final_time;                  ///< the default horizon T
};
/// bouncing, impacting, gravity-paper, two-bars, layered (data in impact_benchmarks.cpp, derived there).
const std::vector<ImpactBenchmark>& impact_benchmarks();
/// The benchmark named `id`; throws InvalidParameter("benchmark", … the allowed names) otherwise.
const ImpactBenchmark& impact_benchmark(const std::string& id);
}  // namespace mrm
