# Thin wrappers over CMake: `make demo`, `make test`, `make bench`.
BUILD ?= build
JOBS ?= $(shell nproc)
EXAMPLE ?= examples/room

.PHONY: deps build demo demo-gui test bench clean

deps:
	@bash scripts/install-deps.sh

$(BUILD)/build.ninja: CMakeLists.txt
	cmake -S . -B $(BUILD) -G Ninja -DCMAKE_BUILD_TYPE=Release

build: deps $(BUILD)/build.ninja
	cmake --build $(BUILD) -j $(JOBS)

demo: build
	@mkdir -p out/demo
	$(BUILD)/src/cli/relight analyze $(EXAMPLE)/scene.json -o out/demo/analysis
	$(BUILD)/src/cli/relight render $(EXAMPLE)/scene.json --rig $(EXAMPLE)/rigs/evening.json \
	    --analysis out/demo/analysis -o out/demo/evening.exr
	@echo "demo: re-lit image in out/demo/evening.exr and out/demo/evening.png;"
	@echo "      recovered albedo in out/demo/analysis/albedo.png"

# relight studio on the example room (analysed on first open, then cached in
# $(EXAMPLE)/scene.analysis/).
demo-gui: build
	$(BUILD)/src/gui/relight-studio $(EXAMPLE)/scene.json

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

bench: build
	$(BUILD)/bench/relight_bench

clean:
	rm -rf $(BUILD) out
