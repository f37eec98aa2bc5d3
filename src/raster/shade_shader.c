/* shade_shader.c - the fragment stage of shader pipelines (see shade_shader.h) and sgSample. */
#include "raster/shade_shader.h"

#include <string.h>

#include "raster/blend.h"
#include "raster/blend_walk.h"
#include "tex/mip.h"

/* 16 lanes as one value (GCC vector types): the fragment stage's setup and conversion and
 * sgSample's RGBA8 path. Each operation is the scalar one in every lane, in the same order. */
typedef float sg_vf __attribute__((vector_size(4 * SG_SHADER_LANES)));
typedef int32_t sg_vi __attribute__((vector_size(4 * SG_SHADER_LANES)));

#define SEL(m, a, b)  ((sg_vf)(((m) & (sg_vi)(a)) | (~(m) & (sg_vi)(b))))
#define SELI(m, a, b) (((m) & (a)) | (~(m) & (b)))

/* Copies for the baseline, AVX2 and AVX-512, chosen at start: the same bits in each (lane-wise
 * IEEE operations, no FMA). Not under the sanitizers, whose builds need no speed. */
/* A sanitizer's runtime is not up yet when the program's start runs the copies' resolvers (gcc
 * says so with __SANITIZE_*, clang with __has_feature). */
#if defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) ||                         \
    __has_feature(memory_sanitizer)
#define SG_UNDER_SANITIZER 1
#endif
#endif
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__SANITIZE_ADDRESS__) &&                  \
    !defined(__SANITIZE_THREAD__) && !defined(SG_UNDER_SANITIZER)
#define LANE_CLONES __attribute__((target_clones("default", "arch=x86-64-v3", "arch=x86-64-v4")))
#else
#define LANE_CLONES
#endif

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
    /* Vector stores, not a call of memset: a tile is a few hundred cycles in all. */
    for (int k = s->varying_count; k < SG_MAX_VARYINGS; k++)
        memcpy(b.varying[k], &zero, sizeof zero);
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

/* A tile of a shader draw shaded in place: the depth test without writing, the fragment stage,
 * then depth (when written) and colour where no lane was discarded. */
