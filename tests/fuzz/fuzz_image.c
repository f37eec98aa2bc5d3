/* fuzz_image.c - libFuzzer target: image file bytes through sc_image_load_memory. */
#include "fuzz.h"
#include "../test_msg.h"

#include <limits.h>

#include "image_io.h"

int fuzz_image(const uint8_t *data, size_t size) {
    TEST_MSG(err);
    sc_image img;
    if (!sc_image_load_memory(data, size, &img, &err)) {
        FUZZ_CHECK(MSG(err)[0] != '\0');
        FUZZ_CHECK(!img.pixels && img.width == 0 && img.height == 0);
        return 0;
    }
    /* What image_io.h promises: width * height RGBA8 pixels. */
    FUZZ_CHECK(img.width > 0 && img.height > 0 && img.width <= INT_MAX / 4);
    fuzz_touch(img.pixels, (size_t)img.width * (size_t)img.height * 4);
    sc_image_free(&img);
    FUZZ_CHECK(!img.pixels);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_image(data, size);
}
#endif
