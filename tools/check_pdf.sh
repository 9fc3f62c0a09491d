#!/usr/bin/env bash
# A typeset document is whole and vector throughout:
#  1. its log names no undefined reference and no label defined twice;
#  2. no bitmap (Type 3) font in the PDF, so that it prints and zooms alike (pdffonts);
#  3. no < or > typeset in text mode, which the text font prints as ¡ or ¿ (pdftotext).
# The two PDF checks read the PDF at once, on two processes (the supplement's text takes the longer).
# Usage: check_pdf.sh LATEX_DIR DOCUMENT   (reads LATEX_DIR/DOCUMENT.log and LATEX_DIR/DOCUMENT.pdf)
# Prints what it found and exits 1 if any check fails.
set -euo pipefail
dir=${1:?usage: check_pdf.sh LATEX_DIR DOCUMENT}
doc=${2:?usage: check_pdf.sh LATEX_DIR DOCUMENT}
log=$dir/$doc.log pdf=$dir/$doc.pdf
[[ -f $log && -f $pdf ]] || { echo "check_pdf: no $log or no $pdf"; exit 1; }
if grep -E "Reference .* undefined|There were undefined references|multiply defined" "$log"; then
  echo "$doc: a reference undefined or a label defined twice (above; $log)"
  exit 1
fi
work=$(mktemp -d "${TMPDIR:-/tmp}/check_pdf.XXXXXX")
trap 'rm -rf -- "$work"' EXIT
pdffonts "$pdf" > "$work/fonts" &
fonts=$!
pdftotext -enc UTF-8 "$pdf" "$work/text" || { echo "$doc: pdftotext failed on $pdf"; exit 1; }
wait "$fonts" || { echo "$doc: pdffonts failed on $pdf"; exit 1; }
status=0
if grep -nF -e '¡' -e '¿' "$work/text"; then
  echo "$doc: a < or > typeset in text mode prints as ¡ or ¿ (above; write \$<\$ or \$>\$)"
  status=1
fi
if grep -q 'Type 3' "$work/fonts"; then
  echo "$doc: a bitmap (Type 3) font in the PDF (pdffonts $pdf)"
  status=1
fi
exit "$status"
