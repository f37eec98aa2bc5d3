/* shade_shader.c - the fragment stage of shader pipelines (see shade_shader.h) and sgSample. */
#include "raster/shade_shader.h"

#include <string.h>

#if defined(__x86_64__)
#include <immintrin.h>
#endif

#include "raster/bin.h"
#include "raster/blend.h"
#include "raster/blend_walk.h"
#include "raster/framebuffer.h"
#include "tex/lanes.h"
#include "tex/mip.h"
#include "tex/sample16.h"

/* Each lane's column, row and bit in a tile (lane i is pixel i, row by row). */
static const _Alignas(64) float sg_tile_lane_x[SG_TILE_PIXELS] = {0, 1, 2, 3, 0, 1, 2, 3,
                                                                  0, 1, 2, 3, 0, 1, 2, 3};
static const _Alignas(64) float sg_tile_lane_y[SG_TILE_PIXELS] = {0, 0, 0, 0, 1, 1, 1, 1,
                                                                  2, 2, 2, 2, 3, 3, 3, 3};
static const _Alignas(64) int32_t sg_tile_lane_bit[SG_TILE_PIXELS] = {
    1 << 0, 1 << 1, 1 << 2,  1 << 3,  1 << 4,  1 << 5,  1 << 6,  1 << 7,
    1 << 8, 1 << 9, 1 << 10, 1 << 11, 1 << 12, 1 << 13, 1 << 14, 1 << 15};

/* shade_shader_tile.h's copies, one per SG_SAMPLE16_* (the device's instruction set, chosen once
 * per draw, as for sgSample's lookups). */
#define SG_LANES_BODY "raster/shade_shader_tile.h"
#include "tex/lanes_copies.h"

static uint32_t shade_tile(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                           uint32_t px[SG_SHADER_LANES], uint32_t *direct) {
    return SG_SAMPLE16_CALL(c->shader.sample16, shade_tile, c, t, x0, y0, mask, px, direct);
}

uint32_t sg_shader_fragments(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                             uint32_t *dst) {
    uint32_t px[SG_SHADER_LANES];
    const uint32_t discard = shade_tile(c, t, x0, y0, mask, px, dst);
    if (!sg_shade_direct(dst, mask, discard)) sg_fb_put_lanes(dst, px, mask & ~discard);
    return mask & ~discard;
}

/* Visibility first, a lane discarded: what visibility found behind it is unknown, so the bin is
 * redone with the draw shaded in place. The state is the draw's, shared by the bins' threads. */
static void note_discard(const sg_shade_ctx *c) {
    __atomic_store_n((int *)&c->shader.discarded, 1, __ATOMIC_RELAXED);
    __atomic_fetch_add(c->shader.pass_discards, 1, __ATOMIC_RELAXED);
}

void sg_shade_shader(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                     uint32_t *dst) {
    if (sg_shader_fragments(c, t, x0, y0, mask, dst) != mask) note_discard(c);
}

void sg_shade_shader2(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, int x1, int y1,
                      uint32_t *dst0, uint32_t *dst1) {
    uint32_t *const dst[2] = {dst0, dst1};
    if (SG_SAMPLE16_CALL(c->shader.sample16, shade_tile2, c, t, x0, y0, x1, y1, dst))
        note_discard(c);
}

uint32_t sg_shader_constant(const void *user, const float *varyings, int *discarded) {
    const sg_shader_konst *k = user;
    return SG_SAMPLE16_CALL(k->ctx->shader.sample16, shade_constant, k->ctx, k->uniforms, varyings,
                            discarded);
}

/* Triangles whose fragments may share a batch: the batch tells one facing (a stage with
 * independent lanes reads neither primitive nor instance). */
static bool same_batch(const sg_tri *a, const sg_tri *b) {
    return a->sh.front_facing == b->sh.front_facing;
}

/* The triangles of a tile of a draw with independent lanes (mt), one batch a facing. Visibility
 * first (deferred false): the colours of the lanes not discarded into mt->dst, and a discard
 * noted. In place (deferred): their depth into dp too (when not NULL). */
static void shade_groups(const sg_shade_ctx *c, const sg_mixed_tile *mt, float *dp,
                         const bool deferred) {
    uint32_t left = (1u << mt->n) - 1u; /* bit j: ts[j] not shaded yet */
    while (left) {
        const sg_tri *ts[SG_TILE_PIXELS];
        uint32_t masks[SG_TILE_PIXELS], mask = 0;
        const int first = __builtin_ctz(left);
        int n = 0;
        for (uint32_t m = left; m; m &= m - 1) {
            const int j = __builtin_ctz(m);
            if (!same_batch(mt->ts[j], mt->ts[first])) continue;
            ts[n] = mt->ts[j];
            masks[n++] = mt->masks[j];
            mask |= mt->masks[j];
            left &= ~(1u << j);
        }
        uint32_t px[SG_SHADER_LANES];
        _Alignas(64) float z[SG_TILE_PIXELS];
        uint32_t *const direct = deferred ? NULL : mt->dst;
        const uint32_t discard =
            n == 1 && !deferred
                ? shade_tile(c, ts[0], mt->x0, mt->y0, mask, px, direct)
                : SG_SAMPLE16_CALL(c->shader.sample16, shade_shared, c, ts, masks, n, mt->x0,
                                   mt->y0, mask, px, deferred ? z : NULL, direct);
        const uint32_t keep = mask & ~discard;
        if (deferred) {
            if (keep) SG_SAMPLE16_CALL(c->shader.sample16, put_tile, keep, z, dp, px, mt->dst);
            continue;
        }
        if (!sg_shade_direct(direct, mask, discard)) sg_fb_put_lanes(mt->dst, px, keep);
        if (keep != mask) note_discard(c);
    }
}

