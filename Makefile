# vri: `make test` and `make experiments` install what is missing, configure, build and run.
BUILD ?= build
JOBS ?= $(shell nproc)
# The volumes: CI and this repository's neighbours keep them in ../shared/data/volumes; elsewhere
# `make data` downloads them into data/.
VRI_DATA_DIR ?= $(if $(wildcard ../shared/data/volumes),$(abspath ../shared/data/volumes),$(abspath data))
export VRI_DATA_DIR

.PHONY: all deps build test experiments experiments-quick clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

# Every experiment file (experiments/datasets.yaml is the dataset catalog, not an experiment).
EXPERIMENTS ?= $(filter-out experiments/datasets.yaml,$(wildcard experiments/*.yaml))

# Only steps whose inputs changed run again; results/README.md is the gallery of all of them.
experiments: build
	$(BUILD)/bin/vri-run --results results --gallery results $(EXPERIMENTS)

# The same at reduced sizes (each file's quick: block), into $(BUILD)/experiments-quick.
experiments-quick: build
	$(BUILD)/bin/vri-run --quick --results $(BUILD)/experiments-quick --gallery $(BUILD)/experiments-quick $(EXPERIMENTS)

clean:
	rm -rf $(BUILD)

# The datasets: checks each one of experiments/datasets.yaml in $(VRI_DATA_DIR) (size, SHA-512) and
# downloads the missing ones there from their published URLs; fails on MISSING or MISMATCH.
.PHONY: data
data: build
	$(BUILD)/bin/vri-data --catalog experiments/datasets.yaml --data-dir "$(VRI_DATA_DIR)"
