# Thin wrapper: `make test` (deps, configure, build, ctest) and `make demo` (the main job).
BUILD_DIR ?= build
JOBS ?= 2
FUZZ_SECONDS ?= 60
ASAN_CTEST_ARGS ?=

.PHONY: deps build test test-slurm demo test-asan test-asan-quick fuzz format clean

deps:
	@scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS) -LE slurm

# rpvio-bench on a real single-node Slurm (scripts/start-slurm.sh installs and starts it; root).
test-slurm: build
	cd $(BUILD_DIR) && ctest --output-on-failure -L slurm

demo: build
	@scripts/demo.sh $(BUILD_DIR)

# ASan + UBSan tree; a UBSan report fails its test as an ASan one does. -O1 and line tables only
# (-g1: reports still name file and line) build 2.5x faster than -O2 -g.
ASAN_OPTIMIZATION = -O1 -g1 -DNDEBUG
ASAN_CONFIGURE = cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRPVIO_SANITIZE=ON \
	-DCMAKE_CXX_FLAGS_RELWITHDEBINFO="$(ASAN_OPTIMIZATION)" -DCMAKE_C_FLAGS_RELWITHDEBINFO="$(ASAN_OPTIMIZATION)"
ASAN_CTEST = cd build-asan && UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
	ctest --output-on-failure -j$(JOBS)

test-asan: deps
	$(ASAN_CONFIGURE)
	cmake --build build-asan -j$(JOBS)
	$(ASAN_CTEST) $(ASAN_CTEST_ARGS)

# What CI runs besides `make test`, area by area as its time allows (.ci/run): the tests of the
# input readers, front-end, planes map, IMU, factors, core, common and initializer under ASan +
# UBSan (the whole suite under sanitizers does not fit CI's time).
ASAN_QUICK_AREAS = rawlog_io rosbag_io frontend planes_map imu factors core common initialization
test-asan-quick: deps
	$(ASAN_CONFIGURE)
	cmake --build build-asan -j$(JOBS) --target $(addprefix test_,$(ASAN_QUICK_AREAS))
	$(ASAN_CTEST) -L '^($(subst $(eval) ,|,$(ASAN_QUICK_AREAS)))$$'

# libFuzzer targets of tests/fuzz (clang), FUZZ_SECONDS each, one after the other, in build-fuzz.
fuzz:
	@scripts/install-deps.sh clang libclang-rt-dev
	@scripts/fuzz.sh build-fuzz $(FUZZ_SECONDS) $(JOBS)

format:
	git ls-files '*.h' '*.cpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz
