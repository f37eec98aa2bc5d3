/* device.h - the device and the objects it owns (internal). */
#ifndef SG_DEVICE_H
#define SG_DEVICE_H

#include <stdarg.h>
#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/pool.h"
#include "core/stage_times.h"
#include "core/workers.h"
#include "pipeline/vertex.h"
#include "raster/bin.h"
#include "raster/framebuffer.h"
#include "raster/rast_bin.h"
#include "raster/rast_tile.h"
#include "raster/shade.h"
#include "sgapi/sgapi.h"

typedef struct sg_image {
    int width, height;
    sgFormat format;
    size_t pixel_size;
    uint8_t *data;     /* linear, top row first, 64-byte aligned */
    void *block;       /* the allocation holding data */
    uint32_t pass_use; /* serial of the last pass a draw sampled it in */
    sg_mip_chain mips; /* its levels, level 0 at data (sgImage2DDesc.mip_levels) */
    /* RGBA8 images (NULL for D32): a byte a 64 x 64 bin of a render pass that targets it, 1
     * where every pixel there is cleared_value, a pass's clear that nothing has written over
     * since (sg_bin_pass.cleared); in the same block as the pixels. */
    uint8_t *cleared;
    uint32_t cleared_value;
} sg_image;

/* The bytes of sg_image.cleared of a width x height image: one a bin. */
static inline size_t sg_image_bins(int width, int height) {
    return (size_t)((width + SG_BIN_SIZE - 1) >> SG_BIN_SHIFT) *
           (size_t)((height + SG_BIN_SIZE - 1) >> SG_BIN_SHIFT);
}

typedef struct sg_geom {
    int vertex_count, index_count;
    const float *positions, *colors, *texcoords, *normals;
    const float *attributes[SG_MAX_ATTRIBUTES]; /* read by shader pipelines only */
    const uint32_t *indices;
    sgPrimitive primitive;
    void *copy; /* the one block holding the copied arrays, or NULL when referenced */
} sg_geom;

typedef struct sg_pso {
    sgPipelineDesc desc;    /* every DEFAULT resolved */
    sg_raster_fn raster_fn; /* coverage and visibility (depth.c), or blending (blend.c) */
    sg_raster_fn depth_fn;  /* coverage and depth alone, for depth-only passes */
    sg_shade_fn shade_fn;
    sg_shade_fn shade_sec;      /* flat and Gouraud lighting with a specular material */
    sg_shade_fn shade_shadow;   /* receiving a shadow map (NULL: flat and Gouraud lighting) */
    sg_shade2_fn shade2_fn;     /* two whole tiles at once (NULL: none for this set or state) */
    sg_shade2_fn shade2_sec;    /* the same for shade_sec */
    sg_shade_runs_fn runs_fn;   /* partly covered tiles packed together (NULL: none) */
    sg_shade_runs_fn runs_sec;  /* the same for shade_sec */
    sg_shade_mixed_fn mixed_fn; /* tiles several triangles share, in one pass (NULL: none) */
    sg_raster_fn raster_shadow; /* raster_fn, for draws that receive a shadow map */
    sg_raster_fn raster_pass;   /* raster_fn without depth test (sg_draw_state), or NULL */
    sg_raster_fn raster_shadow_pass; /* the same for raster_shadow */
    sg_raster_fn raster_line;        /* opaque unlit lines shaded in place (blend.h), or NULL */
    int nattr;
    bool uses_depth;
    /* Shader pipelines (desc.shader set): the fragment stage shaded in place, its fragments put
     * (opaque; a draw whose fragments were seen discarding) or blended, per [depth test][write]. */
    bool shader;
    sg_raster_fn shader_in_place;
    /* Set when a draw of this pipeline discarded a fragment: its later draws are shaded in place
     * from the start instead of visibility first (rast_bin.c redoes a bin that finds a discard). */
    bool discards;
} sg_pso;

struct sgDevice {
    sgAllocator allocator;
    void (*log)(sgResult result, const char *message, void *user_data);
    void *log_user_data;
    int thread_count;
    sg_isa isa;                      /* instruction set of the raster */
    bool texel_window;               /* sg_shade_ctx.texel_window of its draws */
    sg_vertex_lit_fn vertex_gouraud; /* Gouraud lighting of vertices in that set; NULL: scalar */
    /* The last failed call's message (sgGetLastError): NULL (none yet), error_short, or
     * error_long. A message that fits error_short takes no allocation, so a failed call leaves the
     * allocator's counts as they were; a longer one grows error_long to its size (kept until
     * sgDestroyDevice). Only when that allocation fails is the message cut, in error_short. */
    const char *error;
    char *error_long;
    size_t error_long_size;
    char error_short[512];

    sg_pool image_pool, geom_pool, pso_pool;
    sg_image *images;
    sg_geom *geoms;
    sg_pso *psos;

