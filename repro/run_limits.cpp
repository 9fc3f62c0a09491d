/// @file run_limits.cpp
/// @brief Limits of the runs: see run_limits.hpp.
#include "run_limits.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <string>

#include <sys/resource.h>
#include <unistd.h>

#include <doctest/doctest.h>

#include "options.hpp"

namespace mrm::cli {

// steps_to_reach counts ceil(T/Δt − 1e-9): zero when T ≤ 1e-9 Δt, and it refuses T/Δt > 1e12 with a
// std::invalid_argument, which would end the program with status 1 after it has started. The same
// count is made here first, as a usage error.
Index checked_steps(std::string_view time_option, double final_time, double dt, std::string_view step_options) {
  // A step that underflowed to 0 (e.g. --courant 5e-324 times h) is the step option's fault, not the
  // horizon's: it is named first.
  if (!(dt > 0))
    throw UsageError(std::string(step_options) + ": the time step is " + format_real(dt) +
                     " (allowed: a positive step; raise " + std::string(step_options) + ")");
  const double ratio = final_time / dt;
  if (!(ratio <= max_steps))
    throw UsageError(std::string(time_option) + ": " + format_real(final_time) + " needs " +
                     (std::isfinite(ratio) ? format_real(std::ceil(ratio)) : std::string("more than 1e308")) +
                     " steps of " + format_real(dt) + " (allowed: at most 1e12 steps; lower " +
                     std::string(time_option) + " or raise " + std::string(step_options) + ")");
  const Index steps = steps_to_reach(final_time, dt);
  if (steps < 1)
    throw UsageError(std::string(time_option) + ": " + format_real(final_time) + " is reached in 0 steps of " +
                     format_real(dt) + " (allowed: at least one step; raise " + std::string(time_option) +
                     " or lower " + std::string(step_options) + ")");
  return steps;
}

void require_rows(std::string_view option, double rows, std::string_view cause) {
  if (!(rows <= max_rows))
    throw UsageError(std::string(option) + ": " + std::string(cause) + " make " + format_real(rows) +
                     " lines of data (allowed: at most 1e8 lines in a data file)");
}

Index checked_level(std::string_view option, double t, double dt, std::string_view step_options) {
  const double level = std::round(t / dt);
  if (!(level <= max_steps))
    throw UsageError(std::string(option) + ": " + format_real(t) + " is " + format_real(level) + " steps of " +
                     format_real(dt) + " away (allowed: instants within 1e12 steps; lower " + std::string(option) +
                     " or raise " + std::string(step_options) + ")");
  return static_cast<Index>(level);
}

namespace {

// The memory this process may still allocate, in bytes: the machine's physical memory, and the room
// left under the address-space and data-segment limits (ulimit -v, -d) by what the process already
// uses (its virtual size, a safe overestimate of its data segment), whichever is smallest.
double available_memory() {
  const long pages = ::sysconf(_SC_PHYS_PAGES), page_size = ::sysconf(_SC_PAGESIZE);
  double available = pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size) : 1e300;
  double used_pages = 0;
  std::ifstream("/proc/self/statm") >> used_pages;
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    struct rlimit limit {};
    if (::getrlimit(resource, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
      available =
          std::min(available, static_cast<double>(limit.rlim_cur) - used_pages * static_cast<double>(page_size));
  }
  return std::max(available, 0.0);
}

std::string bytes_text(double bytes) {
  const char* units[] = {"bytes", "kB", "MB", "GB", "TB", "PB", "EB"};
  std::size_t unit = 0;
  for (; bytes >= 1000 && unit + 1 < std::size(units); ++unit) bytes /= 1000;
  char text[64];
  std::snprintf(text, sizeof text, "%.3g %s", bytes, units[unit]);
  return text;
}

}  // namespace

void require_mesh_memory(std::string_view option, double elements, double bytes_per_element, double copies) {
  const double bytes = elements * bytes_per_element * copies, available = available_memory();
  if (!(bytes <= available))
    throw UsageError(std::string(option) + ": " + format_real(elements) + " elements need about " + bytes_text(bytes) +
                     " of memory, more than the " + bytes_text(available) +
                     " this process may use (allowed: runs that fit in memory)");
}

void require_memory(std::string_view option, double bytes, std::string_view what) {
  const double available = available_memory();
  if (!(bytes <= available))
    throw UsageError(std::string(option) + ": " + std::string(what) + " needs about " + bytes_text(bytes) +
                     " of memory, more than the " + bytes_text(available) +
                     " this process may use (allowed: runs that fit in memory)");
}

// The stacks of the worker threads: each is reserved at the stack limit's size (glibc's default for a new
// thread, pthread_create(3); 2 MB on x86-64 when the limit is unlimited), and the threads count against
// the limit on processes.
void add_threads_option(Parser& parser, long* threads, const std::string& default_note) {
  parser.add_integer("--threads", "-j", "J",
                     "worker threads, in [1, 256]" + (default_note.empty() ? "" : " (default: " + default_note + ")") +
                         "; the output does not depend on it",
                     threads, [](std::string_view option, double value) {
                       require_in_closed_range(option, value, 1, max_threads);
                       struct rlimit limit {};
                       if (::getrlimit(RLIMIT_NPROC, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY &&
                           value > static_cast<double>(limit.rlim_cur))
                         throw UsageError(std::string(option) + ": " + format_real(value) +
                                          " threads are more than this process may start (ulimit -u " +
                                          std::to_string(limit.rlim_cur) + "; allowed: at most that many)");
                       double stack = 2e6;
                       if (::getrlimit(RLIMIT_STACK, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY)
                         stack = static_cast<double>(limit.rlim_cur);
                       require_memory(option, (value - 1) * stack,
                                      "the stacks of " + format_real(value - 1) + " more threads");
                     });
}

TEST_CASE("the steps of a run are refused before the run unless between 1 and 1e12") {
  CHECK(checked_steps("--final-time", 6.0, 0.005, "--courant") == 1200);
  CHECK(checked_steps("--final-time", 2e-9, 1.0, "--courant") == 1);  // T just above 1e-9 Δt: one step
  CHECK_THROWS_WITH_AS(checked_steps("--final-time", 6.0, 1e-300, "--courant"),
                       "--final-time: 6 needs 6e+300 steps of 1e-300 (allowed: at most 1e12 steps; lower "
                       "--final-time or raise --courant)",
                       UsageError);
  CHECK_THROWS_WITH_AS(checked_steps("--final-time", 1e-300, 0.005, "--courant"),
                       "--final-time: 1e-300 is reached in 0 steps of 0.005 (allowed: at least one step; raise "
                       "--final-time or lower --courant)",
                       UsageError);
  CHECK_THROWS_WITH_AS(checked_steps("--final-time", 1e300, 1e-300, "--courant"),  // T/Δt = inf
                       "--final-time: 1e+300 needs more than 1e308 steps of 1e-300 (allowed: at most 1e12 steps; "
                       "lower --final-time or raise --courant)",
                       UsageError);
  CHECK_THROWS_WITH_AS(checked_steps("--periods", 90, 0.0, "--courant"),  // a step that underflowed to 0
                       "--courant: the time step is 0 (allowed: a positive step; raise --courant)", UsageError);
}

TEST_CASE("data files, levels and memory beyond the limits are refused naming the option") {
  CHECK_NOTHROW(require_rows("--final-time", 1e8, "1e8 steps"));
  CHECK_THROWS_WITH_AS(require_rows("--final-time", 3.6e8, "4e+07 steps of 9 runs"),
                       "--final-time: 4e+07 steps of 9 runs make 3.6e+08 lines of data (allowed: at most 1e8 lines "
                       "in a data file)",
                       UsageError);
  CHECK(checked_level("--instants", 0.5, 0.025, "--courant") == 20);
  CHECK_THROWS_WITH_AS(checked_level("--instants", 1e20, 0.025, "--courant"),
                       "--instants: 1e+20 is 4e+21 steps of 0.025 away (allowed: instants within 1e12 steps; lower "
                       "--instants or raise --courant)",
                       UsageError);
  CHECK_THROWS_WITH_AS(require_mesh_memory("--elements", 1e7, 1e30),
                       doctest::Contains("--elements: 1e+07 elements need about 1e+19 EB of memory, more than the"),
                       UsageError);
  CHECK_NOTHROW(require_mesh_memory("--elements", 100, 256));
}

}  // namespace mrm::cli
