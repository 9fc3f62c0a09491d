// The one table writer of the project: every program that prints a table (the figures' tables of
// errors and orders, the benchmark, the claims) fills a Table with rows of cells and writes it as
// plain text, Markdown or LaTeX, like deal.II's ConvergenceTable. The cells are text in the target's
// own markup (the caller decides what a cell says); the writer owns the layout: separators, rules,
// header, alignment, wrapping. `local_orders` gives the observed order between successive rows.
#pragma once

#include <cstddef>
#include <ostream>
#include <string>
#include <vector>

namespace mrm::repro {

/// How write_latex lays out a table.
struct LatexLayout {
  std::string columns;             ///< the column specification, e.g. "llrrr"
  bool booktabs = true;            ///< \toprule, \midrule, \bottomrule (else \hline)
  bool longtable = false;          ///< a longtable whose header is repeated on every page (booktabs)
  bool rule_between_rows = false;  ///< a \midrule between every two rows
  std::string note_columns;        ///< the p{} specification of a note spanning all columns but the first
  std::string before;              ///< text before \begin (comments, a group opened)
  std::string after_end;           ///< text right after \end{…} (a group closed)
  bool final_newline = true;       ///< a newline after the last line (false inside a \mrmdef value)
};

/// Rows of cells under a header, with rules between groups of rows and optional notes under a row.
class Table {
 public:
  /// Throws std::invalid_argument for an empty header.
  explicit Table(std::vector<std::string> headers);
  /// Appends a row; `note` (may be empty) is a line under it spanning the other columns (LaTeX).
  /// Throws std::invalid_argument unless the row has one cell per column.
  Table& add_row(std::vector<std::string> cells, std::string note = "");
  /// A rule between the rows added so far and the next ones.
  Table& add_rule();

  /// The table of the given columns only, in the given order, with the same rows, notes and rules: a
  /// table too wide for the page is printed as two at the text size, not shrunk. Throws
  /// std::invalid_argument for an empty list or a column index out of range.
  Table columns_subset(const std::vector<std::size_t>& keep) const;

  std::size_t columns() const { return headers_.size(); }
  std::size_t rows() const { return rows_.size(); }

  /// `| a | b |` lines after the header and its alignment line: one of "---", "---:", ":---" per
  /// column, from `alignment` ('l', 'r' or '-' per column; empty: '-' for all). Rules are not drawn.
  /// A '|' inside a cell is escaped.
  void write_markdown(std::ostream& out, const std::string& alignment = "") const;
  /// The LaTeX environment (tabular or longtable): header, rows `a & b \\`, rules, notes.
  void write_latex(std::ostream& out, const LatexLayout& layout) const;
  /// A plain-text grid: each column `widths[c]` display columns wide (UTF-8 aware), the cells
  /// word-wrapped into it, a +---+ rule under the header and after every row.
  void write_text(std::ostream& out, const std::vector<std::size_t>& widths) const;

 private:
  struct Row {
    std::vector<std::string> cells;
    std::string note;
    bool rule_after = false;
  };
  std::vector<std::string> headers_;
  std::vector<Row> rows_;
};

/// The table as a LaTeX tabular (booktabs) with the given column specification, without the final
/// newline: the value of a `\mrmdef` that the report prints where it wants the table.
std::string latex_tabular(const Table& table, const std::string& columns);

/// The observed order between successive rows, as ConvergenceTable's reduction rate: for k ≥ 1,
/// log(e_{k−1}/e_k) / log(s_{k−1}/s_k) (for halved steps, log₂ of the error ratio); NaN for k = 0 and
/// where an error is not positive. Throws std::invalid_argument for sizes that differ.
std::vector<double> local_orders(const std::vector<double>& steps, const std::vector<double>& errors);

/// The number of display columns of UTF-8 text (one per code point).
std::size_t display_width(const std::string& text);
/// Greedy word wrap to `width` display columns; a longer word gets a line of its own.
std::vector<std::string> wrap(const std::string& text, std::size_t width);

}  // namespace mrm::repro
