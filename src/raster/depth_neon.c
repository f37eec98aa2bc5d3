/* depth_neon.c - the LESS visibility tile functions in NEON (AArch64; see depth.h): one row of
 * four pixels a vector, z as depth_neon.h computes it, the same z and clamp as the scalar code. */
#include "raster/depth.h"

#include "raster/depth_neon.h"
#include "raster/depth_walk.h"

#if defined(__aarch64__) && defined(__ARM_NEON)

static inline __attribute__((always_inline)) void
vis_neon(const void *vctx, const sg_tri *t, int x0, int y0, uint32_t mask, const int zwrite) {
    const sg_vis_ctx *v = vctx;
    int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    uint32_t *ids = sg_vis_tile_ids(v, base);
    float *dp = v->depth + base;
    const sg_zrows4n zr = sg_zrows4n_at(t, x0, y0);
    const uint32x4_t id = vdupq_n_u32(v->id);
    for (int j = 0; j < 4; j++) {
        uint32_t bits = (mask >> (4 * j)) & 15u;
        if (!bits) continue;
        float32x4_t z = sg_zrow4n(&zr, j);
        float32x4_t d = vld1q_f32(dp + 4 * j);
        uint32x4_t pass = vcltq_f32(z, d);
        if (bits != 15u) pass = vandq_u32(pass, sg_lanes4n(bits));
        if (!vmaxvq_u32(pass)) continue;
        if (zwrite) vst1q_f32(dp + 4 * j, vbslq_f32(pass, z, d));
        vst1q_u32(ids + 4 * j, vbslq_u32(pass, id, vld1q_u32(ids + 4 * j)));
    }
}

static inline void vis_less_0_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_neon(c, t, x0, y0, m, 0);
}
static inline void vis_less_1_tile(const void *c, const sg_tri *t, int x0, int y0, uint32_t m) {
    vis_neon(c, t, x0, y0, m, 1);
}
/* The walk (NEON's coverage tests, rast_walk.h) with the tile function inlined. */
static void vis_less_0_neon(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_0_tile, c);
}
static void vis_less_1_neon(const sg_tri *t, int x0, int y0, int x1, int y1, const void *c) {
    sg_rast_walk(t, x0, y0, x1, y1, vis_less_1_tile, c);
}

/* The tile body as the sample walk calls it (LESS only). */
#define vis_neon_less(c, t, x0, y0, m, zm, zw) vis_neon(c, t, x0, y0, m, zw)
SG_VIS_SAMPLES_FN(vis_samples_less_0_neon, vis_neon_less, Z_LESS, 0)
SG_VIS_SAMPLES_FN(vis_samples_less_1_neon, vis_neon_less, Z_LESS, 1)

sg_vis_fns sg_depth_less_neon(bool depth_write) {
    return depth_write ? (sg_vis_fns){vis_less_1_neon, vis_samples_less_1_neon, NULL}
                       : (sg_vis_fns){vis_less_0_neon, vis_samples_less_0_neon, NULL};
}

#else

sg_vis_fns sg_depth_less_neon(bool depth_write) {
    (void)depth_write;
    return (sg_vis_fns){NULL, NULL, NULL};
}

#endif
