/* test_error.c - the device's error message is never cut: one longer than the device's own store
 * is kept whole in memory from its allocator (freed by sgDestroyDevice), and only when that
 * allocation fails is it cut, still readable and still logged. Driven through sg_error, since no
 * public call has a message that long.
 */
#include "test_common.h"

#include <stdlib.h>
#include <string.h>

#include "core/device.h"

typedef struct counting {
    int allocs, frees;
    bool fail; /* every allocation fails */
} counting;

static void *count_alloc(size_t size, void *user) {
    counting *c = user;
    if (c->fail) return NULL;
    c->allocs++;
    return malloc(size);
}

static void count_free(void *p, void *user) {
    counting *c = user;
    c->frees++;
    free(p);
}

typedef struct logged {
    int count;
    size_t length; /* of the last message */
} logged;

static void log_cb(sgResult r, const char *message, void *user) {
    (void)r;
    logged *l = user;
    l->count++;
    l->length = strlen(message);
}

/* A path of `n` characters, as a message might name one. */
static char *long_path(size_t n) {
    char *p = malloc(n + 1);
    for (size_t i = 0; i < n; i++) p[i] = i % 16 == 0 ? '/' : (char)('a' + i % 26);
    p[n] = '\0';
    return p;
}

static void long_message_whole(void **state) {
    (void)state;
    counting c = {0};
    logged l = {0};
    sgDeviceDesc d = {.thread_count = 1,
                      .allocator = {count_alloc, count_free, &c},
                      .log = log_cb,
                      .log_user_data = &l};
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&d, &dev), SG_OK);
    assert_string_equal(sgGetLastError(dev), "");
    int before = c.allocs - c.frees;
    /* A short message takes no allocation. */
    assert_int_equal(sg_error(dev, SG_ERROR_INVALID_VALUE, "short %d", 1), SG_ERROR_INVALID_VALUE);
    assert_string_equal(sgGetLastError(dev), "short 1");
    assert_int_equal(c.allocs - c.frees, before);
    /* Longer than the device's store: whole, in one allocation kept for the next. */
    char *path = long_path(3000);
    sg_error(dev, SG_ERROR_INVALID_VALUE, "cannot use '%s': not found", path);
    const char *m = sgGetLastError(dev);
    assert_int_equal(strlen(m), 3000 + strlen("cannot use '': not found"));
    assert_non_null(strstr(m, path));
    assert_string_equal(m + strlen(m) - strlen("': not found"), "': not found");
    assert_int_equal(l.length, strlen(m));
    assert_int_equal(c.allocs - c.frees, before + 1);
    sg_error(dev, SG_ERROR_INVALID_VALUE, "again '%s'", path);
    assert_int_equal(c.allocs - c.frees, before + 1);
    assert_int_equal(strlen(sgGetLastError(dev)), 3000 + strlen("again ''"));
    /* Out of memory for an even longer one: cut, but there, logged, and no crash. */
    char *longer = long_path(5000);
    c.fail = true;
    sg_error(dev, SG_ERROR_INVALID_VALUE, "cannot use '%s'", longer);
    m = sgGetLastError(dev);
    assert_true(strlen(m) > 100 && strlen(m) < 5000);
    assert_memory_equal(m, "cannot use '/", 13);
    assert_int_equal(l.count, 4);
    c.fail = false;
    sgDestroyDevice(dev);
    assert_int_equal(c.allocs, c.frees);
    free(path);
    free(longer);
}

/* sgDraw's lighting message goes through sg_verror with its prefix. */
static void lighting_message_named(void **state) {
    (void)state;
    sgDevice *dev;
    assert_int_equal(sgCreateDevice(&(sgDeviceDesc){.thread_count = 1}, &dev), SG_OK);
    sgLighting li = {.light_count = 99};
    sgImage2D color, depth;
    assert_int_equal(
        sgCreateImage2D(dev,
                        &(sgImage2DDesc){.width = 4, .height = 4, .format = SG_FORMAT_RGBA8_UNORM},
                        &color),
        SG_OK);
    assert_int_equal(
        sgCreateImage2D(
            dev, &(sgImage2DDesc){.width = 4, .height = 4, .format = SG_FORMAT_D32_FLOAT}, &depth),
        SG_OK);
    sgPipelineStateObject pso;
    assert_int_equal(
        sgCreatePipelineStateObject(dev, &(sgPipelineDesc){.lighting = SG_LIGHTING_PHONG}, &pso),
        SG_OK);
    const float pos[12] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1};
    const float nrm[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    const uint32_t idx[3] = {0, 1, 2};
    sgGeom geom;
    assert_int_equal(sgCreateGeom(dev,
                                  &(sgGeomDesc){.vertex_count = 3,
                                                .index_count = 3,
                                                .positions = pos,
                                                .normals = nrm,
                                                .indices = idx},
                                  &geom),
                     SG_OK);
    sgPassDesc pass = {.color = color, .depth = depth};
    assert_int_equal(sgBeginRenderPass(dev, &pass), SG_OK);
    sgDrawParams p = {.lighting = &li};
    for (int i = 0; i < 16; i += 5) p.proj[i] = p.world_view[i] = 1;
    assert_int_equal(sgDraw(dev, pso, geom, &p), SG_ERROR_INVALID_COUNT);
    assert_string_equal(sgGetLastError(dev),
                        "sgDraw: params->lighting->light_count = 99 is outside 0..8");
    sgEndRenderPass(dev, &pass);
    sgDestroyDevice(dev);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(long_message_whole),
        cmocka_unit_test(lighting_message_named),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
