/// @file progress.cpp
/// @brief The progress line of a long run: drawn on a terminal only, after a delay, erased at the end.
#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <utility>

#include <doctest/doctest.h>

#include <fcntl.h>
#include <unistd.h>

namespace mrm::repro {

namespace {

// A number of seconds as a person reads it: "7 s", "3 min 5 s", "2 h 10 min".
std::string duration_text(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  if (s < 60) return std::to_string(s) + " s";
  if (s < 3600) return std::to_string(s / 60) + " min " + std::to_string(s % 60) + " s";
  return std::to_string(s / 3600) + " h " + std::to_string(s % 3600 / 60) + " min";
}

// A position of the run (its simulated time) to three significant digits.
std::string position_text(double t) {
  char text[32];
  std::snprintf(text, sizeof text, "%.3g", t);
  return text;
}

// Writes all of `text` to `descriptor`; a failure is ignored (the line is a courtesy, not an output).
void write_all(int descriptor, const std::string& text) {
  for (std::size_t written = 0; written < text.size();) {
    const ssize_t n = ::write(descriptor, text.data() + written, text.size() - written);
    if (n <= 0) return;
    written += static_cast<std::size_t>(n);
  }
}

}  // namespace

std::string progress_text(const std::string& program, double done, double total, double elapsed_seconds) {
  constexpr int width = 20;
  const double fraction = total > 0 ? std::clamp(done / total, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(fraction * width);
  std::string text = program + " [" + std::string(static_cast<std::size_t>(filled), '#') +
                     std::string(static_cast<std::size_t>(width - filled), '.') + "] ";
  const std::string percent = std::to_string(static_cast<int>(fraction * 100));
  text += std::string(3 - std::min<std::size_t>(3, percent.size()), ' ') + percent + " %  t = " + position_text(done) +
          " of " + position_text(total);
  if (fraction > 0 && fraction < 1)
    text += ", about " + duration_text(elapsed_seconds * (1 - fraction) / fraction) + " left";
  return text;
}

TEST_CASE("the progress line shows the fraction done, where the run is and the time left") {
  CHECK(progress_text("bar1d", 3, 6, 4) == "bar1d [##########..........]  50 %  t = 3 of 6, about 4 s left");
  CHECK(progress_text("bar1d", 1.5, 6, 30) ==
        "bar1d [#####...............]  25 %  t = 1.5 of 6, about 1 min 30 s left");
  CHECK(progress_text("bar1d", 6, 6, 10) == "bar1d [####################] 100 %  t = 6 of 6");
  CHECK(progress_text("bar1d", 0, 6, 0) == "bar1d [....................]   0 %  t = 0 of 6");
  CHECK(progress_text("x", 1, 1e4, 0.36) == "x [....................]   0 %  t = 1 of 1e+04, about 1 h 0 min left");
  CHECK(duration_text(59.6) == "1 min 0 s");
  CHECK(duration_text(-1) == "0 s");
}

ProgressLine::ProgressLine(std::string program, double total, int descriptor, double delay_seconds)
    : program_(std::move(program)),
      total_(total),
      delay_(delay_seconds),
      descriptor_(descriptor),
      terminal_(::isatty(descriptor) == 1),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

ProgressLine::~ProgressLine() {
  // Erase the line (carriage return, the terminal's erase to the end of the line).
  if (shown_) write_all(descriptor_, "\r\033[K");
}

void ProgressLine::update(double done) {
  if (!terminal_ || calls_++ % 64 != 0) return;
  const auto now = std::chrono::steady_clock::now();
  if (std::chrono::duration<double>(now - start_).count() < delay_ ||
      (shown_ && std::chrono::duration<double>(now - last_draw_).count() < 0.1))
    return;
  last_draw_ = now;
  draw(done);
}

void ProgressLine::draw(double done) {
  const double elapsed = std::chrono::duration<double>(last_draw_ - start_).count();
  write_all(descriptor_, "\r" + progress_text(program_, done, total_, elapsed) + "\033[K");
  shown_ = true;
}

TEST_CASE("the progress line is drawn on a terminal only, and erased at the end") {
  // Not a terminal (a pipe): nothing, whatever the delay.
  int pipe_ends[2];
  REQUIRE(::pipe(pipe_ends) == 0);
  {
    ProgressLine progress("p", 10, pipe_ends[1], 0.0);
    for (int k = 0; k <= 640; ++k) progress.update(k / 64.0);
    CHECK_FALSE(progress.shown());
  }
  ::close(pipe_ends[1]);
  char byte;
  CHECK(::read(pipe_ends[0], &byte, 1) == 0);  // end of file: nothing was written
  ::close(pipe_ends[0]);
  // A terminal (a pseudo-terminal's slave side), no delay: the first update draws, the end erases.
  const int master = ::posix_openpt(O_RDWR | O_NOCTTY);
  if (master < 0 || ::grantpt(master) != 0 || ::unlockpt(master) != 0) {
    MESSAGE("no pseudo-terminal on this machine: the terminal case is not checked");
    if (master >= 0) ::close(master);
    return;
  }
  const int slave = ::open(::ptsname(master), O_RDWR | O_NOCTTY);
  REQUIRE(slave >= 0);
  {
    ProgressLine progress("p", 10, slave, 0.0);
    progress.update(5);
    CHECK(progress.shown());
  }
  std::string seen;
  char buffer[256];
  ::fcntl(master, F_SETFL, O_NONBLOCK);
  for (ssize_t n; (n = ::read(master, buffer, sizeof buffer)) > 0;) seen.append(buffer, static_cast<std::size_t>(n));
  ::close(slave);
  ::close(master);
  CHECK(seen.find("p [##########..........]  50 %  t = 5 of 10") != std::string::npos);
  CHECK(seen.size() >= 4);
  CHECK(seen.substr(seen.size() - 4) == "\r\033[K");
}

}  // namespace mrm::repro
