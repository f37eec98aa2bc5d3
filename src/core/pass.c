/* pass.c - render passes: Begin checks the targets and empties the screen bins, the draws fill
 * the bins, and End renders every bin into the targets on the device's threads (rast_bin.c). */
#include "core/device.h"

#include <math.h>
#include <stdlib.h>
#include <stdint.h>
#include <string.h>

#include "raster/rast_msaa.h"
#include "raster/shade.h"

/* Where a pass's binned work starts (sgBeginRenderPass): bytes a target pixel, and the least. */
enum { BIN_START_PER_PIXEL = 32 };
#define BIN_START_MIN ((size_t)32 << 20)

static bool unit_range(float v) {
    return v >= 0.0f && v <= 1.0f;
} /* false for NaN */

/* The jobs of sgEndRenderPass: first one run of the empty bins per thread, each a band of the
 * image that the same thread tends to write every frame (they are taken in order, and the
 * calling thread starts at once), so its cache lines do not move between cores; then the other
 * bins one at a time, busiest first. */
typedef struct bin_jobs {
    const sg_bin_pass *pass;
    const uint64_t *order; /* busy bins first (see busiest_first), then the empty ones */
    int busy, empty, runs;
} bin_jobs;

static void render_bin(void *vjobs, int job) {
    const bin_jobs *j = vjobs;
    if (job < j->runs) {
        int first = j->busy + (int)((int64_t)j->empty * job / j->runs);
        int end = j->busy + (int)((int64_t)j->empty * (job + 1) / j->runs);
        for (int i = first; i < end; i++) sg_rast_bin(j->pass, (int)(j->order[i] & 0xffffffffu));
        return;
    }
    sg_rast_bin(j->pass, (int)(j->order[job - j->runs] & 0xffffffffu));
}

static int cmp_u64(const void *a, const void *b) {
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return (x > y) - (x < y);
}

/* Bins with more triangles first (ties by index, so the order is always the same): the threads
 * start on the long jobs and end on the short ones, instead of one thread being left with a busy
 * bin at the end. Which thread renders a bin never changes its pixels. */
static void busiest_first(const sg_binner *b, uint64_t *order) {
    int n = b->bins_x * b->bins_y;
    for (int i = 0; i < n; i++)
        order[i] = (uint64_t)(UINT32_MAX - b->bins[i].count) << 32 | (uint64_t)i;
    qsort(order, (size_t)n, sizeof *order, cmp_u64);
}

