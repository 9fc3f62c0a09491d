#!/usr/bin/env bash
# The report's presentation rules, checked on the sources so that a new figure or table cannot
# slip past them:
#   - every figure script loads figures/style.gp (the report's typeface, the masses' colours, labels from
#     the data headers) and names no typeface of its own;
#   - no table of the report is shrunk (\resizebox, \scalebox, \widetable): a wide table is split;
#   - the text says "Crank--Nicolson" (an en dash), never "Crank-Nicolson", and the tables it reads from
#     the programs' LaTeX values likewise (repro/configurations.hpp's scheme_label).
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

if grep -nE '\\(resizebox|scalebox|widetable)' "$root/paper/report.tex"; then
  fail "paper/report.tex shrinks a table (split it with Table::columns_subset instead)"
fi
if grep -nE 'Crank-Nicolson' "$root/paper/report.tex"; then
  fail "paper/report.tex writes Crank-Nicolson with a hyphen"
fi
if grep -nE 'return "[^"]*Crank-Nicolson' "$root/repro/configurations.hpp"; then
  fail "repro/configurations.hpp labels a scheme Crank-Nicolson with a hyphen (the label is LaTeX)"
fi

if ((failures > 0)); then
  echo "report_rules: $failures rule(s) broken"
  exit 1
fi
echo "report_rules: every figure script loads style.gp, no table is shrunk, the scheme names are typeset"
