/// @file claims/wording.hpp
/// @brief The words and lists that the claims' rows print, shared by the claim groups (repro/claims/).
#pragma once

#include <string>
#include <vector>

#include "core/problem.hpp"

namespace mrm::claims {

/// The short names of the eight error measures of mathematics.md §5, in ErrorAccumulator::values order.
extern const char* const measure_names[8];
/// The summary's name of a scheme of the sweep ("ps-consistent": Paoli–Schatzman with the consistent mass).
std::string scheme_abbreviation(const std::string& id);
/// One run of the benchmark as the criteria state it: "N = 200, Δt = 0.5h, T = 300".
std::string run_text(Index elements, double courant, double final_time);
/// The parts joined by the separator.
std::string join(const std::vector<std::string>& parts, const std::string& separator);
/// The mesh sizes separated by commas.
std::string list_elements(const std::vector<Index>& elements);
/// The values, each to the table's significant digits, separated by commas.
std::string list_reals(const std::vector<double>& values);
/// The verdict word of a summary line: a claim holds in `holding` of its `total` cells or rows.
std::string summary_verdict(int holding, int total);
/// A factor of growth to three significant digits (two from 1000 on).
std::string magnitude(double x);
/// The report's name of one segment of a row id ("cn" → "CN", "mod3" → "Mod 3", "T=10p" → "T = 10 periods").
std::string readable_segment(const std::string& segment);
/// A row id in the report's notation ("5/cn/mod1" → "5, CN, Mod 1").
std::string readable_id(const std::string& id);
/// The same without the claim number: the name of a row within its claim ("2/mod2" → "Mod 2").
std::string readable_row(const std::string& id);

}  // namespace mrm::claims
