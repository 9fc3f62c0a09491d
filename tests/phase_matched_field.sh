#!/usr/bin/env bash
# bar1d --phase-matched on the field's benchmarks (ctest runs `bash tests/phase_matched_field.sh BIN_DIR`):
# the blend is A = 1/2 - C^2 with C = c dt/h the Courant number of the contact element (c the wave speed
# there; Configuration::step() sets dt = C h/c), not 1/2 - (dt/h)^2 in the benchmark's units, which would give
# A = 1/2 - (C/c)^2, about 1/2, on bouncing (c = 30 m/s) and impacting (c = 5.8 km/s). Checked: the blend
# printed at C = 1/2 and 0.6 (A = 1/4 and 0.14), the same run as --interior-mass blend:A, and C above
# 1/sqrt(2) refused (exit 2).
set -euo pipefail
if (($# != 1)) || [[ ! -x $1/bar1d ]]; then
  echo "usage: bash tests/phase_matched_field.sh BIN_DIR (with BIN_DIR/bar1d)" >&2
  exit 2
fi
bar1d=$(cd "$1" && pwd)/bar1d
failures=0
fail() {
  echo "FAIL $*"
  failures=$((failures + 1))
}
# bouncing: T = 8 is a whole number of steps at these C, so the blend is exactly 1/2 - C^2.
for pair in 0.5:1/4:0.25 0.6:0.14:0.14; do
  courant=${pair%%:*} rest=${pair#*:}
  spec=${rest%%:*} printed=${rest#*:}
  matched=$("$bar1d" --benchmark bouncing --elements 20 --courant "$courant" --phase-matched --no-timing)
  given=$("$bar1d" --benchmark bouncing --elements 20 --courant "$courant" --interior-mass "blend:$spec" --no-timing)
  grep -qx "interior_mass = blend:$printed" <<<"$matched" ||
    fail "bouncing, C = $courant: $(grep interior_mass <<<"$matched") (expected blend:$printed)"
  [[ $(grep '^err_' <<<"$matched") == $(grep '^err_' <<<"$given") ]] ||
    fail "bouncing, C = $courant: --phase-matched is not the run of --interior-mass blend:$spec"
done
# impacting: bar1d shortens dt to end at T exactly (by less than dt/steps), so A = 1/2 - C_eff^2 with
# C_eff <= 1/2: A in [1/4, 1/4 + 1/(2 steps)]; 0.26 bounds it for these 20 elements (233 steps). The old
# bug gave 1/2 - 1e-15.
matched=$("$bar1d" --benchmark impacting --elements 20 --courant 0.5 --phase-matched --no-timing)
blend=$(sed -n 's/^interior_mass = blend://p' <<<"$matched")
awk -v a="$blend" 'BEGIN { exit !(a >= 0.25 && a <= 0.26) }' || fail "impacting, C = 1/2: blend $blend not in [0.25, 0.26]"
given=$("$bar1d" --benchmark impacting --elements 20 --courant 0.5 --interior-mass "blend:$blend" --no-timing)
[[ $(grep '^err_' <<<"$matched") == $(grep '^err_' <<<"$given") ]] ||
  fail "impacting: --phase-matched is not the run of --interior-mass blend:$blend"
for benchmark in bouncing impacting; do
  status=0
  "$bar1d" --benchmark "$benchmark" --elements 20 --courant 0.75 --phase-matched --no-timing >/dev/null 2>&1 || status=$?
  ((status == 2)) || fail "$benchmark, C = 0.75: exit $status, expected 2 (no blend for C > 1/sqrt(2))"
done
((failures == 0)) && echo "phase_matched_field: all checks passed"
exit $((failures > 0))
