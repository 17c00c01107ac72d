# Thin wrapper around CMake. The two set-up commands of the README:
#   make demo    installs missing packages, builds (Release) and renders the default scene
#   make check   installs missing packages, builds (Release) and runs every test through ctest
#   make install [PREFIX=/usr/local]  builds, then installs the library, headers, tool, CMake package,
#                               pkg-config file and docs under PREFIX (docs/versioning.md)
# Also: make build, make sanitize (ASan + UBSan build and unit tests), make bench, make clean,
#   make fuzz [FUZZ_SECONDS=N]  libFuzzer (clang) on every parser, N seconds each (default 60); the
#                               corpus grows in $(FUZZ_BUILD)/fuzz-corpus from run to run
#   make fuzz-ci                each target 60 s from the committed seeds, one per processor at a
#                               time; fails on any finding
BUILD ?= build
SAN_BUILD ?= build-asan
JOBS ?= $(shell nproc)

PREFIX ?= /usr/local

FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60

.PHONY: all build demo check install sanitize bench clean deps fuzz fuzz-ci fuzz-build

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/CMakeCache.txt:
	@scripts/install-deps.sh
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

demo: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS) --target sss_cli
	@scripts/demo.sh $(BUILD)

check: deps build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

install: build
	cmake --install $(BUILD) --prefix $(PREFIX)

sanitize: deps
	cmake -S . -B $(SAN_BUILD) -DCMAKE_BUILD_TYPE=Debug -DSSS_SANITIZE=ON
	cmake --build $(SAN_BUILD) -j $(JOBS)
	cd $(SAN_BUILD) && ASAN_OPTIONS=detect_leaks=1 ctest --output-on-failure -j $(JOBS) -L unit

bench: deps build
	@for b in $(BUILD)/bench/bench_*; do echo "== $$b"; $$b; done

fuzz-build:
	@scripts/install-deps.sh --ci
	cmake -S . -B $(FUZZ_BUILD) -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang \
		-DCMAKE_CXX_COMPILER=clang++ -DSSS_FUZZ=ON
	cmake --build $(FUZZ_BUILD) -j $(JOBS) --target fuzz_all

fuzz: fuzz-build
	fuzz/run_fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS)

fuzz-ci: fuzz-build
	fuzz/run_fuzz.sh --ci $(FUZZ_BUILD) 60

clean:
	rm -rf $(BUILD) $(SAN_BUILD) $(FUZZ_BUILD)
