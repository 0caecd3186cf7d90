# coatcontact: the two commands a user types are `make figures` (default) and `make test`.
# Both install missing Debian packages first (scripts/install-deps.sh), then configure and
# build a Release tree in build/.
BUILD      ?= build
JOBS       ?= 2
CMAKE_ARGS ?=
CLI        := $(BUILD)/bin/coatcontact

.PHONY: all figures test bench clean deps build build-cli fuzz fit-example

all: figures

deps:
	@bash scripts/install-deps.sh

$(BUILD)/CMakeCache.txt: | deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release $(CMAKE_ARGS)

build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# The CLI alone, all `make figures` needs: a built tree's check of the whole suite's 120
# targets costs ~1 s per run; the tests are built by `make test`. Even the CLI's own check
# (cmake --build: ~45 cmake and make processes, ~0.27 s) is skipped when nothing it could
# depend on changed since its last success: no file of the source tree (build trees and .git
# aside), of the CMake cache or of the Debian package database (compilers, system headers and
# libraries) is newer than $(CLI_STAMP). The stamp's time is taken one second before the build
# starts, so a file edited while it runs is seen next time.
CLI_STAMP := $(BUILD)/cli-build.stamp
CLI_INPUTS_NEWER = find . \( -name .git -o -path './build*' -o -path './$(BUILD)' \) -prune -o \
  -newer $(CLI_STAMP) -print -quit; \
  find $(BUILD)/CMakeCache.txt $(wildcard /var/lib/dpkg/status) -newer $(CLI_STAMP) -print -quit
build-cli: deps $(BUILD)/CMakeCache.txt
	@if [ -x $(CLI) ] && [ -f $(CLI_STAMP) ] && [ -z "$$($(CLI_INPUTS_NEWER))" ]; then :; else \
	  touch -d '1 second ago' $(CLI_STAMP).new && \
	  cmake --build $(BUILD) -j $(JOBS) --target coatcontact && \
	  mv -f $(CLI_STAMP).new $(CLI_STAMP); fi

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

bench: deps
	COATCONTACT_EXTRAS=1 bash scripts/install-deps.sh
	cmake -S . -B $(BUILD) -DCOATCONTACT_BUILD_BENCH=ON
	cmake --build $(BUILD) -j $(JOBS)
	bash bench/run.sh $(BUILD)

clean:
	rm -rf $(BUILD)

# Figures: data by the CLI, plots by gnuplot (parameters in data/figures.conf).
include gnuplot/figures.mk

# Fuzzing (issue 7): libFuzzer + ASan/UBSan on the value parsers, the data file reader and the
# AFM and indentation readers (corpus_afm, corpus_indent: small real files or their heads), in
# a separate clang tree (Fortran stays gfortran); only the fuzz targets are built. New corpus
# entries go to $(FUZZ_BUILD)/corpus, crash reproducers to $(FUZZ_BUILD)/artifacts.
FUZZ_BUILD   ?= build-fuzz
FUZZ_SECONDS ?= 60
fuzz:
	COATCONTACT_EXTRAS=1 bash scripts/install-deps.sh
	CC=clang CXX=clang++ cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo \
	  -DCMAKE_C_COMPILER=clang -DCMAKE_CXX_COMPILER=clang++ -DCMAKE_Fortran_COMPILER=gfortran \
	  -DCOATCONTACT_BUILD_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_parsers fuzz_data_file fuzz_afm fuzz_indent
	@for f in parsers data_file afm indent; do \
	  mkdir -p $(FUZZ_BUILD)/corpus/$$f $(FUZZ_BUILD)/artifacts/$$f || exit 1; \
	  echo "== fuzz_$$f for $(FUZZ_SECONDS) s"; \
	  $(FUZZ_BUILD)/fuzz/fuzz_$$f -max_total_time=$(FUZZ_SECONDS) -print_final_stats=1 -malloc_limit_mb=256 \
	    -artifact_prefix=$(FUZZ_BUILD)/artifacts/$$f/ \
	    $(FUZZ_BUILD)/corpus/$$f tests/fuzz/corpus_$$f || exit 1; \
	done

# Fit example (issue 6): fit w and t to both example data sets in data/ and plot data, fit and
# residuals into $(BUILD)/figures/fit_example.png (gnuplot/fit_example.gp).
FIT_MODEL := --radius 5mm --film 1MPa,0.49 --substrate 70GPa,0.22 --free w,t --start t=40um
fit-example: build
	@mkdir -p $(BUILD)/figures
	$(CLI) fit data/example_a_F.tsv --columns a,F $(FIT_MODEL) \
	  --output $(BUILD)/figures/fit_a_F.tsv --curve $(BUILD)/figures/curve_a_F.tsv
	$(CLI) fit data/example_delta_F.tsv --columns delta,F $(FIT_MODEL) \
	  --output $(BUILD)/figures/fit_delta_F.tsv --curve $(BUILD)/figures/curve_delta_F.tsv
	gnuplot -e "gpdir='gnuplot'; dir='$(BUILD)/figures'; outfile='$(BUILD)/figures/fit_example.png.tmp'; fmt='png'" \
	  gnuplot/fit_example.gp && mv $(BUILD)/figures/fit_example.png.tmp $(BUILD)/figures/fit_example.png
	@echo "wrote $(BUILD)/figures/fit_example.png"
