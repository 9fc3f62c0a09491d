#!/usr/bin/env bash
# ctest make_order: the order make runs its recipes in, which parallel jobs (-j) make matter, read from
# make's own database of `all` and `test` (`make -pn all test`: every rule, with the prerequisites that
# pattern rules give, and nothing run) in a scratch build and output directory, as a fresh clone sees it.
#  1. On a fresh machine `make all` and `make test` first install the Debian packages (tools/deps.sh,
#     the phony target `deps`); a recipe that does not wait for `deps` may start before the tool it calls
#     is installed (doxygen, gnuplot, latexmk) and fail. Every target that `all` or `test` reaches must
#     reach `deps` through its prerequisites (normal or order-only); only `deps` itself and a target
#     without recipe and prerequisites (FORCE) are exempt. And no file depends on `deps` as a normal
#     prerequisite: `deps` is phony, always remade, and a file that depended on it normally would be
#     remade on every run (the order-only `| deps` waits without remaking).
#  2. The short benchmark starts with the claims (the Makefile's section on it says why): in the list of
#     `all`, after `build`, come the claims' outputs (one recipe) and then bench_short.tex, which waits for
#     no other result of `all`; make starts recipes in that order, so on two job slots the benchmark runs
#     beside check_claims and every other study waits for a slot.
# Usage: make_order.sh [BIN_DIR]   (BIN_DIR unused: the Makefile is found beside this file)
set -euo pipefail
source_dir=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
work=$(mktemp -d "${TMPDIR:-/tmp}/make_order.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

# The database of a dry run (-n: no recipe runs). The environment's make flags (ctest may be started by
# make, with its job server) are dropped.
env -u MAKEFLAGS -u MFLAGS -u MAKELEVEL make -C "$source_dir" -pn all test OUT="$work/out" BUILD="$work/build" \
  >"$work/database.txt" 2>"$work/make.err" || {
  echo "make_order: make -pn all test failed:"
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
      if (!reaches(t)) { print "make_order: " t " does not wait for deps (its recipe may run before the packages are installed)"; bad = 1 }
      if (!phony[t] && (" " normal[t] " ") ~ / deps /) {
        print "make_order: " t " depends on deps as a normal prerequisite (remade on every run; write | deps)"; bad = 1
      }
    }
    if (!("deps" in seen)) { print "make_order: neither all nor test reaches deps"; bad = 1 }
    printf "make_order: %d targets reached from all and test, %s\n", n, bad ? "not each waits for deps" : "each waits for deps"
    # 2. The short benchmark starts with the claims and waits for no other result.
    bench = ""; at = 0
    m = split(normal["all"], list, " ")
    for (k = 1; k <= m; ++k) if (list[k] ~ /\/bench_short\.tex$/ && bench == "") { bench = list[k]; at = k }
    if (bench == "") { print "make_order: all has no prerequisite bench_short.tex"; exit 1 }
    claims = 0
    for (k = 1; k < at; ++k) {
      if (list[k] == "" || list[k] == "build") continue
      if (list[k] ~ /\/(claims[a-z_]*\.(txt|tex|md)|sweep\.dat)$/) { ++claims; continue }
      print "make_order: " list[k] " comes before the short benchmark in all (only the claims do)"; bad = 1
    }
    if (claims == 0) { print "make_order: the claims do not come first in all"; bad = 1 }
    others = 0
    for (k = 1; k <= m; ++k) {
      p = list[k]
      if (p == "" || p == bench || p == "build" || p in counted) continue
      counted[p] = 1
      ++others
      if (depends(bench, p)) { print "make_order: the short benchmark waits for " p; bad = 1 }
    }
    printf "make_order: the short benchmark comes after the %d outputs of the claims and waits for none of the %d other results of all\n", claims, others - claims
    exit bad
  }
  # Whether a reaches b through prerequisites (a search from a, its own marks).
  function depends(a, b,    stack, top, t, m, k, list, mark) {
    stack[top = 1] = a
    while (top > 0) {
      t = stack[top--]
      m = split(normal[t] " " order_only[t], list, " ")
      for (k = 1; k <= m; ++k) {
        if (list[k] == "" || list[k] in mark) continue
        if (list[k] == b) return 1
        mark[list[k]] = 1
        stack[++top] = list[k]
      }
    }
    return 0
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