    /* The open pass: its targets, and what sgEndRenderPass does with them. */
    bool in_pass;
    uint32_t pass_serial; /* counts passes, to tell which textures the open one samples */
    sgImage2D pass_color, pass_depth;
    sg_bin_pass pass;
    bool pass_depth_store; /* the pass's depth_store is not DONT_CARE */
    /* A draw ran out of memory after a flush had rendered part of it: the pass can only end. */
    bool pass_failed;
    size_t bin_memory_limit; /* bytes of binned work before a flush (sgDeviceDesc) */
    /* Binned bytes at which the open pass flushes, at most bin_memory_limit, and what the next
     * passes start from (pass.c, sgBeginRenderPass). */
    size_t bin_flush_at, bin_working;
    uint64_t pass_first_flush; /* `flushes` when the open pass began */
    float *flush_depth;        /* the depth between flushes of a pass that does not store it */
    size_t flush_depth_capacity;
    /* A multisampled pass's samples between flushes (sg_bin_pass.msaa_color), kept and grown. */
    uint32_t *msaa_color;
    float *msaa_depth;
    size_t msaa_color_capacity, msaa_depth_capacity; /* in samples */
    size_t draw_first;             /* the open draw's first triangle in the binner */
    bool draw_flushed;             /* a flush rendered some of the open draw's triangles */
    size_t room_tris, room_listed; /* bin_slot's next look at the budget (draw.c) */
    uint64_t flushes;              /* flushes before a pass's end, for tests and statistics */
    size_t pass_tris;              /* triangles the open pass's flushes rendered */
    size_t most_tris; /* the most triangles a pass has had: empty storage grows to it (draw.c) */

    /* Arenas, grown as needed and reused. */
    float (*clip)[4]; /* a shader draw's clip positions (a fixed draw stores none: assemble.h) */
    float *lit;       /* a lit draw's vertex attributes (vertex.h, sg_vertex_lit_attributes) */
    size_t lit_capacity;
    uint32_t *outcodes;
    sg_svert *screen;   /* projections of the vertices inside every clip plane */
    uint8_t *screen_ok; /* 1: that projection fits the raster's range */
    size_t vertex_capacity;
    sg_binner binner;     /* set-up triangles of the open pass, by screen bin */
    sg_draw_state *draws; /* the draws of the open pass */
    uint64_t *bin_order;  /* the bins, busiest first, for sgEndRenderPass (pass.c) */
    uint32_t *fe_counts;  /* per front-end chunk and bin: triangles, then write positions */
    size_t fe_counts_capacity;
    uint32_t *fe_ranges; /* per triangle of a front-end round: its bins (sg_binner_count_tri) */
    size_t fe_ranges_capacity;
    unsigned char *uniforms; /* the open pass's shader draws' uniforms, copied (16-byte aligned) */
    size_t uniforms_used, uniforms_capacity;
    int shader_discards; /* counts discarded fragments' tiles in visibility-first bins (rast_bin.c)
                          */
    void *sort_scratch;  /* a sorted draw's keys and its reordered indices (sort.h) */
    size_t sort_scratch_capacity;
    int bin_order_capacity;
    size_t draw_count, draw_capacity;

    /* The raster threads (the calling thread is one of them). */
    sg_workers workers;
    pthread_t *threads;
    bool workers_started;
#if defined(SG_STAGE_TIMES)
    sg_stage_times stage_times;
#endif
};

/** Renders what the open pass has binned into its targets and empties the bins; the rest of the
 *  pass loads the targets. False: out of memory for the depth it keeps (nothing rendered). */
bool sg_pass_flush(sgDevice *dev);

/** Records an error message for sgGetLastError, passes it to the log callback, returns `result`.
 *  The message is never cut unless memory for it runs out; the arguments must not point at the
 *  device's previous message. */
sgResult sg_error(sgDevice *dev, sgResult result, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/** sg_error with `prefix` put before the formatted message, and a va_list. */
sgResult sg_verror(sgDevice *dev, sgResult result, const char *prefix, const char *fmt, va_list ap)
    __attribute__((format(printf, 4, 0)));
/** Allocates through the device's allocator (NULL on failure or size 0). */
void *sg_alloc(sgDevice *dev, size_t size);
/** Frees through the device's allocator; NULL is a no-op. */
void sg_free(sgDevice *dev, void *ptr);

/** Takes a slot of the pool; when none is free, records SG_ERROR_POOL_EXHAUSTED for `fn`, naming
 *  the sgDeviceDesc field that sizes the pool, and returns 0. */
uint32_t sg_acquire(sgDevice *dev, sg_pool *pool, const char *fn, const char *desc_field);

/** The live image behind a handle, or NULL. */
sg_image *sg_lookup_image(sgDevice *dev, sgImage2D h);
/** The live geom behind a handle, or NULL. */
sg_geom *sg_lookup_geom(sgDevice *dev, sgGeom h);
/** The live pipeline behind a handle, or NULL. */
sg_pso *sg_lookup_pso(sgDevice *dev, sgPipelineStateObject h);

/** Frees an image's storage (used by destroy and by device teardown). */
void sg_image_release(sgDevice *dev, sg_image *img);
/** Frees a geom's copies (used by destroy and by device teardown). */
void sg_geom_release(sgDevice *dev, sg_geom *geom);

#endif