void sg_shade_shader_shared(const sg_shade_ctx *c, const sg_mixed_tile *tiles, int count) {
    for (int i = 0; i < count; i++) shade_groups(c, &tiles[i], NULL, false);
}

/* Opaque in-place draws with independent lanes put their fragments off: those that pass the
 * depth test wait in the bin's ids (the triangle's id at each waiting pixel, the tile marked in
 * reached), and a tile's waiting fragments are shaded together, one batch a facing, when a
 * triangle of the draw covers one of its waiting pixels, when another draw's triangle comes or
 * when the bin ends (the bin's sg_blend_pending.flush); then their depth and colour are written
 * where nothing was discarded. A pixel still sees the draw's triangles in order, and a waiting
 * fragment's depth test stays right: nothing else writes its pixel before it is shaded. */
void sg_shader_flush_tile(const sg_vis_ctx *v, int tile) {
    const int base = tile * SG_TILE_PIXELS;
    uint32_t *ids = v->ids + base;
    const sg_shade_ctx *c = v->shade_ctx;
    sg_mixed_tile mt;
    int n = 0;
    for (uint32_t left = ~sg_tile_same_id(ids, 0) & 0xffffu; left; n++) {
        const uint32_t id = ids[__builtin_ctz(left)];
        mt.ts[n] = &c->tris[id - 1];
        mt.masks[n] = sg_tile_same_id(ids, id);
        left &= ~mt.masks[n];
    }
    mt.n = n;
    const int row = SG_BIN_SIZE / SG_TILE; /* tiles a row of the bin */
    mt.x0 = v->bx0 + (tile % row) * SG_TILE;
    mt.y0 = v->by0 + (tile / row) * SG_TILE;
    mt.dst = v->color + base;
    shade_groups(c, &mt, v->pending->depth_write && v->depth ? v->depth + base : NULL, true);
    memset(ids, 0, SG_TILE_PIXELS * sizeof *ids);
    v->reached[tile] = 0;
}

void sg_shader_flush_waiting(sg_blend_pending *w, const sg_vis_ctx *v) {
    for (int word = 0; word < SG_REACHED_WORDS; word++)
        for (uint64_t left = sg_reached_word(v->reached, word); left; left &= left - 1)
            sg_shader_flush_tile(v, word * 64 + __builtin_ctzll(left));
    w->n = 0;
}

/* The portable walks: their depth test and writes from shade_shader_tile.h's portable copy. */
#define SG_SHADER_TILE_DEPTH(v, t, x0, y0, mask, dp, op, z)                                        \
    tile_depth_portable(t, x0, y0, mask, dp, op, z)
#define SG_SHADER_PUT_TILE(v, keep, z, dp, src, dst) put_tile_portable(keep, z, dp, src, dst)
#include "raster/shade_shader_walk.h"

sg_raster_fn sg_shader_in_place_select(bool blend, sgCompare compare, bool depth_write, bool defer,
                                       sg_isa isa) {
    const int kind = blend ? SG_SHADER_BLEND : defer ? SG_SHADER_DEFER : SG_SHADER_PUT;
    const bool test = compare != SG_COMPARE_ALWAYS;
    const sg_raster_fn fn = isa == SG_ISA_AVX512
                                ? sg_shader_in_place_avx512(kind, test, depth_write)
                            : isa == SG_ISA_AVX2 ? sg_shader_in_place_avx2(kind, test, depth_write)
                                                 : NULL;
    return fn ? fn : sg_shader_walks[kind][test][depth_write];
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
static void sample_mip(const sg_shader_tex *tx, const sg_shader_state *s, bool window,
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
    sg_sample16_mip(s->sample16, tx->mips, pick, s->bilinear, s->repeat, window, u, v, texel);
    sg_texels_to_unit(s->sample16, texel, rgba);
}

/* sgSample past its usual case. */
static __attribute__((noinline)) void sample_any(const sgFragmentBatch *b, int slot,
                                                 const float u[SG_SHADER_LANES],
                                                 const float v[SG_SHADER_LANES],
                                                 float rgba[4][SG_SHADER_LANES]) {
    const sg_shade_ctx *c = b && b->internal ? b->internal : NULL;
    const sg_shader_tex *tx =
        c && slot >= 0 && slot < SG_MAX_DRAW_TEXTURES && c->shader.textures[slot].data
            ? &c->shader.textures[slot]
            : NULL;
    if (tx && !tx->depth && c->shader.mipmap > SG_MIPMAP_NONE && tx->mips) {
        sample_mip(tx, &c->shader, c->texel_window, u, v, rgba);
        return;
    }
    if (tx && !tx->depth) {
        sg_sample16_unit(c->shader.sample16, &tx->mips->level[0], c->shader.bilinear,
                         c->shader.repeat, c->texel_window, u, v, rgba);
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

void sgSample(const sgFragmentBatch *b, int slot, const float u[SG_SHADER_LANES],
              const float v[SG_SHADER_LANES], float rgba[4][SG_SHADER_LANES]) {
    /* The usual case in a few instructions: a bound colour texture whose lookup the draw made. */
    const sg_shade_ctx *c = b ? b->internal : NULL;
    if (c && slot >= 0 && slot < SG_MAX_DRAW_TEXTURES && c->shader.textures[slot].unit) {
        const sg_shader_tex *tx = &c->shader.textures[slot];
        tx->unit(&tx->mips->level[0], u, v, rgba);
        return;
    }
    sample_any(b, slot, u, v, rgba);
}
