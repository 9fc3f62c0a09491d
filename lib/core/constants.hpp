#pragma once
/// \file
/// The mathematical constants the method uses, once for the whole library (ISO C++17 has no
/// std::numbers).

namespace mrm {

/// π to the precision of a double (the nearest double to π).
inline constexpr double pi = 3.14159265358979323846;

}  // namespace mrm
