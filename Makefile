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

# The project's scene files: the eight default scenes, then one file per feature.
SCENES = scenes/default.json scenes/transparency.json scenes/lighting.json scenes/shadows.json \
	scenes/lines.json scenes/shapes.json

# Renders the project's scenes to $(OUT)/ and prints, per scene, the time per frame next to the
# error against its golden (lavapipe) image, held to the targets of golden/thresholds.csv; heat
# maps go to $(OUT)/<scene>-heat.png, a report to $(OUT)/report/index.html. Then a
# turntable of three teapots, about their floor's up, as $(OUT)/turntable/shadow_teapots.gif (the
# README's; its frames beside it). The standard shapes and a face-coloured OFF model are among
# the scenes (scenes/shapes.json); last, that OFF file rendered as a model on its own, framed and
# lit by default, as $(OUT)/models/dodecahedron.png.
demo: build
	$(BUILD)/apps/sgapi-render $(SCENES) -o $(OUT) --frames 5 --compare golden \
		--thresholds golden/thresholds.csv --report $(OUT)/report
	$(BUILD)/apps/sgapi-render scenes/assets/dodecahedron.off -o $(OUT)/models
	$(BUILD)/apps/sgapi-render scenes/shadows.json --scene shadow_teapots -o $(OUT)/turntable \
		--turntable 60 --up 0 --video gif --video-width 360 --fps 20

# Every test; then the suite again, built with clang under ASan + UBSan in build-asan/ (without the
# live lavapipe checks, see tools/sanitize.sh); then the default scenes under valgrind memcheck.
# Any sanitizer or memcheck report fails.
test: build
	cd $(BUILD) && ctest --output-on-failure -j $(JOBS)
	sh tools/sanitize.sh build-asan $(JOBS)
	sh tools/memcheck.sh $(BUILD)

clean:
	rm -rf $(BUILD) $(OUT)

# Fuzzes the file loaders (OBJ, scene JSON, images) with libFuzzer in build-fuzz/ (clang, ASan +
# UBSan), FUZZ_SECONDS seconds per target; fails on any crash, found inputs go to
# build-fuzz/crashes/<target>/ (docs/fuzzing.md).
FUZZ_SECONDS ?= 60
.PHONY: fuzz
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) JOBS=$(JOBS) sh tools/fuzz.sh
