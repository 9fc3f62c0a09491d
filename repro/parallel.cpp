// Independent runs on a few worker threads; see parallel.hpp.
#include "parallel.hpp"

#include <atomic>
#include <exception>
#include <mutex>
#include <stdexcept>
#include <string>
#include <system_error>
#include <thread>

#include <doctest/doctest.h>

namespace mrm::repro {

void run_in_parallel(const std::vector<std::size_t>& order, long threads,
                     const std::function<void(std::size_t k)>& work,
                     const std::function<void(std::size_t position, std::size_t k)>& progress) {
  if (threads < 1) throw std::invalid_argument("run_in_parallel: threads must be >= 1");
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr failure;
  std::mutex failure_mutex, progress_mutex;
  const auto worker = [&] {
    while (!failed) {
      const std::size_t position = next++;
      if (position >= order.size()) return;
      try {
        work(order[position]);
        if (progress) {
          std::lock_guard<std::mutex> lock(progress_mutex);
          progress(position + 1, order[position]);
        }
      } catch (...) {
        std::lock_guard<std::mutex> lock(failure_mutex);
        if (!failure) failure = std::current_exception();
        failed = true;
      }
    }
  };
  // A thread that cannot be started (the system's limit on threads) stops the run with a message: the
  // workers already started are told to stop and joined first, never left joinable.
  std::vector<std::thread> pool;
  try {
    for (long t = 1; t < threads; ++t) pool.emplace_back(worker);
  } catch (const std::system_error& error) {
    failed = true;
    for (std::thread& t : pool) t.join();
    throw std::runtime_error("--threads: cannot start worker thread " + std::to_string(pool.size() + 2) + " of " +
                             std::to_string(threads) + ": " + error.what());
  }
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

TEST_CASE("run_in_parallel calls the work once per index and rethrows the first failure") {
  // Prediction: with any number of threads each index is worked on exactly once and the progress
  // positions are 1..n; a throwing index stops the run with its exception.
  for (const long threads : {1L, 2L, 5L}) {
    std::vector<std::size_t> order{3, 0, 2, 1, 4};
    std::vector<int> calls(order.size(), 0);
    std::vector<int> positions(order.size() + 1, 0);
    run_in_parallel(
        order, threads, [&](std::size_t k) { ++calls[k]; },
        [&](std::size_t position, std::size_t) { ++positions[position]; });
    CAPTURE(threads);
    for (int c : calls) CHECK(c == 1);
    for (std::size_t p = 1; p < positions.size(); ++p) CHECK(positions[p] == 1);
    CHECK_THROWS_WITH_AS(run_in_parallel(order, threads,
                                         [](std::size_t k) {
                                           if (k == 2) throw std::runtime_error("run 2 failed");
                                         }),
                         "run 2 failed", std::runtime_error);
  }
  CHECK_THROWS_AS(run_in_parallel({0}, 0, [](std::size_t) {}), std::invalid_argument);
}

}  // namespace mrm::repro
