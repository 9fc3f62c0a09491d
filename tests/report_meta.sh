#!/usr/bin/env bash
# tools/report_meta.sh, the report's title-page values: the authors of a CITATION.cff (a `name:` entry
# and a given/family entry, joined with \and), its version, the date of the last commit inside a git
# checkout and the fixed fallback outside one; a file without authors is an error. The back of the
# title page: the commit (or the fallback), the command (escaped for LaTeX), the values of the build_info
# program appended, and a build_info that writes none is an error.
# Usage: report_meta.sh BIN_DIR (unused: the script is found beside this test).
set -euo pipefail
tool=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)/tools/report_meta.sh
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT

cat > "$dir/CITATION.cff" <<'CFF'
cff-version: 1.2.0
title: "x"
authors:
  - family-names: Doe
    given-names: Jane
  - name: "The x developers"
version: "2.1.0"
references:
  - type: article
    authors:
      - family-names: Other
        given-names: Not
CFF
out=$("$tool" "$dir/CITATION.cff")
grep -qxF '\mrmdef{meta:authors}{Jane Doe \and The x developers}' <<< "$out" \
  || { echo "authors: expected Jane Doe and The x developers only, got:"; echo "$out"; exit 1; }
grep -qxF '\mrmdef{meta:version}{2.1.0}' <<< "$out" || { echo "version wrong:"; echo "$out"; exit 1; }
# $dir is not inside a git checkout: the fixed fallback, so that the output depends on nothing else.
if ! git -C "$dir" rev-parse >/dev/null 2>&1; then
  grep -qxF '\mrmdef{meta:date}{unknown (not a git checkout)}' <<< "$out" \
    || { echo "date outside a checkout: expected the fallback, got:"; echo "$out"; exit 1; }
fi
# The project's own file, inside its checkout (when it is one): the date of the last commit.
root=$(dirname "$(dirname "$tool")")
if git -C "$root" rev-parse >/dev/null 2>&1; then
  expected=$(git -C "$root" log -1 --format=%cs)
  inside=$("$tool" "$root/CITATION.cff")
  grep -qxF "\\mrmdef{meta:date}{$expected}" <<< "$inside" \
    || { echo "date inside the checkout: expected $expected"; exit 1; }
fi

# Outside a checkout the commit has the fallback; the command is "make all" unless given, escaped for
# LaTeX; the build_info program's meta lines are appended, and a program that writes none is an error.
grep -qxF '\mrmdef{meta:commit}{unknown (not a git checkout)}' <<< "$out" \
  || { echo "commit outside a checkout: expected the fallback, got:"; echo "$out"; exit 1; }
grep -qxF '\mrmdef{meta:command}{make all}' <<< "$out" || { echo "default command wrong:"; echo "$out"; exit 1; }
printf '#!/bin/sh\necho "\\\\mrmdef{meta:compiler}{GNU 1.2}"\n' > "$dir/info"
printf '#!/bin/sh\necho nothing\n' > "$dir/silent"
chmod +x "$dir/info" "$dir/silent"
out=$("$tool" "$dir/CITATION.cff" "$dir/info" 'make all OUT=a_b')
grep -qxF '\mrmdef{meta:compiler}{GNU 1.2}' <<< "$out" || { echo "build_info values missing:"; echo "$out"; exit 1; }
grep -qxF '\mrmdef{meta:command}{make all OUT=a\_b}' <<< "$out" || { echo "command not escaped:"; echo "$out"; exit 1; }
status=0
"$tool" "$dir/CITATION.cff" "$dir/silent" > /dev/null 2>&1 || status=$?
[[ $status == 1 ]] || { echo "a build_info without values: expected status 1, got $status"; exit 1; }
if root_commit=$(git -C "$(dirname "$(dirname "$tool")")" rev-parse --short=12 HEAD 2>/dev/null); then
  inside=$("$tool" "$(dirname "$(dirname "$tool")")/CITATION.cff")
  grep -qF "\\mrmdef{meta:commit}{$root_commit" <<< "$inside" \
    || { echo "commit inside the checkout: expected $root_commit"; exit 1; }
fi

printf 'cff-version: 1.2.0\ntitle: "x"\n' > "$dir/none.cff"
status=0
"$tool" "$dir/none.cff" > /dev/null 2>&1 || status=$?
[[ $status == 1 ]] || { echo "a file without authors: expected status 1, got $status"; exit 1; }
echo "report_meta test passed"
