/// @file run_limits.hpp
/// @brief Limits of the runs the programs accept, checked when the options are read, before any work: a
/// request that cannot run (too many elements, steps or curve points for the time or the memory
/// there is, a product of options that overflows, no step at all) is a usage error naming the
/// option, never a late std::bad_alloc, a pivot message, a crash or a run that cannot end.
#pragma once

#include <string>
#include <string_view>

#include "time/schemes.hpp"

namespace mrm::cli {

/// Elements of one mesh (beyond, the memory of one run is gigabytes and a step milliseconds).
constexpr double max_elements = 1e7;
/// Time steps of one run (mrm::steps_to_reach refuses more).
constexpr double max_steps = 1e12;
/// Time step over mesh size, Δt/h: beyond, Δt² overflows the step matrix for some lengths.
constexpr double max_courant = 1e6;
/// Points of one curve of the exact solution in a data file.
constexpr double max_curve_points = 1e6;
/// Worker threads.
constexpr double max_threads = 256;
/// Lines of one data file (about 5 GB at the programs' 50 bytes a line).
constexpr double max_rows = 1e8;

/// The number of steps of size `dt` that reach `final_time` (mrm::steps_to_reach), or a UsageError
/// naming `time_option` unless it is between 1 and max_steps:
///   --final-time: 6 needs 6e+300 steps of 1e-300 (allowed: at most 1e12 steps; lower --final-time or raise --courant)
///   --final-time: 1e-300 is reached in 0 steps of 0.005 (allowed: at least one step; raise --final-time or lower --courant)
/// `step_options` names the options that set the step ("--courant", "--dt or --courant").
Index checked_steps(std::string_view time_option, double final_time, double dt, std::string_view step_options);

/// A UsageError naming `option` unless a data file of `rows` lines (the program's count for the
/// options given) stays within max_rows; `cause` says what makes the lines ("4e+07 steps of 9 runs").
void require_rows(std::string_view option, double rows, std::string_view cause);

/// The time level nearest to the instant t for steps of dt, or a UsageError naming `option` when it is
/// beyond max_steps (a level that no run can reach, and that no integer type may hold); `step_options`
/// names the options that set the step, as for checked_steps.
Index checked_level(std::string_view option, double t, double dt, std::string_view step_options);

/// A UsageError naming `option` unless a run holding `copies` meshes of `elements` elements, at
/// `bytes_per_element` each, fits in the memory the process may use: the machine's physical memory and
/// its address-space and data-segment limits (ulimit -v, -d).
/// A UsageError naming `option` unless `bytes` fit in the memory the process may use; `what` says what
/// needs them ("the exact solution of 4e+06 coefficients up to t = 6").
void require_memory(std::string_view option, double bytes, std::string_view what);

void require_mesh_memory(std::string_view option, double elements, double bytes_per_element, double copies = 1);

class Parser;
/// The option --threads (-j) J of a program that shares its work among worker threads, declared once for
/// every program: an integer in [1, max_threads] (the help says so, `default_note` after it if given, e.g.
/// "one per hardware thread"), and, when the value is read, a UsageError naming --threads if the process
/// could not start J - 1 more threads: more than its limit on processes (ulimit -u) or more thread stacks
/// (ulimit -s each) than the memory it may use (ulimit -v). A thread that cannot start
/// would otherwise stop the run after its work began.
void add_threads_option(Parser& parser, long* threads, const std::string& default_note = "");

}  // namespace mrm::cli
