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
# The results are made on $(JOBS) cores (a -j on the command line takes precedence): every rule writes
# its own files and temporary names, a rule with several outputs is grouped (&: or a pattern rule), and
# the programs' own threads and gnuplot share the cores through this one job list. `clean` with another
# goal runs alone first.
MAKEFLAGS += -j$(JOBS)
ifneq ($(filter clean,$(MAKECMDGOALS)),)
.NOTPARALLEL:
endif

# Generated results: data, figures, the article and its supplement, and the API documentation.
OUT ?= output
DATA := $(OUT)/data
FIGURES := $(OUT)/figures
REPORT := $(OUT)/report.pdf
SUPPLEMENT := $(OUT)/supplement.pdf
DOC := $(OUT)/doc

# ---- The results ---------------------------------------------------------------------------------
# One figure = one program experiments/X.cpp = one data file $(DATA)/X.dat (with the LaTeX values the
# report quotes, $(DATA)/X.tex) = one gnuplot script figures/X.gp = one PDF $(FIGURES)/X.pdf.
# The article paper/report.tex and its supplement paper/supplement.tex \input the .tex fragments (through
# their shared preamble, paper/preamble.tex) and include the PDFs; latexmk builds them.
# The maps of claims 3 and 4 read the sweep that check_claims writes; experiments/fig_energy_schemes.cpp
# has three views, each its own run, data file and figure.
SWEEP_MAPS := fig_ordering_map fig_order_map
ENERGY_SCHEMES_VIEWS := history map measures
FIGURE_NAMES := fig_contact_history fig_energy fig_convergence fig_time_error fig_ps_forms fig_profiles fig_phase \
                fig_stability_map fig_smooth_convergence fig_smooth_benchmarks fig_family \
                $(SWEEP_MAPS) $(ENERGY_SCHEMES_VIEWS:%=fig_energy_schemes_%) \
                fig_benchmark_convergence \
                fig_phase_matched \
                fig_stress
FIGURE_PDFS := $(FIGURE_NAMES:%=$(FIGURES)/%.pdf)
FIGURE_DATA := $(FIGURE_NAMES:%=$(DATA)/%.dat)
FIGURE_TEX := $(FIGURE_NAMES:%=$(DATA)/%.tex)
CLAIMS_OUTPUTS := $(DATA)/claims.txt $(DATA)/claims.tex $(DATA)/claims.md $(DATA)/claims_summary.tex \
                  $(DATA)/claims_summary_table.tex $(DATA)/sweep.dat
BENCH_SHORT := $(OUT)/bench-short
# The baseline over regions (a table, no figure: experiments/baseline_regions.cpp, below).
BASELINE := $(DATA)/baseline_regions.dat $(DATA)/baseline_regions.tex

# Everything `make all` makes: the build, the benchmark run, the claims, every figure with its data and
# values (named, so that make does not take them for intermediate files and delete them), the short
# benchmark, the article with its supplement and the API documentation. Each has its section below; the
# rule `all` is at the end of this file, where every name it lists is defined.
# The claims and the short benchmark come first: make starts its recipes in this order, and these two
# begin together (the short benchmark's section below says why). Then the costliest studies, costliest
# first, so that the short ones fill the cores at the end instead of one long study running last
# (CPU seconds on the 2-core machine, chosen after a run: fig_time_error 16, fig_classes 11,
# baseline_regions 9, fig_stress 6; every other study at most 3.4).
LONGEST_STUDIES = $(DATA)/fig_time_error.dat $(CLASSES) $(BASELINE) $(DATA)/fig_stress.dat
ALL_RESULTS = $(CLAIMS_OUTPUTS) $(BENCH_SHORT)/bench_short.tex $(LONGEST_STUDIES) \
              $(DATA)/benchmark.dat $(DATA)/benchmark.txt $(FIGURE_DATA) $(FIGURE_TEX) $(BASELINE) $(FIGURE_PDFS) $(CLASSES) $(CLASSES_PDFS) \
              $(DATA)/cn_large_step.tex $(PEER_TEX) $(DATA)/report_meta.tex $(DATA)/build_times.tex \
              $(DOC)/html/index.html $(REPORT) $(SUPPLEMENT)

