/// @file claims/tables.cpp
/// @brief The claims' rows as a word-wrapped text table, Markdown and LaTeX (repro/table).
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
// Output: the same rows as a word-wrapped text table (stdout), Markdown and LaTeX (for the report),
// all three written by repro/table.
namespace {

std::string verdict_text(const ClaimResult& r) {
  return r.reason.empty() ? to_string(r.verdict) : to_string(r.verdict) + " (" + r.reason + ")";
}

// "56 rows: 33 reproduced, 7 marginal, 15 not reproduced, 1 FAILED".
std::string counts_text(const std::vector<ClaimResult>& rows) {
  int counts[4] = {0, 0, 0, 0};
  for (const ClaimResult& r : rows) ++counts[static_cast<int>(r.verdict)];
  std::string text = std::to_string(rows.size()) + " rows";
  for (int v = 0; v < 4; ++v) text += (v ? ", " : ": ") + std::to_string(counts[v]) + " " + to_string(Verdict(v));
  return text;
}

// What was measured, then the margin of the criterion: the measured value against the threshold.
std::string measured_text(const ClaimResult& r) { return r.measured + ". Margin: " + r.margin.text(); }

}  // namespace

void write_text_summary(std::ostream& out, const std::vector<SummaryLine>& summary) {
  repro::Table table({"claim", "verdict", "holds", "fails", "decisive numbers"});
  for (const SummaryLine& l : summary) table.add_row({l.claim, l.verdict, l.holds, l.fails, l.numbers});
  table.write_text(out, {26, 11, 34, 30, 60});
}

// The terminal's summary: one line per claim, its verdict in a column of its own, then the counts of the
// rows; at most 12 lines of at most 100 columns (a longer claim text is cut with "…").
void write_short_summary(std::ostream& out, const std::vector<SummaryLine>& summary,
                         const std::vector<ClaimResult>& rows) {
  constexpr std::size_t claim_width = 80;
  for (const SummaryLine& l : summary) {
    std::string claim = l.claim;
    while (repro::display_width(claim) > claim_width - 1) {
      do claim.pop_back();
      while (!claim.empty() && (static_cast<unsigned char>(claim.back()) & 0xC0) == 0x80);
      if (repro::display_width(claim) <= claim_width - 2) claim += "…";
    }
    out << claim << std::string(claim_width - repro::display_width(claim), ' ') << l.verdict << '\n';
  }
  out << counts_text(rows) << " (detail: --detail, --markdown)\n";
}

void write_latex_summary(std::ostream& out, const std::vector<SummaryLine>& summary) {
  for (const SummaryLine& l : summary) {
    tex_define(out, "claim:" + l.key + ":verdict", latex_escape(l.verdict));
    tex_define(out, "claim:" + l.key + ":holds", latex_escape(l.holds));
    tex_define(out, "claim:" + l.key + ":fails", latex_escape(l.fails));
    tex_define(out, "claim:" + l.key + ":numbers", latex_escape(l.numbers));
  }
}

// The two kinds of rows and lines (claims.hpp): the paper's claims 1 to 5 (claim 3's sensitivity to the
// reconstruction among them), and this project's own hypotheses and checks.
bool paper_claim_row(const std::string& id) {
  const std::string claim = id.substr(0, id.find('/'));
  const bool numbered = claim == "1" || claim == "2" || claim == "3" || claim == "4" || claim == "4t" || claim == "5";
  return numbered && id.rfind("3/mechanism", 0) != 0;
}

bool paper_claim_line(const SummaryLine& line) { return line.key != "mechanism" && line.key != "independent"; }

TEST_CASE("the paper's claims and this project's hypotheses are told apart by the row's id") {
  for (const char* id : {"1/cn", "1/cn/large-steps", "2/mod1", "3/cn/dt=0.5h", "3/sensitivity/mod3-3/4", "4/ps/T=1p",
                         "4t/cn/mod3", "5/be/mod2"})
    CHECK(paper_claim_row(id));
  for (const char* id : {"3/mechanism/cn", "6/step/cn", "6/exact", "classes/oscillation/paper/cn", "classes/energy/x",
                         "7/phase-matched/order-u", "7/stress/paper"})
    CHECK_FALSE(paper_claim_row(id));
  CHECK(paper_claim_line({"ordering-cn", "", "", "", "", ""}));
  CHECK(paper_claim_line({"sensitivity", "", "", "", "", ""}));
  CHECK_FALSE(paper_claim_line({"mechanism", "", "", "", "", ""}));
  CHECK_FALSE(paper_claim_line({"independent", "", "", "", "", ""}));
}

