/* shade_shader.c - the fragment stage of shader pipelines (see shade_shader.h) and sgSample. */
#include "raster/shade_shader.h"

#include <string.h>

#include "raster/blend.h"
#include "raster/blend_walk.h"
#include "tex/lanes.h"
#include "tex/mip.h"
#include "tex/sample16.h"

/* A tile through the fragment stage, into RGBA8 pixels px; returns the lanes discarded.
 *
 * The batch: every lane interpolated at its pixel centre (helper lanes too), as the fixed
 * shading does: attribute / w and 1 / w planes, then one division. Varyings past the count and
 * the colour start at 0. The colour: each channel to unorm8 as sg_to_unorm8 rounds it (NaN and
 * below 0 give 0). */
LANE_CLONES static uint32_t shade_tile(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0,
                                       uint32_t mask, uint32_t px[SG_SHADER_LANES]) {
    const sg_shader_state *s = &c->shader;
    const sg_tri_ext *ext = s->varying_count > SG_TRI_ATTRS ? sg_shade_ext(c, t) : NULL;
    sgFragmentBatch b;
    b.mask = mask;
    b.x = x0;
    b.y = y0;
    b.front_facing = t->sh.front_facing != 0;
    b.primitive = t->sh.primitive;
    b.instance = t->sh.instance;
    b.discard = 0;
    b.internal = c;
    const sg_vf lane_x = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};
    const sg_vf lane_y = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
    const sg_vf zero = {0}, one = zero + 1.0f;
    const sg_vf dx = (float)(x0 - t->minx) + lane_x, dy = (float)(y0 - t->miny) + lane_y;
    const sg_vf z = t->z + t->z_dx * dx + t->z_dy * dy;
    const sg_vf zc = SEL(z < 0.0f, zero, SEL(z > 1.0f, one, z)); /* sg_tri_depth */
    memcpy(b.z, &zc, sizeof zc);
    const sg_vf w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
    for (int k = 0; k < s->varying_count; k++) {
        float a, ax, ay;
        if (k < SG_TRI_ATTRS) {
            a = t->a[k];
            ax = t->a_dx[k];
            ay = t->a_dy[k];
        } else {
            a = ext->a[k - SG_TRI_ATTRS];
            ax = ext->a_dx[k - SG_TRI_ATTRS];
            ay = ext->a_dy[k - SG_TRI_ATTRS];
        }
        const sg_vf v = s->flat >> k & 1 ? zero + a : (a + ax * dx + ay * dy) * w;
        memcpy(b.varying[k], &v, sizeof v);
    }
    /* Vector stores, not a call of memset: a tile is a few hundred cycles in all (a loop from
     * the count on became one). */
    for (int k = 0; k < SG_MAX_VARYINGS; k++)
        if (k >= s->varying_count) memcpy(b.varying[k], &zero, sizeof zero);
    for (int ch = 0; ch < 4; ch++) memcpy(b.color[ch], &zero, sizeof zero);
    s->fragment(&b, s->uniforms);
    sg_vi p = {0};
    for (int ch = 0; ch < 4; ch++) {
        sg_vf v;
        memcpy(&v, b.color[ch], sizeof v);
        v = SEL(v > 0.0f, v, zero);
        v = SEL(v < 1.0f, v, one);
        p |= __builtin_convertvector(v * 255.0f + 0.5f, sg_vi) << (8 * ch);
    }
    memcpy(px, &p, sizeof p);
    return b.discard;
}

uint32_t sg_shader_fragments(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                             uint32_t *dst) {
    uint32_t px[SG_SHADER_LANES];
    const uint32_t keep = mask & ~shade_tile(c, t, x0, y0, mask, px);
    if (keep == 0xffffu) {
        memcpy(dst, px, sizeof px);
    } else {
        for (uint32_t m = keep; m; m &= m - 1) {
            const int i = __builtin_ctz(m);
            dst[i] = px[i];
        }
    }
    return keep;
}

void sg_shade_shader(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                     uint32_t *dst) {
    if (sg_shader_fragments(c, t, x0, y0, mask, dst) == mask) return;
    /* A discard: what visibility found behind these pixels is unknown, so the bin is redone
     * with the draw shaded in place. The state is the draw's, shared by the bins' threads. */
    __atomic_store_n((int *)&c->shader.discarded, 1, __ATOMIC_RELAXED);
    __atomic_fetch_add(c->shader.pass_discards, 1, __ATOMIC_RELAXED);
}