.PHONY: all build clean deps help test test-unit bench install readme field-asymptotics

# ---- Rules --------------------------------------------------------------------------------------

# Check the Debian packages, installing the missing ones when allowed (quiet when all present).
# Every recipe waits for it (order only: `deps` is phony, and a file that depended on it normally would
# be remade on every run): the build through `build: deps`, every result through the directory it is
# written in, so that on a fresh machine no recipe calls a tool (doxygen, gnuplot, latexmk) that is still
# being installed (the directories wait for it: "Output directories" below). The ctest entry
# make_order checks it on make's database of `all` and `test`.
deps:
	tools/deps.sh

# Configure (always: it is cheap and applies WERROR/SANITIZE) and build every program into
# $(BUILD)/bin. MAKEFLAGS is dropped so that our command line does not leak into CMake's makefiles. A new
# build directory uses Ninja (tools/deps.sh installs it), whose check of a build with nothing to do takes
# a tenth of a second where CMake's makefiles take seconds; one made before keeps its generator (CMake
# cannot change it in place).
build: deps
	cmake -S . -B $(BUILD) $$(test -f $(BUILD)/CMakeCache.txt || echo -G Ninja) $(CMAKE_FLAGS)
	env -u MAKEFLAGS -u MFLAGS cmake --build $(BUILD) -j$(JOBS)

# The programs come from `build`; results depending on one are remade only if it was relinked.
$(BUILD)/bin/%: build ;

# Build, then run the whole suite (the doctests, one ctest entry per test case; the programs, the
# claims, the golden output, the shell tests); zero tests found is a failure. `make test-unit`: the
# doctests alone (ctest -L unit, seconds).
# The claims run once: `test` makes $(CLAIMS_OUTPUTS), whose rule (below) runs check_claims and fails iff
# a check FAILED, as the ctest entry check_claims does; after `make all` they are up to date with the
# program and nothing runs. ctest then leaves out its entry check_claims (and, -FS, does not add it back
# as the setup of the fixture claims_detail), and readme_generated reads the detail make wrote
# (MRM_CLAIMS_DETAIL). The sanitized build keeps the ctest entry: its results are not `make all`'s.
ifeq ($(SANITIZE),1)
TEST_CLAIMS :=
CTEST_CLAIMS :=
else
TEST_CLAIMS := $(CLAIMS_OUTPUTS)
CTEST_CLAIMS := -E '^check_claims$$' -FS claims_detail
endif
test: build $(TEST_CLAIMS)
	$(if $(TEST_CLAIMS),MRM_CLAIMS_DETAIL=$(abspath $(DATA)/claims.txt)) \
	  ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --no-tests=error $(CTEST_CLAIMS)

test-unit: build
	ctest --test-dir $(BUILD) --output-on-failure -j$(JOBS) --no-tests=error -L unit

# Install the method library (lib/, built without its doctests: its own target, compiled only here),
# its headers and its CMake package under $(PREFIX) (find_package(mrm), target mrm::mrm).
PREFIX ?= /usr/local
install: build
	env -u MAKEFLAGS -u MFLAGS cmake --build $(BUILD) -j$(JOBS) --target mrm
	cmake --install $(BUILD) --prefix $(PREFIX)

# The README's generated blocks (tools/readme.sh): the claims, their verdicts and where each holds and
# fails from the claims detail of `make all`, the times of the two commands from doc/build_times.txt
# (tools/measure_commands.sh measures them in a fresh clone).
readme: $(DATA)/claims.txt
	tools/readme.sh $(DATA)/claims.txt

# The benchmark run: its data file and its stdout summary (written whole, via a temporary file; without
# the wall time, so that the same command gives the same bytes).
$(DATA)/benchmark.dat $(DATA)/benchmark.txt &: $(BUILD)/bin/bar1d | $(DATA)
	$< --scheme cn --mass mod3 --elements 100 --courant 0.5 --final-time 6 --no-timing \
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

