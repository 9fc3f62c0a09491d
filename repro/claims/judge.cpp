/// @file claims/judge.cpp
/// @brief The verdict of a row: its margin against the criterion, judged against the expectation table.
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

std::string to_string(Verdict v) {
  static const char* const words[] = {"reproduced", "marginal", "not reproduced", "FAILED"};  // in the enum's order
  return words[static_cast<int>(v)];
}

double Margin::fraction() const {
  if (std::isnan(measured)) return -INFINITY;  // a value that cannot be computed fails
  return (at_most ? threshold - measured : measured - threshold) / scale;
}
std::string Margin::text() const {
  const double f = fraction();
  return what + ": " + significant(measured) + (at_most ? " ≤ " : " ≥ ") + significant(threshold) + "? margin " +
         (!std::isfinite(f)                                     ? std::string(f > 0 ? "∞" : "−∞")
          : std::abs(100 * f) >= 100 && std::abs(100 * f) < 1e6 ? decimals(100 * f, 0) + " %"
                                                                : significant(100 * f, 2) + " %");
}
Margin at_most(std::string what, double measured, double threshold, double scale) {
  return {measured, threshold, scale > 0 ? scale : std::abs(threshold), true, std::move(what)};
}
Margin at_least(std::string what, double measured, double threshold, double scale) {
  return {measured, threshold, scale > 0 ? scale : std::abs(threshold), false, std::move(what)};
}
Margin tighter(const Margin& a, const Margin& b) { return b.fraction() < a.fraction() ? b : a; }

ClaimResult Judge::operator()(std::string id, std::string claim, std::string measured, std::string criterion,
                              const Margin& margin, bool holds) {
  const auto expected_failure = expectations_.find(id);
  const bool expected_to_hold = expected_failure == expectations_.end();
  if (!expected_to_hold) used_.push_back(id);
  ClaimResult row{
      std::move(id), std::move(claim), std::move(measured), std::move(criterion), margin, Verdict::reproduced, "", {}};
  if (holds && expected_to_hold) {
    if (margin.fraction() < marginal_fraction) {
      row.verdict = Verdict::marginal;
      row.reason = "the criterion holds within " + significant(100 * marginal_fraction) + " % of its threshold";
    }
    return row;
  }
  if (!holds && !expected_to_hold) {
    row.verdict = Verdict::not_reproduced;
    row.reason = "expected failure: " + expected_failure->second;
  } else if (!holds) {
    row.verdict = Verdict::failed;
    row.reason = "the criterion does not hold";
  } else {
    row.verdict = Verdict::failed;
    row.reason =
        "unexpected pass: the criterion holds although the expectation table lists this row as not "
        "reproduced; update the table";
  }
  return row;
}

// An entry of the expectation table that no check produced (a renamed row, a removed check) would
// silently excuse nothing; it is reported as a failed row of its own.
std::vector<ClaimResult> Judge::stale() const {
  std::vector<ClaimResult> rows;
  for (const auto& [id, reason] : expectations_) {
    if (std::find(used_.begin(), used_.end(), id) != used_.end()) continue;
    rows.push_back({id,
                    "Expectation table entry",
                    "no check produced this row",
                    "every entry names a row",
                    at_least("rows with this id", 0, 1),
                    Verdict::failed,
                    "stale expectation: remove or rename the entry",
                    {}});
  }
  return rows;
}

TEST_CASE("a row's verdict follows its criterion, its margin and the expectation table, both ways") {
  Judge judge({{"x/listed", "it is known not to hold"}, {"x/stale", "no row has this id"}});
  const Margin clear = at_most("e", 0.5, 1), hair = at_most("e", 0.95, 1), over = at_most("e", 1.05, 1);
  CHECK(clear.fraction() == doctest::Approx(0.5));
  CHECK(at_least("p", 0.16, 1.0 / 6, 1.0 / 6).fraction() == doctest::Approx(-0.04));
  CHECK(judge("x/other", "", "", "", clear).verdict == Verdict::reproduced);
  CHECK(judge("x/other", "", "", "", hair).verdict == Verdict::marginal);  // within 10 %: not "reproduced"
  CHECK(judge("x/other", "", "", "", over).verdict == Verdict::failed);
  CHECK(judge("x/other", "", "", "", clear, false).verdict == Verdict::failed);  // a discrete part fails
  CHECK(judge("x/other", "", "", "", at_most("e", std::nan(""), 1)).verdict == Verdict::failed);
  CHECK(tighter(clear, hair).measured == 0.95);
  const ClaimResult expected = judge("x/listed", "", "", "", over);
  CHECK(expected.verdict == Verdict::not_reproduced);
  CHECK(expected.reason.find("it is known not to hold") != std::string::npos);
  const ClaimResult unexpected = judge("x/listed", "", "", "", clear);
  CHECK(unexpected.verdict == Verdict::failed);
  CHECK(unexpected.reason.find("unexpected pass") != std::string::npos);
  // An entry that no row used is a failed row of its own.
  const std::vector<ClaimResult> stale = judge.stale();
  REQUIRE(stale.size() == 1);
  CHECK(stale[0].id == "x/stale");
  CHECK(stale[0].verdict == Verdict::failed);
}

}  // namespace mrm::claims
