/* device.c - device creation, allocation, error reporting. */
#define _POSIX_C_SOURCE 200809L
#include "core/device.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <stdint.h>
#include <unistd.h>

/* Names of the instruction sets, for messages. */
static const char *const isa_names[SG_ISA_COUNT] = {"scalar", "SSE2", "AVX2", "AVX-512", "NEON"};
/* An sgSimd past DEFAULT is an sg_isa offset by SG_SIMD_SCALAR. */
_Static_assert(SG_SIMD_AVX512 - SG_SIMD_SCALAR == SG_ISA_AVX512, "sgSimd and sg_isa out of step");
_Static_assert(SG_SIMD_NEON - SG_SIMD_SCALAR == SG_ISA_NEON, "sgSimd and sg_isa out of step");

/* The Gouraud lighting of vertices in the device's instruction set, as sg_shade_phong_select
 * picks the per-pixel one: AVX-512, else AVX2, else scalar; NEON, else scalar. */
static sg_vertex_lit_fn vertex_gouraud_select(sg_isa isa) {
    if (isa == SG_ISA_NEON) return sg_vertex_gouraud_neon();
    sg_vertex_lit_fn fn = isa >= SG_ISA_AVX512 ? sg_vertex_gouraud_avx512() : NULL;
    return fn || isa < SG_ISA_AVX2 ? fn : sg_vertex_gouraud_avx2();
}

static void *default_alloc(size_t size, void *user) {
    (void)user;
    return malloc(size);
}

static void default_free(void *ptr, void *user) {
    (void)user;
    free(ptr);
}

static void *default_resize(void *ptr, size_t size, void *user) {
    (void)user;
    return realloc(ptr, size);
}

void *sg_alloc(sgDevice *dev, size_t size) {
    return size ? dev->allocator.alloc(size, dev->allocator.user_data) : NULL;
}

void sg_free(sgDevice *dev, void *ptr) {
    if (ptr) dev->allocator.free(ptr, dev->allocator.user_data);
}

sgResult sg_verror(sgDevice *dev, sgResult result, const char *prefix, const char *fmt,
                   va_list ap) {
    va_list measure;
    va_copy(measure, ap);
    int n = vsnprintf(NULL, 0, fmt, measure);
    va_end(measure);
    size_t plen = strlen(prefix);
    size_t need = plen + (n > 0 ? (size_t)n : 0) + 1;
    char *to = dev->error_short;
    size_t size = sizeof dev->error_short;
    if (need > size) {
        /* Grown only, so a long message allocates once. sgCreateDevice's stand-in device has no
         * allocator: its messages hold numbers and names alone and fit error_short. */
        if (need > dev->error_long_size && dev->allocator.alloc) {
            char *grown = sg_alloc(dev, need);
            if (grown) {
                sg_free(dev, dev->error_long);
                dev->error_long = grown;
                dev->error_long_size = need;
            }
        }
        if (need <= dev->error_long_size) {
            to = dev->error_long;
            size = dev->error_long_size;
        }
    }
    size_t at = plen < size ? plen : size - 1;
    memcpy(to, prefix, at);
    to[at] = '\0';
    vsnprintf(to + at, size - at, fmt, ap);
    dev->error = to;
    if (dev->log) dev->log(result, to, dev->log_user_data);
    return result;
}

sgResult sg_error(sgDevice *dev, sgResult result, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    sg_verror(dev, result, "", fmt, ap);
    va_end(ap);
    return result;
}

const char *sgResultName(sgResult result) {
    static const char *const names[SG_RESULT_COUNT] = {
        "SG_OK",
        "SG_ERROR_NULL_POINTER",
        "SG_ERROR_INVALID_ENUM",
        "SG_ERROR_INVALID_HANDLE",
        "SG_ERROR_INVALID_VALUE",
        "SG_ERROR_INVALID_SIZE",
        "SG_ERROR_INVALID_COUNT",
        "SG_ERROR_INDEX_OUT_OF_RANGE",
        "SG_ERROR_NOT_IN_PASS",
        "SG_ERROR_ALREADY_IN_PASS",
        "SG_ERROR_PASS_MISMATCH",
        "SG_ERROR_FORMAT_MISMATCH",
        "SG_ERROR_NOT_SAMPLEABLE",
        "SG_ERROR_MISSING_ATTRIBUTE",
        "SG_ERROR_MISSING_TEXTURE",
        "SG_ERROR_MISSING_DEPTH",
        "SG_ERROR_IN_USE",
        "SG_ERROR_UNSUPPORTED",
        "SG_ERROR_POOL_EXHAUSTED",
        "SG_ERROR_OUT_OF_MEMORY",
    };
    if ((int)result < 0 || result >= SG_RESULT_COUNT) return "SG_ERROR_UNKNOWN";
    return names[result];
}

const char *sgGetLastError(const sgDevice *device) {
    if (!device) return "no device (the device pointer is NULL)";
    return device->error ? device->error : "";
}

