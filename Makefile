# Thin wrapper: `make test` (deps, configure, build, ctest) and `make demo` (the main job).
BUILD_DIR ?= build
JOBS ?= 2
FUZZ_SECONDS ?= 60
ASAN_CTEST_ARGS ?=

.PHONY: deps build test demo test-asan fuzz format clean

deps:
	@scripts/install-deps.sh

build: deps
	cmake -S . -B $(BUILD_DIR) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD_DIR) -j$(JOBS)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j$(JOBS)

demo: build
	@scripts/demo.sh $(BUILD_DIR)

test-asan: deps
	cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=RelWithDebInfo -DRPVIO_SANITIZE=ON
	cmake --build build-asan -j$(JOBS)
	cd build-asan && ctest --output-on-failure -j$(JOBS) $(ASAN_CTEST_ARGS)

# libFuzzer targets of tests/fuzz (clang), FUZZ_SECONDS each, one after the other, in build-fuzz.
fuzz:
	@scripts/install-deps.sh clang libclang-rt-dev
	@scripts/fuzz.sh build-fuzz $(FUZZ_SECONDS) $(JOBS)

format:
	find rawlog_io planes_map mrpt_modules apps tests -name '*.h' -o -name '*.cpp' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) build-asan build-fuzz
