#!/usr/bin/env bash
# The library's floors: lib/ is in folders from the ground floor up, and a file may include only a file
# of its own folder or of a lower one, with no include cycle between the files (a file and its header
# taken as one unit: lib/fem/p1.hpp and lib/fem/p1.cpp are fem/p1). A file that names a higher folder,
# or a cycle, is reported; the test fails on either.
# Usage: lib_layers.sh BIN_DIR (unused: the sources are found beside this test).
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
# The floors, lowest first.
floors=(core fem exact steps classes time measures batched studies)
# The allowed exceptions, "FILE -> INCLUDED" (paths under lib/): includes that would point upward or close
# a cycle, left out of both checks. None today; an exception listed here that no longer exists fails the test.
allowed=()
declare -A rank
for i in "${!floors[@]}"; do rank[${floors[$i]}]=$i; done
cd "$root/lib"
mapfile -t files < <(find . -name '*.cpp' -o -name '*.hpp' | sed 's|^\./||' | LC_ALL=C sort)
((${#files[@]} > 0)) || { echo "lib_layers: no file under $root/lib"; exit 1; }
failed=0
edges=""
declare -A seen
for file in "${files[@]}"; do
  folder=${file%%/*}
  [[ -n ${rank[$folder]+x} ]] || { echo "lib_layers: $file is in a folder that is not a floor: $folder"; failed=1; continue; }
  unit=${file%.*}
  edges+="$unit $unit"$'\n'
  while IFS= read -r included; do
    target=${included%%/*}
    [[ -n ${rank[$target]+x} ]] || continue  # not a file of the library (an include directory of repro/)
    edge="$file -> $included"
    if [[ " ${allowed[*]/#/|} " == *"|$edge "* ]]; then
      seen[$edge]=1
      continue
    fi
    edges+="$unit ${included%.*}"$'\n'
    if ((rank[$target] > rank[$folder])); then
      echo "lib_layers: $edge: $target/ is above $folder/ (${floors[*]})"
      failed=1
    fi
  done < <(sed -n 's|^[[:space:]]*#[[:space:]]*include[[:space:]]*"\([^"]*/[^"]*\)".*|\1|p' "$file")
done
for edge in "${allowed[@]}"; do
  [[ -n ${seen[$edge]+x} ]] || { echo "lib_layers: the allowed exception \"$edge\" no longer exists: remove it"; failed=1; }
done
# tsort names the units on a cycle on its standard error.
if ! cycles=$(tsort <<<"$edges" 2>&1 >/dev/null) || [[ -n $cycles ]]; then
  echo "lib_layers: include cycle between the units of lib/:"
  echo "$cycles"
  failed=1
fi
((failed == 0)) || exit 1
echo "lib_layers: ${#files[@]} files of lib/ include only their own or lower floors (${floors[*]}), no cycle;" \
  "${#allowed[@]} allowed exception(s)"
