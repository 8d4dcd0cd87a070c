# vri: `make test` and `make experiments` install what is missing, configure, build and run.
BUILD ?= build
JOBS ?= $(shell nproc)
# The volumes: CI and this repository's neighbours keep them in ../shared/data/volumes; elsewhere
# `make data` downloads them into data/.
VRI_DATA_DIR ?= $(if $(wildcard ../shared/data/volumes),$(abspath ../shared/data/volumes),$(abspath data))
export VRI_DATA_DIR

.PHONY: all deps deps-fuzz build test test-full test-slurm-timeout test-no-vulkan test-sanitize fuzz install experiments experiments-quick bench bricks-memory bricks-slurm estimate clean

all: build

# The Debian packages the build and the tests need (scripts/install-deps.sh); build, test and
# experiments depend on it, so it runs first everywhere. Then the web peers' npm packages (npm ci in
# tools/peers/web) when node_modules is missing or older than package-lock.json, if npm is here.
deps:
	@scripts/install-deps.sh
	@cd tools/peers/web && { [ node_modules/.package-lock.json -nt package-lock.json ] || ! command -v npm >/dev/null || npm ci --no-audit --no-fund --loglevel=error; }

# ccache, when installed (make deps installs it), keeps compiled objects across build folders and
# clones: a second clone, or a build after a pull, recompiles only what changed. Looked up when the
# build is configured, after deps; paths under this folder are hashed relative to it, so that two
# clones share objects.
CCACHE = $(shell command -v ccache 2>/dev/null)
export CCACHE_BASEDIR ?= $(CURDIR)
CMAKE_CONFIGURE = cmake -S . -G Ninja $(if $(CCACHE),-DCMAKE_CXX_COMPILER_LAUNCHER=$(CCACHE))

$(BUILD)/build.ninja: | deps
	$(CMAKE_CONFIGURE) -B $(BUILD) -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

# ctest with one CPU slot a job (tests/CMakeLists.txt, "CPU slots"): JOBS CPU-bound tests at once, and the
# tests that mostly wait on a cluster beside them. $(1): the build folder.
CTEST = printf '{"version":{"major":1,"minor":0},"local":[{"cpus":[{"id":"0","slots":%d}]}]}\n' $(JOBS) \
          >$(1)/ctest-cpu-slots.json && \
        ctest --test-dir $(1) --output-on-failure -j $$(($(JOBS) + 2)) --resource-spec-file $(abspath $(1))/ctest-cpu-slots.json

test: build
	$(call CTEST,$(BUILD))

# vri-run's retry after TIMEOUT on a real Slurm cluster (tests/long/slurm_timeout.sh): Slurm's smallest time
# limit is a minute, so it waits about 4 minutes and is not part of `make test`; needs root.
test-slurm-timeout: build
	VRI_BIN=$(abspath $(BUILD))/bin VRI_SOURCE=$(CURDIR) VRI_SCRATCH=$(abspath $(BUILD))/slurm-timeout tests/long/slurm_timeout.sh

# Every test at full size: the exact bound's adversarial suites run all their transfer functions, not the
# quick tier's third (docs/testing.md, "Tiers").
test-full: export VRI_TEST_TIER = full
test-full: build
	$(call CTEST,$(BUILD))

# The tools, libraries, headers, vriConfig.cmake and vri.pc under PREFIX (README, "Using vri as a library").
PREFIX ?= /usr/local
install: build
	cmake --install $(BUILD) --prefix "$(PREFIX)"

# Everything without the Vulkan backend (-DVRI_VULKAN=OFF) in $(NOVULKAN_BUILD): it must configure,
# build and pass every test that does not need Vulkan (those skip).
NOVULKAN_BUILD ?= build-novulkan
$(NOVULKAN_BUILD)/build.ninja: | deps
	$(CMAKE_CONFIGURE) -B $(NOVULKAN_BUILD) -DCMAKE_BUILD_TYPE=Release -DVRI_VULKAN=OFF

test-no-vulkan: deps $(NOVULKAN_BUILD)/build.ninja
	cmake --build $(NOVULKAN_BUILD) -j $(JOBS)
	$(call CTEST,$(NOVULKAN_BUILD))

# Every test again, built with ASan + UBSan (float-to-integer casts included); the first report fails
# its test. About 30 min on 2 cores, so not part of .ci/run (README, Testing).
SANITIZE_BUILD ?= build-sanitize
$(SANITIZE_BUILD)/build.ninja: | deps
	$(CMAKE_CONFIGURE) -B $(SANITIZE_BUILD) -DCMAKE_BUILD_TYPE=Release -DVRI_SANITIZE=ON

