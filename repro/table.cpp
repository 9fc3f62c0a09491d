// The table writer; see table.hpp.
#include "table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <doctest/doctest.h>

namespace mrm::repro {

Table::Table(std::vector<std::string> headers) : headers_(std::move(headers)) {
  if (headers_.empty()) throw std::invalid_argument("Table: a table needs at least one column");
}

Table& Table::add_row(std::vector<std::string> cells, std::string note) {
  if (cells.size() != headers_.size())
    throw std::invalid_argument("Table::add_row: " + std::to_string(cells.size()) + " cells for " +
                                std::to_string(headers_.size()) + " columns");
  rows_.push_back({std::move(cells), std::move(note), false});
  return *this;
}

Table& Table::add_rule() {
  if (!rows_.empty()) rows_.back().rule_after = true;
  return *this;
}

Table Table::columns_subset(const std::vector<std::size_t>& keep) const {
  if (keep.empty()) throw std::invalid_argument("Table::columns_subset: no column kept");
  std::vector<std::string> headers;
  for (std::size_t c : keep) {
    if (c >= headers_.size())
      throw std::invalid_argument("Table::columns_subset: column " + std::to_string(c) + " of a table with " +
                                  std::to_string(headers_.size()));
    headers.push_back(headers_[c]);
  }
  Table subset(std::move(headers));
  for (const Row& row : rows_) {
    std::vector<std::string> cells;
    for (std::size_t c : keep) cells.push_back(row.cells[c]);
    subset.add_row(std::move(cells), row.note);
    if (row.rule_after) subset.add_rule();
  }
  return subset;
}

void Table::write_markdown(std::ostream& out, const std::string& alignment) const {
  const auto cell = [](const std::string& s) {
    std::string t;
    for (char c : s) t += c == '|' ? std::string("\\|") : std::string(1, c);
    return t;
  };
  const auto line = [&](const std::vector<std::string>& cells) {
    out << '|';
    for (const std::string& c : cells) out << ' ' << cell(c) << " |";
    out << '\n';
  };
  line(headers_);
  out << '|';
  for (std::size_t c = 0; c < columns(); ++c) {
    const char a = c < alignment.size() ? alignment[c] : '-';
    out << (a == 'r' ? "---:" : a == 'l' ? ":---" : "---") << '|';
  }
  out << '\n';
  for (const Row& r : rows_) line(r.cells);
}

void Table::write_latex(std::ostream& out, const LatexLayout& layout) const {
  const char* top = layout.booktabs ? "\\toprule\n" : "\\hline\n";
  const char* mid = layout.booktabs ? "\\midrule\n" : "\\hline\n";
  const char* bottom = layout.booktabs ? "\\bottomrule\n" : "\\hline\n";
  const auto cells = [&](const std::vector<std::string>& c) {
    for (std::size_t k = 0; k < c.size(); ++k) out << (k ? " & " : "") << c[k];
    out << " \\\\\n";
  };
  const std::string environment = layout.longtable ? "longtable" : "tabular";
  out << layout.before << "\\begin{" << environment << "}{" << layout.columns << "}\n";
  if (layout.longtable) {
    for (const char* end : {"\\endfirsthead\n", "\\endhead\n"}) {
      out << top;
      cells(headers_);
      out << mid << end;
    }
    out << bottom << "\\endfoot\n";
  } else {
    out << top;
    cells(headers_);
    out << mid;
  }
  for (std::size_t k = 0; k < rows_.size(); ++k) {
    const Row& r = rows_[k];
    cells(r.cells);
    if (!r.note.empty())
      out << " & \\multicolumn{" << columns() - 1 << "}{" << layout.note_columns << "}{" << r.note << "} \\\\\n";
    if (k + 1 < rows_.size() && (r.rule_after || layout.rule_between_rows)) out << mid;
  }
  if (!layout.longtable) out << bottom;
  out << "\\end{" << environment << "}" << layout.after_end << (layout.final_newline ? "\n" : "");
}

std::size_t display_width(const std::string& text) {
  std::size_t w = 0;
  for (unsigned char c : text) w += (c & 0xC0) != 0x80;
  return w;
}

std::vector<std::string> wrap(const std::string& text, std::size_t width) {
  std::vector<std::string> lines;
  std::istringstream words(text);
  std::string word, line;
  while (words >> word) {
    if (!line.empty() && display_width(line) + 1 + display_width(word) > width) {
      lines.push_back(line);
      line.clear();
    }
    line += (line.empty() ? "" : " ") + word;
  }
  if (!line.empty() || lines.empty()) lines.push_back(line);
  return lines;
}

void Table::write_text(std::ostream& out, const std::vector<std::size_t>& widths) const {
  if (widths.size() != columns())
    throw std::invalid_argument("Table::write_text: " + std::to_string(widths.size()) + " widths for " +
                                std::to_string(columns()) + " columns");
  const auto rule = [&] {
    for (std::size_t w : widths) out << '+' << std::string(w + 2, '-');
    out << "+\n";
  };
  const auto print_row = [&](const std::vector<std::string>& cells) {
    std::vector<std::vector<std::string>> wrapped;
    std::size_t height = 0;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      wrapped.push_back(wrap(cells[c], widths[c]));
      height = std::max(height, wrapped.back().size());
    }
    for (std::size_t l = 0; l < height; ++l) {
      for (std::size_t c = 0; c < cells.size(); ++c) {
        const std::string cell = l < wrapped[c].size() ? wrapped[c][l] : "";
        const std::size_t w = display_width(cell);
        out << "| " << cell << std::string(w < widths[c] ? widths[c] - w : 0, ' ') << ' ';
      }
      out << "|\n";
    }
  };
  rule();
  print_row(headers_);
  rule();
  for (const Row& r : rows_) {
    print_row(r.cells);
    rule();
  }
}

