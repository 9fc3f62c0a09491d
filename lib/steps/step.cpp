/// @file step.cpp
/// @brief A registry entry's lookups (step.hpp).
#include "steps/step.hpp"

#include <algorithm>

namespace mrm {

bool SchemeInfo::takes(SchemeParameter parameter) const {
  return std::find(parameters.begin(), parameters.end(), parameter) != parameters.end();
}

const SchemeInfo* find_entry(const std::vector<SchemeInfo>& entries, Scheme scheme) {
  for (const SchemeInfo& info : entries)
    if (info.scheme == scheme) return &info;
  return nullptr;
}

}  // namespace mrm
