/// @file claims/wording.cpp
/// @brief The claims' shared pieces: the paper's schemes and masses, and the words and lists the rows print.
#include <algorithm>
#include <array>
#include <cctype>
#include <chrono>
#include <cstddef>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

#include "batched/batched_step.hpp"
#include "claims.hpp"
#include "claims/wording.hpp"
#include "configurations.hpp"
#include "exact/exact_solution.hpp"
#include "labels.hpp"
#include "fem/period_law.hpp"
#include "regions.hpp"
#include "report_values.hpp"
#include "studies/convergence.hpp"
#include "sweep.hpp"
#include "table.hpp"
#include "steps/contact.hpp"
#include "time_family.hpp"

namespace mrm::claims {

// ---------------------------------------------------------------------------------------------------
// Shared pieces: the schemes and masses of the paper, numbers in the table, the benchmark runs.

// "ps-literal" is Paoli–Schatzman with the literal contact row; every other label is the registry's id.
SchemeChoice scheme_choice(const std::string& label) {
  if (label == "ps-literal") return {label, repro::scheme_parameters(Scheme::paoli_schatzman, "literal", "mod3")};
  return scheme_choice(scheme_by_name(label));
}
SchemeChoice scheme_choice(Scheme scheme) {
  return {to_string(scheme), repro::scheme_parameters(scheme, "algebraic", "mod3")};
}

std::vector<SchemeChoice> paper_schemes() {
  std::vector<SchemeChoice> schemes;
  for (const std::string& id : repro::scheme_names()) schemes.push_back(scheme_choice(id));
  schemes.push_back(scheme_choice("ps-literal"));
  return schemes;
}
std::vector<MassRedistribution> paper_masses() {
  std::vector<MassRedistribution> masses;
  for (const std::string& id : repro::mass_names()) masses.push_back(mass_redistribution_by_name(id));
  return masses;
}

// The short names of the eight error measures of mathematics.md §5, in ErrorAccumulator::values order,
// as the claims' prose writes them in lists. (The label table's plain names, "u, L∞_t L²", are made for
// gnuplot keys: their comma and subscript markup would make these lists ambiguous.)
const char* const measure_names[8] = {"u(0,·) L²(0,T)", "λ L²(0,T)", "u L∞(L²)", "u L∞(H¹)",
                                      "u_t L∞(L²)",     "u L²(L²)",  "u L²(H¹)", "u_t L²(L²)"};

// The summary's name of a scheme of the sweep: its abbreviation (repro/labels: CN, BE, PS); the sweep's
// baseline "ps-consistent" is Paoli–Schatzman with the consistent mass.
std::string scheme_abbreviation(const std::string& id) {
  if (id == "ps-consistent")
    return repro::scheme_label(Scheme::paoli_schatzman).abbreviation + " (" + repro::mass_label("consistent").plain +
           ")";
  return repro::scheme_label(id).abbreviation;
}

// One run of the benchmark as the criteria state it: "N = 200, Δt = 0.5h, T = 300".
std::string run_text(Index elements, double courant, double final_time) {
  return "N = " + std::to_string(elements) + ", Δt = " + significant(courant) + "h, T = " + significant(final_time);
}

std::string join(const std::vector<std::string>& parts, const std::string& separator) {
  std::string s;
  for (std::size_t k = 0; k < parts.size(); ++k) s += (k ? separator : "") + parts[k];
  return s;
}

std::string list_elements(const std::vector<Index>& elements) {
  std::vector<std::string> s;
  for (Index n : elements) s.push_back(std::to_string(n));
  return join(s, ", ");
}

// The values of a list, each to the table's significant digits, separated by commas.
std::string list_reals(const std::vector<double>& values) {
  std::vector<std::string> s;
  for (double v : values) s.push_back(significant(v));
  return join(s, ", ");
}

// The verdict word of a summary line: a claim holds in `holding` of its `total` cells or rows.
std::string summary_verdict(int holding, int total) {
  return holding == total ? "reproduced" : holding == 0 ? "not reproduced" : "partly reproduced";
}

// A factor of growth to three significant digits (two from 1000 on).
std::string magnitude(double x) { return x < 1000 ? significant(x, 3) : significant(x, 2); }

// The rows' ids in the report's notation: the claims table of the appendix names each row by them, and
// the summary names the rows where a claim holds or fails by them, without the claim number.

// The report's name of one segment of a row id ("cn" → "CN", "mod3" → "Mod 3", "dt=0.5h" → "Δt = 0.5h",
// "T=10p" → "T = 10 periods"); an unknown segment is kept.
std::string readable_segment(const std::string& segment) {
  // Paoli–Schatzman (¼, 0) in its three forms, the other schemes and the masses by their labels.
  const std::string ps = repro::scheme_label(Scheme::paoli_schatzman).abbreviation + "(¼, 0), ";
  if (segment == to_string(Scheme::paoli_schatzman)) return ps + "algebraic row";
  if (segment == "ps-literal") return ps + "literal row";
  if (segment == "ps-consistent") return ps + repro::mass_label("consistent").plain;
  for (const SchemeInfo& scheme : scheme_registry())
    if (segment == scheme.id) return repro::scheme_label(scheme.scheme).abbreviation;
  for (const std::string& mass : mass_redistribution_names())
    if (segment == mass) return repro::mass_label(mass).plain;
  // The claims' own rows: the kinds of check and the variants of the masses (check_reconstruction_sensitivity).
  static const std::pair<const char*, const char*> names[] = {
      {"step", "contact step"},
      {"exact", "exact solution"},
      {"large-steps", "large steps"},
      {"1000-periods", "1000 periods"},
      {"mechanism", "mechanism (period law)"},
      {"sensitivity", "sensitivity"},
      {"mod2-diagonal", "Mod 2 spread on the diagonal"},
      {"mod3-spread2", "Mod 3 spread on nodes 1, 2"},
      {"mod3-3/4", "Mod 3 as ¾ and ¼ on nodes 1, 2"},
  };
  for (const auto& [id, name] : names)
    if (segment == id) return name;
  if (segment.rfind("dt=", 0) == 0) return "Δt = " + segment.substr(3);
  if (segment.rfind("T=", 0) == 0 && segment.back() == 'p') {
    const std::string periods = segment.substr(2, segment.size() - 3);
    return "T = " + periods + (periods == "1" ? " period" : " periods");
  }
  return segment;
}

// The segments of an id, split at '/' except inside a segment that contains one ("mod3-3/4").
std::vector<std::string> id_segments(const std::string& id) {
  static const char* const with_slash[] = {"mod3-3/4"};
  std::vector<std::string> segments;
  std::size_t begin = 0;
  for (;;) {
    std::size_t end = id.find('/', begin);
    for (const char* s : with_slash)
      if (id.compare(begin, std::string(s).size(), s) == 0) end = id.find('/', begin + std::string(s).size());
    segments.push_back(id.substr(begin, end == std::string::npos ? std::string::npos : end - begin));
    if (end == std::string::npos) return segments;
    begin = end + 1;
  }
}

std::string readable_id(const std::string& id) {
  const std::vector<std::string> segments = id_segments(id);
  std::string out = segments.front() == "4t" ? std::string("4 (time)") : segments.front();
  for (std::size_t k = 1; k < segments.size(); ++k) out += ", " + readable_segment(segments[k]);
  return out;
}

// The same without the claim number: the name of a row within its claim ("2/mod2" → "Mod 2").
std::string readable_row(const std::string& id) {
  const std::vector<std::string> segments = id_segments(id);
  std::string out;
  for (std::size_t k = 1; k < segments.size(); ++k) out += (k > 1 ? ", " : "") + readable_segment(segments[k]);
  return out.empty() ? readable_id(id) : out;
}

TEST_CASE("a row id reads in the report's notation") {
  CHECK(readable_id("1/ps-literal") == "1, PS(¼, 0), literal row");
  CHECK(readable_id("5/cn/mod1") == "5, CN, Mod 1");
  CHECK(readable_id("4t/cn/mod3") == "4 (time), CN, Mod 3");
  CHECK(readable_id("6/exact") == "6, exact solution");
  CHECK(readable_id("3/cn/dt=0.25h") == "3, CN, Δt = 0.25h");
  CHECK(readable_id("4/ps-consistent/T=1p") == "4, PS(¼, 0), consistent mass, T = 1 period");
  CHECK(readable_id("4/be/T=30p") == "4, BE, T = 30 periods");
  CHECK(readable_id("3/sensitivity/mod3-3/4") == "3, sensitivity, Mod 3 as ¾ and ¼ on nodes 1, 2");
  CHECK(readable_id("9/new-case") == "9, new-case");  // an unknown segment is kept as it is
  CHECK(readable_row("2/mod2") == "Mod 2");
  CHECK(readable_row("6/step/cn") == "contact step, CN");
  CHECK(readable_row("7") == "7");  // an id without segments keeps its number
}

}  // namespace mrm::claims