# ---- The short benchmark (part of `make all`) ------------------------------------------------------
# The report's Performance section is filled by every `make all`: bench_step on N = 2^8..2^14 with few,
# short batches (a few seconds), its two tables (the fast step against the bare tridiagonal solve and
# Eigen's SimplicialLDLT, and the reference step) and the values the text quotes, in
# $(BENCH_SHORT)/bench_short.tex. Timings are not deterministic: like $(BENCH), this directory is
# outside the results that CI compares byte for byte (.ci/run). A full `make bench` takes precedence in
# the report when its table exists.
# It times on the thread's CPU clock and takes the minimum of its repetitions: whatever else the machine
# runs, the least disturbed batch is the closest to the cost itself. It starts with the claims, the longest
# study (the first two of ALL_RESULTS), and every other study waits for a free job slot. On the 2-core
# machine its timings beside check_claims were those of the benchmark run alone: four alternated runs of
# each, and 3 of its 244 minima beside the claims above every run alone, by at most 2 % of the largest
# run alone, less than the spread of the runs alone (checked after a run). Its 4.5 s on one core are then
# no longer added to the wall time of `make all` after every study. A figure that cannot be trusted is
# written n/a with its reason (bench_step), and the report says on what machine and load the timings were
# taken.
BENCH_SHORT_OPTIONS := --min-log2 8 --max-log2 14 --repetitions 5 --batch-ms 5 --clock cpu --statistic min
$(BENCH_SHORT)/bench_short.tex: $(BUILD)/bin/bench_step | $(BENCH_SHORT)
	$< $(BENCH_SHORT_OPTIONS) --tex $@ > $(BENCH_SHORT)/bench_short.txt

$(BENCH_SHORT):
	mkdir -p $@

# ---- The claims of the paper (mathematics.md §6) ----------------------------------------------------
# `make check-claims` runs every check of repro/claims/ (the program experiments/check_claims.cpp)
# and prints its summary (at most 12 lines of at most 100 columns: each claim and its verdict); the table
# claim | measured, with the margin | criterion, with its basis | verdict is $(DATA)/claims.txt (--detail).
# It fails iff a check FAILED (expected
# failures, listed with their reasons in repro/claims/expectations.cpp, do not fail it). `make test` runs it (the
# ctest entry check_claims). The same table for the report, as LaTeX and Markdown: $(DATA)/claims.tex and
# $(DATA)/claims.md; its summary (at most 12 lines: verdict and region of each claim) as \mrmdef values
# and as a table, $(DATA)/claims_summary.tex and $(DATA)/claims_summary_table.tex; and the sweep behind
# claims 3 and 4 (every measure of every run), $(DATA)/sweep.dat, which the two maps below read: all
# part of `make all` ($(CLAIMS_OUTPUTS)), from one run of check_claims.
.PHONY: check-claims
check-claims: build
	$(BUILD)/bin/check_claims

$(CLAIMS_OUTPUTS) &: $(BUILD)/bin/check_claims | $(DATA)
	$< --detail $(DATA)/claims.txt --tex $(DATA)/claims.tex --markdown $(DATA)/claims.md \
	  --summary-tex $(DATA)/claims_summary.tex \
	  --summary-table $(DATA)/claims_summary_table.tex --sweep $(DATA)/sweep.dat > /dev/null

# The maps of claims 3 and 4 read the sweep (one computation for the claims and the maps).
$(SWEEP_MAPS:%=$(DATA)/%.dat): $(DATA)/%.dat: $(BUILD)/bin/% $(DATA)/sweep.dat | $(DATA)
	$< --sweep $(DATA)/sweep.dat --output $@ --tex $(DATA)/$*.tex
$(SWEEP_MAPS:%=$(DATA)/%.tex): $(DATA)/%.tex: $(DATA)/%.dat ;