static inline __attribute__((always_inline)) void in_place(const void *vctx, const sg_tri *t,
                                                           int x0, int y0, uint32_t mask,
                                                           const int zmode, const int zwrite,
                                                           const int put) {
    const sg_vis_ctx *v = vctx;
    const int base = sg_bin_tile_offset(x0 - v->bx0, y0 - v->by0);
    float *dp = v->depth ? v->depth + base : NULL;
    const float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    float z[SG_TILE_PIXELS];
    if (zmode != Z_NONE || zwrite) {
        uint32_t pass = 0;
        for (uint32_t left = mask; left; left &= left - 1) {
            const int bit = __builtin_ctz(left);
            z[bit] = sg_tri_depth(t, ox + (float)(bit & 3), oy + (float)(bit >> 2));
            if (zmode == Z_NONE || sg_depth_passes(v->compare, z[bit], dp[bit])) pass |= 1u << bit;
        }
        mask = pass;
    }
    if (!mask) return;
    uint32_t src[SG_TILE_PIXELS];
    const uint32_t keep = sg_shader_fragments(v->shade_ctx, t, x0, y0, mask, src);
    uint32_t *dst = v->color + base;
    for (uint32_t m = keep; m; m &= m - 1) {
        const int bit = __builtin_ctz(m);
        if (zwrite) dp[bit] = z[bit];
        dst[bit] = put ? src[bit] : sg_blend_rgba8(src[bit], dst[bit]);
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

/* ---- 16 lanes of an RGBA8 texture at once: what sg_sample computes per lane (tex/sample.h),
 * on GCC vector types. Every step is the same operation as the scalar one (float coordinates,
 * then integer indices, weights and sums), so each lane gets its bits. */

/* Byte k of an RGBA8 texel read as one 32-bit word is channel k: its shift in the word. */
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#define CHANNEL_SHIFT(k) (8 * (3 - (k)))
#else
#define CHANNEL_SHIFT(k) (8 * (k))
#endif

/* floorf, lane by lane: truncation corrected below 2^23 in magnitude; from there up every float
 * is an integer (and NaN and the infinities are their own floor). */
#define VFLOOR(out, x)                                                                             \
    do {                                                                                           \
        const sg_vf x_ = (x);                                                                      \
        const sg_vf t_ = __builtin_convertvector(__builtin_convertvector(x_, sg_vi), sg_vf);       \
        const sg_vf f_ = SEL(t_ > x_, t_ - 1.0f, t_);                                              \
        (out) = SEL((x_ < 8388608.0f) & (x_ > -8388608.0f), f_, x_);                               \
    } while (0)

/* The texel coordinate of s scaled by size (sg_texcoord_repeat / sg_texcoord_clamp). */
#define VCOORD(out, s, size, repeat)                                                               \
    do {                                                                                           \
        const sg_vf s_ = (s);                                                                      \
        if (repeat) {                                                                              \
            sg_vf fl_;                                                                             \
            VFLOOR(fl_, s_);                                                                       \
            const sg_vf x_ = (s_ - fl_) * (size);                                                  \
            (out) = SEL(x_ >= 0.0f, x_, zero);                                                     \
        } else {                                                                                   \
            sg_vf c_ = SEL(s_ >= -1.0f, s_, zero - 1.0f);                                          \
            c_ = SEL(c_ > 2.0f, zero + 2.0f, c_);                                                  \
            (out) = c_ * (size);                                                                   \
        }                                                                                          \
    } while (0)

/* sg_wrap_index, lane by lane. */
static inline __attribute__((always_inline)) void wrap16(int32_t *idx, int n, bool repeat) {
    sg_vi i;
    memcpy(&i, idx, sizeof i);
    if (repeat) {
        i = SELI(i < 0, i + n, i);
        i = SELI(i >= n, i - n, i);
    } else {
        i = SELI(i < 0, i - i, i);
        i = SELI(i >= n, i - i + (n - 1), i);
    }
    memcpy(idx, &i, sizeof i);
}

LANE_CLONES static void sample_rgba8(const sg_shader_tex *tx, bool bilinear, bool repeat,
                                     const float *u, const float *v,
                                     float rgba[4][SG_SHADER_LANES]) {
    const int w = tx->width, h = tx->height;
    const sg_vf zero = {0};
    sg_vf s, t;
    memcpy(&s, u, sizeof s);
    memcpy(&t, v, sizeof t);
    /* the texels of each lane: 1 (nearest) or 4, and the 8-bit weights of the 4 */
    uint32_t texel[4][SG_SHADER_LANES];
    sg_vi wt[4];
    const uint32_t *const base = (const uint32_t *)(const void *)tx->data;
    if (!bilinear) {
        sg_vf x, y;
        VCOORD(x, s, (float)w, repeat);
        VCOORD(y, t, (float)h, repeat);
        VFLOOR(x, x);
        VFLOOR(y, y);
        _Alignas(64) int32_t i[SG_SHADER_LANES], j[SG_SHADER_LANES];
        const sg_vi iv = __builtin_convertvector(x, sg_vi), jv = __builtin_convertvector(y, sg_vi);
        memcpy(i, &iv, sizeof i);
        memcpy(j, &jv, sizeof j);
        wrap16(i, w, repeat);
        wrap16(j, h, repeat);
        for (int l = 0; l < SG_SHADER_LANES; l++)
            memcpy(&texel[0][l], base + (size_t)(h - 1 - j[l]) * (size_t)w + (size_t)i[l], 4);
        for (int k = 0; k < 4; k++) {
            sg_vi c;
            memcpy(&c, texel[0], sizeof c);
            c = (c >> CHANNEL_SHIFT(k)) & 255;
            const sg_vf f = __builtin_convertvector(c, sg_vf) / 255.0f;
            memcpy(rgba[k], &f, sizeof f);
        }
        return;
    }
    sg_vf x, y;
    VCOORD(x, s, 256.0f * (float)w, repeat);
    VCOORD(y, t, 256.0f * (float)h, repeat);
    if (!repeat) { /* beyond one texel outside, clamp-to-edge reads the edge texel anyway */
        const float xmax = 256.0f * (float)(w + 1), ymax = 256.0f * (float)(h + 1);
        x = SEL(x < -256.0f, zero - 256.0f, SEL(x > xmax, zero + xmax, x));
        y = SEL(y < -256.0f, zero - 256.0f, SEL(y > ymax, zero + ymax, y));
    }
    VFLOOR(x, x);
    VFLOOR(y, y);
    /* sg_bilinear_split */
    const sg_vi xv = __builtin_convertvector(x, sg_vi) - 128 + 512,
                yv = __builtin_convertvector(y, sg_vi) - 128 + 512;
    const sg_vi fx = xv & 255, fy = yv & 255;
    _Alignas(64) int32_t i0[SG_SHADER_LANES], j0[SG_SHADER_LANES], i1[SG_SHADER_LANES],
        j1[SG_SHADER_LANES];
    const sg_vi i0v = (xv >> 8) - 2, j0v = (yv >> 8) - 2, i1v = i0v + 1, j1v = j0v + 1;
    memcpy(i0, &i0v, sizeof i0);
    memcpy(j0, &j0v, sizeof j0);
    memcpy(i1, &i1v, sizeof i1);
    memcpy(j1, &j1v, sizeof j1);
    wrap16(i1, w, repeat);
    wrap16(j1, h, repeat);
    wrap16(i0, w, repeat);
    wrap16(j0, h, repeat);
    for (int l = 0; l < SG_SHADER_LANES; l++) {
        const uint32_t *r0 = base + (size_t)(h - 1 - j0[l]) * (size_t)w,
                       *r1 = base + (size_t)(h - 1 - j1[l]) * (size_t)w;
        memcpy(&texel[0][l], r0 + i0[l], 4);
        memcpy(&texel[1][l], r0 + i1[l], 4);
        memcpy(&texel[2][l], r1 + i0[l], 4);
        memcpy(&texel[3][l], r1 + i1[l], 4);
    }
    wt[0] = (256 - fx) * (256 - fy);
    wt[1] = fx * (256 - fy);
    wt[2] = (256 - fx) * fy;
    wt[3] = fx * fy;
    sg_vi p[4];
    for (int q = 0; q < 4; q++) memcpy(&p[q], texel[q], sizeof p[q]);
    for (int k = 0; k < 4; k++) {
        const sg_vi c = (((p[0] >> CHANNEL_SHIFT(k)) & 255) * wt[0] +
                         ((p[1] >> CHANNEL_SHIFT(k)) & 255) * wt[1] +
                         ((p[2] >> CHANNEL_SHIFT(k)) & 255) * wt[2] +
                         ((p[3] >> CHANNEL_SHIFT(k)) & 255) * wt[3] + 32768) >>
                        16;
        const sg_vf f = __builtin_convertvector(c, sg_vf) / 255.0f;
        memcpy(rgba[k], &f, sizeof f);
    }
}

/* sgSample of a mipmapped pipeline on an RGBA8 texture: each 2 x 2 quad of lanes (a tile's lanes
 * are its pixels, row by row) takes its levels from its own differences of u and v, as the fixed
 * shading does (shade_mip.c). */
static void sample_mip(const sg_shader_tex *tx, const sg_shader_state *s,
                       const float u[SG_SHADER_LANES], const float v[SG_SHADER_LANES],
                       float rgba[4][SG_SHADER_LANES]) {
    const int linear = s->mipmap == SG_MIPMAP_LINEAR;
    for (int q = 0; q < 4; q++) {
        const int l0 = (q & 1) * 2 + (q >> 1) * 8; /* the quad's top-left lane */
        const sg_mip_pick p = sg_mip_select(tx->mips, u[l0 + 1] - u[l0], v[l0 + 1] - v[l0],
                                            u[l0 + 4] - u[l0], v[l0 + 4] - v[l0], linear);
        for (int j = 0; j < 4; j++) {
            const int i = l0 + (j & 1) + (j >> 1) * 4;
            sg_texel e = sg_sample_mip(tx->mips, p, u[i], v[i], s->bilinear, s->repeat);
            for (int k = 0; k < 4; k++) rgba[k][i] = (float)e.c[k] / 255.0f;
        }
    }
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
        sample_rgba8(tx, c->shader.bilinear, c->shader.repeat, u, v, rgba);
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
