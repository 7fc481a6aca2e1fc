# The two set-up commands on a fresh Debian machine: `make demo` and `make test`.
# Each installs what is missing (scripts/install-deps.sh), configures, builds and runs.
# Hardening (CI runs all of them, .ci/run): `make sanitize` (ASan + UBSan, the whole suite),
# `make tsan` (ThreadSanitizer, the parallel stages), `make fuzz` (libFuzzer targets, clang)
# and `make fuzz-run` (each target for FUZZ_SECONDS).
PRESET ?= release
JOBS   ?= $(shell nproc)
FUZZ_SECONDS ?= 15
FUZZ_SEED ?= 0
# ThreadSanitizer checks the threads tessera synchronises itself: the background frame writers
# (std::thread, mutex, condition variable). The oneTBB stages are left out: Debian's libtbb
# is not built with -fsanitize=thread, so TSan cannot see the synchronisation inside it
# (task spawn, waits, its small-object pool) and reports every parallel_for as a race.
# Checking them needs oneTBB built from source with TSan (see README, "Sanitizers").
# The tsan preset builds only these tests (TESSERA_THREAD_TESTS_ONLY) and the layers they use.
TSAN_TESTS ?= FrameWriter|FrameStream

.PHONY: all deps build test demo bench bench-report peer same-bytes sanitize tsan fuzz fuzz-run clean

all: build

deps:
	bash scripts/install-deps.sh

build: deps
	cmake --preset $(PRESET)
	cmake --build --preset $(PRESET) -j $(JOBS)

test: build
	ctest --preset $(PRESET) -j $(JOBS)

demo: build
	bash scripts/install-deps.sh demo
	bash scripts/demo.sh

bench: build
	bash scripts/bench.sh

# Tables and plots from the newest bench/results/<stamp>/ (or RESULTS=DIR).
bench-report:
	python3 scripts/bench-report.py $(RESULTS)

# tessera vs Mesa llvmpipe on the same workloads (PEER_ARGS, e.g. --workload sphere-1m --cpu).
peer: build
	bash scripts/peer.sh $(PEER_ARGS)

# The release build (this machine's SIMD width) and the portable one (x86-64-v3, AVX2) write
# the same bytes: every example scene, the raster command, the generators. CI runs it after
# `make test` (only the tessera target is built a second time).
same-bytes: build
	cmake --preset portable
	cmake --build --preset portable -j $(JOBS) --target tessera
	bash tests/builds_same_bytes.sh build/bin/tessera build-portable/bin/tessera

sanitize: deps
	cmake --preset sanitize
	cmake --build --preset sanitize -j $(JOBS)
	ctest --preset sanitize -j $(JOBS)

tsan: deps
	cmake --preset tsan
	cmake --build --preset tsan -j $(JOBS) --target tessera_tests
	ctest --preset tsan -j $(JOBS) -R '$(TSAN_TESTS)'

fuzz: deps
	cmake --preset fuzz
	cmake --build --preset fuzz -j $(JOBS)

fuzz-run: fuzz
	FUZZ_SEED=$(FUZZ_SEED) bash scripts/fuzz.sh $(FUZZ_SECONDS)

clean:
	rm -rf build build-debug build-sanitize build-portable build-tsan build-fuzz
