// check_claims: every claim of the paper (mathematics.md §6) checked by one command.
//
// What it computes. It runs the checks of repro/claims.cpp on the benchmark of mathematics.md §2 — stability
// over 100 periods, total mass, the ordering Mod 3 < Mod 2 < Mod 1 of the paper's Figure 1, convergence
// in h and in Δt, energy conservation and dissipation, and two comparisons with independent
// computations (the closed-form contact step against a sparse LU solve of the step's saddle-point
// system; the closed-form solution against a very fine numerical solution) — and prints one table:
// claim | what was measured | criterion | verdict. The verdict is "reproduced", "not reproduced" (an
// expected failure, listed with its reason and numbers in repro/claims.cpp's expectation table) or
// "FAILED". The exit status is 0 iff no row FAILED; an expected failure that unexpectedly holds is a
// failure too. The table is deterministic; the time each check took goes to stderr only.
//
// Sample runs:
//   check_claims
//   check_claims --tex output/data/claims.tex --markdown output/data/claims.md
//
// Description. Steps: (1) read the options; (2) open the output files (so that a bad path fails before
// the checks run); (3) run every check; (4) print the table on stdout, write the files, and exit with
// the verdict.
#include <chrono>
#include <cmath>
#include <iostream>
#include <memory>
#include <string>

#include "claims.hpp"
#include "options.hpp"
#include "output_file.hpp"

namespace cli = mrm::cli;
namespace claims = mrm::claims;

int main(int argc, char** argv) {
  return cli::guarded_main("check_claims", [&] {
    // 1. Options.
    std::string tex, markdown;
    cli::Parser parser("check_claims",
                       "Checks every claim of the paper (mathematics.md §6) on the benchmark and prints a table: claim, "
                       "what was measured, criterion, verdict (reproduced, not reproduced = expected failure, or "
                       "FAILED). Exits 0 iff no check FAILED.",
                       {"check_claims", "check_claims --tex output/data/claims.tex --markdown output/data/claims.md"});
    parser.add_string("--tex", "", "FILE", "also write the table as a LaTeX longtable fragment (booktabs) to FILE",
                      &tex);
    parser.add_string("--markdown", "", "FILE", "also write the table as Markdown to FILE", &markdown);
    if (parser.parse(argc, argv, std::cout) == cli::Outcome::exit_success) return 0;

    // 2. Outputs, opened before the checks run.
    std::unique_ptr<cli::AtomicFile> tex_file, markdown_file;
    if (parser.given("--tex")) tex_file = std::make_unique<cli::AtomicFile>(tex, "--tex");
    if (parser.given("--markdown")) markdown_file = std::make_unique<cli::AtomicFile>(markdown, "--markdown");

    // 3. The checks (timings on stderr).
    const auto start = std::chrono::steady_clock::now();
    const std::vector<claims::ClaimResult> rows = claims::check_all(claims::paper_expectations(), &std::cerr);
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::cerr << "check_claims: all checks took " << cli::format_real(std::round(elapsed * 100) / 100) << " s\n";

    // 4. The table, the files, the verdict.
    claims::write_text_table(std::cout, rows);
    if (tex_file) {
      claims::write_latex_table(tex_file->stream(), rows);
      tex_file->commit();
    }
    if (markdown_file) {
      claims::write_markdown_table(markdown_file->stream(), rows);
      markdown_file->commit();
    }
    int failed = 0;
    for (const claims::ClaimResult& r : rows) failed += r.verdict == claims::Verdict::failed;
    if (failed > 0) std::cerr << "check_claims: " << failed << " check(s) FAILED\n";
    return failed > 0 ? 1 : 0;
  });
}
