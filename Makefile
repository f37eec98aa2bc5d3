# The two commands: `make demo` and `make test`. Both install missing Debian packages first.
BUILD ?= build
OUT ?= out
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test clean

all: build

deps:
	@sh tools/install-deps.sh

build: deps
	cmake -S . -B $(BUILD) -DCMAKE_BUILD_TYPE=Release
	cmake --build $(BUILD) -j $(JOBS)

# Renders the default scenes to $(OUT)/ and prints, per scene, the time per frame next to the
# error against its golden (lavapipe) image; heat maps go to $(OUT)/<scene>-heat.png.
demo: build
	$(BUILD)/apps/sgapi-render scenes/default.json -o $(OUT) --frames 5 --compare golden

test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)

clean:
	rm -rf $(BUILD) $(OUT)
