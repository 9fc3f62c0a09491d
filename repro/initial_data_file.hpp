/// @file initial_data_file.hpp
/// @brief Initial data read from a text file (bar1d --initial-data FILE): samples x, u0, v0, linearly
/// interpolated, checked row by row with the file's line numbers in every message.
#pragma once

#include <string>
#include <string_view>

#include "exact/characteristics.hpp"

namespace mrm::repro {

/// Reads initial data on [0, L] from a text file: one sample per line, the three numbers x u0 v0
/// separated by blanks; '#' starts a comment and blank lines are skipped; L is the last x. The samples
/// are interpolated linearly (mrm::initial_data_from_samples). Throws cli::UsageError, its message
/// starting with `option`, then "FILE:LINE:", for a file that cannot be opened, a line that is not
/// three numbers, a value that is not finite, a first x other than 0, x not increasing, u0(L) ≠ 0,
/// u0(0) < 0, and fewer than two samples (the last line then).
InitialData read_initial_data(const std::string& path, std::string_view option = "--initial-data");

}  // namespace mrm::repro