/* The depth test of a tile shaded in place, on its 16 lanes at once (its own copies per set,
 * since the walk's baseline code would split the vectors lane by lane): each lane's window depth
 * into z (sg_tri_depth's operations, so its bits), and the lanes of mask that pass `op` against
 * the tile's stored depths dp (all of them when dp is NULL). */
LANE_CLONES static uint32_t tile_depth(const sg_tri *t, int x0, int y0, uint32_t mask,
                                       const float *dp, sgCompare op, float z[SG_TILE_PIXELS]) {
    const sg_vf lane_x = {0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3, 0, 1, 2, 3};
    const sg_vf lane_y = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
    const sg_vf zero = {0}, one = zero + 1.0f;
    const sg_vf dx = (float)(x0 - t->minx) + lane_x, dy = (float)(y0 - t->miny) + lane_y;
    const sg_vf zr = t->z + t->z_dx * dx + t->z_dy * dy;
    const sg_vf zc = SEL(zr < 0.0f, zero, SEL(zr > 1.0f, one, zr));
    memcpy(z, &zc, sizeof zc);
    if (!dp) return mask;
    sg_vf d;
    memcpy(&d, dp, sizeof d);
    sg_vi pass;
    switch (op) { /* sg_depth_passes, lane by lane */
    case SG_COMPARE_NEVER:
        return 0;
    case SG_COMPARE_LESS:
        pass = zc < d;
        break;
    case SG_COMPARE_EQUAL:
        pass = zc == d;
        break;
    case SG_COMPARE_LESS_EQUAL:
        pass = zc <= d;
        break;
    case SG_COMPARE_GREATER:
        pass = zc > d;
        break;
    case SG_COMPARE_NOT_EQUAL:
        pass = zc != d;
        break;
    case SG_COMPARE_GREATER_EQUAL:
        pass = zc >= d;
        break;
    default:
        return mask;
    }
    uint32_t bits = 0; /* lane i in bit i */
    for (int i = 0; i < SG_TILE_PIXELS; i++) bits |= (uint32_t)(pass[i] & 1) << i;
    return mask & bits;
}

/* The lanes of keep written: depth z into dp (when not NULL) and the colours src put into dst. */
LANE_CLONES static void put_tile(uint32_t keep, const float z[SG_TILE_PIXELS], float *dp,
                                 const uint32_t src[SG_TILE_PIXELS], uint32_t *dst) {
    const sg_vi bit = {1 << 0, 1 << 1, 1 << 2,  1 << 3,  1 << 4,  1 << 5,  1 << 6,  1 << 7,
                       1 << 8, 1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 13, 1 << 14, 1 << 15};
    const sg_vi m = (bit & (int32_t)keep) != 0;
    sg_vi a, b;
    if (dp) {
        memcpy(&a, z, sizeof a);
        memcpy(&b, dp, sizeof b);
        b = SELI(m, a, b);
        memcpy(dp, &b, sizeof b);
    }
    memcpy(&a, src, sizeof a);
    memcpy(&b, dst, sizeof b);
    b = SELI(m, a, b);
    memcpy(dst, &b, sizeof b);
}

/* A tile of a shader draw shaded in place: the depth test without writing, the fragment stage,
 * then depth (when written) and colour where no lane was discarded. */