// The summary's lines of one kind as a longtable: each claim, where it holds and where it fails, its
// numbers in italics under it (the verdict is the report's, from write_latex_summary's values).
void write_latex_summary_table(std::ostream& out, const std::vector<SummaryLine>& summary) {
  out << "% The summary of the claims checks: generated by check_claims --summary-table (do not edit).\n"
         "% Needs \\usepackage{longtable,booktabs,array} and the report's \\mrmdef.\n";
  repro::LatexLayout layout;
  layout.columns =
      ">{\\raggedright}p{0.22\\textwidth}>{\\raggedright}p{0.35\\textwidth}"
      ">{\\raggedright\\arraybackslash}p{0.33\\textwidth}";
  layout.longtable = true;
  layout.rule_between_rows = true;
  layout.note_columns = ">{\\raggedright\\arraybackslash}p{0.69\\textwidth}";
  layout.before = "{\\small\\setlength{\\tabcolsep}{3pt}\n";
  layout.after_end = "}";
  for (const bool paper : {true, false}) {
    repro::Table table({"claim", "holds", "fails"});
    for (const SummaryLine& l : summary)
      if (paper_claim_line(l) == paper)
        table.add_row({latex_escape(l.claim), latex_escape(l.holds), latex_escape(l.fails)},
                      "\\emph{" + latex_escape(l.numbers) + "}");
    std::ostringstream table_tex;
    table.write_latex(table_tex, layout);
    out << "\\mrmdef{claims:summary:" << (paper ? "paper" : "project") << "}{" << table_tex.str() << "}\n";
  }
}

// Rows of one group share their criterion and often their reason: from the second row on, the text
// table says "as above" instead of repeating them (the Markdown table repeats everything).
void write_text_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  repro::Table table({"claim", "measured", "criterion", "verdict"});
  for (std::size_t k = 0; k < rows.size(); ++k) {
    const ClaimResult& r = rows[k];
    const bool same_criterion = k > 0 && rows[k - 1].criterion == r.criterion;
    const bool same_reason = k > 0 && !r.reason.empty() && rows[k - 1].reason == r.reason;
    table.add_row({"[" + r.id + "] " + r.claim + " (alone: check_claims --only " + r.id + ")", measured_text(r),
                   same_criterion ? "(as above)" : r.criterion,
                   same_reason ? to_string(r.verdict) + " (as above)" : verdict_text(r)});
  }
  table.write_text(out, {34, 58, 40, 30});
  out << counts_text(rows) << '\n';
}

void write_markdown_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  repro::Table table({"claim", "measured", "criterion", "verdict"});
  for (const ClaimResult& r : rows)
    table.add_row({"**" + r.id + "** " + r.claim, measured_text(r), r.criterion, verdict_text(r)});
  table.write_markdown(out);
}

// The LaTeX form of a claim text: LaTeX's special characters escaped, the energy E_h and the velocity
// u_t as math. Every other character stands as it is: the report's preamble typesets the Unicode
// symbols of the texts (\newunicodechar in paper/report.tex), and a symbol it does not know stops the
// report's build ("Unicode character … not set up for use with LaTeX").
std::string latex_escape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    // The discrete energy's symbol, a subscript, not an escaped underscore.
    if (text.compare(i, 3, "E_h") == 0) {
      out += "\\ensuremath{E_h}";
      i += 3;
      continue;
    }
    // The velocity's symbol u_t, likewise (not inside a longer name such as err_u_t).
    if (text.compare(i, 3, "u_t") == 0 &&
        (i == 0 || !(std::isalnum(static_cast<unsigned char>(text[i - 1])) || text[i - 1] == '_'))) {
      out += "\\ensuremath{u_t}";
      i += 3;
      continue;
    }
    switch (const char c = text[i++]) {
      case '\\':
        out += "\\textbackslash{}";
        break;
      case '{':
      case '}':
      case '$':
      case '&':
      case '#':
      case '_':
      case '%':
        out += '\\';
        out += c;
        break;
      case '^':
        out += "\\textasciicircum{}";
        break;
      case '~':
        out += "\\textasciitilde{}";
        break;
      case '<':
      case '>':
      case '|':
        out += std::string("\\ensuremath{") + c + "}";
        break;
      default:
        out += c;
    }
  }
  return out;
}

