# Two entry points for a new user: `make demo` and `make test`. Both install what is missing.
BUILD_DIR ?= build
BUILD_TYPE ?= Release
JOBS ?= $(shell nproc)
DEMO_CONFIG ?= config-ini/exhibition_dynamic.ini
DEMO_OUT ?= out/demo
DEMO_PLANNER ?= daep
PREFIX ?= /usr/local

CMAKE_FLAGS = -DCMAKE_BUILD_TYPE=$(BUILD_TYPE)
ifneq ($(shell command -v ccache 2>/dev/null),)
CMAKE_FLAGS += -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
# Paths inside the tree hash as relative ones, so clones in other folders share the cache.
export CCACHE_BASEDIR := $(CURDIR)
endif

# Sanitizer + fuzz build: clang, ASan + UBSan on our code, libFuzzer coverage on the libraries.
SAN_BUILD_DIR ?= build-san
SAN_CXX ?= clang++-14
# SANITIZE=undefined (with another SAN_BUILD_DIR) fuzzes about 3 x faster, for long runs.
SANITIZE ?= address,undefined
SAN_CMAKE_FLAGS = -DCMAKE_BUILD_TYPE=RelWithDebInfo -DCMAKE_CXX_COMPILER=$(SAN_CXX) \
	-DDAEP_SANITIZE=$(SANITIZE) -DDAEP_FUZZ=ON
ifneq ($(shell command -v ccache 2>/dev/null),)
SAN_CMAKE_FLAGS += -DCMAKE_CXX_COMPILER_LAUNCHER=ccache
endif
# Exported for the test discovery during the build and for the apps the e2e tests start.
SAN_SYMBOLIZER = external_symbolizer_path=/usr/lib/llvm-14/bin/llvm-symbolizer
export ASAN_OPTIONS ?= halt_on_error=1:detect_leaks=1:$(SAN_SYMBOLIZER)
export UBSAN_OPTIONS ?= halt_on_error=1:print_stacktrace=1:$(SAN_SYMBOLIZER)
export LSAN_OPTIONS ?= suppressions=$(CURDIR)/tests/sanitizer/lsan.supp:print_suppressions=0
FUZZ_SECONDS ?= 60
FUZZ_RUNS ?= 1000000
FUZZ_SHORT_TARGETS ?= experiment_ini benchmark_config world_file gazebo_import eth_ucy rawlog

.PHONY: all deps configure build demo test bench install format clean
.PHONY: sanitize-build sanitize fuzz-short fuzz

all: build

deps:
	@./scripts/install-deps.sh

configure: deps
	@cmake -S . -B $(BUILD_DIR) $(CMAKE_FLAGS) > /dev/null

build: configure
	@cmake --build $(BUILD_DIR) -j $(JOBS)

demo: build
	$(BUILD_DIR)/apps/daep-explore/daep-explore $(DEMO_CONFIG) --set experiment.planner=$(DEMO_PLANNER) --out $(DEMO_OUT)

test: build
	cd $(BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The apps into PREFIX/bin, worlds, configs, experiments and datasets into PREFIX/share/daep.
install: build
	cmake --install $(BUILD_DIR) --prefix $(PREFIX)

bench: build
	$(BUILD_DIR)/tests/bench/daep-bench

sanitize-build: deps
	@cmake -S . -B $(SAN_BUILD_DIR) $(SAN_CMAKE_FLAGS) > /dev/null
	@cmake --build $(SAN_BUILD_DIR) -j $(JOBS)

# The whole suite under ASan + UBSan (the fuzz targets replay their corpora as tests, too).
sanitize: sanitize-build
	cd $(SAN_BUILD_DIR) && ctest --output-on-failure -j $(JOBS)

# The fuzz targets for FUZZ_SECONDS each (CI), or all for FUZZ_RUNS executions each (make fuzz).
fuzz-short: sanitize-build
	./scripts/fuzz.sh $(SAN_BUILD_DIR) -max_total_time=$(FUZZ_SECONDS) -- $(FUZZ_SHORT_TARGETS)

fuzz: sanitize-build
	./scripts/fuzz.sh $(SAN_BUILD_DIR) -runs=$(FUZZ_RUNS)

format:
	@find apps libs tests -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR) $(SAN_BUILD_DIR)