sgResult sgBeginRenderPass(sgDevice *dev, const sgPassDesc *pass) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!pass) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgBeginRenderPass: pass is NULL");
    if (dev->in_pass)
        return sg_error(dev, SG_ERROR_ALREADY_IN_PASS,
                        "sgBeginRenderPass: a render pass is already open; end it first");
    /* No colour target: a depth-only pass (shadow maps), sized by its depth target. */
    sg_image *color = NULL;
    if (pass->color.id) {
        color = sg_lookup_image(dev, pass->color);
        if (!color)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgBeginRenderPass: color target id 0x%08x is not a live image",
                            pass->color.id);
        if (color->format != SG_FORMAT_RGBA8_UNORM)
            return sg_error(dev, SG_ERROR_FORMAT_MISMATCH,
                            "sgBeginRenderPass: the color target must be RGBA8_UNORM");
    } else if (!pass->depth.id) {
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgBeginRenderPass: the pass has no target (color and depth are both 0)");
    }
    sg_image *depth = NULL;
    if (pass->depth.id) {
        depth = sg_lookup_image(dev, pass->depth);
        if (!depth)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgBeginRenderPass: depth target id 0x%08x is not a live image",
                            pass->depth.id);
        if (depth->format != SG_FORMAT_D32_FLOAT)
            return sg_error(dev, SG_ERROR_FORMAT_MISMATCH,
                            "sgBeginRenderPass: the depth target must be D32_FLOAT");
        if (color && (depth->width != color->width || depth->height != color->height))
            return sg_error(dev, SG_ERROR_INVALID_SIZE,
                            "sgBeginRenderPass: depth target is %dx%d but color target is %dx%d",
                            depth->width, depth->height, color->width, color->height);
    }
    const sg_image *size = color ? color : depth;
    if (pass->samples != 0 && pass->samples != 1 && pass->samples != 4)
        return sg_error(
            dev, SG_ERROR_INVALID_VALUE,
            "sgBeginRenderPass: samples = %d; a pass takes 1 (or 0) or 4 samples a pixel",
            pass->samples);
    if ((int)pass->depth_store < SG_STORE_DEFAULT || pass->depth_store > SG_STORE_DONT_CARE)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgBeginRenderPass: depth_store %d is not an sgStoreOp",
                        (int)pass->depth_store);
    if ((int)pass->color_load < SG_LOAD_DEFAULT || pass->color_load > SG_LOAD_LOAD ||
        (int)pass->depth_load < SG_LOAD_DEFAULT || pass->depth_load > SG_LOAD_LOAD)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgBeginRenderPass: color_load %d / depth_load %d is not an sgLoadOp",
                        (int)pass->color_load, (int)pass->depth_load);
    for (int k = 0; k < 4 && color && pass->color_load != SG_LOAD_LOAD; k++)
        if (!unit_range(pass->clear_color[k]))
            return sg_error(dev, SG_ERROR_INVALID_VALUE,
                            "sgBeginRenderPass: clear_color[%d] = %g is outside [0, 1]", k,
                            (double)pass->clear_color[k]);
    if (depth && pass->depth_load == SG_LOAD_CLEAR && !unit_range(pass->clear_depth))
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgBeginRenderPass: clear_depth = %g is outside [0, 1]",
                        (double)pass->clear_depth);

    if (!sg_binner_reset(&dev->binner, size->width, size->height))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgBeginRenderPass: out of memory for the screen bins of a %dx%d target",
                        size->width, size->height);
    int nbins = dev->binner.bins_x * dev->binner.bins_y;
    if (nbins > dev->bin_order_capacity) {
        uint64_t *order = sg_alloc(dev, (size_t)nbins * sizeof *order);
        if (!order)
            return sg_error(
                dev, SG_ERROR_OUT_OF_MEMORY,
                "sgBeginRenderPass: out of memory for the screen bins of a %dx%d target",
                size->width, size->height);
        sg_free(dev, dev->bin_order);
        dev->bin_order = order;
        dev->bin_order_capacity = nbins;
    }
    const float *c = pass->clear_color;
    sg_bin_pass *p = &dev->pass;
    memset(p, 0, sizeof *p);
    p->binner = &dev->binner;
    p->draws = dev->draws;
    p->width = size->width;
    p->height = size->height;
    p->color = color ? color->data : NULL;
    p->depth = depth ? (float *)(void *)depth->data : NULL;
    p->load_color = pass->color_load == SG_LOAD_LOAD;
    p->load_depth = pass->depth_load == SG_LOAD_LOAD;
    p->clear_color = sg_pack_rgba8(sg_to_unorm8(c[0]), sg_to_unorm8(c[1]), sg_to_unorm8(c[2]),
                                   sg_to_unorm8(c[3]));
    p->clear_depth = pass->depth_load == SG_LOAD_CLEAR ? pass->clear_depth : 1.0f;
    p->store_depth = pass->depth_store != SG_STORE_DONT_CARE;
    p->samples = pass->samples == 4 ? 4 : 1;
    if (color && color->cleared) { /* the bins known to hold this pass's clear already */
        if (!p->load_color && color->cleared_value != p->clear_color) {
            memset(color->cleared, 0, sg_image_bins(color->width, color->height));
            color->cleared_value = p->clear_color;
        }
        p->cleared = color->cleared;
    }
    p->fb = dev->isa == SG_ISA_AVX512 ? &sg_fb_ops_avx512
            : dev->isa == SG_ISA_AVX2 ? &sg_fb_ops_avx2
                                      : &sg_fb_ops_portable;
