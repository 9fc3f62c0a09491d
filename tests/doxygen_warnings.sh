#!/usr/bin/env bash
# The API documentation is complete and shows the derivations: doxygen over lib/ (with the Doxyfile of
# the repository and the documents of doc/ that exist) must write no warning at all (every public
# member documented, no broken reference), and the pages of schemes.cpp and contact.cpp must carry
# their derivations with MathJax formulas; and no markup shows as text (tools/doc_markup.sh: an escaped
# tag such as a heading's literal <tt>, a literal **, a Markdown table not rendered, a column layout that
# doxygen joins into one paragraph).
# Usage: doxygen_warnings.sh [BIN_DIR] (BIN_DIR unused: ctest passes it to every shell test)
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/mrm-doxygen.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
cd "$root"
inputs=lib
mainpage=doc/mainpage.md
for f in doc/mainpage.md doc/mathematics.md doc/architecture.md doc/benchmarks.md doc/contact_treatments.md doc/peer.md doc/module_*.md; do [[ -f $f ]] && inputs+=" $f"; done
[[ -f $mainpage ]] || mainpage=''
{ cat Doxyfile; echo "OUTPUT_DIRECTORY = $work"; echo "INPUT = $inputs"; echo "USE_MDFILE_AS_MAINPAGE = $mainpage"; } |
  doxygen - >"$work/doxygen.log" 2>&1
status=0
if [[ -s $work/doxygen.log ]]; then
  echo "doxygen_warnings: doxygen wrote $(wc -l <"$work/doxygen.log") warning line(s):"
  cat "$work/doxygen.log"
  status=1
fi
expect() {  # expect FILE TEXT WHAT
  if ! grep -qF -- "$2" "$work/html/$1"; then
    echo "doxygen_warnings: $1 lacks $3 (\"$2\")"
    status=1
  fi
}
expect index.html 'src="mathjax/MathJax.js"' 'the MathJax script'
expect one__step__form_8cpp.html 'The massless contact row.' "the schemes' derivation"
expect one__step__form_8cpp.html '\( A U^{n+1} = B_1 U^n' 'a MathJax formula'
expect contact_8cpp.html 'Condensation of the massless contact node' "the contact node's derivation"
expect contact_8cpp.html 'The closed-form contact step' "the contact step's derivation"
expect contact_8cpp.html '\( A U = b - \kappa \lambda e_0' 'a MathJax formula'
# One page per module of the field's classes, the phase-matched mass, the batched step, the impact
# benchmarks' exact solution and the phase diagnostics, each with its derivation as MathJax formulas.
for page in contact_classes explicit_schemes interior_mass batched_step impact_solution phase; do
  expect "module_$page.html" '\[' "the derivation of $page as a displayed formula"
done
# The pages of the field: the benchmarks, the contact treatments and the peer, each with its references.
for page in benchmarks contact_treatments peer; do
  expect "$page.html" 'References' "the references of $page"
done
# The markup rendered, not shown as text.
bash tools/doc_markup.sh "$work/html" "$root" || status=1
((status == 0)) && echo "doxygen_warnings: no warning; derivations and formulas on the pages of schemes.cpp, contact.cpp and the modules; no markup shown as text"
exit "$status"
