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

.PHONY: all deps configure build demo test bench install format clean

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

format:
	@find apps libs tests -name '*.cpp' -o -name '*.h' | xargs clang-format -i

clean:
	rm -rf $(BUILD_DIR)
