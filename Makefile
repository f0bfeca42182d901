# revisit: the commands a user runs. Each installs what it needs (Debian bookworm) and builds first.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)

.PHONY: all setup build test demo bench fuzz clean

all: build

setup:
	@scripts/setup-debian.sh

build: setup
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j $(JOBS)

## The whole test suite (GoogleTest through ctest).
test: build
	ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

## The built-in demo: simulate a city drive with revisits (cached), run the whole chain, print the report.
demo: build
	$(BUILD_DIR)/revisit demo

## Google Benchmark micro-benchmarks (not part of the tests). Missing real data fails (exit 2) unless
## BENCH_ARGS=--skip-missing; BENCH_ARGS="--data DIR" names the data folder (default ../shared/data).
bench: build
	cmake --build $(BUILD_DIR) --target revisit_benchmarks -j $(JOBS)
	@status=0; for b in $(BUILD_DIR)/bench/bench_*; do echo "== $$b"; $$b $(BENCH_ARGS) || status=1; done; exit $$status

## libFuzzer on every reader, each target FUZZ_SECONDS long (default 60), one after another.
fuzz:
	scripts/fuzz.sh $(or $(FUZZ_SECONDS),60)

clean:
	rm -rf $(BUILD_DIR) build-fuzz
