# Ballista top-level entry points. `make demo` and `make test` are the two README commands.
BUILD_DIR ?= build
JOBS ?= $(shell nproc)
PY := /usr/bin/python3
# Ninja schedules every object file as soon as its own inputs exist; Make's generator waits for a
# target's dependencies to link first, which idles a core at each layer of the library (the build
# took ~9 % longer on two cores). A tree configured earlier keeps its generator.
GENERATOR = $(if $(wildcard $(1)/CMakeCache.txt),,-G Ninja)

.PHONY: all deps configure build demo demo-converged test test-sanitize validate bench install package clean format

all: build

deps:
	@./scripts/install-deps

configure: deps
	@cmake -S . -B $(BUILD_DIR) $(call GENERATOR,$(BUILD_DIR)) -DCMAKE_BUILD_TYPE=Release >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	@./scripts/run-demo $(BUILD_DIR)

# The demo's depth and casing hole each within 5 % of converged: the deck as written, about 9 minutes on 2 cores.
demo-converged: build
	@./scripts/run-converged-demo $(BUILD_DIR)

test: build
	@cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS) -LE slow

# The V&V report at the documented sizes (tens of minutes): out/validate/report.html. `make test`
# runs its quick level (ctest validate.quick).
validate: build
	@$(BUILD_DIR)/ballista validate --level full -o out/validate

# The default suite (same -LE slow selection) under AddressSanitizer + UBSan (CMake option
# BALLISTA_SANITIZE) in its own tree, build-sanitize/; the Python checkers run the sanitized
# `ballista` ($<TARGET_FILE:ballista> of that tree). RelWithDebInfo (-O2 -g -DNDEBUG): the same
# NDEBUG as the Release suite, and -O2 keeps the MPM examples and verification problems well
# inside their ctest timeouts on top of ASan's slowdown (-O1 would be slower still); frame
# pointers are kept, so the stacks stay readable. LeakSanitizer works here (no ptrace
# restriction), so leaks count too, except under mpirun (label mpi): Open MPI's dlopen'ed
# components leave allocations whose stacks LeakSanitizer cannot name (tests/mpi/CMakeLists.txt).
# Some tests expect `ballista` to exit non-zero (a deck typo, a failing sweep run), where a
# sanitizer abort would pass unseen: ASan/LSan reports go to files in $(SAN_DIR)/sanitizer-logs/
# and any file there fails the target; UBSan ignores log_path when combined with ASan (GCC 12),
# so its reports stay on stderr and the checkers of those runs fail on "runtime error:".
SAN_DIR ?= build-sanitize
SAN_LOG = $(abspath $(SAN_DIR))/sanitizer-logs
SAN_ENV = ASAN_OPTIONS=detect_leaks=1:log_path=$(SAN_LOG)/asan UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1

test-sanitize: deps
	@cmake -S . -B $(SAN_DIR) $(call GENERATOR,$(SAN_DIR)) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DBALLISTA_SANITIZE=ON >/dev/null
	@cmake --build $(SAN_DIR) -j $(JOBS)
	@rm -rf $(SAN_LOG) && mkdir -p $(SAN_LOG)
	@cd $(SAN_DIR) && $(SAN_ENV) ctest --output-on-failure -j $(JOBS) -LE slow; status=$$?; \
	  if [ -n "$$(ls -A $(SAN_LOG))" ]; then \
	    echo "test-sanitize: sanitizer reports in $(SAN_LOG):"; cat $(SAN_LOG)/*; exit 1; fi; \
	  exit $$status

# The benchmark executables (bench/*.cpp) are built here, not by `build`: no test runs them.
bench: build
	@cmake --build $(BUILD_DIR) --target benches -j $(JOBS)
	@./$(BUILD_DIR)/bench/mpm_block_impact_bench

# Installs build/'s binary (tuned to this machine's CPU), the presets, the tools and the examples
# under PREFIX (default /usr/local; cmake/install.cmake).
PREFIX ?= /usr/local
install: build
	@cmake --install $(BUILD_DIR) --prefix $(PREFIX)

# A Debian package (build-package/ballista_<version>_<arch>.deb) of a binary for any x86-64 CPU
# (no -march=native), without the tests: `apt install ./build-package/ballista_*.deb`.
PKG_DIR ?= build-package
package: deps
	@cmake -S . -B $(PKG_DIR) $(call GENERATOR,$(PKG_DIR)) -DCMAKE_BUILD_TYPE=Release -DBALLISTA_NATIVE=OFF -DBALLISTA_TESTS=OFF >/dev/null
	@cmake --build $(PKG_DIR) -j $(JOBS)
	@cd $(PKG_DIR) && cpack -G DEB

clean:
	rm -rf $(BUILD_DIR) $(SAN_DIR) $(PKG_DIR) out

format:
	@find src apps tests bench -name '*.[ch]pp' | xargs clang-format -i
