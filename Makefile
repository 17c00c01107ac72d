# Thin wrapper around CMake. The two set-up commands of the README:
#   make demo    installs missing packages, builds (Release) and renders the default scene
#   make check   installs missing packages, builds (Release) and runs every test through ctest
# Also: make build, make sanitize (ASan + UBSan build and unit tests), make bench, make clean.
BUILD ?= build
SAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)
DEPS_STAMP := $(BUILD)/.deps-ok

.PHONY: all build demo check sanitize bench clean deps

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	@scripts/install-deps.sh
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: deps build
	@scripts/demo.sh $(BUILD)

check: deps build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DSSS_SANITIZE=ON
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS) -L unit

bench: deps build
	@for b in $(BUILD)/bench/bench_*; do echo "== $$b"; $$b; done

clean:
	rm -rf $(BUILD) $(SAN_BUILD)