# ---- Figures, article, supplement and API documentation ---------------------------------------------
REPORT_SOURCES := $(wildcard paper/*.tex)
# The claims table (experiments/check_claims.cpp, see the claims section above).
CLAIMS_TEX := $(DATA)/claims.tex $(DATA)/claims_summary.tex $(DATA)/claims_summary_table.tex
# Fixed dates in the PDFs (pdfTeX and cairo honour SOURCE_DATE_EPOCH).
REPRODUCIBLE := SOURCE_DATE_EPOCH=0 FORCE_SOURCE_DATE=1

.PHONY: figures report doc
figures: $(FIGURE_PDFS)
report: $(REPORT) $(SUPPLEMENT)
doc: $(DOC)/html/index.html

# The figure programs are reached through the pattern rule $(BUILD)/bin/%: make must not take them for
# intermediate files and delete them after use.
.SECONDARY: $(FIGURE_NAMES:%=$(BUILD)/bin/%)

# The data of figure X and the report's values: run the program X (a pattern rule with two targets:
# one run makes both).
$(DATA)/%.dat $(DATA)/%.tex: $(BUILD)/bin/% | $(DATA)
	$< --output $(DATA)/$*.dat --tex $(DATA)/$*.tex

# Figure X from its gnuplot script and its data (written under a temporary name, then renamed). This
# cairo ignores SOURCE_DATE_EPOCH: its creation date is replaced by a fixed one of the same length (so
# the PDF's byte offsets stay valid), and the same data give the same figure, byte for byte.
$(FIGURES)/%.pdf: figures/%.gp figures/style.gp $(DATA)/%.dat | $(FIGURES)
	$(REPRODUCIBLE) gnuplot -e "data='$(DATA)/$*.dat'; output='$@.tmp'" $<
	LC_ALL=C sed -i 's|/CreationDate (D:[0-9]\{14\}Z)|/CreationDate (D:19700101000000Z)|' $@.tmp
	mv $@.tmp $@

# The report's title page and its back: the authors and version of CITATION.cff, the last commit and its
# date, the tools' and libraries' versions, the vector target of the batched step (build_info) and the
# command, `make all` whatever variables were given (CI compares `make all WERROR=1` with `make all`,
# byte for byte; tools/report_meta.sh). Remade on every run, but rewritten only when it changes, so that the
# report is not rebuilt for nothing; the same commit gives the same bytes.
.PHONY: FORCE
.SECONDARY: $(BUILD)/bin/build_info
$(DATA)/report_meta.tex: FORCE $(BUILD)/bin/build_info | $(DATA)
	tools/report_meta.sh CITATION.cff $(BUILD)/bin/build_info > $@.tmp
	if cmp -s $@.tmp $@; then rm -f $@.tmp; else mv $@.tmp $@; fi

# The times of the README's two commands for the article's section on reproducing it: the values of
# doc/build_times.txt (tools/measure_commands.sh measures them; tools/readme.sh writes the README's
# sentence from the same file).
$(DATA)/build_times.tex: doc/build_times.txt tools/build_times_tex.sh tools/build_times.awk | $(DATA)
	tools/build_times_tex.sh doc/build_times.txt > $@.tmp
	mv $@.tmp $@

# EC and CN-switch against Crank–Nicolson and backward Euler (mathematics.md §12): one program,
# experiments/fig_energy_schemes.cpp, three views, each its own run, data file, values and figure
# (a pattern rule more specific than the one above: make takes the one with the shorter stem).
.SECONDARY: $(BUILD)/bin/fig_energy_schemes
$(DATA)/fig_energy_schemes_%.dat $(DATA)/fig_energy_schemes_%.tex: $(BUILD)/bin/fig_energy_schemes | $(DATA)
	$< --view $* --output $(DATA)/fig_energy_schemes_$*.dat --tex $(DATA)/fig_energy_schemes_$*.tex

# The baseline over regions: PS (¼, 0) with the consistent mass against CN + Mod 3, EC and CN-switch
# (experiments/baseline_regions.cpp): one data file, and the report's two tables and conclusion values.
.SECONDARY: $(BUILD)/bin/baseline_regions
$(BASELINE) &: $(BUILD)/bin/baseline_regions | $(DATA)
	$< --output $(DATA)/baseline_regions.dat --tex $(DATA)/baseline_regions.tex

# The field's benchmarks on fine meshes (experiments/field_asymptotics.cpp; `make field-asymptotics`, never
# part of `make all`): Crank–Nicolson with Mod 1/2/3 up to N = 2560, about 240 CPU-s (two minutes on 2
# cores). Its data file and values are committed in doc/results/, which the report reads; the ctest entry
# field_asymptotics_committed reruns the coarse meshes and compares them, byte for byte, with the
# committed rows, so that the committed file stays this code's output.
FIELD_ASYMPTOTICS := doc/results/field_asymptotics.dat doc/results/field_asymptotics.tex
field-asymptotics: $(BUILD)/bin/field_asymptotics
	$< --output doc/results/field_asymptotics.dat --tex doc/results/field_asymptotics.tex

# The peer match (doc/peer.md): bar1d --peer getfem-vK against the measures GetFEM's demo printed
# (tests/data/getfem/measures.dat, its header says how they were made), compared and tabulated by
# tools/getfem_peer.sh (a few seconds; the same comparison is the ctest entry getfem_peer).
PEER_TEX := $(DATA)/peer_getfem.tex
$(PEER_TEX): $(BUILD)/bin/bar1d tests/data/getfem/measures.dat tools/getfem_peer.sh | $(DATA)
	tools/getfem_peer.sh $< tests/data/getfem/measures.dat $@ > $(DATA)/peer_getfem.txt

# The contact classes side by side (doc/contact_treatments.md, experiments/fig_classes.cpp): one run (its wall
# time on standard output, ~10 s), one data file and values, four figures read from that file.
CLASSES_VIEWS := accuracy oscillation energy penetration
CLASSES := $(DATA)/fig_classes.dat $(DATA)/fig_classes.tex
CLASSES_PDFS := $(CLASSES_VIEWS:%=$(FIGURES)/fig_classes_%.pdf)
$(REPORT) $(SUPPLEMENT): $(CLASSES) $(CLASSES_PDFS)
.SECONDARY: $(BUILD)/bin/fig_classes
$(CLASSES) &: $(BUILD)/bin/fig_classes | $(DATA)
	$< --output $(DATA)/fig_classes.dat --tex $(DATA)/fig_classes.tex
$(FIGURES)/fig_classes_%.pdf: figures/fig_classes_%.gp figures/style.gp figures/fig_classes_blocks.awk $(DATA)/fig_classes.dat | $(FIGURES)
	$(REPRODUCIBLE) gnuplot -e "data='$(DATA)/fig_classes.dat'; output='$@.tmp'" $<
	LC_ALL=C sed -i 's|/CreationDate (D:[0-9]\{14\}Z)|/CreationDate (D:19700101000000Z)|' $@.tmp
	mv $@.tmp $@

# Crank–Nicolson's largest energy for Δt ≫ h, relative to E_h(0) (experiments/cn_large_step.cpp).
$(DATA)/cn_large_step.tex: $(BUILD)/bin/cn_large_step | $(DATA)
	$< --tex $@

# The article and its supplement: every figure and fragment is found through TEXINPUTS (so OUT=dir
# works); latexmk keeps its auxiliary files in $(OUT)/latex. The full benchmark's table and plot (make
# bench) are included if present, the short benchmark's otherwise. Each document refers to the other's
# sections, figures and tables through the other's .aux (xr-hyper's \externaldocument, found through
# TEXINPUTS): one rule makes both, in two rounds. Before each round it copies each document's .aux to
# xr-<document>.aux (an empty one if there is none yet), which the other document reads, then typesets
# both at once, on two cores: neither reads a file the other is writing, and the second round sees the
# labels the first one settled (numbers of sections, tables and figures, which do not depend on the
# other document's text: two rounds are what the documents need, as two runs in turn each did before).
# The first round is one pdflatex run of each in draft mode (no PDF): the numbers of the labels are
# those of the first run, as neither document refers to a page of the other. The second is latexmk,
# which reruns a document only while a file it read changed (its own .aux, its table of contents): the
# supplement takes three runs in all instead of four when the first round was latexmk too. Each document,
# as soon as its second round is done (the article's while the supplement is still typeset), is checked
# (tools/check_pdf.sh): a reference left undefined or a label defined twice fails the rule; so does a < or
# > in text mode, which the text font prints as ¡ or ¿, and a bitmap (Type 3) font: both documents are
# vector throughout (so that they print and zoom alike). The article has at most 20 pages.
TEX_ENV := TEXINPUTS=paper:$(DATA):$(FIGURES):$(OUT)/bench:$(BENCH_SHORT):doc/results:$(OUT)/latex: $(REPRODUCIBLE)
LATEXMK := $(TEX_ENV) latexmk -pdf -silent -interaction=nonstopmode -halt-on-error -outdir=$(OUT)/latex
PDFLATEX_DRAFT := $(TEX_ENV) pdflatex -draftmode -interaction=nonstopmode -halt-on-error -output-directory=$(OUT)/latex
$(REPORT) $(SUPPLEMENT) &: $(REPORT_SOURCES) tools/check_pdf.sh $(FIGURE_PDFS) $(FIGURE_TEX) $(CLAIMS_TEX) $(DATA)/cn_large_step.tex \
           $(BASELINE) $(FIELD_ASYMPTOTICS) \
           $(DATA)/report_meta.tex $(DATA)/build_times.tex $(BENCH_SHORT)/bench_short.tex $(PEER_TEX) \
           $(wildcard $(OUT)/bench/bench_step.tex $(OUT)/bench/bench_step.pdf) | $(DATA)
	mkdir -p $(OUT)/latex
	for round in 1 2; do \
	  for doc in report supplement; do \
	    rm -f $(OUT)/latex/xr-$$doc.aux; \
	    if [[ -e $(OUT)/latex/$$doc.aux ]]; then cp $(OUT)/latex/$$doc.aux $(OUT)/latex/xr-$$doc.aux; \
	    else : > $(OUT)/latex/xr-$$doc.aux; fi; \
	  done; \
	  failed=0; \
	  if ((round == 1)); then \
	    $(PDFLATEX_DRAFT) paper/supplement.tex > /dev/null & supplement=$$!; \
	    $(PDFLATEX_DRAFT) paper/report.tex > /dev/null & report=$$!; \
	  else \
	    { $(LATEXMK) paper/supplement.tex && tools/check_pdf.sh $(OUT)/latex supplement; } & supplement=$$!; \
	    { $(LATEXMK) paper/report.tex && tools/check_pdf.sh $(OUT)/latex report; } & report=$$!; \
	  fi; \
	  wait $$supplement || { failed=1; grep -A4 '^!' $(OUT)/latex/supplement.log || true; }; \
	  wait $$report || { failed=1; grep -A4 '^!' $(OUT)/latex/report.log || true; }; \
	  ((failed == 0)); \
	done
	@pages=$$(pdfinfo $(OUT)/latex/report.pdf | awk '/^Pages:/ { print $$2 }'); ((pages <= 20)) \
	  || { echo "report: the article has $$pages pages, at most 20 (move the evidence to the supplement)"; exit 1; }
	cp $(OUT)/latex/report.pdf $(REPORT).tmp
	cp $(OUT)/latex/supplement.pdf $(SUPPLEMENT).tmp
	mv $(REPORT).tmp $(REPORT)
	mv $(SUPPLEMENT).tmp $(SUPPLEMENT)

# The API documentation (Doxyfile): lib/ and the documents of doc/ that exist (the main page, the
# mathematics, the field's benchmarks, contact treatments and peer, and one page per module whose
# derivation it renders, doc/module_*.md). Any warning in $(DOC)/doxygen.log (an undocumented public
# member, a broken reference) fails the build, and so does markup that doxygen printed as text without a
# warning (tools/doc_markup.sh: a code span in a heading, a bold span it did not take, a table it did not
# render; its findings in $(DOC)/doc_markup.log). The formulas are rendered by MathJax 2 from Debian's
# libjs-mathjax, whose needed parts are copied beside the HTML (MATHJAX_RELPATH = mathjax), so that the
# pages work offline.
DOC_INPUT := lib $(wildcard doc/mainpage.md doc/mathematics.md doc/architecture.md doc/benchmarks.md doc/contact_treatments.md doc/peer.md \
                            doc/module_*.md)
MATHJAX := /usr/share/javascript/mathjax
MATHJAX_PARTS := MathJax.js extensions jax/input/TeX jax/element jax/output/HTML-CSS fonts/HTML-CSS/TeX \
                 localization/en

$(DOC)/html/index.html: Doxyfile tools/doc_markup.sh $(wildcard lib/*/*.hpp lib/*/*.cpp doc/*.md) | $(DOC)
	rm -rf $(DOC)/html
	( cat Doxyfile; echo 'OUTPUT_DIRECTORY = $(DOC)'; echo 'INPUT = $(DOC_INPUT)'; \
	  $(if $(filter doc/mainpage.md,$(DOC_INPUT)),,echo 'USE_MDFILE_AS_MAINPAGE =') ) \
	  | doxygen - > $(DOC)/doxygen.log 2>&1
	if [[ -s $(DOC)/doxygen.log ]]; then cat $(DOC)/doxygen.log; \
	  echo 'doxygen: warnings (above, in $(DOC)/doxygen.log): document every public member of lib/'; exit 1; fi
	tools/doc_markup.sh $(DOC)/html > $(DOC)/doc_markup.log || { cat $(DOC)/doc_markup.log; exit 1; }
	for part in $(MATHJAX_PARTS); do \
	  mkdir -p $(DOC)/html/mathjax/$$(dirname $$part); cp -r $(MATHJAX)/$$part $(DOC)/html/mathjax/$$part; \
	done
	touch $@

# Output directories. Each waits for the packages, and so does every rule that writes in one (deps above).
$(DATA) $(FIGURES) $(DOC):
	mkdir -p $@
$(DATA) $(FIGURES) $(DOC) $(BENCH) $(BENCH_SHORT): | deps

# `make all`.
all: build $(ALL_RESULTS)

# Remove every build directory and every generated result.
clean:
	rm -rf -- $(sort $(BUILD) build build-sanitize $(OUT))

# List the targets and options.
help:
	@echo 'Targets:'
	@echo '  all      (default) build, then regenerate the results in $(OUT)/'
	@echo '  build    configure and build the library, tests and programs into $(BUILD)/bin/'
	@echo '  test     build, then run the whole test suite with ctest (the claims included)'
	@echo '  test-unit  build, then run the doctests alone (ctest -L unit)'
	@echo '  check-claims  build, then check every claim of the paper and print the table'
	@echo '  bench    build, then time one step per node for N = 2^6..2^20 ($(OUT)/bench/bench_step.*)'
	@echo '           (all runs a short one, N = 2^8..2^14, into $(OUT)/bench-short/ for the report)'
	@echo '  deps     check the Debian packages, installing the missing ones if root (tools/deps.sh)'
	@echo '  install  build the method library without its doctests and install it under $(PREFIX)'
	@echo '  readme   rewrite the README'"'"'s generated blocks (verdicts, times) from $(DATA)/claims.txt'
	@echo '  field-asymptotics  rerun the field'"'"'s benchmarks up to N = 2560 into doc/results/ (committed; ~2 min)'
	@echo '  figures  the figures in $(FIGURES)/ (part of all)'
	@echo '  report   the article $(REPORT) and its supplement $(SUPPLEMENT) (part of all)'
	@echo '  doc      the API documentation, $(DOC)/html/index.html (part of all)'
	@echo '  clean    remove build/, build-sanitize/ and $(OUT)/'
	@echo '  help     this list'
	@echo 'Options (on the command line):'
	@echo '  WERROR=1    compiler warnings are errors'
	@echo '  SANITIZE=1  ASan + UBSan build (RelWithDebInfo) in build-sanitize/'
	@echo '  BUILD=dir   build directory (default: build, or build-sanitize with SANITIZE=1)'
	@echo '  OUT=dir     output directory (default: output)'
	@echo '  PREFIX=dir  where make install installs (default: /usr/local)'
	@echo '  JOBS=n      parallel compile jobs (default: nproc)'
	@echo '  BENCH_CLOCK=cpu  make bench times thread CPU time instead of wall time (loaded machine)'
