/// @file smooth_benchmarks.hpp
/// @brief Smooth initial data with an impact (S1) and a grazing contact (S2, S3), on which the mass
/// redistributions differ in their order of convergence (mathematics.md §11).
#pragma once

#include <string>

#include "exact/characteristics.hpp"

namespace mrm {

/// The smooth benchmarks of mathematics.md §11.
enum class SmoothBenchmark {
  generic_impact,   ///< S1: the end hits the obstacle with non-zero velocity
  grazing,          ///< S2: it arrives with zero velocity and acceleration, (x − t*)² in P′
  grazing_quartic,  ///< S3: as S2 with (x − t*)⁴
};

/// The short name: s1, s2, s3.
std::string to_string(SmoothBenchmark);
/// s1, s2, s3; throws std::invalid_argument listing them for another name.
SmoothBenchmark smooth_benchmark_by_name(const std::string&);

/// The data u⁰ = P, v⁰ = P′ on [0, 1] and what was computed to build them.
struct SmoothBenchmarkData {
  SmoothBenchmark which;  ///< S1, S2 or S3
  InitialData data;       ///< u⁰ = P and v⁰ = P′ on pieces of [0, 1]
  double contact_height;  ///< P(0) = u⁰(0) = ¼
  double scale;           ///< K in P′ = −K q (computed so that P(0) = ¼)
  double support_begin;   ///< q vanishes outside [support_begin, support_end]
  double support_end;     ///< the end of the support of q
  double touch_time;      ///< t*: y(t*) = 2P(t*) − P(0) = 0, the first contact
  double release_time;    ///< t_r: where β = 2P′ turns positive (S2, S3); NaN for S1 (see the .cpp)
  double final_time;      ///< T = 2
};

/// Builds S1, S2 or S3 of mathematics.md §11 (L = 1): the constants K and (S2, S3) t_r are computed
/// (t_r by GSL's Brent root finder); throws std::runtime_error if a computation fails.
SmoothBenchmarkData smooth_benchmark(SmoothBenchmark which);

}  // namespace mrm
