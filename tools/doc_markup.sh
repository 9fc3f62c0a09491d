#!/usr/bin/env bash
# The API documentation shows its markup rendered, not as text. Doxygen prints some markup literally
# without a warning; this finds what it left, in the generated HTML and, for what the HTML cannot show,
# in the sources:
#  1. an escaped HTML tag in a page or in the search index (`&lt;tt&gt;`: doxygen 1.9.4 writes a code
#     span in a heading as a literal <tt>...</tt>, which a browser shows as text);
#  2. a literal ** (a bold span that doxygen did not take: one holding a formula or a code span at its
#     end, or one that opens with a quote; <b>...</b> renders in every case);
#  3. a Markdown table row or rule that was not rendered as a table (a `| a | b |` line in the text);
#  4. a doxygen command left as text: a formula delimiter \f$ \f[ \f] or a \ref / @ref;
#  5. in the sources (the doc comments /// and //! of lib/, the pages doc/*.md), two or more lines laid
#     out in columns (runs of two or more spaces inside the line) but indented too little to be a code
#     block: doxygen runs them into one paragraph, so a table must be a Markdown table.
# The code listings (*_source.html) and the code blocks of the pages are left out: a `**` or a `|` is
# code there.
# Usage: doc_markup.sh HTML_DIR [SOURCE_DIR]  (SOURCE_DIR: the repository, default: beside this file)
# Prints each finding as FILE:LINE: WHAT and exits 1 if there is one.
set -euo pipefail
html=${1:?usage: doc_markup.sh HTML_DIR [SOURCE_DIR]}
src=${2:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
[[ -f $html/index.html ]] || { echo "doc_markup: no index.html in $html"; exit 1; }
mapfile -t pages < <(find "$html" -maxdepth 1 -name '*.html' ! -name '*_source.html' | LC_ALL=C sort)
mapfile -t index < <(find "$html" -path '*/search/*.js' | LC_ALL=C sort)
work=$(mktemp -d "${TMPDIR:-/tmp}/doc_markup.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
found=0
report() {  # report KIND < FINDINGS: prints each finding (FILE:LINE:TEXT), shortened, under KIND
  local line
  while IFS= read -r line; do
    echo "doc_markup: $1: ${line:0:240}"
    found=$((found + 1))
  done
}
# The text of the pages, without their code: the lines of a code block (<div class="line">, within
# <pre>...</pre>) are dropped, and <code>...</code> spans removed from the others.
awk '
  /<pre[ >]/ { pre = 1 }
  pre { if (/<\/pre>/) pre = 0; next }
  /<div class="line">/ { next }
  { gsub(/<code>[^<]*<\/code>/, ""); print FILENAME ":" FNR ":" $0 }
' "${pages[@]}" >"$work/text"
tags='tt|b|i|em|strong|code|pre|a|br|p|sub|sup|table|tr|td|th|ul|ol|li|dl|dt|dd|h[1-6]|span|div|small|kbd|hr|img'
escaped="&lt;/?($tags)( [^&]*)?/?&gt;"
report 'escaped HTML tag' < <(grep -E "$escaped" "$work/text"; grep -HnE "$escaped" "${index[@]}" /dev/null)
report 'literal ** (bold not rendered)' < <(grep -F '**' "$work/text")
row='(^|[>[:space:]])\|[[:space:]][^|]*[[:space:]]\|[[:space:]][^|]*\|([[:space:]]|$|<)'
rule='\|[[:space:]]*:?-{3,}:?[[:space:]]*\|'
report 'Markdown table not rendered' < <(grep -E "$row|$rule" "$work/text")
report 'doxygen command left as text' < <(grep -E '\\f[][$]|[\\@]ref[[:space:]]' "$work/text")
# 5. The sources. A doc comment's text starts one space after /// (or //!), a page's at its margin; a
# code block is indented by at least four more. Lines between ``` or ~~~ fences and between \f[ and \f]
# are code or formulas; list items and Markdown table rows are left alone.
mapfile -t sources < <(cd "$src" && { find lib -name '*.hpp' -o -name '*.cpp'; ls doc/*.md; } | LC_ALL=C sort)
report 'column layout not rendered' < <(cd "$src" && awk '
  function flush() {
    if (run >= 2) print first ": " run " lines in columns, which doxygen joins into one paragraph"
    run = 0
  }
  FNR == 1 { flush(); fence = 0; md = FILENAME ~ /\.md$/ }
  {
    if (md) text = " " $0
    else if (match($0, /^[ \t]*\/\/[\/!]/)) text = substr($0, RLENGTH + 1)
    else { flush(); next }
    t = text; sub(/^[ \t]+/, "", t)
    if (t ~ /^(```|~~~)/) { fence = !fence; flush(); next }
    if (t ~ /^[\\@]f\[/) { fence = 1; flush(); next }
    if (t ~ /^[\\@]f\]/) { fence = 0; flush(); next }
    if (fence || t == "") { flush(); next }
    if (length(text) - length(t) >= 5 || t ~ /^([-*+]|[0-9]+\.)[ \t]/ || t ~ /^\|/ || t !~ /[^ ]  +[^ ]/) {
      flush(); next
    }
    if (run++ == 0) first = FILENAME ":" FNR
  }
  END { flush() }
' "${sources[@]}")
if ((found > 0)); then
  echo "doc_markup: $found place(s) where the documentation shows its markup as text (above)"
  exit 1
fi
echo "doc_markup: ${#pages[@]} pages and ${#sources[@]} sources, no markup left as text"
