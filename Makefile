# pkm top-level targets. `make demo` and `make test` are the two commands a newcomer needs.
BUILD      ?= build
ASAN_BUILD ?= build-asan
BENCH_BUILD ?= build-bench
JOBS       ?= $(shell nproc)
# The compiler. Clang (installed by scripts/setup.sh) builds pkm in about a third less time than GCC 12 on
# the same machine (docs/architecture.md, "Build time"); `make PKM_CXX=g++ test` uses GCC.
PKM_CXX    ?= clang++
CMAKE_FLAGS ?=
# CI builds treat warnings as errors.
WERROR := $(if $(CI),-DPKM_WARNINGS_AS_ERRORS=ON,)

.PHONY: all setup build build-asan demo test test-release test-asan check-size bench fuzz format clean

all: build

setup:
	@bash scripts/setup.sh
	@bash scripts/fetch-linuxcnc.sh

build: setup
	@cmake -S . -B $(BUILD) -G Ninja -DCMAKE_CXX_COMPILER=$(PKM_CXX) -DCMAKE_BUILD_TYPE=Release $(WERROR) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(BUILD) -j $(JOBS)

# The main job: the built-in default campaign (the four papers' scenarios) on the virtual
# machines, a summary table and report.html in $(BUILD)/demo, results in pkm.db.
demo: build
	@$(BUILD)/bin/pkm campaign run default --out $(BUILD)/demo --force --db pkm.db

test-release: build
	@cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

# The sanitizer build: asserts on, -O1 (AddressSanitizer's advice; Eigen and Ceres's automatic
# derivatives at -O0 run some tests hundreds of times slower than Release), line-table debug
# information only (-g1: file:line in sanitizer reports at a fraction of -g's compile time),
# shared module libraries (static ones put ~220 MB into each test program: 29 GB in all).
build-asan: setup
	@cmake -S . -B $(ASAN_BUILD) -G Ninja -DCMAKE_CXX_COMPILER=$(PKM_CXX) -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-g1 -O1" "-DPKM_SANITIZERS=address;undefined" -DPKM_SHARED_LIBS=ON $(WERROR) $(CMAKE_FLAGS) >/dev/null
	@cmake --build $(ASAN_BUILD) -j $(JOBS)

# The sanitizer run leaves the tests in tests/release-only.txt (a running LinuxCNC, Chromium, the
# largest fits) to the Release run: they take most of its time and add no sanitizer coverage.
RELEASE_ONLY := $(shell grep -v -e '^\#' -e '^$$' tests/release-only.txt | paste -sd'|')
test-asan: build-asan
	@cd $(ASAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1 ctest --output-on-failure -j $(JOBS) -E '$(RELEASE_ONLY)'

# House style's size limits (files <= 400 lines, functions <= 80): prints the offenders and fails
# the run if there are any (docs/architecture.md, "Size limits").
check-size:
	@/usr/bin/python3 scripts/check-size.py --strict

test: check-size test-release test-asan

# The whole-process comparisons with reference programs, run (and tabled) by benchmarks/summary.sh.
BENCH_VS_REFERENCE = $(addprefix benchmarks/,fk_vs_genhexkins_whole_process.sh \
  gcode_vs_rs274_whole_process.sh circle_vs_scipy_whole_process.sh table_read_whole_process.sh \
  calibration_vs_scipy_whole_process.sh)
bench: setup
	@cmake -S . -B $(BENCH_BUILD) -G Ninja -DCMAKE_CXX_COMPILER=$(PKM_CXX) -DCMAKE_BUILD_TYPE=Release -DPKM_BUILD_BENCHMARKS=ON -DPKM_BUILD_TESTS=OFF >/dev/null
	@cmake --build $(BENCH_BUILD) -j $(JOBS)
	@for b in $(BENCH_BUILD)/bin/bench_*; do echo "== $$b"; $$b || exit 1; done
	@for s in $(filter-out $(BENCH_VS_REFERENCE),$(wildcard benchmarks/*_whole_process.sh)); do \
	  echo "== $$s"; bash $$s $(BENCH_BUILD)/bin/pkm || exit 1; done
	@bash benchmarks/summary.sh $(BENCH_BUILD)

# The fuzz harnesses (docs/fuzzing.md): built with clang++-14, libFuzzer, ASan and UBSan in
# build-fuzz/, each run for FUZZ_SECONDS on its corpus (fuzz/corpus/<name>), one after the other;
# FUZZ_TARGETS picks some (e.g. FUZZ_TARGETS="csv tool_table"). `make test` replays the corpora.
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?=
fuzz: setup
	@bash fuzz/run.sh $(FUZZ_SECONDS) $(FUZZ_TARGETS)

format:
	@bash scripts/format.sh

clean:
	rm -rf $(BUILD) $(ASAN_BUILD) $(BENCH_BUILD)
