// Independent runs on a few worker threads (the figure programs whose runs take seconds): each worker
// takes the next run from a shared counter, so the longest runs, started first, do not wait for one
// another. The results do not depend on the number of threads: every run writes only its own slot.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

namespace mrm::repro {

/// Calls work(k) for every k of `order`, in that order of starting, on `threads` ≥ 1 workers (the calling
/// thread is one of them). After each call that returns, `progress(position, k)` (if given) is called
/// under a lock, position being the 1-based rank of k in `order`. The first exception thrown by `work`
/// stops the workers from starting more calls and is rethrown once all have stopped.
void run_in_parallel(const std::vector<std::size_t>& order, long threads,
                     const std::function<void(std::size_t k)>& work,
                     const std::function<void(std::size_t position, std::size_t k)>& progress = {});

}  // namespace mrm::repro
