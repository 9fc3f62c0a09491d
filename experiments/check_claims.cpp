// check_claims: every claim of the paper (mathematics.md §6) checked by one command.
//
// What it computes. It runs the checks of repro/claims/ on the benchmark of mathematics.md §2 — stability
// over 100 periods and over a region of Δt/h and 1000 periods, total mass, the ordering Mod 3 < Mod 2 <
// Mod 1 of the paper's Figure 1 per cell (scheme, Δt/h, N, horizon) of a sweep, with its mechanism (the
// drift of the impact times, mathematics.md §8) and its sensitivity to the reconstruction of the masses,
// convergence in h against the predicted orders (mathematics.md §9) and in Δt, energy conservation and
// dissipation, and two comparisons with independent computations (the closed-form contact step against
// a sparse LU solve of the step's saddle-point system; the closed-form solution against a very fine
// numerical solution) — and prints a summary of at most 12 lines (each claim, its verdict, the region
// where it holds and where it fails, the decisive numbers), then one table: claim | what was measured |
// criterion | verdict. The verdict is "reproduced", "not reproduced" (an
// expected failure, listed with its reason and numbers in repro/claims/expectations.cpp) or
// "FAILED". The exit status is 0 iff no row FAILED; an expected failure that unexpectedly holds is a
// failure too. The table is deterministic; the time each check took goes to stderr only.
//
// Sample runs:
//   check_claims
//   check_claims --detail output/data/claims.txt --tex output/data/claims.tex --markdown output/data/claims.md
//
// Description. Steps: (1) read the options; (2) open the output files (so that a bad path fails before
// the checks run); (3) run every check; (4) print the table on stdout, write the files, and exit with
// the verdict.
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <stdexcept>
#include <string>

#include "claims.hpp"
#include "regions.hpp"
#include "sweep.hpp"
#include "options.hpp"
#include "output_file.hpp"

namespace cli = mrm::cli;
namespace claims = mrm::claims;

int main(int argc, char** argv) {
  return cli::guarded_main("check_claims", [&] {
    // 1. Options.
    std::string tex, markdown, summary_tex, summary_table, sweep, detail, only;
    cli::Parser parser(
        "check_claims",
        "Checks every claim of the paper (mathematics.md §6) on the benchmark and prints a table: claim, "
        "what was measured, criterion, verdict (reproduced, not reproduced = expected failure, or "
        "FAILED). Exits 0 iff no check FAILED.",
        {"check_claims", "check_claims --tex output/data/claims.tex --markdown output/data/claims.md"});
    parser.add_output("--detail", "",
                      "also write the summary with its regions and numbers and the table of every row (claim, "
                      "measured with the margin, criterion with its basis, verdict) as plain text to FILE",
                      &detail);
    parser.add_output("--tex", "",
                      "also write the table as two LaTeX longtables (booktabs), the paper's claims and this project's "
                      "hypotheses, as report values to FILE",
                      &tex);
    parser.add_output("--markdown", "", "also write the table as Markdown to FILE", &markdown);
    parser.add_output("--summary-tex", "",
                      "also write the summary as \\mrmdef lines (claim:KEY:verdict, holds, fails, numbers) to FILE",
                      &summary_tex);
    parser.add_output(
        "--summary-table", "",
        "also write the summary as two LaTeX longtables (the paper's claims, this project's hypotheses) to FILE",
        &summary_table);
    parser.add_output("--sweep", "",
                      "also write every measure of the sweep behind claims 3 and 4 (the maps' data) to FILE", &sweep);
    parser.add_string("--only", "", "ID",
                      "run only the checks of the rows whose id starts with ID (a row's id, as the detail prints it "
                      "in brackets, or a prefix such as 7/stress/): the same numbers as the full run, without the "
                      "summary",
                      &only);
    mrm::repro::SweepOptions sweep_options;
    mrm::repro::add_sweep_options(parser, sweep_options);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;
    mrm::repro::apply_sweep_options(sweep_options);
    if (parser.given("--only")) {  // a prefix no row can have: refused before any check runs
      try {
        claims::require_claim_row_prefix(only);
      } catch (const std::invalid_argument& e) {
        throw cli::UsageError(std::string("--only: ") + e.what());
      }
      for (const char* whole : {"--summary-tex", "--summary-table", "--sweep"})  // they need every row
        if (parser.given(whole))
          throw cli::UsageError(std::string(whole) +
                                ": does not apply with --only (it needs every row; allowed with --only: --detail, "
                                "--tex, --markdown)");
    }

    // 2. Outputs, opened before the checks run.
    const auto open = [&](const std::string& option, const std::string& path) {
      return parser.given(option) ? std::make_unique<cli::AtomicFile>(path, option) : nullptr;
    };
    const std::unique_ptr<cli::AtomicFile> tex_file = open("--tex", tex), markdown_file = open("--markdown", markdown),
                                           summary_tex_file = open("--summary-tex", summary_tex),
                                           summary_table_file = open("--summary-table", summary_table),
                                           sweep_file = open("--sweep", sweep), detail_file = open("--detail", detail);

    // 3. The checks (timings on stderr).
    const auto start = std::chrono::steady_clock::now();
    const claims::ClaimsReport report = claims::check_all(claims::paper_expectations(), &std::cerr, only);
    const std::vector<claims::ClaimResult>& rows = report.rows;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "check_claims: all checks took " << cli::format_real(std::round(elapsed * 100) / 100) << " s\n";

    // 4. The summary, the table, the files, the verdict.
    if (only.empty())
      claims::write_short_summary(std::cout, report.summary, rows);
    else
      claims::write_text_table(std::cout, rows);
    if (detail_file) {
      if (only.empty()) {
        detail_file->stream() << "Summary: each claim of the paper (1 to 5) and this project's hypotheses H1, H2, its "
                                 "verdict and the region where it holds\n";
        claims::write_text_summary(detail_file->stream(), report.summary);
        detail_file->stream() << '\n';
      }
      detail_file->stream() << "Detail: one row per check (check_claims --only ID runs the checks of row ID alone)\n";
      claims::write_text_table(detail_file->stream(), rows);
    }
    if (summary_tex_file) claims::write_latex_summary(summary_tex_file->stream(), report.summary);
    if (summary_table_file) claims::write_latex_summary_table(summary_table_file->stream(), report.summary);
    if (sweep_file) mrm::repro::write_sweep(sweep_file->stream(), report.sweep);
    if (tex_file) claims::write_latex_table(tex_file->stream(), rows);
    if (markdown_file) claims::write_markdown_table(markdown_file->stream(), rows);
    // The table on stdout, then every file or none.
    cli::commit_all({summary_tex_file.get(), summary_table_file.get(), sweep_file.get(), tex_file.get(),
                     markdown_file.get(), detail_file.get()});
    int failed = 0;
    for (const claims::ClaimResult& r : rows) failed += r.verdict == claims::Verdict::failed;
    if (failed > 0) std::cerr << "check_claims: " << failed << " check(s) FAILED\n";
    return failed > 0 ? 1 : 0;
  });
}
