# vri: `make test` and `make experiments` install what is missing, configure, build and run.
BUILD ?= build
JOBS ?= $(shell nproc)
# The volumes: CI and this repository's neighbours keep them in ../shared/data/volumes.
VRI_DATA_DIR ?= $(abspath ../shared/data/volumes)
export VRI_DATA_DIR

.PHONY: all deps build test experiments clean

all: build

deps:
	@scripts/install-deps.sh

$(BUILD)/build.ninja: | deps
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

test: build
	ctest --test-dir $(BUILD) --output-on-failure -j $(JOBS)

experiments: build
	scripts/run-experiments.sh $(BUILD)/bin results

clean:
	rm -rf $(BUILD)