/* Pool arrays are carved from one block per pool: generations, live flags, free stack, objects. */
static void *pool_create(sgDevice *dev, sg_pool *pool, int capacity, uint32_t kind,
                         size_t object_size) {
    size_t n = (size_t)capacity;
    size_t objects = n * object_size;
    size_t gens = (n * sizeof(uint16_t) + 15) & ~(size_t)15;
    size_t live = (n * sizeof(bool) + 15) & ~(size_t)15;
    size_t freel = (n * sizeof(int) + 15) & ~(size_t)15;
    uint8_t *block = sg_alloc(dev, objects + gens + live + freel);
    if (!block) return NULL;
    memset(block, 0, objects);
    /* The device's address seeds its generations, so ids of two live devices rarely coincide. */
    uint32_t seed = (uint32_t)(((uintptr_t)dev >> 4) * 2654435761u >> 8);
    sg_pool_init(pool, capacity, kind, seed, (uint16_t *)(void *)(block + objects),
                 (bool *)(void *)(block + objects + gens),
                 (int *)(void *)(block + objects + gens + live));
    return block;
}

static int pool_size(int requested, int fallback) {
    return requested ? requested : fallback;
}

sgResult sgCreateDevice(const sgDeviceDesc *desc, sgDevice **out_device) {
    sgDeviceDesc d;
    memset(&d, 0, sizeof d);
    if (desc) d = *desc;
    /* No device exists yet to hold a message, so failures here go to the log callback only. */
    sgDevice tmp;
    memset(&tmp, 0, sizeof tmp);
    tmp.log = d.log;
    tmp.log_user_data = d.log_user_data;
    if (!out_device)
        return sg_error(&tmp, SG_ERROR_NULL_POINTER, "sgCreateDevice: out_device is NULL");
    *out_device = NULL;
    if (!d.allocator.alloc != !d.allocator.free)
        return sg_error(&tmp, SG_ERROR_NULL_POINTER,
                        "sgCreateDevice: allocator.alloc and allocator.free must be set together");
    int ip = pool_size(d.image_pool_size, 256), gp = pool_size(d.geom_pool_size, 1024),
        pp = pool_size(d.pipeline_pool_size, 64);
    if (ip < 1 || ip > SG_POOL_MAX_SLOTS || gp < 1 || gp > SG_POOL_MAX_SLOTS || pp < 1 ||
        pp > SG_POOL_MAX_SLOTS)
        return sg_error(&tmp, SG_ERROR_INVALID_COUNT,
                        "sgCreateDevice: pool sizes must be 0 (default) or 1..%d, got %d/%d/%d",
                        SG_POOL_MAX_SLOTS, d.image_pool_size, d.geom_pool_size,
                        d.pipeline_pool_size);
    if (d.thread_count < 0)
        return sg_error(&tmp, SG_ERROR_INVALID_COUNT,
                        "sgCreateDevice: thread_count must be >= 0 (0: all cores), got %d",
                        d.thread_count);
    if ((int)d.simd < SG_SIMD_DEFAULT || d.simd > SG_SIMD_NEON)
        return sg_error(&tmp, SG_ERROR_INVALID_ENUM, "sgCreateDevice: simd %d is not an sgSimd",
                        (int)d.simd);
    /* One triangle, its extension and a bin-list entry: the least a flush can make progress with.
     */
    const size_t min_limit = sizeof(sg_tri) + sizeof(sg_tri_ext) + sizeof(uint32_t);
    if (d.bin_memory_limit && d.bin_memory_limit < min_limit)
        return sg_error(&tmp, SG_ERROR_INVALID_VALUE,
                        "sgCreateDevice: bin_memory_limit = %zu bytes is less than one triangle's "
                        "records; it must be 0 (default, %zu) or at least %zu",
                        d.bin_memory_limit, SG_DEFAULT_BIN_MEMORY_LIMIT, min_limit);
    sg_isa best = sg_isa_detect();
    sg_isa isa = d.simd == SG_SIMD_DEFAULT ? best : (sg_isa)(d.simd - SG_SIMD_SCALAR);
    if (!sg_isa_runs(isa))
        return sg_error(&tmp, SG_ERROR_UNSUPPORTED,
                        "sgCreateDevice: simd %s is not supported by this CPU (the best it runs "
                        "is %s)",
                        isa_names[isa], isa_names[best]);
    sgAllocator a = d.allocator;
    if (!a.alloc) {
        a.alloc = default_alloc;
        a.free = default_free;
    }
    sgDevice *dev = a.alloc(sizeof *dev, a.user_data);
    if (!dev) return sg_error(&tmp, SG_ERROR_OUT_OF_MEMORY, "sgCreateDevice: out of memory");
    memset(dev, 0, sizeof *dev);
    dev->allocator = a;
    dev->log = d.log;
    dev->log_user_data = d.log_user_data;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    dev->thread_count = d.thread_count ? d.thread_count : (cores > 0 ? (int)cores : 1);
    dev->isa = isa;
    dev->texel_window = sg_texel_window_detect();
    dev->vertex_gouraud = vertex_gouraud_select(isa);
    dev->images = pool_create(dev, &dev->image_pool, ip, 1, sizeof(sg_image));
    dev->geoms = pool_create(dev, &dev->geom_pool, gp, 2, sizeof(sg_geom));
    dev->psos = pool_create(dev, &dev->pso_pool, pp, 3, sizeof(sg_pso));
    if (!dev->images || !dev->geoms || !dev->psos) {
        sgDestroyDevice(dev);
        return sg_error(&tmp, SG_ERROR_OUT_OF_MEMORY, "sgCreateDevice: out of memory for pools");
    }
    dev->binner.alloc = dev->allocator.alloc;
    dev->binner.free = dev->allocator.free;
    /* A user's allocator has no resize: its storage grows by copying (and flushing, draw.c). */
    dev->binner.resize = dev->allocator.alloc == default_alloc ? default_resize : NULL;
    dev->binner.user = dev->allocator.user_data;
    dev->bin_memory_limit = d.bin_memory_limit ? d.bin_memory_limit : SG_DEFAULT_BIN_MEMORY_LIMIT;
    dev->binner.memory_limit = dev->bin_memory_limit;
    if (dev->thread_count > 1) {
        dev->threads = sg_alloc(dev, (size_t)(dev->thread_count - 1) * sizeof *dev->threads);
        if (!dev->threads) {
            int threads = dev->thread_count; /* read before the device is gone */
            sgDestroyDevice(dev);
            return sg_error(&tmp, SG_ERROR_OUT_OF_MEMORY,
                            "sgCreateDevice: out of memory for %d threads", threads);
        }
    }
    dev->workers_started = sg_workers_start(&dev->workers, dev->thread_count, dev->threads);
    if (!dev->workers_started) {
        sgDestroyDevice(dev);
        return sg_error(&tmp, SG_ERROR_OUT_OF_MEMORY, "sgCreateDevice: cannot start threads");
    }
    *out_device = dev;
    return SG_OK;
}