TEST_CASE("LaTeX escaping handles the special characters and leaves the symbols to the preamble") {
  CHECK(latex_escape("a_b & 50% #1 {x} $") == "a\\_b \\& 50\\% \\#1 \\{x\\} \\$");
  CHECK(latex_escape("λ ≤ 0.5h^½ |x| < 1") ==
        "λ ≤ 0.5h\\textasciicircum{}½ \\ensuremath{|}x\\ensuremath{|} \\ensuremath{<} 1");
  CHECK(latex_escape("a\\b ~") == "a\\textbackslash{}b \\textasciitilde{}");
  CHECK(latex_escape("E_hⁿ/E_h(0)") == "\\ensuremath{E_h}ⁿ/\\ensuremath{E_h}(0)");
  CHECK(latex_escape("u_t L²") == "\\ensuremath{u_t} L²");
  CHECK(latex_escape("err_u_t") == "err\\_u\\_t");  // inside a name: escaped underscores
}

// Rows of one group share their criterion and often their reason: from the second row on, the LaTeX
// table says "as above" instead of repeating them, and a reason gets a line of its own under its row,
// across the three last columns, so that the table stays a few pages long.
void write_latex_table(std::ostream& out, const std::vector<ClaimResult>& rows) {
  const std::string column = ">{\\raggedright\\arraybackslash}p{";
  repro::LatexLayout layout;
  layout.before = "{\\footnotesize\\setlength{\\tabcolsep}{3pt}\n";
  layout.columns = column + "0.20\\linewidth}" + column + "0.40\\linewidth}" + column + "0.23\\linewidth}" + column +
                   "0.11\\linewidth}";
  layout.longtable = true;
  layout.rule_between_rows = true;
  layout.note_columns = column + "0.76\\linewidth}";
  layout.after_end = "}";
  // The tables as report values: the report reads this file in its preamble and prints the paper's rows
  // and this project's each in a table of its own (\mrm{claims:table:paper}, \mrm{claims:table:project}),
  // the rows of each in their order; the summaries before them come from write_latex_summary_table.
  out << "% The claims of the paper as executable checks: generated by check_claims --tex (do not edit).\n"
         "% Needs \\usepackage{longtable,booktabs,array} and the report's \\mrmdef.\n";
  for (const bool paper : {true, false}) {
    repro::Table table({"Claim", "Measured", "Criterion", "Verdict"});
    const ClaimResult* previous = nullptr;  // the row above in this table
    for (const ClaimResult& r : rows) {
      if (paper_claim_row(r.id) != paper) continue;
      const bool same_criterion = previous && previous->criterion == r.criterion;
      const bool same_reason = previous && previous->reason == r.reason;
      const std::string verdict =
          r.verdict == Verdict::reproduced ? to_string(r.verdict) : "\\textbf{" + to_string(r.verdict) + "}";
      table.add_row({"\\textbf{" + latex_escape(readable_id(r.id)) + ".} " + latex_escape(r.claim),
                     latex_escape(measured_text(r)),
                     same_criterion ? std::string("\\emph{as above}") : latex_escape(r.criterion), verdict},
                    r.reason.empty()
                        ? std::string()
                        : "\\emph{Why:} " + (same_reason ? std::string("as above.") : latex_escape(r.reason)));
      previous = &r;
    }
    std::ostringstream table_tex;
    table.write_latex(table_tex, layout);
    out << "\\mrmdef{claims:table:" << (paper ? "paper" : "project") << "}{" << table_tex.str() << "}\n";
  }
  // The verdicts of each group of rows (the first two segments of the id: "classes/oscillation",
  // "7/phase-matched", "3/sensitivity"), for the report's decision page and replication chapter:
  // \mrmdef{claims:group:classes:oscillation}{5 of 6 rows reproduced, 1 marginal}; a group whose rows
  // all hold reads "all N rows reproduced".
  std::vector<std::string> groups;
  std::map<std::string, std::array<int, 4>> counts;
  for (const ClaimResult& r : rows) {
    const std::size_t first = r.id.find('/');
    const std::size_t second = first == std::string::npos ? first : r.id.find('/', first + 1);
    std::string group = r.id.substr(0, second);
    for (char& c : group)
      if (c == '/') c = ':';
    if (counts.find(group) == counts.end()) groups.push_back(group), counts[group] = {0, 0, 0, 0};
    ++counts[group][static_cast<std::size_t>(r.verdict)];
  }
  // The numbers a row gives the report (ClaimResult::values): \mrmdef{claims:value:7:phase-matched:order-u:order}{0.784}.
  for (const ClaimResult& r : rows)
    for (const auto& [name, value] : r.values) {
      std::string key = r.id;
      for (char& c : key)
        if (c == '/') c = ':';
      tex_define(out, "claims:value:" + key + ":" + name, latex_escape(value));
    }
  for (const std::string& g : groups) {
    const std::array<int, 4>& c = counts[g];
    const int total = c[0] + c[1] + c[2] + c[3];
    std::string text = c[0] == total ? (total == 1 ? std::string("its one row reproduced")
                                                   : "all " + std::to_string(total) + " rows reproduced")
                                     : std::to_string(c[0]) + " of " + std::to_string(total) + " rows reproduced";
    for (int v = 1; v < 4; ++v)
      if (c[static_cast<std::size_t>(v)] > 0 && c[0] != total)
        text += ", " + std::to_string(c[static_cast<std::size_t>(v)]) + " " + to_string(Verdict(v));
    tex_define(out, "claims:group:" + g, text);
  }
}

