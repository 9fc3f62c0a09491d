/// @file progress.hpp
/// @brief A progress line on standard error for a run that takes a while, shown only to a person: when
/// standard error is a terminal and the run has lasted two seconds.
#pragma once

#include <chrono>
#include <cstdint>
#include <string>

namespace mrm::repro {

/// The line a run redraws in place: a bar of the fraction done, the fraction in percent, where the run
/// is (`done` of `total` in the run's own unit, its simulated time) and an estimate of the time left
/// (the time so far, scaled by what is left over what is done):
///
///   bar1d [##########..........]  50 %  t = 3 of 6, about 4 s left
std::string progress_text(const std::string& program, double done, double total, double elapsed_seconds);

/// The progress of a run, on standard error (descriptor `descriptor`) when it is a terminal, and only
/// once the run has lasted `delay_seconds`: a run that ends sooner, or whose standard error goes to a file
/// or a pipe (a make recipe, a test), shows nothing. The line is redrawn at most ten times a second and
/// erased when the ProgressLine is destroyed, so that what the program prints after it starts on a clean
/// line. `update` is cheap enough to call at every step: it reads the clock every 64th call only.
///
///   ProgressLine progress("bar1d", final_time);
///   for (...) { step(); progress.update(t); }
class ProgressLine {
 public:
  ProgressLine(std::string program, double total, int descriptor = 2, double delay_seconds = 2.0);
  ~ProgressLine();
  ProgressLine(const ProgressLine&) = delete;
  ProgressLine& operator=(const ProgressLine&) = delete;

  /// Where the run is now (0 ≤ done ≤ total, in the unit of `total`).
  void update(double done);
  /// Whether a line has been drawn (and will be erased).
  bool shown() const { return shown_; }

 private:
  void draw(double done);

  std::string program_;
  double total_, delay_;
  int descriptor_;
  bool terminal_, shown_ = false;
  std::uint64_t calls_ = 0;
  std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace mrm::repro