void sgDestroyDevice(sgDevice *dev) {
    if (!dev) return;
#if defined(SG_STAGE_TIMES)
    static const char *const stages[SG_STAGE_COUNT] = {"front-end", "bin-start", "visibility",
                                                       "shading", "bin-write"};
    sg_stage_print(&dev->stage_times, stages, SG_STAGE_COUNT);
#endif
    if (dev->workers_started) sg_workers_stop(&dev->workers);
    sg_free(dev, dev->threads);
    sg_binner_release(&dev->binner);
    sg_free(dev, dev->draws);
    sg_free(dev, dev->bin_order);
    sg_free(dev, dev->fe_counts);
    sg_free(dev, dev->fe_ranges);
    sg_free(dev, dev->flush_depth);
    sg_free(dev, dev->msaa_color);
    sg_free(dev, dev->msaa_depth);
    sg_free(dev, dev->sort_scratch);
    sg_free(dev, dev->uniforms);
    sg_free(dev, dev->lit);
    if (dev->images)
        for (int i = 0; i < dev->image_pool.capacity; i++)
            if (dev->image_pool.live[i]) sg_image_release(dev, &dev->images[i]);
    if (dev->geoms)
        for (int i = 0; i < dev->geom_pool.capacity; i++)
            if (dev->geom_pool.live[i]) sg_geom_release(dev, &dev->geoms[i]);
    sg_free(dev, dev->images);
    sg_free(dev, dev->geoms);
    sg_free(dev, dev->psos);
    sg_free(dev, dev->clip);
    sg_free(dev, dev->outcodes);
    sg_free(dev, dev->screen);
    sg_free(dev, dev->screen_ok);
    sg_free(dev, dev->error_long);
    dev->allocator.free(dev, dev->allocator.user_data);
}

uint32_t sg_acquire(sgDevice *dev, sg_pool *pool, const char *fn, const char *desc_field) {
    uint32_t id = sg_pool_acquire(pool);
    if (!id)
        sg_error(dev, SG_ERROR_POOL_EXHAUSTED, "%s: all %d slots are in use (sgDeviceDesc.%s)", fn,
                 pool->capacity, desc_field);
    return id;
}

sg_image *sg_lookup_image(sgDevice *dev, sgImage2D h) {
    int slot = sg_pool_lookup(&dev->image_pool, h.id);
    return slot < 0 ? NULL : &dev->images[slot];
}

sg_geom *sg_lookup_geom(sgDevice *dev, sgGeom h) {
    int slot = sg_pool_lookup(&dev->geom_pool, h.id);
    return slot < 0 ? NULL : &dev->geoms[slot];
}

sg_pso *sg_lookup_pso(sgDevice *dev, sgPipelineStateObject h) {
    int slot = sg_pool_lookup(&dev->pso_pool, h.id);
    return slot < 0 ? NULL : &dev->psos[slot];
}
