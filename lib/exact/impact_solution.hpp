/// @file impact_solution.hpp
/// @brief The exact solution of the field's 1D impact benchmarks (doc/benchmarks.md): the chain of
/// segments and its solution (impact_chain.hpp), the reference of the error measures
/// (impact_reference.hpp) and the named benchmarks (impact_benchmarks.hpp), in one include.
#pragma once

#include "exact/impact_benchmarks.hpp"
#include "exact/impact_chain.hpp"
#include "exact/impact_reference.hpp"
