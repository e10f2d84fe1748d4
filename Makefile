# The two commands of the README: `make demo` and `make test`.
# Both install what they need (Debian packages, CGAL's sample data) and build.
BUILD_DIR ?= build
SANITIZE_DIR ?= build-sanitize
JOBS ?= $(shell nproc)
CMAKE_FLAGS ?=

.PHONY: all deps data configure build demo readme-figure test test-sanitize bench clean

all: build

deps:
	@scripts/install-deps

data: deps
	@scripts/fetch-data

# Warnings are errors here (Debian 12's GCC is the reference compiler); a plain
# `cmake -B build` leaves them warnings for other compilers.
configure: deps
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHARPMESH_STRICT_WARNINGS=ON $(CMAKE_FLAGS) >/dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build data
	@scripts/demo $(BUILD_DIR)/apps/sharpmesh/sharpmesh

# The README's picture: the demo's reconstruction of fandisk with its feature lines.
readme-figure: demo
	@cp demo-output/fandisk.png docs/fandisk.png && echo "docs/fandisk.png updated"

test: build data
	@ctest --test-dir $(BUILD_DIR) --output-on-failure -j $(JOBS)

# ASan and UBSan over the library's unit tests (but those on 30,000 points or
# more: label `large`) and the adversarial inputs; only the two executables
# those need, not the Python module, viewer or examples.
test-sanitize: data
	@scripts/install-deps --sanitize
	@cmake -S . -B $(SANITIZE_DIR) -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSHARPMESH_SANITIZE=ON >/dev/null
	@cmake --build $(SANITIZE_DIR) -j $(JOBS) --target sharpmesh_tests sharpmesh_cli
	@ASAN_OPTIONS=detect_leaks=1 ctest --test-dir $(SANITIZE_DIR) --output-on-failure -j $(JOBS) -L "unit|adversarial" -LE slow

bench: data
	@scripts/install-deps --bench
	@cmake -S . -B $(BUILD_DIR) -G Ninja -DCMAKE_BUILD_TYPE=Release -DSHARPMESH_BUILD_BENCH=ON >/dev/null
	@cmake --build $(BUILD_DIR) -j $(JOBS)
	@bench/run $(BUILD_DIR)
	@bench/corpus $(BUILD_DIR)
	@bench/accuracy_vs_size $(BUILD_DIR)
	@bench/compactness $(BUILD_DIR)
	@bench/fig714 $(BUILD_DIR)
	@bench/sampling_seeds $(BUILD_DIR)
	@bench/scans $(BUILD_DIR)
	@bench/corpus_generated $(BUILD_DIR)
	@bench/city/run $(BUILD_DIR)
	@bench/colmap_baseline $(BUILD_DIR)
	@bench/laz $(BUILD_DIR)
	@bench/stereo_study $(BUILD_DIR)
	@bench/ci_time

clean:
	rm -rf $(BUILD_DIR) $(SANITIZE_DIR)
