#!/usr/bin/env bash
# ctest install_consumer: builds the installed method library (the target mrm: lib/ without its doctests,
# which the default build does not make), installs it from the build tree BUILD into a fresh prefix,
# configures and builds the consumer project SOURCE (tests/consumer) against it with find_package(mrm),
# runs it, and checks that the Mod 3 total mass it prints equals the length L it prints, to round-off
# (|total − L| ≤ 64 ε L: a sum of about 3N entries of size h, each with one rounding).
# It also checks that the library references no function that the sources it leaves out define (LEFT_OUT:
# the objects of the default build's mrm_test_cases, with their test cases, ;-separated).
# Usage: run.sh BUILD SOURCE [CXX [FLAGS [LEFT_OUT]]]   (FLAGS: compile and link flags of a sanitized build)
set -euo pipefail
build=$1 source=$2 cxx=${3:-c++} flags=${4:-} left_out=${5:-}
work=$(mktemp -d "${TMPDIR:-/tmp}/mrm-consumer.XXXXXX")
trap 'rm -rf -- "$work"' EXIT

cmake --build "$build" --target mrm >"$work/install.log" 2>&1 || { cat "$work/install.log"; exit 1; }
if [[ -n $left_out ]]; then
  IFS=';' read -r -a objects <<<"$left_out"
  for o in "${objects[@]}"; do [[ -f $o ]] || { echo "install_consumer: no object $o (build the default target first)"; exit 1; }; done
  defined=$(nm --defined-only "${objects[@]}" | awk 'NF == 3 && $2 == "T" { print $3 }' | sort -u)
  called=$(nm -u "$build/libmrm.a" | awk 'NF == 2 && $1 == "U" { print $2 }' | sort -u)
  both=$(comm -12 <(printf '%s\n' "$defined") <(printf '%s\n' "$called"))
  if [[ -n $both ]]; then
    echo "install_consumer: the installed library calls functions of the sources it leaves out:"
    c++filt <<<"$both"
    exit 1
  fi
fi
cmake --install "$build" --prefix "$work/prefix" >>"$work/install.log" || { cat "$work/install.log"; exit 1; }
for f in lib/libmrm.a include/mrm/core/problem.hpp include/mrm/fem/p1.hpp lib/cmake/mrm/mrmConfig.cmake lib/cmake/mrm/mrmConfigVersion.cmake; do
  [[ -f $work/prefix/$f ]] || { echo "install_consumer: $f was not installed"; exit 1; }
done
if grep -rlE --include='*.hpp' '^[[:space:]]*#[[:space:]]*include[[:space:]]*[<"]doctest' "$work"/prefix/include/mrm; then
  echo "install_consumer: an installed header includes doctest (listed above)"; exit 1
fi
cmake -S "$source" -B "$work/build" -DCMAKE_PREFIX_PATH="$work/prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="$flags" -DCMAKE_EXE_LINKER_FLAGS="$flags" >"$work/configure.log" 2>&1 || { cat "$work/configure.log"; exit 1; }
cmake --build "$work/build" >"$work/build.log" 2>&1 || { cat "$work/build.log"; exit 1; }
output=$("$work/build/consumer")
echo "$output"
awk '/^length = / {l = $3} /^total = / {t = $3}
     END {
       if (l == "" || t == "") { print "install_consumer: missing length or total"; exit 1 }
       d = t - l; if (d < 0) d = -d
       tol = 64 * 2^-52 * l
       printf "install_consumer: |total - L| = %.3g, allowed %.3g\n", d, tol
       exit !(d <= tol)
     }' <<<"$output"
