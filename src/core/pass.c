/* pass.c - render passes: the tiled framebuffer is filled at Begin and resolved at End. */
#include "core/device.h"

#include <math.h>
#include <string.h>

#include "raster/shade.h"

static bool unit_range(float v) {
    return v >= 0.0f && v <= 1.0f;
} /* false for NaN */

/* Grows a tiled array to hold `pixels`, keeping nothing (it is about to be cleared or loaded). */
static bool ensure(sgDevice *dev, void **ptr, size_t *capacity, size_t pixels) {
    if (*capacity >= pixels) return true;
    sg_free(dev, *ptr);
    *ptr = sg_alloc(dev, pixels * 4);
    *capacity = *ptr ? pixels : 0;
    return *ptr != NULL;
}

/* Clearing or loading the tiled framebuffer at Begin, and resolving it at End, one band of 64
 * pixel rows a job, so the whole frame's fixed cost is spread over the raster threads. */
typedef struct band_job {
    sg_fb *fb;
    sg_image *color, *depth; /* depth may be NULL */
    bool resolve;            /* End: tiles -> images; Begin: clear or load */
    bool load_color, load_depth;
    uint32_t clear_color;
    float clear_depth;
} band_job;

static int bands_of(int height) {
    return (height + SG_BIN_SIZE - 1) / SG_BIN_SIZE;
}

static void run_band(void *vjob, int band) {
    const band_job *j = vjob;
    sg_fb *fb = j->fb;
    int y0 = band * SG_BIN_SIZE;
    int h = fb->height - y0 < SG_BIN_SIZE ? fb->height - y0 : SG_BIN_SIZE;
    /* A band starts on a tile row, so its tiles are one contiguous run of the tiled arrays. */
    size_t first = (size_t)(y0 >> SG_TILE_SHIFT) * (size_t)fb->tiles_x * SG_TILE_PIXELS;
    size_t count =
        (size_t)((h + SG_TILE - 1) >> SG_TILE_SHIFT) * (size_t)fb->tiles_x * SG_TILE_PIXELS;
    size_t cpitch = (size_t)fb->width * 4;
    uint8_t *cdata = j->color->data + (size_t)y0 * cpitch;
    float *ddata = j->depth ? (float *)(void *)(j->depth->data + (size_t)y0 * cpitch) : NULL;
    if (j->resolve) {
        sg_tile_to_linear_rgba8(cdata, cpitch, fb->color + first, fb->width, h);
        if (ddata) sg_tile_to_linear_f32(ddata, cpitch, fb->depth + first, fb->width, h);
        return;
    }
    if (j->load_color)
        sg_tile_from_linear_rgba8(fb->color + first, cdata, cpitch, fb->width, h);
    else
        sg_fb_fill_color(fb->color + first, count, j->clear_color);
    if (ddata) {
        if (j->load_depth)
            sg_tile_from_linear_f32(fb->depth + first, ddata, cpitch, fb->width, h);
        else
            sg_fb_fill_depth(fb->depth + first, count, j->clear_depth);
    }
}

sgResult sgBeginRenderPass(sgDevice *dev, const sgPassDesc *pass) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!pass) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgBeginRenderPass: pass is NULL");
    if (dev->in_pass)
        return sg_error(dev, SG_ERROR_ALREADY_IN_PASS,
                        "sgBeginRenderPass: a render pass is already open; end it first");
    sg_image *color = sg_lookup_image(dev, pass->color);
    if (!color)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgBeginRenderPass: color target id 0x%08x is not a live image",
                        pass->color.id);
    if (color->format != SG_FORMAT_RGBA8_UNORM)
        return sg_error(dev, SG_ERROR_FORMAT_MISMATCH,
                        "sgBeginRenderPass: the color target must be RGBA8_UNORM");
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
        if (depth->width != color->width || depth->height != color->height)
            return sg_error(dev, SG_ERROR_INVALID_SIZE,
                            "sgBeginRenderPass: depth target is %dx%d but color target is %dx%d",
                            depth->width, depth->height, color->width, color->height);
    }
    if ((int)pass->depth_store < SG_STORE_DEFAULT || pass->depth_store > SG_STORE_DONT_CARE)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgBeginRenderPass: depth_store %d is not an sgStoreOp",
                        (int)pass->depth_store);
    if ((int)pass->color_load < SG_LOAD_DEFAULT || pass->color_load > SG_LOAD_LOAD ||
        (int)pass->depth_load < SG_LOAD_DEFAULT || pass->depth_load > SG_LOAD_LOAD)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgBeginRenderPass: color_load %d / depth_load %d is not an sgLoadOp",
                        (int)pass->color_load, (int)pass->depth_load);
    for (int k = 0; k < 4 && pass->color_load != SG_LOAD_LOAD; k++)
        if (!unit_range(pass->clear_color[k]))
            return sg_error(dev, SG_ERROR_INVALID_VALUE,
                            "sgBeginRenderPass: clear_color[%d] = %g is outside [0, 1]", k,
                            (double)pass->clear_color[k]);
    if (depth && pass->depth_load == SG_LOAD_CLEAR && !unit_range(pass->clear_depth))
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgBeginRenderPass: clear_depth = %g is outside [0, 1]",
                        (double)pass->clear_depth);

    size_t pixels = sg_fb_tiled_pixels(color->width, color->height);
    if (!ensure(dev, (void **)&dev->fb.color, &dev->fb_color_capacity, pixels) ||
        (depth && !ensure(dev, (void **)&dev->fb.depth, &dev->fb_depth_capacity, pixels)))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgBeginRenderPass: out of memory for a %dx%d framebuffer", color->width,
                        color->height);
    sg_fb *fb = &dev->fb;
    fb->width = color->width;
    fb->height = color->height;
    fb->tiles_x = (color->width + SG_TILE - 1) / SG_TILE;
    fb->tiles_y = (color->height + SG_TILE - 1) / SG_TILE;
    const float *c = pass->clear_color;
    band_job job = {fb,
                    color,
                    depth,
                    false,
                    pass->color_load == SG_LOAD_LOAD,
                    pass->depth_load == SG_LOAD_LOAD,
                    sg_pack_rgba8(sg_to_unorm8(c[0]), sg_to_unorm8(c[1]), sg_to_unorm8(c[2]),
                                  sg_to_unorm8(c[3])),
                    pass->depth_load == SG_LOAD_CLEAR ? pass->clear_depth : 1.0f};
    sg_workers_run(&dev->workers, bands_of(color->height), run_band, &job);
    dev->in_pass = true;
    dev->store_depth = pass->depth_store != SG_STORE_DONT_CARE;
    dev->pass_color = pass->color;
    dev->pass_depth = pass->depth;
    return SG_OK;
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
    /* Targets cannot be destroyed while the pass is open, so both lookups succeed. */
    sg_image *color = sg_lookup_image(dev, dev->pass_color);
    sg_image *depth =
        dev->pass_depth.id && dev->store_depth ? sg_lookup_image(dev, dev->pass_depth) : NULL;
    band_job job = {&dev->fb, color, depth, true, false, false, 0, 0.0f};
    sg_workers_run(&dev->workers, bands_of(color->height), run_band, &job);
    dev->in_pass = false;
    dev->pass_color.id = 0;
    dev->pass_depth.id = 0;
    return SG_OK;
}
