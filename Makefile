# The two set-up commands on a fresh Debian machine: `make demo` and `make test`.
# Each installs what is missing (scripts/install-deps.sh), configures, builds and runs.
PRESET ?= release
JOBS   ?= $(shell nproc)

.PHONY: all deps build test demo bench clean

all: build

deps:
	bash scripts/install-deps.sh

build: deps
	cmake --preset $(PRESET)
	cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	ctest --preset $(PRESET) -j $(JOBS)

demo: build
	bash scripts/demo.sh

bench: build
	bash scripts/bench.sh

clean:
	rm -rf build build-debug build-sanitize build-portable