#if defined(SG_STAGE_TIMES)
    p->stage_times = &dev->stage_times;
    dev->stage_times.passes++;
#endif
    dev->draw_count = 0;
    dev->uniforms_used = 0;
    dev->shader_discards = 0;
    p->shader_discards = &dev->shader_discards;
    /* The binned work a pass holds before it flushes starts small, so that a large scene's first
     * frame touches little new memory, and is the device's limit once a pass had to flush: a
     * scene that keeps being drawn grows to its size in its second frame, each of its bytes
     * faulted in once, and then does not flush. (Doubling at each flushing pass spread the
     * growth over three frames that cost more in all.) A flush costs about one pass over the
     * target, so a larger target starts larger. */
    const size_t pixels = (size_t)p->width * (size_t)p->height;
    size_t start = pixels > dev->bin_memory_limit / BIN_START_PER_PIXEL
                       ? dev->bin_memory_limit
                       : pixels * BIN_START_PER_PIXEL;
    start = start > BIN_START_MIN ? start : BIN_START_MIN;
    start = start > dev->bin_working ? start : dev->bin_working;
    dev->bin_flush_at = start < dev->bin_memory_limit ? start : dev->bin_memory_limit;
    dev->binner.memory_limit = dev->bin_flush_at; /* the storage grows with it */
    dev->pass_first_flush = dev->flushes;
    dev->room_tris = dev->room_listed = 0; /* bin_slot looks at the budget first */
    dev->pass_failed = false;
    dev->pass_tris = 0;
    dev->pass_depth_store = p->store_depth;
    dev->pass_serial++;
    dev->in_pass = true;
    dev->pass_color = pass->color;
    dev->pass_depth = pass->depth;
    return SG_OK;
}

/* Renders every bin of the pass into its targets, on the device's threads. */
static void render_bins(sgDevice *dev) {
    /* Lit shading finds a triangle's extension beside it: the arrays are final now. */
    for (size_t i = 0; i < dev->draw_count; i++) {
        sg_shade_ctx *c = &dev->draws[i].ctx;
        c->tris = dev->binner.tris;
        c->ext = dev->binner.use_ext ? dev->binner.ext : NULL;
        if (c->shader.fragment) { /* the uniform arena may have moved since the draw */
            c->shader.uniforms = c->shader.uniform_offset != SIZE_MAX
                                     ? dev->uniforms + c->shader.uniform_offset
                                     : NULL;
            c->shader.pass_discards = &dev->shader_discards;
        }
    }
    dev->pass.shader_discards = &dev->shader_discards;
    busiest_first(&dev->binner, dev->bin_order);
    int nbins = dev->binner.bins_x * dev->binner.bins_y, busy = 0;
    while (busy < nbins && dev->binner.bins[dev->bin_order[busy] & 0xffffffffu].count) busy++;
    bin_jobs jobs = {&dev->pass, dev->bin_order, busy, nbins - busy, 0};
    jobs.runs = jobs.empty < dev->thread_count ? jobs.empty : dev->thread_count;
    sg_workers_run(&dev->workers, jobs.runs + busy, render_bin, &jobs);
    /* A pipeline whose fragments were seen discarding shades its next draws in place from the
     * start, sparing those bins the redo (the pipeline may have been destroyed since). */
    for (size_t i = 0; dev->pass.any_shader && i < dev->draw_count; i++) {
        const sg_shader_state *s = &dev->draws[i].ctx.shader;
        sg_pso *pso = s->discarded ? sg_lookup_pso(dev, (sgPipelineStateObject){s->pso}) : NULL;
        if (pso && pso->shader) pso->discards = true;
    }
}

/* Grows a sample buffer of the device to n samples; false: out of memory (nothing changed). */
static bool msaa_room(sgDevice *dev, void **buf, size_t *capacity, size_t n) {
    if (n <= *capacity) return true;
    void *b = sg_alloc(dev, n * 4);
    if (!b) return false;
    sg_free(dev, *buf);
    *buf = b;
    *capacity = n;
    return true;
}

