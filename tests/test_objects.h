/* test_objects.h - the objects the API tests make over and over, each asserted to succeed. */
#ifndef SG_TEST_OBJECTS_H
#define SG_TEST_OBJECTS_H

#include "test_common.h"

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "sgapi/sgapi.h"

/** A w x h image of format f. */
static inline sgImage2D test_image(sgDevice *dev, int w, int h, sgFormat f) {
    sgImage2D img;
    assert_int_equal(
        sgCreateImage2D(dev, &(sgImage2DDesc){.width = w, .height = h, .format = f}, &img), SG_OK);
    return img;
}

/** A pipeline of desc d. */
static inline sgPipelineStateObject test_pso(sgDevice *dev, sgPipelineDesc d) {
    sgPipelineStateObject p;
    assert_int_equal(sgCreatePipelineStateObject(dev, &d, &p), SG_OK);
    return p;
}

/** Whether this CPU runs instruction set `simd` (a device of it can be made). */
static inline bool test_simd_runs(sgSimd simd) {
    sgDevice *probe;
    if (sgCreateDevice(&(sgDeviceDesc){.simd = simd}, &probe) != SG_OK) return false;
    sgDestroyDevice(probe);
    return true;
}

/** Renders `scene` into out (threads, instruction set; one_by_one: each primitive in a pass of
 *  its own that loads the last one's colour and depth, the plain order). */
typedef void (*test_order_render)(const void *scene, int threads, sgSimd simd, bool one_by_one,
                                  uint8_t *out);

/** Fails unless render(scene, ..., false) gives want (size bytes) at 1, 2 and 3 threads with
 *  every instruction set this CPU runs; got: size bytes to render into. */
static inline void test_same_in_one_pass(test_order_render render, const void *scene,
                                         const uint8_t *want, uint8_t *got, size_t size) {
    for (int simd = SG_SIMD_SCALAR; simd <= SG_SIMD_NEON; simd++) {
        if (!test_simd_runs((sgSimd)simd)) continue;
        for (int threads = 1; threads <= 3; threads++) {
            render(scene, threads, (sgSimd)simd, false, got);
            if (memcmp(want, got, size) != 0)
                fail_msg("simd %d, %d threads: differs from the one-by-one render", simd, threads);
        }
    }
}

#endif