std::string latex_tabular(const Table& table, const std::string& columns) {
  LatexLayout layout;
  layout.columns = columns;
  layout.final_newline = false;
  std::ostringstream out;
  table.write_latex(out, layout);
  return out.str();
}

std::vector<double> local_orders(const std::vector<double>& steps, const std::vector<double>& errors) {
  if (steps.size() != errors.size())
    throw std::invalid_argument("local_orders: " + std::to_string(steps.size()) + " steps for " +
                                std::to_string(errors.size()) + " errors");
  std::vector<double> orders(errors.size(), std::numeric_limits<double>::quiet_NaN());
  for (std::size_t k = 1; k < errors.size(); ++k)
    if (errors[k] > 0 && errors[k - 1] > 0)
      orders[k] = std::log2(errors[k - 1] / errors[k]) / std::log2(steps[k - 1] / steps[k]);
  return orders;
}

TEST_SUITE_BEGIN("table");

TEST_CASE("the same rows give a Markdown table, a booktabs tabular and a text grid") {
  Table t({"N", "error"});
  t.add_row({"8", "0.5"}).add_row({"16", "0.25"}).add_rule().add_row({"a|b", "x"});
  std::ostringstream md, tex, text;
  t.write_markdown(md, "rl");
  CHECK(md.str() == "| N | error |\n|---:|:---|\n| 8 | 0.5 |\n| 16 | 0.25 |\n| a\\|b | x |\n");
  LatexLayout layout;
  layout.columns = "rr";
  layout.final_newline = false;
  t.write_latex(tex, layout);
  CHECK(tex.str() ==
        "\\begin{tabular}{rr}\n\\toprule\nN & error \\\\\n\\midrule\n8 & 0.5 \\\\\n16 & 0.25 \\\\\n\\midrule\n"
        "a|b & x \\\\\n\\bottomrule\n\\end{tabular}");
  CHECK(latex_tabular(t, "rr") == tex.str());  // the same, as a \mrmdef value
  t.write_text(text, {3, 5});
  CHECK(text.str() ==
        "+-----+-------+\n| N   | error |\n+-----+-------+\n| 8   | 0.5   |\n+-----+-------+\n| 16  | 0.25  |\n"
        "+-----+-------+\n| a|b | x     |\n+-----+-------+\n");
}

TEST_CASE("a longtable repeats its header and puts a note under its row") {
  Table t({"a", "b", "c"});
  t.add_row({"1", "2", "3"}, "why").add_row({"4", "5", "6"});
  LatexLayout layout;
  layout.columns = "lll";
  layout.longtable = true;
  layout.rule_between_rows = true;
  layout.note_columns = "l";
  std::ostringstream tex;
  t.write_latex(tex, layout);
  CHECK(tex.str() ==
        "\\begin{longtable}{lll}\n\\toprule\na & b & c \\\\\n\\midrule\n\\endfirsthead\n\\toprule\na & b & c \\\\\n"
        "\\midrule\n\\endhead\n\\bottomrule\n\\endfoot\n1 & 2 & 3 \\\\\n & \\multicolumn{2}{l}{why} \\\\\n\\midrule\n"
        "4 & 5 & 6 \\\\\n\\end{longtable}\n");
}

TEST_CASE("a subset of the columns keeps every row, note and rule") {
  Table t({"a", "b", "c"});
  t.add_row({"1", "2", "3"}, "why").add_rule().add_row({"4", "5", "6"});
  LatexLayout layout;
  layout.columns = "ll";
  layout.final_newline = false;
  std::ostringstream tex;
  t.columns_subset({0, 2}).write_latex(tex, layout);
  CHECK(tex.str() ==
        "\\begin{tabular}{ll}\n\\toprule\na & c \\\\\n\\midrule\n1 & 3 \\\\\n & \\multicolumn{1}{}{why} \\\\\n"
        "\\midrule\n4 & 6 \\\\\n\\bottomrule\n\\end{tabular}");
  CHECK_THROWS_AS(t.columns_subset({}), std::invalid_argument);
  CHECK_THROWS_AS(t.columns_subset({0, 3}), std::invalid_argument);
}

TEST_CASE("a row with the wrong number of cells is refused") {
  Table t({"a", "b"});
  CHECK_THROWS_AS(t.add_row({"1"}), std::invalid_argument);
  CHECK_THROWS_AS(Table({}), std::invalid_argument);
}

TEST_CASE("text cells are wrapped at word boundaries by display width") {
  CHECK(wrap("λ ≤ 0 and more words", 7) == std::vector<std::string>{"λ ≤ 0", "and", "more", "words"});
  CHECK(display_width("λ≤x") == 3);
}

TEST_CASE("the local orders of errors that halve with the step are one") {
  // e = C s: halving s halves e, so every local order is exactly 1; e = C s² gives 2; a zero error none.
  const std::vector<double> steps{0.4, 0.2, 0.1}, first{0.8, 0.4, 0.2}, second{0.16, 0.04, 0.01};
  const auto p1 = local_orders(steps, first), p2 = local_orders(steps, second);
  CHECK(std::isnan(p1[0]));
  CHECK(p1[1] == 1.0);
  CHECK(p1[2] == 1.0);
  CHECK(p2[1] == 2.0);
  CHECK(std::isnan(local_orders({1, 0.5}, {1, 0})[1]));
  CHECK_THROWS_AS(local_orders({1}, {1, 2}), std::invalid_argument);
}

TEST_SUITE_END();

}  // namespace mrm::repro
