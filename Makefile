# Ballista top-level entry points. `make demo` and `make test` are the two README commands.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
PY := /usr/bin/python3

.PHONY: all deps configure build demo test bench clean format

all: build

deps:
	@./scripts/install-deps

configure: deps
	@cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@./scripts/run-demo $(BUILD_DIR)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow

bench: build
	@./$(BUILD_DIR)/bench/mpm_block_impact_bench

clean:
	rm -rf $(BUILD_DIR) out

format:
	@find src apps tests bench -name '*.[ch]pp' | xargs clang-format -i