# Two passes. Mesa's lavapipe leaks a few hundred bytes per Vulkan instance from a driver the loader has
# unloaded by exit, so LeakSanitizer can neither name nor suppress them: every other test runs first with no
# Vulkan driver visible and leak checking on, then the tests that need a Vulkan driver run with leak
# checking off: the Vulkan backend's, and those that start Chromium, whose WebGL runs on its own SwiftShader
# Vulkan driver (the web peers, and tool.reproduce's quick experiments, which run them). ASan and UBSan stop
# at their first report in both.
SANITIZE_ENV = UBSAN_OPTIONS=print_stacktrace=1 VK_DRIVER_FILES=/nonexistent.json VK_ICD_FILENAMES=/nonexistent.json
VULKAN_TESTS = Vulkan|tool[.](vulkan|sampler_probe|render_tau_sweep|peers_web|peers_web_slurm|reproduce)$$
test-sanitize: deps $(SANITIZE_BUILD)/build.ninja
	cmake --build $(SANITIZE_BUILD) -j $(JOBS)
	$(SANITIZE_ENV) ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS) -E '$(VULKAN_TESTS)'
	UBSAN_OPTIONS=print_stacktrace=1 ASAN_OPTIONS=detect_leaks=0:abort_on_error=1 \
	  ctest --test-dir $(SANITIZE_BUILD) --output-on-failure -j $(JOBS) -R '$(VULKAN_TESTS)'

# The parsers' libFuzzer targets (tests/fuzz), FUZZ_SECONDS each, built with clang in $(FUZZ_BUILD).
FUZZ_BUILD ?= build-fuzz
FUZZ_SECONDS ?= 60
FUZZ_TARGETS ?= nhdr mhd dat tf_yaml experiment_yaml vdb_metadata squeue tile_stats manifest
FUZZ_CXX ?= clang++-14
deps-fuzz:
	@scripts/install-deps.sh fuzz

$(FUZZ_BUILD)/build.ninja: | deps-fuzz
	cmake -S . -B $(FUZZ_BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release -DVRI_FUZZ=ON -DCMAKE_CXX_COMPILER=$(FUZZ_CXX)

fuzz: deps-fuzz $(FUZZ_BUILD)/build.ninja
	cmake --build $(FUZZ_BUILD) -j $(JOBS)
	scripts/fuzz.sh $(FUZZ_BUILD) $(FUZZ_SECONDS) $(FUZZ_TARGETS)

# Every experiment file (experiments/datasets.yaml is the dataset catalog, not an experiment), the benchmark
# experiments/bench.yaml included; `make bench` runs the benchmark alone (experiments/README.md, "What an
# experiment costs"; `make estimate` prices each experiment from its last manifest).
EXPERIMENTS ?= $(filter-out experiments/datasets.yaml,$(wildcard experiments/*.yaml))

# Only steps whose inputs changed run again; results/README.md is the gallery of all of them. Renders run
# alone; diffs, tables and figures up to $(JOBS) at once.
experiments: build
	$(BUILD)/bin/vri-run --jobs $(JOBS) --results results --gallery results $(EXPERIMENTS)

bench: build
	$(BUILD)/bin/vri-run --jobs $(JOBS) --results results --gallery results experiments/bench.yaml

# Peak memory of a synthetic 1024^3 volume rendered whole and as 2 x 2 x 2 bricks (docs/conventions/bricks.md).
bricks-memory: build
	scripts/brick-memory.sh $(BUILD) 1024 2

# A synthetic 2048^3 volume (8 GiB) as 2 x 2 x 2 bricks through a two-node Slurm test cluster of this machine
# that enforces memory, each brick's job given 2 GiB, against the whole volume rendered locally (about 11 GiB of
# this machine's memory); needs root (docs/conventions/bricks.md).
bricks-slurm: build
	scripts/brick-memory-slurm.sh $(BUILD) 2048 2 2048

estimate: build
	$(BUILD)/bin/vri-run --estimate --results results $(EXPERIMENTS)

# The same at reduced sizes (each file's quick: block), into $(BUILD)/experiments-quick.
experiments-quick: build
	$(BUILD)/bin/vri-run --jobs $(JOBS) --quick --results $(BUILD)/experiments-quick --gallery $(BUILD)/experiments-quick $(EXPERIMENTS)

clean:
	rm -rf $(BUILD) $(SANITIZE_BUILD) $(FUZZ_BUILD) $(NOVULKAN_BUILD)

# The datasets: checks each one of experiments/datasets.yaml in $(VRI_DATA_DIR) (size, SHA-512) and
# downloads the missing ones there from their published URLs; fails on MISSING or MISMATCH.
.PHONY: data
data: build
	$(BUILD)/bin/vri-data --catalog experiments/datasets.yaml --data-dir "$(VRI_DATA_DIR)"
