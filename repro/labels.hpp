// The one table of labels of the harness: how the programs, the report and the figures name the
// schemes, the masses, the error measures and the benchmarks. The ids are the library's (its
// registries: mrm::scheme_registry, mrm::mass_form_registry; ErrorAccumulator::names); the labels are
// here, each in two forms: `plain`, Unicode text for help texts, data headers and gnuplot keys (the
// figure programs write `# label <id> = <plain>` lines that figures/style.gp reads), and `latex`, for
// the report's tables and values.
#pragma once

#include <array>
#include <ostream>
#include <string>
#include <vector>

#include "time/schemes.hpp"

namespace mrm::repro {

struct Label {
  std::string id;                    ///< the id of data files and command lines ("cn", "mod3", "err_u0_L2", "grazing")
  std::string plain;                 ///< "Crank–Nicolson", "Mod 3"
  std::string latex;                 ///< "Crank--Nicolson", "Mod~3"
  std::string abbreviation = plain;  ///< ASCII, for narrow table cells: "CN", "Mod 3"
};

/// The label of a scheme of the registry.
const Label& scheme_label(Scheme scheme);
const Label& scheme_label(const std::string& id);
/// The LaTeX label of a table row: Paoli–Schatzman's says which contact row it uses ("…, literal row"),
/// so that a row of the literal form is never read as the scheme's algebraic form.
std::string scheme_row_label(const std::string& id, const std::string& ps_form);
/// The label of a named mass (consistent, mod1, mod2, mod3); any other spec ("node1:7/6") is its own label.
Label mass_label(const std::string& spec);
/// The eight measures of mathematics.md §5, in the order of ErrorAccumulator::names.
const std::array<Label, 8>& measure_labels();
/// The ids of the registry of benchmarks (mrm::benchmarks(), lib/exact/benchmarks.hpp), in the order of
/// their choice list: paper, smooth-impact, grazing, then the field's.
std::vector<std::string> benchmark_names();

/// The three schemes of the paper (cn, be, ps), in the order of its Figure 1 and of every data file.
const std::vector<std::string>& scheme_names();
/// The three mass choices of the paper (mod1, mod2, mod3).
const std::vector<std::string>& mass_names();
/// The ids of every scheme of the registry, for choice lists.
std::vector<std::string> scheme_ids();

/// The help text of a choice of scheme or benchmark: `what`, then each id with the summary of its registry
/// entry (mrm::scheme_registry, mrm::benchmarks), one a line (the help lists them one a line: options.hpp).
std::string scheme_help(const std::string& what);
std::string benchmark_help(const std::string& what);

/// `# label <id> = <plain>` for every scheme and named mass: the lines figures/style.gp reads.
void write_labels(std::ostream& out);
/// `# title <id> = <plain>` for every scheme, with ", <contact_row> contact row" for a scheme that takes
/// a contact row (SchemeParameter::contact_row): the titles of the blocks of a figure whose schemes are
/// its rows, so that its script compares no id.
void write_scheme_titles(std::ostream& out, const std::string& contact_row);

}  // namespace mrm::repro
