/* depth_neon.h - the window depth of a tile's pixels and its compare in NEON (AArch64), shared by
 * visibility (depth_neon.c) and blending (blend_neon.c): the NEON side of depth_simd.h.
 *
 * z = (z0 + z_dx dx) + z_dy dy, each product and sum rounded as in the scalar code, then clamped
 * to [0, 1] by compares and selects, as sg_tri_depth does (a NaN z stays NaN): FMAX would not
 * do, since it orders -0 below +0 where the scalar clamp keeps a -0, which a depth write stores.
 */
#ifndef SG_DEPTH_NEON_H
#define SG_DEPTH_NEON_H

#include "pipeline/setup.h"
#include "sgapi/sgapi.h"

#if defined(__aarch64__) && defined(__ARM_NEON)
#include <arm_neon.h>

/* The parts of z that are the same on every row of a tile: z0 + z_dx dx per lane, z_dy, and the
 * tile's first row's dy. */
typedef struct sg_zrows4n {
    float32x4_t zx, zdy;
    float oy;
} sg_zrows4n;

static inline sg_zrows4n sg_zrows4n_at(const sg_tri *t, int x0, int y0) {
    const float32x4_t i = {0.0f, 1.0f, 2.0f, 3.0f};
    float32x4_t dx = vaddq_f32(vdupq_n_f32((float)(x0 - t->minx)), i);
    sg_zrows4n r = {vaddq_f32(vdupq_n_f32(t->z), vmulq_f32(vdupq_n_f32(t->z_dx), dx)),
                    vdupq_n_f32(t->z_dy), (float)(y0 - t->miny)};
    return r;
}

/* The clamped z of row j (0..3) of the tile. */
static inline float32x4_t sg_zrow4n(const sg_zrows4n *r, int j) {
    float32x4_t z = vaddq_f32(r->zx, vmulq_f32(r->zdy, vdupq_n_f32(r->oy + (float)j)));
    const float32x4_t zero = vdupq_n_f32(0.0f), one = vdupq_n_f32(1.0f);
    z = vbslq_f32(vcltq_f32(z, zero), zero, z);
    return vbslq_f32(vcgtq_f32(z, one), one, z);
}

/* All ones where z passes the compare against the stored d (a NaN z passes only NOT_EQUAL and
 * ALWAYS, as in the scalar code). */
static inline uint32x4_t sg_compare4n(sgCompare op, float32x4_t z, float32x4_t d) {
    switch (op) {
    case SG_COMPARE_NEVER:
        return vdupq_n_u32(0);
    case SG_COMPARE_LESS:
        return vcltq_f32(z, d);
    case SG_COMPARE_EQUAL:
        return vceqq_f32(z, d);
    case SG_COMPARE_LESS_EQUAL:
        return vcleq_f32(z, d);
    case SG_COMPARE_GREATER:
        return vcgtq_f32(z, d);
    case SG_COMPARE_NOT_EQUAL:
        return vmvnq_u32(vceqq_f32(z, d));
    case SG_COMPARE_GREATER_EQUAL:
        return vcgeq_f32(z, d);
    default:
        return vdupq_n_u32(~0u);
    }
}

/* The lanes of a row whose bit is set in `bits` (4 bits), all ones. */
static inline uint32x4_t sg_lanes4n(uint32_t bits) {
    const uint32x4_t lane = {1, 2, 4, 8};
    return vtstq_u32(vdupq_n_u32(bits), lane);
}
#endif

#endif
