#!/usr/bin/env bash
# Check that the Debian packages this project needs are installed, and install the missing ones
# when we may (as root, or through password-less sudo). Otherwise print the exact command to run
# and exit 1. Quiet and fast (one dpkg-query call) when everything is present: `make` calls this
# on every build.
#
# Exit status: 0 when every package is present at the end, 1 otherwise.
#
# Environment:
#   MRM_DEPS_EXTRA="pkg ..."  extra Debian package names to require (space separated), e.g. to
#                             exercise the missing-package path.
#   MRM_DEPS_DRY_RUN=1        print the apt-get commands instead of running them (and exit 1 if
#                             packages are missing, since nothing was installed).
set -euo pipefail

# The packages, with what needs them.
packages=(
  g++ make cmake ninja-build       # the build (Ninja: a build with nothing to do takes no time)
  libeigen3-dev libgsl-dev         # the library
  doctest-dev                      # the embedded unit tests
  libcli11-dev                     # the command-line options (CLI11)
  numdiff                          # the golden outputs compared at a stated tolerance (tests/expected)
  gnuplot-nox                      # the figures (any gnuplot with the pdfcairo/cairolatex terminals)
  fonts-lmodern                    # the figures' typeface: Latin Modern, the report's Computer Modern
  doxygen libjs-mathjax            # the API documentation (MathJax renders its formulas offline)
  latexmk texlive-latex-base texlive-latex-recommended texlive-latex-extra
  texlive-fonts-recommended texlive-pictures  # the report
  poppler-utils                    # pdftoppm and pdffonts, to check the report's pages and fonts
  clang-format                     # the one C++ style, checked by tests/format.sh
  libhwy-dev                       # Google Highway: the batched step's vector lanes (lib/batched/batched_step.cpp)
  parallel                         # GNU parallel: runs a sweep's job list (repro/sweep.hpp, ctest sweep_job_list)
)

say() { printf 'deps: %s\n' "$*" >&2; }
die() { say "$*"; exit 1; }

# Extra packages from the environment; refuse anything that is not a Debian package name
# (optionally with an :arch qualifier), since the names end up on an apt-get command line.
read -r -a extra <<< "${MRM_DEPS_EXTRA:-}"
for p in "${extra[@]}"; do
  [[ $p =~ ^[a-z0-9][a-z0-9+.-]+(:[a-z0-9-]+)?$ ]] || die "MRM_DEPS_EXTRA: '$p' is not a Debian package name"
done
packages+=("${extra[@]}")
dry_run=${MRM_DEPS_DRY_RUN:-0}

install=(apt-get install -y --no-install-recommends)

if ! command -v dpkg-query >/dev/null 2>&1 || ! command -v apt-get >/dev/null 2>&1; then
  say "this is not a Debian-like system (no dpkg-query/apt-get); install the equivalents of these Debian packages:"
  say "  ${packages[*]}"
  exit 1
fi

# gnuplot can draw the report's figures if it has the pdfcairo terminal.
gnuplot_ok() {
  command -v gnuplot >/dev/null 2>&1 && gnuplot -e 'set terminal pdfcairo' </dev/null >/dev/null 2>&1
}

# Sets `missing` to the packages that are not installed. One dpkg-query call for all of them
# (unknown names make it print to stderr and exit 1: ignored). A package counts as installed when
# its status is "<want> ok installed" (normally "install ok installed"; "hold" counts too).
find_missing() {
  local -A installed=()
  local name status p
  while IFS=$'\t' read -r name status; do
    if [[ $status == *" ok installed" ]]; then installed[$name]=1; fi
  done < <(dpkg-query -W -f='${Package}\t${Status}\n' "${packages[@]}" 2>/dev/null || true)
  missing=()
  for p in "${packages[@]}"; do
    [[ -n ${installed[${p%%:*}]:-} ]] && continue
    # Another gnuplot flavour (gnuplot-qt, gnuplot-x11) with pdfcairo is as good as gnuplot-nox.
    [[ $p == gnuplot-nox ]] && gnuplot_ok && continue
    missing+=("$p")
  done
}

# Run a command, or only show it in dry-run mode.
run() {
  if [[ $dry_run == 1 ]]; then
    say "dry run, would run: $*"
  else
    say "running: $*"
    "$@"
  fi
}

find_missing
if ((${#missing[@]} > 0)); then
  say "missing Debian packages: ${missing[*]}"
  if ((EUID == 0)); then
    sudo=()
  elif command -v sudo >/dev/null 2>&1 && sudo -n true >/dev/null 2>&1; then
    sudo=(sudo -n)
  else
    say "cannot install them (not root, and no password-less sudo); run:"
    printf '  sudo %s %s\n' "${install[*]}" "${missing[*]}" >&2
    exit 1
  fi
  run "${sudo[@]}" apt-get update || die "apt-get update failed"
  run "${sudo[@]}" env DEBIAN_FRONTEND=noninteractive "${install[@]}" "${missing[@]}" \
    || die "apt-get install failed"
  if [[ $dry_run == 1 ]]; then
    die "dry run: nothing installed, ${#missing[@]} package(s) still missing"
  fi
  find_missing
  ((${#missing[@]} == 0)) || die "still missing after apt-get install: ${missing[*]}"
fi

# gnuplot-nox has pdfcairo, but a local build earlier on the PATH might not.
gnuplot_ok || die "'gnuplot' ($(command -v gnuplot || echo 'not on PATH')) lacks the pdfcairo terminal" \
  "(gnuplot-nox has it: is another gnuplot earlier on the PATH?)"

say "all ${#packages[@]} packages present"
