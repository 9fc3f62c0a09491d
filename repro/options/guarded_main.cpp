/// @file options/guarded_main.cpp
/// @brief The guard of a program's main: the exceptions mapped to exit statuses, the standard streams checked.
#include "options.hpp"
#include "output_file.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <csignal>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <new>
#include <optional>
#include <sstream>
#include <system_error>
#include <type_traits>

#include <fcntl.h>
#include <sys/stat.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

namespace mrm::cli {

TEST_SUITE_BEGIN("cli");

// A program's main function delegates to guarded_main, which maps the exceptions to an exit
// status and a single line of message. The final check of the output stream catches a failure to
// write the results to standard output (a full disk, a closed pipe), which would otherwise go
// unnoticed, since a C++ stream reports write errors only through its state.
//
// Before the body runs, the standard descriptors are made to be open (prepare_standard_descriptors,
// output_file.hpp): otherwise the first file the program opens would take the place of a closed one,
// and whatever is written to standard error (progress lines) or standard output would go into it.
// After the body, both streams are checked: a body whose diagnostics could not be written also ends
// with status 1.
//
// What the program prints on the standard output goes through a WatchedBuffer (output_file.hpp): a
// non-finite value printed ends the run with status 1 (and commit_all commits no file), and so does a
// failed write through C's stdio (printf), which the C++ stream does not see.
//
// A file-size limit (ulimit -f) would kill the process by SIGXFSZ at the first write beyond it, leaving
// no message and a status that says nothing of the cause: the signal is ignored, so that the write fails
// with EFBIG and is reported as every other write error (the output named, status 1, nothing committed).
int guarded_main(std::string_view program, const std::function<int()>& body, std::ostream& output,
                 std::ostream& errors) {
  std::signal(SIGXFSZ, SIG_IGN);
  const bool output_closed = prepare_standard_descriptors();
  const bool watched = &output == &std::cout;
  WatchedBuffer watch(output.rdbuf());
  struct Restore {
    std::ostream& stream;
    std::streambuf* buffer;
    bool active;
    ~Restore() {
      if (!active) return;
      stream.rdbuf(buffer);
      standard_output_watch = nullptr;
    }
  } restore{output, output.rdbuf(), watched};
  if (watched) {
    output.rdbuf(&watch);
    standard_output_watch = &watch.watch();
  }
  try {
    const int status = body();
    output.flush();
    const bool stdio_failed = watched && (std::fflush(stdout) != 0 || std::ferror(stdout));
    if (!output || stdio_failed) {
      errors << program << ": error: writing the standard output failed"
             << (output_closed && watched ? ": it is closed" : "") << '\n';
      return status != 0 ? status : 1;
    }
    if (watched && watch.watch().found()) {
      errors << program << ": error: the standard output: " << watch.watch().what() << '\n';
      return status != 0 ? status : 1;
    }
    errors.flush();
    if (!errors) {
      return status != 0 ? status : 1;
    }
    return status;
  } catch (const UsageError& error) {
    errors << program << ": " << error.what() << '\n';
    return 2;
  } catch (const std::bad_alloc&) {
    // A run the checks of the options let through whose memory was not there after all (the machine's
    // other processes, an estimate exceeded): said as such, not as "std::bad_alloc".
    errors << program << ": error: out of memory: an allocation failed during the run (allowed: a smaller run, "
           << "or more memory for the process)\n";
    return 1;
  } catch (const std::exception& error) {
    errors << program << ": error: " << error.what() << '\n';
    return 1;
  } catch (...) {
    errors << program << ": error: unknown exception\n";
    return 1;
  }
}

TEST_CASE("guarded_main maps usage errors to status 2 and other failures to status 1") {
  std::ostringstream output, errors;
  SUBCASE("success") {
    CHECK(guarded_main(
              "p", [] { return 0; }, output, errors) == 0);
    CHECK(guarded_main(
              "p", [] { return 3; }, output, errors) == 3);
    CHECK(errors.str().empty());
  }
  SUBCASE("usage error") {
    CHECK(guarded_main(
              "p", []() -> int { throw UsageError("--dt: bad"); }, output, errors) == 2);
    CHECK(errors.str() == "p: --dt: bad\n");
  }
  SUBCASE("other error") {
    CHECK(guarded_main(
              "p", []() -> int { throw std::runtime_error("no convergence"); }, output, errors) == 1);
    CHECK(errors.str() == "p: error: no convergence\n");
  }
  SUBCASE("out of memory") {
    CHECK(guarded_main(
              "p", []() -> int { throw std::bad_alloc(); }, output, errors) == 1);
    CHECK(errors.str() ==
          "p: error: out of memory: an allocation failed during the run (allowed: a smaller run, or more memory "
          "for the process)\n");
  }
  SUBCASE("not a standard exception") {
    CHECK(guarded_main(
              "p", []() -> int { throw 42; }, output, errors) == 1);
    CHECK(errors.str() == "p: error: unknown exception\n");
  }
  SUBCASE("failed output") {
    output.setstate(std::ios::badbit);
    CHECK(guarded_main(
              "p", [] { return 0; }, output, errors) == 1);
    CHECK(errors.str() == "p: error: writing the standard output failed\n");
  }
  SUBCASE("failed diagnostics") {
    errors.setstate(std::ios::badbit);
    CHECK(guarded_main(
              "p", [] { return 0; }, output, errors) == 1);
    CHECK(guarded_main(
              "p", [] { return 3; }, output, errors) == 3);
  }
}

TEST_SUITE_END();

}  // namespace mrm::cli
