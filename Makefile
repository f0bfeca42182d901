# revisit: the commands a user runs. Each installs what it needs (Debian bookworm) and builds first.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?= -DCMAKE_BUILD_TYPE=Release

.PHONY: all setup setup-test build build-all test demo bench fuzz clean

all: build

## What building and running `revisit` needs.
setup:
	@scripts/setup-debian.sh

## Also what the tests, the fuzz smoke, Slurm's test and the micro-benchmarks need.
setup-test:
	@scripts/setup-debian.sh --test

## The `revisit` command alone (no tests): build/revisit.
build: setup
	cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS) -DREVISIT_BUILD_TESTS=OFF
	cmake --build $(BUILD_DIR) --target revisit_cli -j $(JOBS)

## Everything: the command, the tests.
build-all: setup-test
	cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS) -DREVISIT_BUILD_TESTS=ON
	cmake --build $(BUILD_DIR) -j $(JOBS)

## The whole test suite (GoogleTest through ctest); skipped tests are listed with their reasons at the end.
test: build-all
	@scripts/run-tests.sh $(BUILD_DIR) $(JOBS)

## The built-in demo: a simulated city drive with revisits, read straight from the simulator (nothing
## cached), the whole chain, the report. Builds only the command.
demo: build
	$(BUILD_DIR)/revisit demo

## Google Benchmark micro-benchmarks in microbench/ (not part of the tests). Missing real data fails
## (exit 2) unless BENCH_ARGS=--skip-missing; BENCH_ARGS="--data DIR" names the data folder (default
## ../shared/data). `build/revisit bench` is the command's own benchmark suite.
bench: build-all
	cmake --build $(BUILD_DIR) --target revisit_benchmarks -j $(JOBS)
	@status=0; for b in $(BUILD_DIR)/microbench/bench_*; do echo "== $$b"; $$b $(BENCH_ARGS) || status=1; done; exit $$status

## libFuzzer on every reader, each target FUZZ_SECONDS long (default 60), one after another.
fuzz: setup-test
	scripts/fuzz.sh $(or $(FUZZ_SECONDS),60)

clean:
	rm -rf $(BUILD_DIR) build-fuzz
