/// @file benchmarks.hpp
/// @brief The registry of benchmarks: each benchmark a program can run (the paper's, the smooth S1 and
/// S2, the field's) is one entry that knows its id, its summary and literature, its time unit and
/// default horizon, and builds its problem, its mesh and its exact solution.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/problem.hpp"
#include "exact/characteristics.hpp"
#include "exact/impact_benchmarks.hpp"
#include "exact/reference_solution.hpp"
#include "exact/smooth_benchmarks.hpp"
#include "fem/p1.hpp"

namespace mrm {

/// Where a benchmark's data and exact solution come from.
enum class BenchmarkKind {
  paper,   ///< u⁰(x) = a (L − x), v⁰ = 0 on (0, L): the closed form of mathematics.md §2
  smooth,  ///< smooth data of mathematics.md §11 on (0, 1): the characteristic solution (§10)
  field,   ///< a chain of the field (doc/benchmarks.md §3–§7): its load, gap, material, far end, units
};

/// One entry of the registry of benchmarks: everything the library and the programs name or decide
/// about a benchmark, spelled once (as SchemeInfo is for a scheme): its id on command lines, its one-line
/// summary for help texts, where its data come from, its time unit and default horizon, and the builders
/// of its problem, mesh and exact solution.
struct Benchmark {
  std::string id;                          ///< the name on the command line ("paper", "grazing", "layered")
  std::string summary;                     ///< one line for help texts
  std::string source;                      ///< where its data come from (the paper, doc/benchmarks.md §…)
  std::string time_unit;                   ///< "s" for SI data, empty for dimensionless ones
  double final_time;                       ///< the default horizon T, in its time unit
  BenchmarkKind kind;                      ///< the paper's, a smooth one or a field one
  SmoothBenchmark smooth;                  ///< which smooth benchmark (kind smooth only)
  const ImpactBenchmark* field = nullptr;  ///< its chain and data (kind field only; null otherwise)

  /// Whether the bar's length L and the amplitude a are chosen by the run (the paper's benchmark only:
  /// the smooth benchmarks have L = 1, a field benchmark its own chain).
  bool takes_length() const { return kind == BenchmarkKind::paper; }
  /// Whether it is two bodies in contact with each other (two-bars: is_two_body_chain), which has no
  /// one-body problem nor mesh of its own.
  bool two_bodies() const;
  /// The wave speed √(E/ρ) at the contact end (1 but on a field benchmark).
  double wave_speed() const;
  /// The length of its bar: `length` on the paper's, 1 on the smooth ones, the chain's Σℓ on a field one.
  double bar_length(double length = 1.0) const;
  /// Its initial data u⁰, v⁰ as piecewise polynomials (`length` and `amplitude`: the paper's only).
  InitialData data(double length = 1.0, double amplitude = 0.5) const;
  /// Its continuous problem: the paper's closed-form data as functions (benchmark_problem), the smooth
  /// data, or a field chain's data with its load and gap (chain_problem). Throws InvalidParameter
  /// ("benchmark") on two bodies.
  Problem problem(double length = 1.0, double amplitude = 0.5) const;
  /// The mesh of N elements on its bar, graded by `grading` (graded_mesh; 1: uniform), on a field
  /// benchmark with its material per element and its far end (chain_mesh: body `body` of two bodies).
  /// Throws InvalidParameter ("grading") for a grading on a field benchmark, ("elements") when a
  /// material interface is not a node.
  UniformMesh mesh(Index elements, double grading = 1.0, double length = 1.0, int body = 0) const;
  /// Its exact solution up to `horizon`: the closed form (paper), the chain's ImpactReference (field),
  /// the characteristic solution of its data (smooth).
  std::shared_ptr<const ReferenceSolution> reference(double horizon, double length = 1.0, double amplitude = 0.5) const;
};

/// The benchmarks, in the order of their choice lists: paper, smooth-impact, grazing, then the field's
/// (bouncing, impacting, gravity-paper, two-bars, layered).
const std::vector<Benchmark>& benchmarks();
/// The entry named `id`; throws InvalidParameter("benchmark", … the allowed ids) otherwise.
const Benchmark& benchmark(const std::string& id);
/// The ids of benchmarks(), joined by ", " (the allowed values of a benchmark option).
std::string benchmark_ids();

/// The problem of a field chain (its own, or one scaled to unit size): its data, f its load (a polynomial
/// in each segment's σ, steady), its obstacle's gap. Throws InvalidParameter ("benchmark") on two bodies.
Problem chain_problem(const ImpactBenchmark& chain);
/// The mesh of a field chain: N uniform elements on its length with its material per element and its far
/// end; on two bodies (is_two_body_chain), body `body` (0 the left one) in its own frame
/// (lib/time/two_bodies.hpp: ξ from its contact end), N elements on its length. Throws InvalidParameter
/// ("elements") when an interface between two materials is not a node (the allowed N named),
/// ("benchmark") for a chain without a rigid obstacle that is not two bodies.
UniformMesh chain_mesh(const ImpactBenchmark& chain, Index elements, int body = 0);

}  // namespace mrm
