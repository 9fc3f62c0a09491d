# Top-level driver: Debian packages, build, tests and the generated results. `make help` lists the
# targets. The C++ build itself is CMake's (CMakeLists.txt); this file only calls it.
#
#   make                  build, then regenerate the results in $(OUT)
#   make test             build, then run the test suite
#   make test WERROR=1    ... with compiler warnings as errors
#   make test SANITIZE=1  ... under AddressSanitizer + UndefinedBehaviorSanitizer (own build dir)
.DELETE_ON_ERROR:
SHELL := /bin/bash
.SHELLFLAGS := -eu -o pipefail -c
.DEFAULT_GOAL := all

# ---- Configuration ------------------------------------------------------------------------------

ifeq ($(SANITIZE),1)
BUILD ?= build-sanitize
BUILD_TYPE := RelWithDebInfo
MRM_SANITIZE := ON
else
BUILD ?= build
BUILD_TYPE := Release
MRM_SANITIZE := OFF
endif
# Passed explicitly (ON or OFF) so that a WERROR=1 run does not stick in the CMake cache.
MRM_WERROR := $(if $(filter 1,$(WERROR)),ON,OFF)
CMAKE_FLAGS := -DCMAKE_BUILD_TYPE=$(BUILD_TYPE) -DMRM_WERROR=$(MRM_WERROR) -DMRM_SANITIZE=$(MRM_SANITIZE)
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

# Generated results: data, figures, the report and the API documentation.
OUT ?= output
DATA := $(OUT)/data
FIGURES := $(OUT)/figures
REPORT := $(OUT)/report.pdf
DOC := $(OUT)/doc

# Hook: extra prerequisites of `make test`. check-claims prints the claims table (see its section);
# it is then left out of the ctest run below so that the checks do not run twice.
TEST_EXTRA := check-claims
CTEST_EXCLUDE := -E '^check_claims$$'

.PHONY: all build clean deps help test bench

# ---- Rules --------------------------------------------------------------------------------------

# Everything: the build and the generated results.
all: build $(DATA)/benchmark.dat $(DATA)/benchmark.txt

# Check the Debian packages, installing the missing ones when allowed (quiet when all present).
deps:
	tools/deps.sh

# Configure (always: it is cheap and applies WERROR/SANITIZE) and build every program into
# $(BUILD)/bin. MAKEFLAGS is dropped so that our command line does not leak into CMake's makefiles.
build: deps
	cmake -S . -B $(BUILD) $(CMAKE_FLAGS)
	env -u MAKEFLAGS -u MFLAGS cmake --build $(BUILD) -j$(JOBS)

# The programs come from `build`; results depending on one are remade only if it was relinked.
$(BUILD)/bin/%: build ;

# Build, then run the doctests (one ctest entry per test case); zero tests found is a failure.
test: build $(TEST_EXTRA)
	ctest --test-dir $(BUILD) --output-on-failure -j2 --no-tests=error $(CTEST_EXCLUDE)

# The benchmark run: its data file and its stdout summary (written whole, via a temporary file).
$(DATA)/benchmark.dat $(DATA)/benchmark.txt &: $(BUILD)/bin/bar1d | $(DATA)
	$< --scheme cn --mass mod3 --elements 100 --courant 0.5 --final-time 6 \
	  --output $(DATA)/benchmark.dat > $(DATA)/benchmark.txt.tmp \
	  || { rm -f $(DATA)/benchmark.txt.tmp; exit 1; }
	mv $(DATA)/benchmark.txt.tmp $(DATA)/benchmark.txt

# ---- Benchmark (make bench; never part of `make all`) ----------------------------------------------
# The cost of one time step per node against N, the bare tridiagonal solve and Eigen's solve
# (experiments/bench_step.cpp), with its table for the report (.tex) and the README (.md) and its plot
# (PDF for the report, PNG for the README). Timings depend on the machine and its load: they live in
# $(BENCH), outside the deterministic results, and are remade on every `make bench`.
# BENCH_CLOCK=cpu times with the thread's CPU time instead of the wall clock (for a loaded machine).
BENCH := $(OUT)/bench
BENCH_CLOCK ?= wall

bench: build | $(BENCH)
	$(BUILD)/bin/bench_step --clock $(BENCH_CLOCK) --output $(BENCH)/bench_step.dat --tex $(BENCH)/bench_step.tex \
	  --markdown $(BENCH)/bench_step.md > $(BENCH)/bench_step.txt.tmp || { rm -f $(BENCH)/bench_step.txt.tmp; exit 1; }
	mv $(BENCH)/bench_step.txt.tmp $(BENCH)/bench_step.txt
	gnuplot -e "data='$(BENCH)/bench_step.dat'; output='$(BENCH)/bench_step.pdf.tmp'" figures/bench_step.gp
	mv $(BENCH)/bench_step.pdf.tmp $(BENCH)/bench_step.pdf
	gnuplot -e "data='$(BENCH)/bench_step.dat'; output='$(BENCH)/bench_step.png.tmp'; format='png'" figures/bench_step.gp
	mv $(BENCH)/bench_step.png.tmp $(BENCH)/bench_step.png
	cat $(BENCH)/bench_step.md

$(BENCH):
	mkdir -p $@

# ---- The claims of the paper (problem.md §6) ----------------------------------------------------
# `make check-claims` runs every check of lib/claims.cpp and prints the table claim | measured |
# criterion | verdict; it fails iff a check FAILED (expected failures, listed with their reasons in
# lib/claims.cpp, do not fail it). `make test` runs it (TEST_EXTRA); ctest also knows it as the test
# check_claims, for whoever runs ctest directly. The same table for the report, as LaTeX and Markdown:
# $(DATA)/claims.tex and $(DATA)/claims.md, part of `make all`.
.PHONY: check-claims
check-claims: build
	$(BUILD)/bin/check_claims

all: $(DATA)/claims.tex $(DATA)/claims.md

$(DATA)/claims.tex $(DATA)/claims.md &: $(BUILD)/bin/check_claims | $(DATA)
	$< --tex $(DATA)/claims.tex --markdown $(DATA)/claims.md > /dev/null

# Output directories.
$(DATA) $(FIGURES) $(DOC):
	mkdir -p $@

# Remove every build directory and every generated result.
clean:
	rm -rf -- $(sort $(BUILD) build build-sanitize $(OUT))

# List the targets and options.
help:
	@echo 'Targets:'
	@echo '  all      (default) build, then regenerate the results in $(OUT)/'
	@echo '  build    configure and build the library, tests and programs into $(BUILD)/bin/'
	@echo '  test     build, then run the test suite with ctest and the claims table'
	@echo '  check-claims  build, then check every claim of the paper and print the table'
	@echo '  bench    build, then time one step per node for N = 2^6..2^20 ($(OUT)/bench/bench_step.*)'
	@echo '  deps     check the Debian packages, installing the missing ones if root (tools/deps.sh)'
	@echo '  clean    remove build/, build-sanitize/ and $(OUT)/'
	@echo '  help     this list'
	@echo 'Options (on the command line):'
	@echo '  WERROR=1    compiler warnings are errors'
	@echo '  SANITIZE=1  ASan + UBSan build (RelWithDebInfo) in build-sanitize/'
	@echo '  BUILD=dir   build directory (default: build, or build-sanitize with SANITIZE=1)'
	@echo '  OUT=dir     output directory (default: output)'
	@echo '  JOBS=n      parallel compile jobs (default: nproc)'
	@echo '  BENCH_CLOCK=cpu  make bench times thread CPU time instead of wall time (loaded machine)'
