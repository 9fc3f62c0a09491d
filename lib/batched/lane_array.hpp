/// @file lane_array.hpp
/// @brief The arrays of a group of lanes (batched_step.cpp), each aligned for the vector loads and placed at
/// its own offset within a 4 KiB page, so that the sweeps' streams do not share their low twelve address
/// bits (lane_array.cpp).
#pragma once

#include <cstddef>
#include <memory>

/// @cond MRM_INTERNAL (a group's storage: not part of the library's interface)
namespace mrm::batched {

/// The offset, in bytes past a 4 KiB boundary, of a group's array number `slot` (lane_array.cpp).
std::size_t lane_array_offset(std::size_t slot);

/// `count` doubles, owned, uninitialised: at `offset` bytes past a 4 KiB boundary (a multiple of 64 below
/// 4096, so aligned for the widest vector load: a group's array by node number k takes lane_array_offset(k)),
/// or, without an offset, aligned to 64 bytes only (a group's values per lane, read a few times a step).
/// Throws std::invalid_argument for another offset and std::bad_alloc when the memory is not there. A
/// default-made LaneArray holds nothing (get() is null).
class LaneArray {
 public:
  LaneArray() = default;
  LaneArray(std::size_t count, std::size_t offset);
  explicit LaneArray(std::size_t count);
  double* get() const { return data_; }
  double& operator[](std::size_t i) const { return data_[i]; }

 private:
  struct Free {
    void operator()(void* block) const;
  };
  std::unique_ptr<void, Free> block_;
  double* data_ = nullptr;
};

}  // namespace mrm::batched
/// @endcond