TEST_CASE(
    "the claims table's group verdicts count each group's rows by verdict, and a row's values are report values") {
  const auto row = [](std::string id, Verdict v) {
    ClaimResult r;
    r.id = std::move(id);
    r.verdict = v;
    return r;
  };
  std::ostringstream out;
  write_latex_table(out, {row("classes/oscillation/paper/cn", Verdict::reproduced),
                          row("classes/oscillation/s1/cn", Verdict::marginal),
                          row("classes/oscillation/s1/ec", Verdict::not_reproduced), row("2/mod2", Verdict::reproduced),
                          row("2/mod3", Verdict::reproduced)});
  const std::string tex = out.str();
  // Two tables: the paper's rows (2/mod2, 2/mod3) in the first, this project's (classes/...) in the second.
  const std::size_t paper = tex.find("\\mrmdef{claims:table:paper}"),
                    project = tex.find("\\mrmdef{claims:table:project}");
  REQUIRE(paper != std::string::npos);
  REQUIRE(project != std::string::npos);
  CHECK(paper < project);
  CHECK(tex.find("Mod 2") > paper);
  CHECK(tex.find("Mod 2") < project);
  CHECK(tex.find("classes, oscillation") > project);
  CHECK(tex.find("\\mrmdef{claims:table}") == std::string::npos);
  CHECK(tex.find("\\mrmdef{claims:group:classes:oscillation}{1 of 3 rows reproduced, 1 marginal, 1 not reproduced}") !=
        std::string::npos);
  CHECK(tex.find("\\mrmdef{claims:group:2:mod2}{its one row reproduced}") != std::string::npos);
  CHECK(tex.find("claims:group:2:mod3") != std::string::npos);
  ClaimResult valued = row("7/phase-matched/order-u", Verdict::reproduced);
  valued.values = {{"order", "0.784"}};
  std::ostringstream with_value;
  write_latex_table(with_value, {valued});
  CHECK(with_value.str().find("\\mrmdef{claims:value:7:phase-matched:order-u:order}{0.784}") != std::string::npos);
}

}  // namespace mrm::claims
