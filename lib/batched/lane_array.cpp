/// @file lane_array.cpp
/// @brief Where a group's arrays start within a page, and why (lane_array.hpp).
///
/// The sweeps of a group (kernels.cpp) stream through several arrays row by row: the sweep down loads
/// rows i − 1 … i + 1 of U and W′ and stores row i of y; the sweep up loads row i of y, U and W′ and stores
/// row i of y and W′, and off the plateau of the factors both also load a row of two or three factor
/// arrays. A load issued soon after a store whose address has the same low twelve bits (the same offset
/// within a 4 KiB page) is held back until the store's whole address is compared: the processor's memory
/// disambiguation matches the page offset first ("4K aliasing" in the vendors' optimisation manuals). A
/// row of W lanes is 8W bytes, so two arrays 8W·k bytes apart modulo 4096 alias k rows apart; arrays
/// aligned to 64 bytes by an allocator may lie 0, 64 or 128 bytes apart (Highway's AllocateAligned started
/// consecutive blocks at 0x140, 0x140, 0x180, 0x1c0, ... past a page boundary in a test program on the
/// machine measured below), which for 8 lanes is 0, 1 or 2 rows: the
/// distance between a store and the loads that follow it.
///
/// Array number `slot` of a group therefore starts at r(slot) · 256 bytes past a page boundary, where r
/// reverses the four bits of slot mod 16 (the van der Corput sequence: 0, 2048, 1024, 3072, 512, ...): the
/// first 2^k arrays are 4096 / 2^k bytes apart, so the three a sweep streams on the plateau (U, y, W′,
/// allocated first) are at least 1024 bytes apart, the nine of the fused step (with X and the five
/// factors) at least 256, and sixteen arrays take sixteen distinct offsets.
///
/// Chosen after a run: the batched Crank–Nicolson step of 8 runs in one group of 8 lanes (Mod 3, Δt = h/2,
/// AVX-512 on a Zen 4 core, the median of 5 fresh batches of the minimum of 5 timed ones, CPU clock), with
/// its arrays k·S bytes apart: S = 64 took 0.94, 1.02 and 0.93 ns per node, step and run at N = 2048, 4096
/// and 16384; S = 448, 1024 and this layout 0.68–0.69, 0.78–0.79 and 0.67–0.68. At N = 4096 the step took
/// 0.95, 0.87, 0.85, 0.74, 0.71 and 0.71 ns with S = 0, 64, 128, 256, 448 and 1024. bench_step's batched table
/// measures the effect at each of its runs: its column "aliased" is the traffic skeleton of the step with
/// its arrays 64 bytes apart, beside "traffic", the same skeleton at these offsets. Where the arrays lie
/// changes no bit of a lane.
#include "batched/lane_array.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <stdexcept>
#include <vector>

#include <doctest/doctest.h>

/// @cond MRM_INTERNAL (a group's storage: not part of the library's interface)
namespace mrm::batched {

namespace {
constexpr std::size_t page = 4096, spacing = 256;  // sixteen offsets per page
}  // namespace

std::size_t lane_array_offset(std::size_t slot) {
  std::size_t reversed = 0;  // the 4 bits of slot mod 16 in reverse order
  for (int b = 0; b < 4; ++b) reversed |= ((slot >> b) & 1u) << (3 - b);
  return reversed * spacing;
}

LaneArray::LaneArray(std::size_t count, std::size_t offset) {
  if (offset >= page || offset % 64 != 0)
    throw std::invalid_argument("LaneArray: the offset must be a multiple of 64 below 4096");
  const std::size_t bytes = offset + count * sizeof(double);
  // std::aligned_alloc wants a size that is a multiple of the alignment.
  void* block = std::aligned_alloc(page, (bytes + page - 1) / page * page);
  if (block == nullptr) throw std::bad_alloc();
  block_.reset(block);
  data_ = reinterpret_cast<double*>(static_cast<char*>(block) + offset);
}

LaneArray::LaneArray(std::size_t count) {
  constexpr std::size_t line = 64;
  // std::aligned_alloc wants a size that is a multiple of the alignment (and here not 0).
  void* block = std::aligned_alloc(line, std::max<std::size_t>(1, (count * sizeof(double) + line - 1) / line) * line);
  if (block == nullptr) throw std::bad_alloc();
  block_.reset(block);
  data_ = static_cast<double*>(block);
}

void LaneArray::Free::operator()(void* block) const { std::free(block); }

TEST_CASE("a group's arrays start at distinct page offsets, the first 2^k of them 4096 / 2^k bytes apart") {
  // The offsets of slots 0 … 15: sixteen distinct multiples of 256 below 4096, any two of the first 2^k at
  // least 4096 / 2^k apart (0 and 2048; then 1024 and 3072 between them; ...), and slot 16 starts over.
  std::vector<std::size_t> offsets;
  for (std::size_t slot = 0; slot < 16; ++slot) offsets.push_back(lane_array_offset(slot));
  CHECK(offsets[0] == 0);
  CHECK(offsets[1] == 2048);
  CHECK(offsets[2] == 1024);
  CHECK(offsets[3] == 3072);
  for (std::size_t count = 2; count <= 16; count *= 2)
    for (std::size_t a = 0; a < count; ++a)
      for (std::size_t b = a + 1; b < count; ++b) {
        const std::size_t apart = offsets[a] > offsets[b] ? offsets[a] - offsets[b] : offsets[b] - offsets[a];
        CAPTURE(count);
        CHECK(std::min(apart, page - apart) >= page / count);
      }
  for (const std::size_t offset : offsets) CHECK((offset < page && offset % 256 == 0));
  CHECK(lane_array_offset(16) == 0);
  CHECK(lane_array_offset(17) == 2048);
}

TEST_CASE("a lane array lies at its page offset, aligned for the widest vector load, all its entries there") {
  for (std::size_t slot = 0; slot < 20; ++slot) {
    const LaneArray a(100, lane_array_offset(slot));
    const auto address = reinterpret_cast<std::uintptr_t>(a.get());
    CHECK(address % 64 == 0);
    CHECK(address % page == lane_array_offset(slot));
    a[0] = 1.0, a[99] = 2.0;  // the sanitized build checks that the whole count is there
    CHECK(a[0] + a[99] == 3.0);
  }
  for (const std::size_t count : {std::size_t{1}, std::size_t{8}, std::size_t{100}}) {
    const LaneArray a(count);
    CHECK(reinterpret_cast<std::uintptr_t>(a.get()) % 64 == 0);
    a[0] = 1.0, a[count - 1] = 2.0;  // the sanitized build checks that the whole count is there
    CHECK(a[count - 1] == 2.0);
  }
  CHECK(LaneArray().get() == nullptr);
  CHECK_THROWS_AS(LaneArray(100, 4096), std::invalid_argument);
  CHECK_THROWS_AS(LaneArray(100, 32), std::invalid_argument);
}

}  // namespace mrm::batched
/// @endcond
