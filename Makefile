# The two commands: `make demo` and `make test`. Both install missing Debian packages first.
BUILD ?= build
OUT ?= out
JOBS ?= $(shell nproc 2>/dev/null || echo 2)

.PHONY: all deps build demo test clean

all: build

deps:
	@sh tools/install-deps.sh

build: deps
	cmake -S . -B "$(BUILD)" -DCMAKE_BUILD_TYPE=Release
	cmake --build "$(BUILD)" -j $(JOBS)

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
	"$(BUILD)/apps/sgapi-render" $(SCENES) -o "$(OUT)" --frames 5 --compare golden \
		--thresholds golden/thresholds.csv --report "$(OUT)/report"
	"$(BUILD)/apps/sgapi-render" scenes/assets/dodecahedron.off -o "$(OUT)/models"
	"$(BUILD)/apps/sgapi-render" scenes/shadows.json --scene shadow_teapots -o "$(OUT)/turntable" \
		--turntable 60 --up 0 --video gif --video-width 360 --fps 20

# Every test (the allocation-failure injection and the API-sequence corpus among them); then the
# suite again, built with clang under ASan + UBSan in build-asan/ (without the live lavapipe
# checks, see tools/sanitize.sh); then the threaded programs under ThreadSanitizer in build-tsan/
# (tools/tsan.sh); then the default scenes under valgrind memcheck; then the AArch64 build under
# emulation (test-arm64, below) when its packages are installed. Any sanitizer or memcheck report
# fails.
test: build
	cd "$(BUILD)" && ctest --output-on-failure -j $(JOBS)
	sh tools/sanitize.sh build-asan $(JOBS)
	sh tools/tsan.sh build-tsan $(JOBS)
	sh tools/memcheck.sh "$(BUILD)"
	@if sh tools/test-arm64.sh --available; then sh tools/test-arm64.sh "$(BUILD)" build-arm64 $(JOBS); \
	else echo "test-arm64: skipped (no gcc-aarch64-linux-gnu or qemu-user-static)"; fi

# The AArch64 build (NEON) under emulation: cross-built with Debian's gcc-aarch64-linux-gnu into
# build-arm64/, its unit tests run under qemu-user, and every scene rendered with its scalar and
# NEON code compared byte for byte with this machine's images (tools/test-arm64.sh).
.PHONY: test-arm64
test-arm64: build
	sh tools/test-arm64.sh "$(BUILD)" build-arm64 $(JOBS)

clean:
	rm -rf "$(BUILD)" "$(OUT)" build-arm64

# Fuzzes the file loaders (OBJ, scene JSON, images) and sequences of API calls with libFuzzer in
# build-fuzz/ (clang, ASan + UBSan), FUZZ_SECONDS seconds per target; fails on any crash, found
# inputs go to build-fuzz/crashes/<target>/ (docs/fuzzing.md).
FUZZ_SECONDS ?= 60
.PHONY: fuzz
fuzz: deps
	FUZZ_SECONDS=$(FUZZ_SECONDS) JOBS=$(JOBS) sh tools/fuzz.sh
