#!/usr/bin/env bash
# ctest make_waits_for_deps: on a fresh machine, `make all` and `make test` first install the Debian
# packages (tools/deps.sh, the phony target `deps`), and make runs its recipes in parallel: a recipe that
# does not wait for `deps` may start before the tool it calls is installed (doxygen, gnuplot, latexmk)
# and fail. This test reads make's own database of the two goals (`make -pn all test`: every rule, with
# the prerequisites that pattern rules give, and nothing run) in a scratch build and output directory,
# as a fresh clone sees them, and checks, for every target that `all` or `test` reaches:
#   - it reaches `deps` through its prerequisites (normal or order-only), so that its recipe starts only
#     after tools/deps.sh has finished; only `deps` itself and a target without recipe and prerequisites
#     (FORCE) are exempt;
#   - no file depends on `deps` as a normal prerequisite: `deps` is phony, always remade, and a file
#     that depends on it normally would be remade on every run (the order-only `| deps` waits without
#     remaking).
# Usage: make_waits_for_deps.sh [BIN_DIR]   (BIN_DIR unused: the Makefile is found beside this file)
set -euo pipefail
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/make_waits_for_deps.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

# The database of a dry run (-n: no recipe runs). The environment's make flags (ctest may be started by
# make, with its job server) are dropped.
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -C "$source_dir" -pn all test OUT="$work/out" BUILD="$work/build" \
  >"$work/database.txt" 2>"$work/make.err" || {
  echo "make_waits_for_deps: make -pn all test failed:"
  cat "$work/make.err"
  exit 1
}

# From the database's "# Files" section: each entry `target: normal | order-only`, whether it is a target
# at all (a source file is listed under "# Not a target:"), phony, and whether it has a recipe (its own,
# or a pattern rule's: a non-empty stem). Then the targets reachable from all and test, and the checks.
awk '
  /^# Files/ { files = 1; next }
  /^# (files hash-table stats|VPATH Search Paths|Pattern-specific|Finished Make data base)/ { files = 0 }
  !files { next }
  /^# Not a target:/ { not_target = 1; next }
  /^[^#\t ][^:]*:/ && !/^[^:]*:=/ {
    target = substr($0, 1, index($0, ":") - 1)
    rest = substr($0, index($0, ":") + 1)
    split(rest, sides, "|")
    normal[target] = sides[1]; order_only[target] = sides[2]
    is_target[target] = !not_target; not_target = 0
    next
  }
  /^#  Phony target/ { phony[target] = 1 }
  /^#  recipe to execute/ { recipe[target] = 1 }
  /^#  Implicit\/static pattern stem: .[^'"'"']/ { recipe[target] = 1 }
  END {
    # The targets all and test reach.
    queue[1] = "all"; queue[2] = "test"; n = 2; seen["all"] = seen["test"] = 1
    for (i = 1; i <= n; ++i) {
      t = queue[i]
      m = split(normal[t] " " order_only[t], list, " ")
      for (k = 1; k <= m; ++k) if (list[k] != "" && !(list[k] in seen)) { seen[list[k]] = 1; queue[++n] = list[k] }
    }
    # For each, whether it reaches deps (a depth-first search with memo).
    bad = 0
    for (i = 1; i <= n; ++i) {
      t = queue[i]
      if (!is_target[t] || t == "deps") continue
      if (!recipe[t] && normal[t] order_only[t] ~ /^[ \t]*$/) continue
      if (!reaches(t)) { print "make_waits_for_deps: " t " does not wait for deps (its recipe may run before the packages are installed)"; bad = 1 }
      if (!phony[t] && (" " normal[t] " ") ~ / deps /) {
        print "make_waits_for_deps: " t " depends on deps as a normal prerequisite (remade on every run; write | deps)"; bad = 1
      }
    }
    if (!("deps" in seen)) { print "make_waits_for_deps: neither all nor test reaches deps"; bad = 1 }
    printf "make_waits_for_deps: %d targets reached from all and test, %s\n", n, bad ? "FAILED" : "each waits for deps"
    exit bad
  }
  function reaches(t,    m, k, list) {
    if (t in memo) return memo[t]
    memo[t] = 0  # a cycle does not reach deps through itself
    m = split(normal[t] " " order_only[t], list, " ")
    for (k = 1; k <= m; ++k)
      if (list[k] == "deps" || (list[k] != "" && reaches(list[k]))) { memo[t] = 1; return 1 }
    return 0
  }
' "$work/database.txt" | sed "s|$work/||g"