static inline __attribute__((always_inline)) void in_place(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite,
                                                           const int put) {
    const sg_vis_ctx *v = vctx;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    float *dp = v->depth ? v->depth + base : NULL;
    float z[SG_TILE_PIXELS];
    if (zmode != Z_NONE || zwrite)
        mask = tile_depth(t, x0, y0, mask, zmode != Z_NONE ? dp : NULL, v->compare, z);
    if (!mask) return;
    uint32_t src[SG_TILE_PIXELS];
    const uint32_t keep = sg_shader_fragments(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    if (put) {
        if (keep) put_tile(keep, z, zwrite ? dp : NULL, src, dst);
        return;
    }
    for (uint32_t m = keep; m; m &= m - 1) {
        const int bit = __builtin_ctz(m);
        if (zwrite) dp[bit] = z[bit];
        dst[bit] = sg_blend_rgba8(src[bit], dst[bit]);
    }
}

SG_IN_PLACE_BODY(shader_blend_body, in_place, 0)
SG_IN_PLACE_BODY(shader_put_body, in_place, 1)
SG_IN_PLACE_SET(shader_blend, shader_blend_body)
SG_IN_PLACE_SET(shader_put, shader_put_body)

sg_raster_fn sg_shader_in_place_select(bool blend, sgCompare compare, bool depth_write) {
    static const sg_raster_fn fns[2][2][2] = {SG_IN_PLACE_TABLE(shader_put),
                                              SG_IN_PLACE_TABLE(shader_blend)};
    return fns[blend][compare != SG_COMPARE_ALWAYS][depth_write];
}

/* ---- sgSample ---- */

/* A depth image at (s, t) with the pipeline's filter and wrap, in float. */
static float sample_depth(const sg_shader_tex *tx, float s, float t, bool bilinear, bool repeat) {
    const float *d = (const float *)(const void *)tx->data;
    const int w = tx->width, h = tx->height;
    float x = repeat ? sg_texcoord_repeat(s, (float)w) : sg_texcoord_clamp(s, (float)w);
    float y = repeat ? sg_texcoord_repeat(t, (float)h) : sg_texcoord_clamp(t, (float)h);
    if (!bilinear) {
        int i = sg_wrap_index((int)floorf(x), w, repeat),
            j = sg_wrap_index((int)floorf(y), h, repeat);
        return d[(size_t)(h - 1 - j) * (size_t)w + (size_t)i];
    }
    x -= 0.5f;
    y -= 0.5f;
    const float fx = x - floorf(x), fy = y - floorf(y);
    const int i0 = (int)floorf(x), j0 = (int)floorf(y);
    float v[2][2];
    for (int dj = 0; dj < 2; dj++)
        for (int di = 0; di < 2; di++) {
            int i = sg_wrap_index(i0 + di, w, repeat), j = sg_wrap_index(j0 + dj, h, repeat);
            v[dj][di] = d[(size_t)(h - 1 - j) * (size_t)w + (size_t)i];
        }
    return (v[0][0] * (1.0f - fx) + v[0][1] * fx) * (1.0f - fy) +
           (v[1][0] * (1.0f - fx) + v[1][1] * fx) * fy;
}

/* sgSample of a mipmapped pipeline on an RGBA8 texture: each 2 x 2 quad of lanes (a tile's lanes
 * are its pixels, row by row) takes its levels from its own differences of u and v, as the fixed
 * shading does (shade_mip.c). */
static void sample_mip(const sg_shader_tex *tx, const sg_shader_state *s,
                       const float u[SG_SHADER_LANES], const float v[SG_SHADER_LANES],
                       float rgba[4][SG_SHADER_LANES]) {
    const int linear = s->mipmap == SG_MIPMAP_LINEAR;
    sg_mip_pick pick[4];
    for (int q = 0; q < 4; q++) {
        const int l0 = (q & 1) * 2 + (q >> 1) * 8; /* the quad's top-left lane */
        pick[q] = sg_mip_select(tx->mips, u[l0 + 1] - u[l0], v[l0 + 1] - v[l0], u[l0 + 4] - u[l0],
                                v[l0 + 4] - v[l0], linear);
    }
    int32_t texel[4][SG_SHADER_LANES];
    sg_sample16_mip(s->sample16, tx->mips, pick, s->bilinear, s->repeat, u, v, texel);
    sg_texels_to_unit(s->sample16, texel, rgba);
}

void sgSample(const sgFragmentBatch *b, int slot, const float u[SG_SHADER_LANES],
              const float v[SG_SHADER_LANES], float rgba[4][SG_SHADER_LANES]) {
    const sg_shade_ctx *c = b && b->internal ? b->internal : NULL;
    const sg_shader_tex *tx =
        c && slot >= 0 && slot < SG_MAX_DRAW_TEXTURES && c->shader.textures[slot].data
            ? &c->shader.textures[slot]
            : NULL;
    if (tx && !tx->depth && c->shader.mipmap > SG_MIPMAP_NONE && tx->mips) {
        sample_mip(tx, &c->shader, u, v, rgba);
        return;
    }
    if (tx && !tx->depth) {
        sg_sample16_unit(c->shader.sample16, tx->data, tx->width, tx->height, c->shader.bilinear,
                         c->shader.repeat, u, v, rgba);
        return;
    }
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        if (!tx) {
            rgba[0][i] = rgba[1][i] = rgba[2][i] = 0.0f;
            rgba[3][i] = 1.0f;
        } else {
            float d = sample_depth(tx, u[i], v[i], c->shader.bilinear, c->shader.repeat);
            rgba[0][i] = rgba[1][i] = rgba[2][i] = d;
            rgba[3][i] = 1.0f;
        }
    }
}
