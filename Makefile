# terrasprite: set-up, build, demo and tests.  `make demo` and `make test` are
# the two commands a fresh Debian machine needs; both install what is missing.
SHELL := /bin/bash
BUILD ?= build
JOBS ?= $(shell nproc)

# Debian packages the build, the tests and the reports need.  llvmpipe
# (libegl-mesa0, libgl1-mesa-dri) is only a Recommends elsewhere, so it is named.
PACKAGES := build-essential cmake pkg-config git \
  libegl-dev libgl-dev libegl-mesa0 libgl1-mesa-dri libepoxy-dev libglm-dev \
  libgdal-dev libstb-dev libtbb-dev libcli11-dev nlohmann-json3-dev libfmt-dev \
  libgtest-dev libgmock-dev libbenchmark-dev gnuplot-nox ffmpeg python3 python3-skimage \
  libmeshoptimizer-dev libtinyobjloader-dev libtinygltf-dev libglfw3-dev libimgui-dev \
  xvfb xauth clang-14 libclang-rt-14-dev libzstd-dev zlib1g-dev ninja-build

.PHONY: all deps build build-all build-tests demo test test-asan consumer fuzz fuzz-seeds fuzz-run clean

all: build

deps:
	@missing=$$(for p in $(PACKAGES); do dpkg-query -W -f='$${Status}\n' $$p 2>/dev/null | grep -q '^install ok installed' || echo $$p; done); \
	if [ -z "$$missing" ]; then echo "deps: all packages present"; exit 0; fi; \
	line="apt-get install -y --no-install-recommends $$(echo $$missing)"; \
	if [ "$$(id -u)" != 0 ]; then echo "deps: missing packages; run as root: $$line"; exit 1; fi; \
	export DEBIAN_FRONTEND=noninteractive; \
	echo "deps: $$line"; \
	$$line || { apt-get update && $$line; }

# Ninja when it is installed (deps installs it): it keeps both cores busy
# across the module libraries; a build folder keeps the generator it was made with.
GENERATOR = $$(command -v ninja >/dev/null && echo -G Ninja)

$(BUILD)/CMakeCache.txt:
	cmake -S . -B $(BUILD) $(GENERATOR) -DCMAKE_BUILD_TYPE=Release

# The demo needs only the CLI: build just that target on a fresh machine.
build: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) --target terrasprite_cli -j $(JOBS)

build-all: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) -j $(JOBS)

# What ctest runs (the CLI, the test executables, the fuzz corpora replays):
# all targets but the micro-benchmarks.
build-tests: deps $(BUILD)/CMakeCache.txt
	cmake --build $(BUILD) --target ts_tests -j $(JOBS)

demo: build
	$(BUILD)/terrasprite demo --out out/demo

test: build-tests
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	$(MAKE) consumer

# The installed package must stay usable from another project: the whole
# library, and the quality module alone with no GL, EGL, epoxy or GDAL in its
# binary's NEEDED entries.
consumer: build-tests
	rm -rf $(BUILD)/_install $(BUILD)/_consumer $(BUILD)/_consumer_quality
	cmake --install $(BUILD) --prefix $(BUILD)/_install >/dev/null
	cmake -S tests/consumer -B $(BUILD)/_consumer -DCMAKE_PREFIX_PATH=$(CURDIR)/$(BUILD)/_install >/dev/null
	cmake --build $(BUILD)/_consumer -j $(JOBS) >/dev/null
	$(BUILD)/_consumer/consumer
	cmake -S tests/consumer_quality -B $(BUILD)/_consumer_quality -DCMAKE_PREFIX_PATH=$(CURDIR)/$(BUILD)/_install >/dev/null
	cmake --build $(BUILD)/_consumer_quality -j $(JOBS) >/dev/null
	$(BUILD)/_consumer_quality/quality_consumer
	@if readelf -d $(BUILD)/_consumer_quality/quality_consumer | grep -E 'NEEDED.*(libEGL|libGL|libepoxy|libgdal)'; then \
	  echo "consumer: the quality-only binary depends on GL/EGL/GDAL"; exit 1; \
	else echo "consumer: quality-only binary has no GL/EGL/epoxy/GDAL dependency"; fi

# The suite under ASan + UBSan (CI runs it after `test`). Tests whose ctest
# label matches ASAN_SKIP are left out: too slow instrumented for CI's budget
# (docs/testing.md). Leak checking is off: Mesa's llvmpipe and GDAL keep
# process-lifetime allocations.
ASAN_SKIP ?=
test-asan: deps
	cmake -S . -B build-asan $(if $(wildcard build-asan/CMakeCache.txt),,$(GENERATOR)) -DCMAKE_BUILD_TYPE=ASan -DTERRASPRITE_UNITY=OFF -DCMAKE_CXX_FLAGS_ASAN='-O1 -g1' \
	  -DCMAKE_C_FLAGS_ASAN='-O1 -g1' -DTERRASPRITE_SANITIZE=ON -DTERRASPRITE_BUILD_BENCH=OFF
	cmake --build build-asan -j $(JOBS)
	cd build-asan && ASAN_OPTIONS=detect_leaks=0 UBSAN_OPTIONS=print_stacktrace=1 \
	  ctest --output-on-failure -j $(JOBS) $(if $(ASAN_SKIP),-LE '$(ASAN_SKIP)')

# libFuzzer targets (clang-14, ASan + UBSan), not part of CI: `make fuzz` builds
# them into build-fuzz/fuzz/; `make fuzz-run FUZZ_SECONDS=600` runs each from the
# committed corpus plus fresh seeds (fuzz-seeds: crops of ../shared/data) and
# merges what it finds into a scratch corpus (build-fuzz/corpus/<target>/);
# minimise and commit it by hand (see fuzz/README.md).
FUZZ_SECONDS ?= 600
FUZZ_TARGETS := dem png16 path obj gltf cache scene script tiles
fuzz: deps
	cmake -S . -B build-fuzz -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_C_COMPILER=clang-14 \
	  -DCMAKE_CXX_COMPILER=clang++-14 -DTERRASPRITE_FUZZ=ON -DTERRASPRITE_BUILD_TESTS=OFF \
	  -DTERRASPRITE_BUILD_BENCH=OFF
	cmake --build build-fuzz -j $(JOBS) --target $(addprefix fuzz_,$(FUZZ_TARGETS))

fuzz-seeds: deps
	mkdir -p build-fuzz
	$(CXX) -std=c++20 -O1 $$(pkg-config --cflags gdal 2>/dev/null || echo -I/usr/include/gdal) \
	  fuzz/make_seeds.cpp -lgdal -o build-fuzz/make_seeds
	rm -rf build-fuzz/seeds && build-fuzz/make_seeds ../shared/data build-fuzz/seeds

fuzz-run: fuzz fuzz-seeds
	for t in $(FUZZ_TARGETS); do \
	  mkdir -p build-fuzz/corpus/$$t build-fuzz/artifacts/$$t; \
	  build-fuzz/fuzz/fuzz_$$t build-fuzz/corpus/$$t fuzz/corpus/$$t build-fuzz/seeds/$$t \
	    -max_total_time=$(FUZZ_SECONDS) -max_len=65536 -rss_limit_mb=4096 -timeout=20 \
	    -artifact_prefix=build-fuzz/artifacts/$$t/ -print_final_stats=1 2>&1 | tail -20; \
	done

clean:
	rm -rf $(BUILD) build-asan build-fuzz out
