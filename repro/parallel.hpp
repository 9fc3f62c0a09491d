// Independent runs on a few worker threads: the figure programs call parallel_for with the number of
// runs and a body that fills the run's own slot, and write their results afterwards in a fixed order,
// so that the output does not depend on the number of threads.
#pragma once

#include <atomic>
#include <cstddef>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <vector>

namespace mrm::repro {

/// Calls body(k) for k = 0..count−1 on `threads` workers (the calling thread is one of them), each
/// taking the next k from a shared counter: list the costliest items first for the best balance. The
/// first exception stops the workers from taking new items and is rethrown here, after all have
/// stopped. `threads` < 1 is taken as 1.
inline void parallel_for(std::size_t count, long threads, const std::function<void(std::size_t)>& body) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex;
  auto worker = [&] {
    while (!failed) {
      const std::size_t k = next++;
      if (k >= count) return;
      try {
        body(k);
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  for (long t = 1; t < threads; ++t) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace mrm::repro