/* A flush of a multisampled pass: the bins keep their samples in the device's buffers, and the
 * targets are written only when the pass ends (a resolve cannot be undone). */
static bool flush_msaa(sgDevice *dev) {
    sg_bin_pass *p = &dev->pass;
    const size_t n = (size_t)dev->binner.bins_x * (size_t)dev->binner.bins_y * SG_MSAA_BIN_SAMPLES;
    if (p->color && !msaa_room(dev, (void **)&dev->msaa_color, &dev->msaa_color_capacity, n))
        return false;
    if (p->depth && !msaa_room(dev, (void **)&dev->msaa_depth, &dev->msaa_depth_capacity, n))
        return false;
    p->msaa_color = dev->msaa_color;
    p->msaa_depth = dev->msaa_depth;
    p->msaa_store = true;
    render_bins(dev);
    p->msaa_store = false;
    p->msaa_load = true;
    dev->pass_tris += dev->binner.tri_count;
    sg_binner_clear(&dev->binner);
    dev->room_tris = dev->room_listed = 0;
    dev->flushes++;
    return true;
}

bool sg_pass_flush(sgDevice *dev) {
    sg_bin_pass *p = &dev->pass;
    if (p->samples > 1) return flush_msaa(dev);
    /* A bin goes on from what the flush leaves in the targets. A depth target the pass does not
     * store keeps its contents, so the depth goes on in a scratch image of the device. */
    if (p->depth && !dev->pass_depth_store && p->depth != dev->flush_depth) {
        size_t n = (size_t)p->width * (size_t)p->height;
        if (n > dev->flush_depth_capacity) {
            float *d = sg_alloc(dev, n * sizeof *d);
            if (!d) return false;
            sg_free(dev, dev->flush_depth);
            dev->flush_depth = d;
            dev->flush_depth_capacity = n;
        }
        if (p->load_depth) memcpy(dev->flush_depth, p->depth, n * sizeof *p->depth);
        p->depth = dev->flush_depth;
    }
    p->store_depth = true;
    render_bins(dev);
    dev->pass_tris += dev->binner.tri_count;
    p->store_depth = dev->pass_depth_store;
    p->load_color = p->color != NULL;
    p->load_depth = p->depth != NULL;
    sg_binner_clear(&dev->binner);
    dev->room_tris = dev->room_listed = 0;
    dev->flushes++;
    return true;
}

sgResult sgEndRenderPass(sgDevice *dev, const sgPassDesc *pass) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!pass) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgEndRenderPass: pass is NULL");
    if (!dev->in_pass)
        return sg_error(dev, SG_ERROR_NOT_IN_PASS, "sgEndRenderPass: no render pass is open");
    if (pass->color.id != dev->pass_color.id || pass->depth.id != dev->pass_depth.id)
        return sg_error(dev, SG_ERROR_PASS_MISMATCH,
                        "sgEndRenderPass: targets (color 0x%08x, depth 0x%08x) differ from those "
                        "of sgBeginRenderPass (color 0x%08x, depth 0x%08x)",
                        pass->color.id, pass->depth.id, dev->pass_color.id, dev->pass_depth.id);
    bool failed = dev->pass_failed;
    if (!failed) render_bins(dev);
    dev->in_pass = false;
    dev->pass_failed = false;
    if (!failed && dev->flushes != dev->pass_first_flush) dev->bin_working = dev->bin_memory_limit;
    if (dev->pass_tris + dev->binner.tri_count > dev->most_tris)
        dev->most_tris = dev->pass_tris + dev->binner.tri_count;
    dev->pass_color.id = 0;
    dev->pass_depth.id = 0;
    if (failed)
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgEndRenderPass: a draw of the pass ran out of memory after part of it "
                        "was rendered (bin_memory_limit flush); the targets hold an unfinished "
                        "pass. The pass is closed");
    return SG_OK;
}
