# Ballista top-level entry points. `make demo` and `make test` are the two README commands.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
PY := /usr/bin/python3

.PHONY: all deps configure build demo test test-sanitize bench clean format

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

# The default suite (same -LE slow selection) under AddressSanitizer + UBSan (CMake option
# BALLISTA_SANITIZE) in its own tree, build-sanitize/; the Python checkers run the sanitized
# `ballista` ($<TARGET_FILE:ballista> of that tree). RelWithDebInfo (-O2 -g): -O1 makes the
# MPM examples and verification problems about twice as slow again on top of ASan's ~2-3x, while
# -O2 still gives usable stacks with frame pointers kept. LeakSanitizer works here (no ptrace
# restriction), so leaks fail a test too. Every sanitizer report fails the test that made it.
SAN_DIR ?= build-sanitize
SAN_ENV := ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

test-sanitize: deps
	@cmake -S . -B $(SAN_DIR) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBALLISTA_SANITIZE=ON >/dev/null
	@cmake --build $(SAN_DIR) -j $(JOBS)
	@cd $(SAN_DIR) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) -LE slow

bench: build
	@./$(BUILD_DIR)/bench/mpm_block_impact_bench

clean:
	rm -rf $(BUILD_DIR) $(SAN_DIR) out

format:
	@find src apps tests bench -name '*.[ch]pp' | xargs clang-format -i
