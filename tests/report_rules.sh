#!/usr/bin/env bash
# The report's presentation rules, checked on the sources so that a new figure or table cannot
# slip past them:
#   - every figure script loads figures/style.gp (the report's typeface, the masses' colours, labels from
#     the data headers) and names no typeface of its own;
#   - no table of the article or its supplement (paper/*.tex) is shrunk (\resizebox, \scalebox,
#     \widetable): a wide table is split;
#   - the text says "Crank--Nicolson" (an en dash), never "Crank-Nicolson", and the tables it reads from
#     the programs' LaTeX values likewise (repro/configurations.hpp's scheme_label);
#   - each verdict is stated once: the verdict words of the paper's claims (\mrm{claim:KEY:verdict})
#     only in the article's table of the paper's results (paper/report.tex), those of this project's
#     hypotheses (claim:mechanism:verdict, claim:independent:verdict, \mrm{claims:group:...}) only in
#     the supplement's list of them (paper/supplement.tex); everything else refers to them.
# Usage: report_rules.sh BIN_DIR (unused: the sources are found beside this test).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
failures=0
fail() { echo "report_rules: $*"; failures=$((failures + 1)); }

for script in "$root"/figures/fig_*.gp "$root"/figures/bench_step.gp; do
  name=$(basename "$script")
  grep -q "^load dir.'style.gp'" "$script" || fail "$name does not load style.gp"
  if grep -nE 'font "[A-Za-z]' "$script"; then fail "$name names a typeface (use font(size) of style.gp)"; fi
done

if grep -nE '\\(resizebox|scalebox|widetable)' "$root"/paper/*.tex; then
  fail "a table of paper/ is shrunk (split it with Table::columns_subset instead)"
fi
if grep -nE 'Crank-Nicolson' "$root"/paper/*.tex; then
  fail "paper/ writes Crank-Nicolson with a hyphen"
fi
project_keys='mechanism|independent'  # this project's hypotheses among the summary's lines (tables.cpp)
for tex in "$root"/paper/*.tex; do
  name=$(basename "$tex")
  paper_verdicts=$(grep -nE '\\mrm\{claim:[a-z-]+:verdict\}' "$tex" | grep -vE "claim:($project_keys):verdict" || true)
  project_verdicts=$(grep -nE "\\\\mrm\\{(claim:($project_keys):verdict|claims:group:)" "$tex" || true)
  if [[ $name != report.tex && -n $paper_verdicts ]]; then
    echo "$paper_verdicts"
    fail "paper/$name states a verdict of the paper's claims (the article's Table 1 states it; refer to R1-R6)"
  fi
  if [[ $name != supplement.tex && -n $project_verdicts ]]; then
    echo "$project_verdicts"
    fail "paper/$name states a verdict of this project's hypotheses (the supplement states it; refer to H1-H6)"
  fi
done
if grep -nE 'return "[^"]*Crank-Nicolson' "$root/repro/configurations.hpp"; then
  fail "repro/configurations.hpp labels a scheme Crank-Nicolson with a hyphen (the label is LaTeX)"
fi

if ((failures > 0)); then
  echo "report_rules: $failures rule(s) broken"
  exit 1
fi
echo "report_rules: every figure script loads style.gp, no table is shrunk, the scheme names are typeset, each verdict stated once"
