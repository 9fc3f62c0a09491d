/// @file problem.cpp
/// @brief The benchmark's problem (mathematics.md §2) and the parameter error.
#include "core/problem.hpp"

namespace mrm {

InvalidParameter::InvalidParameter(const std::string& name, const std::string& message)
    : std::invalid_argument(name + ": " + message), parameter(name) {}

// The problem of the benchmark (mathematics.md §2).

Problem benchmark_problem(double length, double amplitude) {
  Problem p;
  p.length = length;
  p.initial_displacement = [length, amplitude](double x) { return amplitude * (length - x); };
  p.initial_velocity = [](double) { return 0.0; };
  return p;
}

}  // namespace mrm
