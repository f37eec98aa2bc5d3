/* test_shade_simd.c - the SSE2, AVX2, AVX-512 and NEON shading functions give the scalar
 * reference's bytes. For every variant and flat mode, many random cases: plausible and perspective
 * plane equations, 1/q near 0, colours outside [0, 1], texture coordinates far outside [0, 1] (1e4,
 * 1e30, infinite, NaN), random masks over a sentinel-filled tile, and textures from 1x1 to 16384
 * texels wide; the same for the variants that add a secondary colour (flat and Gouraud lighting
 * with a specular material), for per-pixel lighting (random positions, normals, lights, materials),
 * and for shading that receives a shadow map (random maps, projections, PCF or not). The texels sit
 * in exactly-sized allocations (a stray load shows under AddressSanitizer) and, where there is
 * mmap, also right before or right after an inaccessible page, which catches stray reads in any
 * build, AVX2 and AVX-512 gathers (which AddressSanitizer does not see) included.
 */
#define _DEFAULT_SOURCE /* mmap, MAP_ANONYMOUS */
#include "test_common.h"
#include "test_rng.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#if defined(__unix__)
#include <sys/mman.h>
#include <unistd.h>
#define HAVE_GUARD_PAGES 1
#endif

#include "raster/bin.h"
#include "raster/framebuffer.h"
#include "raster/shade.h"
#include "tex/mipgen.h"

enum { CASES_PER_FLAT = 70000, VARIANTS = 5, FLATS = 3 };

static const char *const variant_names[VARIANTS] = {
    "vertex colour", "nearest repeat", "nearest clamp", "bilinear repeat", "bilinear clamp"};
static const char *const flat_names[FLATS] = {"NONE", "COLOR", "WHITE"};

/* A float of any kind: special values, extremes, or random bits (denormals, NaN payloads). */
static float wild(rng *g) {
    static const float special[] = {0.0f,  -0.0f,   1.0f,    -1.0f,        1e-30f,   -1e-30f,
                                    1e30f, -1e30f,  1e4f,    -1e4f,        INFINITY, -INFINITY,
                                    NAN,   -1e-10f, 8388608, 2147483648.0f};
    if (chance(g, 60)) return special[irange(g, 0, (int)(sizeof special / sizeof *special) - 1)];
    uint32_t bits = (uint32_t)next(g);
    float f;
    memcpy(&f, &bits, 4);
    return f;
}

/* A value within a few ulps of (n + 0.5) / 255, where v * 255 + 0.5 is nearly an integer. */
static float rounding_edge(rng *g) {
    float v = ((float)irange(g, -1, 255) + 0.5f) / 255.0f;
    for (int i = irange(g, -3, 3); i > 0; i--) v = nextafterf(v, INFINITY);
    for (int i = irange(g, -3, 3); i > 0; i--) v = nextafterf(v, -INFINITY);
    return v;
}

/* A texture coordinate at the tile: mostly near [0, 1], some far away or not finite. */
static float coord(rng *g) {
    switch (irange(g, 0, 9)) {
    case 0:
        return frange(g, -1e4f, 1e4f);
    case 1:
        return (chance(g, 50) ? 1.0f : -1.0f) * frange(g, 1e29f, 1e31f);
    case 2:
        return wild(g);
    case 3:
        return (float)irange(g, -4096, 4096) / 256.0f; /* on texel and half-texel edges */
    case 4:
        return -frange(g, 0.0f, 1e-6f); /* tiny negative: fraction rounds to 1 */
    default:
        return frange(g, -2.0f, 3.0f);
    }
}

/* A random triangle setup for the tile at (x0, y0); the planes are built so that the values at
 * the tile are the chosen ones (a = value * q), with gradients from none to steep. */
static void random_tri(rng *g, sg_tri *t, int flat, int tw, int th, int *x0, int *y0) {
    memset(t, 0, sizeof *t);
    t->minx = irange(g, 0, 1000);
    t->miny = irange(g, 0, 1000);
    *x0 = chance(g, 70) ? (t->minx & ~3) + 4 * irange(g, 0, 40) : t->minx + irange(g, -3, 200);
    *y0 = chance(g, 70) ? (t->miny & ~3) + 4 * irange(g, 0, 40) : t->miny + irange(g, -3, 200);
    float ox = (float)(*x0 - t->minx), oy = (float)(*y0 - t->miny);
    float q = 1.0f;
    switch (irange(g, 0, 5)) {
    case 0: /* affine: w = 1 exactly */
        t->q = 1.0f;
        break;
    case 1: /* constant but not 1 */
        t->q = q = frange(g, 0.01f, 4.0f);
        break;
    case 2: /* q near 0: w huge, or infinite at q == 0 */
        q = chance(g, 30) ? 0.0f : frange(g, -1e-6f, 1e-6f);
        t->q_dx = chance(g, 50) ? 0.0f : frange(g, -1e-7f, 1e-7f);
        t->q_dy = chance(g, 50) ? 0.0f : frange(g, -1e-7f, 1e-7f);
        t->q = q - t->q_dx * ox - t->q_dy * oy;
        break;
    case 3: /* anything */
        t->q = wild(g);
        t->q_dx = chance(g, 50) ? 0.0f : wild(g);
        t->q_dy = chance(g, 50) ? 0.0f : wild(g);
        break;
    default: /* perspective */
        q = frange(g, 0.02f, 2.0f);
        t->q_dx = q * frange(g, -0.05f, 0.05f);
        t->q_dy = q * frange(g, -0.05f, 0.05f);
        t->q = q - t->q_dx * ox - t->q_dy * oy;
        break;
    }
    for (int k = 0; k < 6; k++) {
        float v, d;
        if (k < 4) { /* colours, a few outside [0, 1], some on a rounding edge of unorm8 */
            v = chance(g, 5) ? wild(g) : frange(g, -0.3f, 1.3f);
            d = frange(g, -0.1f, 0.1f);
            if (chance(g, 20)) {
                v = rounding_edge(g);
                d = chance(g, 50) ? 0.0f : d * 1e-6f;
            }
        } else {
            int n = k == 4 ? tw : th;
            v = coord(g);
            d = chance(g, 20) ? 0.0f : frange(g, -3.0f, 3.0f) / (float)n;
            if (chance(g, 10)) d = (float)irange(g, -64, 64) / 1024.0f;
            if (chance(g, 3)) d = wild(g);
        }
        float dx = d * frange(g, -1.0f, 1.0f), dy = d * frange(g, -1.0f, 1.0f);
        t->a_dx[k] = dx * q;
        t->a_dy[k] = dy * q;
        t->a[k] = v * q - t->a_dx[k] * ox - t->a_dy[k] * oy;
        if (chance(g, 2)) t->a[k] = wild(g);
    }
    t->nattr = 6;
    t->flat = flat;
    for (int k = 0; k < 4; k++)
        t->color[k] = flat == SG_FLAT_WHITE ? 1.0f
                      : chance(g, 5)        ? wild(g)
                      : chance(g, 20)       ? rounding_edge(g)
                                            : frange(g, -0.2f, 1.2f);
}

static uint32_t random_mask(rng *g) {
    switch (irange(g, 0, 5)) {
    case 0:
        return 0xffffu;
    case 1:
        return 1u << irange(g, 0, 15);
    case 2:
        return 0xfu << (4 * irange(g, 0, 3)); /* one row */
    case 3:
        return (uint32_t)next(g) & (uint32_t)next(g) & 0xffffu;
    default:
        return (uint32_t)next(g) & 0xffffu;
    }
}

/* A texture and up to three placements of the same texels. */
typedef struct texture {
    int w, h;
    uint8_t *heap; /* malloc of exactly w * h * 4 */
#ifdef HAVE_GUARD_PAGES
    uint8_t *map; /* [guard][texels, flush against both guards][guard] */
    size_t map_size;
    uint8_t *at_start, *at_end; /* the two guarded copies */
#endif
} texture;

/* Random texels, or with `depth`, a shadow map: depths in [0, 1], many exactly 0 or 1, a few of
 * any kind. */
static void texture_make(texture *tex, rng *g, int w, int h, int depth) {
    size_t size = (size_t)w * (size_t)h * 4;
    tex->w = w;
    tex->h = h;
    tex->heap = malloc(size);
    assert_non_null(tex->heap);
    for (size_t i = 0; i < size && !depth; i++) tex->heap[i] = (uint8_t)next(g);
    for (size_t i = 0; i < size && depth; i += 4) {
        float d = chance(g, 10)  ? 1.0f
                  : chance(g, 5) ? 0.0f
                  : chance(g, 2) ? wild(g)
                                 : frange(g, 0.0f, 1.0f);
        memcpy(tex->heap + i, &d, 4);
    }
#ifdef HAVE_GUARD_PAGES
    size_t page = (size_t)sysconf(_SC_PAGESIZE);
    size_t body = (size + page - 1) / page * page;
    tex->map_size = body + 2 * page;
    tex->map =
        mmap(NULL, tex->map_size, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
    assert_true(tex->map != MAP_FAILED);
    assert_int_equal(mprotect(tex->map, page, PROT_NONE), 0);
    assert_int_equal(mprotect(tex->map + page + body, page, PROT_NONE), 0);
    tex->at_start = tex->map + page;
    tex->at_end = tex->map + page + body - size;
    memmove(tex->at_end, tex->heap, size);
    if (tex->at_start != tex->at_end) memcpy(tex->at_start, tex->heap, size);
#endif
}

/* The copy the next case reads: the heap one or a guarded one. Two copies overlap when the texture
 * is a whole number of pages; both hold the same texels. */
static const uint8_t *texture_pick(const texture *tex, rng *g) {
#ifdef HAVE_GUARD_PAGES
    int k = irange(g, 0, 2);
    if (k == 1) return tex->at_start;
    if (k == 2) return tex->at_end;
#else
    (void)g;
#endif
    return tex->heap;
}

static void texture_free(texture *tex) {
    free(tex->heap);
#ifdef HAVE_GUARD_PAGES
    munmap(tex->map, tex->map_size);
#endif
}

static void print_case(const char *isa, int variant, int flat, long n, const sg_tri *t, int x0,
                       int y0, uint32_t mask, const sg_texview *tv, const uint32_t *ref,
                       const uint32_t *got) {
    printf("%s differs: variant %d (%s), flat %s, case %ld, tile (%d, %d), mask %04x, texture "
           "%dx%d\n",
           isa, variant, variant_names[variant], flat_names[flat], n, x0, y0, (unsigned)mask,
           tv->width, tv->height);
    printf("  min (%d, %d) q %a %a %a color %a %a %a %a\n", t->minx, t->miny, (double)t->q,
           (double)t->q_dx, (double)t->q_dy, (double)t->color[0], (double)t->color[1],
           (double)t->color[2], (double)t->color[3]);
    for (int k = 0; k < 6; k++)
        printf("  a[%d] %a %a %a\n", k, (double)t->a[k], (double)t->a_dx[k], (double)t->a_dy[k]);
    for (int i = 0; i < 16; i++)
        if (ref[i] != got[i])
            printf("  pixel %2d%s: reference %08x, got %08x\n", i,
                   mask >> i & 1 ? "" : " (outside the mask)", (unsigned)ref[i], (unsigned)got[i]);
}

/* Runs `fn` on the case and compares with the reference output; false (and a report) on any
 * difference, inside or outside the mask. */
static int same_as_reference(sg_shade_fn fn, const char *isa, const sg_shade_ctx *ctx,
                             const sg_tri *t, const sg_tri_ext *ext, int x0, int y0, uint32_t mask,
                             uint32_t sentinel, const uint32_t *ref, int variant, int flat,
                             long n) {
    uint32_t got[16];
    for (int i = 0; i < 16; i++) got[i] = sentinel;
    (void)ext; /* found through ctx (sg_shade_ext) */
    fn(ctx, t, x0, y0, mask, got);
    if (!memcmp(ref, got, sizeof got)) return 1;
    print_case(isa, variant, flat, n, t, x0, y0, mask, &ctx->tex, ref, got);
    return 0;
}

/* A two-tile function on the tile at (x0, y0) and another of the triangle (a random one near it),
 * whole, against two calls of the reference. */
static int same_pair(sg_shade_fn ref, sg_shade2_fn pair, const sg_shade_ctx *ctx, const sg_tri *t,
                     int x0, int y0, rng *g) {
    const int x1 = x0 + 4 * (int)(next(g) % 5) - 8, y1 = y0 + 4 * (int)(next(g) % 3);
    uint32_t r0[16], r1[16], p0[16], p1[16];
    ref(ctx, t, x0, y0, 0xffffu, r0);
    ref(ctx, t, x1, y1, 0xffffu, r1);
    pair(ctx, t, x0, y0, x1, y1, p0, p1);
    if (!memcmp(r0, p0, sizeof r0) && !memcmp(r1, p1, sizeof r1)) return 1;
    printf("tiles (%d, %d) and (%d, %d): ", x0, y0, x1, y1);
    return 0;
}

enum { BIN_TILES = SG_BIN_SIZE / SG_TILE, BIN_PIXELS = SG_BIN_SIZE * SG_BIN_SIZE };

/* A packed-runs function on runs of distinct tiles of a bin around the tile at (x0, y0) (random
 * masks, some whole), against one reference call a run; bin_ref and bin_out hold a bin each. */
static int same_runs(sg_shade_fn ref, sg_shade_runs_fn runs, const sg_shade_ctx *ctx,
                     const sg_tri *t, int x0, int y0, uint32_t sentinel, rng *g, uint32_t *bin_ref,
                     uint32_t *bin_out) {
    const int bx0 = x0 - 4 * irange(g, 0, BIN_TILES - 1);
    const int by0 = y0 - 4 * irange(g, 0, BIN_TILES - 1);
    sg_run list[64];
    int nruns = irange(g, 1, 64);
    for (int i = 0; i < BIN_PIXELS; i++) bin_ref[i] = bin_out[i] = sentinel;
    for (int i = 0; i < nruns; i++) {
        int tile = irange(g, 0, BIN_TILES * BIN_TILES - 1);
        for (int j = 0; j < i; j++)
            if (list[j].tile == tile) tile = -1;
        if (tile < 0) { /* a triangle's runs are in different tiles */
            nruns = i;
            break;
        }
        uint32_t m = chance(g, 10) ? 0xffffu : random_mask(g);
        list[i] = (sg_run){(uint16_t)tile, (uint16_t)m};
        ref(ctx, t, bx0 + 4 * (tile % BIN_TILES), by0 + 4 * (tile / BIN_TILES), m,
            bin_ref + tile * 16);
    }
    runs(ctx, t, bx0, by0, list, nruns, bin_out);
    if (!memcmp(bin_ref, bin_out, BIN_PIXELS * sizeof *bin_out)) return 1;
    printf("%d runs: ", nruns);
    return 0;
}

/* The lit part of a case: a secondary colour's planes (kind SECONDARY), or a view position and
 * normal and the draw's lights (kind PHONG: positions around the eye, normals of any length or
 * none, one to eight lights of both kinds, specular colours and shininess from 0 to 128). */
enum { UNLIT, SECONDARY, PHONG, PHONG_SHADOW, UNLIT_SHADOW, SPLIT_SHADOW };

static void random_plane(rng *g, float value, float spread, float q, int x0, int y0,
                         const sg_tri *t, float *a, float *adx, float *ady) {
    float dx = spread * frange(g, -1.0f, 1.0f), dy = spread * frange(g, -1.0f, 1.0f);
    *adx = dx * q;
    *ady = dy * q;
    *a = value * q - *adx * (float)(x0 - t->minx) - *ady * (float)(y0 - t->miny);
}

static void random_lit(rng *g, int kind, int flat, const sg_tri *t, int x0, int y0, sg_tri_ext *ext,
                       sg_shade_ctx *ctx) {
    memset(ext, 0, sizeof *ext);
    float q = 1.0f / ((t->q + t->q_dx * (float)(x0 - t->minx)) + t->q_dy * (float)(y0 - t->miny));
    q = isfinite(q) && q != 0.0f ? 1.0f / q : 1.0f;
    if (kind == SECONDARY) {
        for (int k = 0; k < 3; k++) {
            float v = chance(g, 5) ? wild(g) : frange(g, -0.2f, 1.4f);
            if (flat)
                ext->a[k] = v; /* a flat triangle keeps its secondary colour as it is */
            else
                random_plane(g, v, 0.05f, q, x0, y0, t, &ext->a[k], &ext->a_dx[k], &ext->a_dy[k]);
        }
        return;
    }
    const int ep = SG_LIT_POS - SG_TRI_ATTRS, en = SG_LIT_NRM - SG_TRI_ATTRS;
    for (int k = 0; k < 3; k++) {
        float p = k == 2 ? frange(g, -6.0f, -0.5f) : frange(g, -2.0f, 2.0f);
        random_plane(g, p, 0.01f, q, x0, y0, t, &ext->a[ep + k], &ext->a_dx[ep + k],
                     &ext->a_dy[ep + k]);
        float nv = chance(g, 3) ? 0.0f : frange(g, -1.5f, 1.5f);
        random_plane(g, nv, chance(g, 50) ? 0.0f : 0.05f, q, x0, y0, t, &ext->a[en + k],
                     &ext->a_dx[en + k], &ext->a_dy[en + k]);
        if (chance(g, 1)) ext->a[en + k] = wild(g);
    }
    if (kind == SPLIT_SHADOW) /* flat and Gouraud receivers: the split colours (light.h) */
        for (int k = SG_LIT_SPLIT_D - SG_TRI_ATTRS; k < SG_LIT_SPLIT_END - SG_TRI_ATTRS; k++) {
            float v = chance(g, 5) ? wild(g) : frange(g, -0.2f, 1.4f);
            if (flat)
                ext->a[k] = v; /* constant on a flat triangle, kept as it is */
            else
                random_plane(g, v, 0.05f, q, x0, y0, t, &ext->a[k], &ext->a_dx[k], &ext->a_dy[k]);
        }
    sgLighting l;
    memset(&l, 0, sizeof l);
    l.light_count = irange(g, 0, SG_MAX_LIGHTS);
    for (int k = 0; k < 3; k++) l.ambient[k] = frange(g, 0.0f, 0.4f);
    for (int i = 0; i < l.light_count; i++) {
        sgLight *li = &l.lights[i];
        li->type = chance(g, 50) ? SG_LIGHT_DIRECTIONAL : SG_LIGHT_POINT;
        for (int k = 0; k < 3; k++) {
            li->direction[k] = frange(g, -1.0f, 1.0f);
            li->position[k] = k == 2 ? frange(g, -6.0f, 2.0f) : frange(g, -3.0f, 3.0f);
            li->color[k] = frange(g, 0.0f, 1.5f);
            li->attenuation[k] = chance(g, 50) ? 0.0f : frange(g, 0.0f, 0.5f);
        }
        li->direction[0] += 0.01f; /* never zero */
    }
    float spec[3] = {chance(g, 30) ? 0.0f : frange(g, 0.0f, 1.0f), frange(g, 0.0f, 1.0f),
                     frange(g, 0.0f, 1.0f)};
    float shine = chance(g, 10) ? 0.0f : chance(g, 10) ? 128.0f : frange(g, 0.0f, 128.0f);
    assert_true(sg_light_prepare(&l, spec, shine, &ctx->lights, NULL, NULL));
}

/* The shadow map of a case (kinds PHONG_SHADOW, UNLIT_SHADOW): one of the maps, a light's
 * orthographic or perspective projection of the positions random_lit makes (most points land
 * inside the map, with depths around its values), sometimes with points behind the light or wild
 * entries; PCF or not, and any of the draw's lights. */
static void random_shadow(rng *g, const texture *maps, int nmaps, sg_shade_ctx *ctx) {
    const texture *m = &maps[irange(g, 0, nmaps - 1)];
    sg_shadow_view *s = &ctx->shadow;
    s->map = (const float *)(const void *)texture_pick(m, g);
    s->width = m->w;
    s->height = m->h;
    s->pcf = chance(g, 50);
    s->light = ctx->lights.count ? irange(g, 0, ctx->lights.count - 1) : 0;
    float *a = s->m;
    memset(a, 0, sizeof s->m);
    float scale = frange(g, 0.2f, 1.0f);
    for (int i = 0; i < 16; i++) a[i] = frange(g, -0.05f, 0.05f);
    a[0] += scale;
    a[5] += scale;
    a[3] += frange(g, -0.3f, 0.3f);
    a[7] += frange(g, -0.3f, 0.3f);
    if (chance(g, 50)) { /* orthographic: w = 1 */
        a[10] += -0.33f;
        a[11] += -1.0f;
        a[12] = a[13] = a[14] = 0.0f;
        a[15] = 1.0f;
    } else { /* perspective: w = -z + c (c < 0 puts near points behind the light) */
        a[10] += -1.2f;
        a[11] += -1.5f;
        a[12] = a[13] = 0.0f;
        a[14] = -1.0f;
        a[15] = frange(g, -1.0f, 2.0f);
    }
    if (chance(g, 3)) a[irange(g, 0, 15)] = wild(g);
}

/* How much of the shadowing light reaches the tile's first pixel (0 none, 1 part, 2 all): a
 * check that the random cases cover every outcome. */
static int shadow_kind(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0,
                       int y0) {
    const float dx = (float)(x0 - t->minx), dy = (float)(y0 - t->miny);
    const float w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
    const int ep = SG_LIT_POS - SG_TRI_ATTRS;
    float P[3];
    for (int k = 0; k < 3; k++)
        P[k] = (ext->a[ep + k] + ext->a_dx[ep + k] * dx + ext->a_dy[ep + k] * dy) * w;
    float vis = sg_shadow_visibility(&c->shadow, P);
    return vis == 0.0f ? 0 : vis == 1.0f ? 2 : 1;
}

/* cases_per_flat: CASES_PER_FLAT, or main's argument (fewer under emulation). */
static void compare_variant(long cases_per_flat, int variant, int kind) {
    static const int sizes[][2] = {{1, 1},
                                   {1, 7},
                                   {3, 5},
                                   {64, 64},
                                   {256, 128},
                                   {17, 300},
                                   {7, 1},
                                   {2048, 40},
                                   {16384, 1},
                                   {1, 16384},
                                   {5, 3},
                                   {33, 2},
                                   /* the smallest textures AVX-512 reads through an 8 x 8 window */
                                   {8, 8},
                                   {8, 9},
                                   {9, 8},
                                   {7, 8}};
    enum { NSIZES = sizeof sizes / sizeof *sizes };
    rng g = {0x5eed0000u + (uint64_t)variant + 100u * (uint64_t)kind};
    texture tex[NSIZES];
    for (int i = 0; i < NSIZES; i++) texture_make(&tex[i], &g, sizes[i][0], sizes[i][1], 0);
    static const int map_sizes[][2] = {{1, 1}, {7, 5}, {64, 64}, {300, 17}, {16, 1024}};
    enum { NMAPS = sizeof map_sizes / sizeof *map_sizes };
    texture maps[NMAPS];
    for (int i = 0; i < NMAPS; i++) texture_make(&maps[i], &g, map_sizes[i][0], map_sizes[i][1], 1);
    const int shadow = kind == PHONG_SHADOW || kind == UNLIT_SHADOW || kind == SPLIT_SHADOW;
    const int textured = variant != 0;
    /* NEON is not "above" the x86 sets: each set is asked for by whether this CPU runs it. */
    const bool has_avx2 = sg_isa_runs(SG_ISA_AVX2), has_avx512 = sg_isa_runs(SG_ISA_AVX512),
               has_neon = sg_isa_runs(SG_ISA_NEON);
    const int index = variant + (kind == SECONDARY ? SG_SHADE_SECONDARY : 0);
    sg_shade_fn scalar, sse2 = NULL, avx2 = NULL, avx512 = NULL, neon = NULL;
    /* AVX2's and AVX-512's two whole tiles at once, for the unlit variants */
    sg_shade2_fn pair[2] = {NULL, NULL};
    /* AVX2's and AVX-512's partly covered tiles packed together */
    sg_shade_runs_fn runs[2] = {NULL, NULL};
    /* AVX2's and AVX-512's tiles that several triangles share, in one pass */
    sg_shade_mixed_fn mixed[2] = {NULL, NULL};
    static const char *const set_name[2] = {"AVX2", "AVX-512"};
    if (kind >= PHONG) {
        const int pixel = (kind == PHONG          ? SG_PIXEL_PHONG
                           : kind == PHONG_SHADOW ? SG_PIXEL_PHONG_SHADOW
                           : kind == SPLIT_SHADOW ? SG_PIXEL_SPLIT_SHADOW
                                                  : SG_PIXEL_SHADOW) +
                          variant;
        scalar = sg_shade_phong_scalar(pixel);
        if (has_avx2) avx2 = sg_shade_phong_avx2(pixel);
        if (has_avx512) avx512 = sg_shade_phong_avx512(pixel);
        if (has_neon) neon = sg_shade_phong_neon(pixel);
#if defined(__aarch64__)
        assert_non_null(neon);
#endif
    } else {
        scalar = sg_shade_scalar(index);
        sse2 = sg_shade_sse2(index);
        if (has_avx2) avx2 = sg_shade_avx2(index);
        if (has_avx512) avx512 = sg_shade_avx512(index);
        if (has_avx2) pair[0] = sg_shade2_avx2(index);
        if (has_avx512) pair[1] = sg_shade2_avx512(index);
        if (has_avx2) runs[0] = sg_shade_runs_avx2(index);
        if (has_avx512) runs[1] = sg_shade_runs_avx512(index);
        if (has_avx2 && kind == UNLIT) mixed[0] = sg_shade_mixed_avx2(index);
        if (has_avx512 && kind == UNLIT) mixed[1] = sg_shade_mixed_avx512(index);
        if (has_neon) neon = sg_shade_neon(index);
#if defined(__aarch64__)
        assert_non_null(neon); /* Advanced SIMD is the AArch64 baseline */
#endif
#if defined(__x86_64__)
        if (kind == UNLIT) assert_non_null(sse2); /* SSE2 is the x86-64 baseline */
        if (has_avx2) assert_non_null(avx2);
        if (has_avx512) assert_non_null(avx512);
        if (has_avx2 && kind == UNLIT) assert_non_null(mixed[0]);
        if (has_avx512 && kind == UNLIT) assert_non_null(mixed[1]);
#endif
    }
    const long cases = kind >= PHONG ? cases_per_flat / 7 : cases_per_flat;
    long seen[3] = {0, 0, 0}; /* shadow kinds: pixel 0 hidden, partly seen, seen */
    long failures = 0;
    uint32_t *bin_ref = malloc(BIN_PIXELS * sizeof *bin_ref);
    uint32_t *bin_out = malloc(BIN_PIXELS * sizeof *bin_out);
    assert_non_null(bin_ref);
    assert_non_null(bin_out);
    for (int flat = 0; flat < FLATS; flat++) {
        for (long n = 0; n < cases && failures < 5; n++) {
            const texture *tx = &tex[n % NSIZES];
            sg_shade_ctx ctx;
            memset(&ctx, 0, sizeof ctx);
            ctx.texel_window = n & 1; /* the window tried or not: the same texels */
            ctx.tex = sg_texview_of(texture_pick(tx, &g), tx->w, tx->h);
            if (!textured) ctx.tex.texels = NULL; /* a vertex-colour pipeline binds none */
            sg_tri t;
            sg_tri_ext ext, *e = kind == UNLIT ? NULL : &ext;
            int x0, y0;
            random_tri(&g, &t, flat, tx->w, tx->h, &x0, &y0);
            if (kind != UNLIT)
                random_lit(&g, kind == SECONDARY || kind == SPLIT_SHADOW ? kind : PHONG, flat, &t,
                           x0, y0, &ext, &ctx);
            if (shadow) {
                random_shadow(&g, maps, NMAPS, &ctx);
                seen[shadow_kind(&ctx, &t, &ext, x0, y0)]++;
            }
            uint32_t mask = random_mask(&g), sentinel = (uint32_t)next(&g);
            uint32_t ref[16];
            for (int i = 0; i < 16; i++) ref[i] = sentinel;
            ctx.tris = &t;
            ctx.ext = e;
            scalar(&ctx, &t, x0, y0, mask, ref);
            for (int i = 0; i < 16; i++)
                if (!(mask >> i & 1)) assert_int_equal(ref[i], sentinel);
            if (sse2 && !same_as_reference(sse2, "SSE2", &ctx, &t, e, x0, y0, mask, sentinel, ref,
                                           variant, flat, n))
                failures++;
            if (avx2 && !same_as_reference(avx2, "AVX2", &ctx, &t, e, x0, y0, mask, sentinel, ref,
                                           variant, flat, n))
                failures++;
            if (avx512 && !same_as_reference(avx512, "AVX-512", &ctx, &t, e, x0, y0, mask, sentinel,
                                             ref, variant, flat, n))
                failures++;
            if (neon && !same_as_reference(neon, "NEON", &ctx, &t, e, x0, y0, mask, sentinel, ref,
                                           variant, flat, n))
                failures++;
            for (int set = 0; set < 2; set++) {
                if (!pair[set]) continue;
                if (!same_pair(scalar, pair[set], &ctx, &t, x0, y0, &g)) {
                    printf("%s pair differs: variant %d flat %d case %ld\n", set_name[set], variant,
                           flat, n);
                    failures++;
                }
            }
            for (int set = 0; set < 2; set++) {
                if (!mixed[set] || n % 2 != 0) continue;
                /* One or two tiles, each shared by two to four triangles of the same flat kind,
                 * its pixels dealt out at random: as one scalar call per triangle. Each triangle
                 * is made at a tile of its own and moved, bounds and all, to this one (the second
                 * tile: a neighbour), which keeps its values there. */
                sg_tri ts[2][4];
                sg_mixed_tile mt[2];
                uint32_t got[2][16], want[2][16];
                const int count = irange(&g, 1, 2);
                int made = 0;
                for (int i = 0; i < count; i++) {
                    const int cx = x0 + 4 * i, cy = y0;
                    const int k = irange(&g, 2, 4);
                    uint32_t masks[4] = {0, 0, 0, 0};
                    const uint32_t all = chance(&g, 30) ? 0xffffu : random_mask(&g);
                    for (int b = 0; b < 16; b++)
                        if (all >> b & 1) masks[irange(&g, 0, k - 1)] |= 1u << b;
                    sg_mixed_tile *m = &mt[made];
                    m->n = 0;
                    for (int j = 0; j < k; j++) {
                        int xj, yj;
                        random_tri(&g, &ts[made][j], flat, tx->w, tx->h, &xj, &yj);
                        ts[made][j].minx += cx - xj;
                        ts[made][j].miny += cy - yj;
                        if (!masks[j]) continue;
                        m->ts[m->n] = &ts[made][j];
                        m->masks[m->n++] = masks[j];
                    }
                    if (m->n < 2) continue;
                    m->x0 = cx;
                    m->y0 = cy;
                    m->dst = got[made];
                    for (int b = 0; b < 16; b++) got[made][b] = want[made][b] = sentinel;
                    for (int j = 0; j < m->n; j++)
                        scalar(&ctx, m->ts[j], cx, cy, m->masks[j], want[made]);
                    made++;
                }
                if (made) {
                    mixed[set](&ctx, mt, made);
                    if (memcmp(got, want, (size_t)made * sizeof got[0])) {
                        printf("%s mixed tiles differ: variant %d flat %d case %ld, %d tiles\n",
                               set_name[set], variant, flat, n, made);
                        failures++;
                    }
                }
            }
            for (int set = 0; set < 2; set++) {
                if (!runs[set] || n % 8 != 0) continue;
                if (!same_runs(scalar, runs[set], &ctx, &t, x0, y0, sentinel, &g, bin_ref,
                               bin_out)) {
                    printf("%s runs differ: variant %d flat %d case %ld\n", set_name[set], variant,
                           flat, n);
                    failures++;
                }
            }
        }
    }
    for (int i = 0; i < NSIZES; i++) texture_free(&tex[i]);
    for (int i = 0; i < NMAPS; i++) texture_free(&maps[i]);
    free(bin_ref);
    free(bin_out);
    assert_int_equal(failures, 0);
    if (shadow) { /* the cases reach every outcome of the comparison */
        printf("pixel 0 hidden %ld, partly seen %ld, seen %ld\n", seen[0], seen[1], seen[2]);
        assert_true(seen[0] > cases / 20 && seen[2] > cases / 20);
        if (cases > 0) assert_true(seen[1] > cases / 100);
    }
}

/* Mipmapped shading (shade_mip.c, the portable reference, against AVX-512's single tiles,
 * pairs and packed runs, and AVX2's): chains from 1 x 1 to 300 x 17 texels,
 * derivatives from magnified to far past the last level, every filter, wrap, secondary colour and
 * flat kind, random masks (quads with no covered pixel among them). Each level is an allocation of
 * its own, exactly sized. */
static void compare_mip(int linear) {
    static const int sizes[][2] = {{1, 1}, {2, 1}, {8, 8}, {64, 64}, {300, 17}, {9, 130}, {33, 32}};
    enum { NSIZES = sizeof sizes / sizeof *sizes, MIP_CASES = 6000 };
    /* the sets with their own mipmapped shading; the portable reference is every other set's */
    static const struct {
        sg_isa isa;
        const char *name;
        sg_shade_fn (*fn)(int);
        sg_shade2_fn (*pair)(int);
        sg_shade_runs_fn (*runs)(int);
    } sets[] = {
        {SG_ISA_AVX512, "AVX-512", sg_shade_mip_avx512, sg_shade2_mip_avx512,
         sg_shade_runs_mip_avx512},
        {SG_ISA_AVX2, "AVX2", sg_shade_mip_avx2, sg_shade2_mip_avx2, sg_shade_runs_mip_avx2},
    };
    rng g = {0x5eed4d00u + (uint64_t)linear};
    sg_mip_chain chains[NSIZES];
    for (int i = 0; i < NSIZES; i++) {
        int w = sizes[i][0], h = sizes[i][1];
        chains[i].levels = sg_mip_chain_length(w, h);
        for (int l = 0; l < chains[i].levels; l++) {
            uint8_t *texels = malloc((size_t)w * (size_t)h * 4);
            assert_non_null(texels);
            for (size_t b = 0; b < (size_t)w * (size_t)h * 4; b++) texels[b] = (uint8_t)next(&g);
            chains[i].level[l] = sg_texview_of(texels, w, h);
            w = sg_mip_next_side(w);
            h = sg_mip_next_side(h);
        }
    }
    uint32_t *bin_ref = malloc(BIN_PIXELS * sizeof *bin_ref);
    uint32_t *bin_out = malloc(BIN_PIXELS * sizeof *bin_out);
    assert_non_null(bin_ref);
    assert_non_null(bin_out);
    long failures = 0;
    for (size_t set = 0; set < sizeof sets / sizeof *sets; set++) {
        const char *name = sets[set].name;
        if (!sg_isa_runs(sets[set].isa)) {
            printf("%s is not run here: not compared\n", name);
            continue;
        }
        for (int index = linear * 8; index < linear * 8 + 8 && failures < 5; index++) {
            const int sec = index & 1;
            const sg_shade_fn ref = sg_shade_mip_portable(index), fn = sets[set].fn(index);
            const sg_shade2_fn pair = sets[set].pair(index);
            const sg_shade_runs_fn runs = sets[set].runs ? sets[set].runs(index) : NULL;
            assert_non_null(fn);
            assert_non_null(pair);
            assert_true(runs || !sets[set].runs);
            for (int flat = 0; flat < FLATS; flat++) {
                for (long n = 0; n < MIP_CASES && failures < 5; n++) {
                    const sg_mip_chain *m = &chains[n % NSIZES];
                    sg_shade_ctx ctx;
                    memset(&ctx, 0, sizeof ctx);
                    ctx.texel_window = n & 1;
                    ctx.tex = m->level[0];
                    ctx.mips = m;
                    sg_tri t;
                    sg_tri_ext ext;
                    int x0, y0;
                    random_tri(&g, &t, flat, m->level[0].width, m->level[0].height, &x0, &y0);
                    const float minify = (float)(1 << irange(&g, 0, 12));
                    for (int k = 4; k < 6; k++) {
                        t.a_dx[k] *= minify;
                        t.a_dy[k] *= minify;
                    }
                    if (sec) random_lit(&g, SECONDARY, flat, &t, x0, y0, &ext, &ctx);
                    ctx.tris = &t;
                    ctx.ext = sec ? &ext : NULL;
                    const uint32_t mask = random_mask(&g), sentinel = (uint32_t)next(&g);
                    uint32_t want[16], got[16];
                    for (int i = 0; i < 16; i++) want[i] = got[i] = sentinel;
                    ref(&ctx, &t, x0, y0, mask, want);
                    fn(&ctx, &t, x0, y0, mask, got);
                    if (memcmp(want, got, sizeof got)) {
                        printf("%s mipmapped differs: index %d flat %d case %ld, mask %04x\n", name,
                               index, flat, n, (unsigned)mask);
                        failures++;
                    }
                    if (!same_pair(ref, pair, &ctx, &t, x0, y0, &g)) {
                        printf("%s mipmapped pair differs: index %d flat %d case %ld\n", name,
                               index, flat, n);
                        failures++;
                    }
                    if (runs && n % 4 == 0 &&
                        !same_runs(ref, runs, &ctx, &t, x0, y0, sentinel, &g, bin_ref, bin_out)) {
                        printf("%s mipmapped runs differ: index %d flat %d case %ld\n", name, index,
                               flat, n);
                        failures++;
                    }
                }
            }
        }
    }
    for (int i = 0; i < NSIZES; i++)
        for (int l = 0; l < chains[i].levels; l++) free((void *)chains[i].level[l].texels);
    free(bin_ref);
    free(bin_out);
    assert_int_equal(failures, 0);
}

static void mip_nearest_level(void **state) {
    (void)state;
    compare_mip(0);
}

static void mip_linear(void **state) {
    (void)state;
    compare_mip(1);
}

static void vertex_colour(void **state) {
    compare_variant(*(const long *)*state, 0, UNLIT);
}

static void vertex_colour_secondary(void **state) {
    compare_variant(*(const long *)*state, 0, SECONDARY);
}

static void vertex_colour_phong(void **state) {
    compare_variant(*(const long *)*state, 0, PHONG);
}

static void nearest_repeat(void **state) {
    compare_variant(*(const long *)*state, 1, UNLIT);
}

static void nearest_repeat_secondary(void **state) {
    compare_variant(*(const long *)*state, 1, SECONDARY);
}

static void nearest_repeat_phong(void **state) {
    compare_variant(*(const long *)*state, 1, PHONG);
}

static void nearest_clamp(void **state) {
    compare_variant(*(const long *)*state, 2, UNLIT);
}

static void nearest_clamp_secondary(void **state) {
    compare_variant(*(const long *)*state, 2, SECONDARY);
}

static void nearest_clamp_phong(void **state) {
    compare_variant(*(const long *)*state, 2, PHONG);
}

static void bilinear_repeat(void **state) {
    compare_variant(*(const long *)*state, 3, UNLIT);
}

static void bilinear_repeat_secondary(void **state) {
    compare_variant(*(const long *)*state, 3, SECONDARY);
}

static void bilinear_repeat_phong(void **state) {
    compare_variant(*(const long *)*state, 3, PHONG);
}

static void bilinear_clamp(void **state) {
    compare_variant(*(const long *)*state, 4, UNLIT);
}

static void bilinear_clamp_secondary(void **state) {
    compare_variant(*(const long *)*state, 4, SECONDARY);
}

static void bilinear_clamp_phong(void **state) {
    compare_variant(*(const long *)*state, 4, PHONG);
}

static void vertex_colour_phong_shadow(void **state) {
    compare_variant(*(const long *)*state, 0, PHONG_SHADOW);
}

static void vertex_colour_unlit_shadow(void **state) {
    compare_variant(*(const long *)*state, 0, UNLIT_SHADOW);
}

static void nearest_repeat_phong_shadow(void **state) {
    compare_variant(*(const long *)*state, 1, PHONG_SHADOW);
}

static void nearest_repeat_unlit_shadow(void **state) {
    compare_variant(*(const long *)*state, 1, UNLIT_SHADOW);
}

static void nearest_clamp_phong_shadow(void **state) {
    compare_variant(*(const long *)*state, 2, PHONG_SHADOW);
}

static void nearest_clamp_unlit_shadow(void **state) {
    compare_variant(*(const long *)*state, 2, UNLIT_SHADOW);
}

static void bilinear_repeat_phong_shadow(void **state) {
    compare_variant(*(const long *)*state, 3, PHONG_SHADOW);
}

static void bilinear_repeat_unlit_shadow(void **state) {
    compare_variant(*(const long *)*state, 3, UNLIT_SHADOW);
}

static void bilinear_clamp_phong_shadow(void **state) {
    compare_variant(*(const long *)*state, 4, PHONG_SHADOW);
}

static void bilinear_clamp_unlit_shadow(void **state) {
    compare_variant(*(const long *)*state, 4, UNLIT_SHADOW);
}

static void vertex_colour_split_shadow(void **state) {
    compare_variant(*(const long *)*state, 0, SPLIT_SHADOW);
}

static void nearest_repeat_split_shadow(void **state) {
    compare_variant(*(const long *)*state, 1, SPLIT_SHADOW);
}

static void nearest_clamp_split_shadow(void **state) {
    compare_variant(*(const long *)*state, 2, SPLIT_SHADOW);
}

static void bilinear_repeat_split_shadow(void **state) {
    compare_variant(*(const long *)*state, 3, SPLIT_SHADOW);
}

static void bilinear_clamp_split_shadow(void **state) {
    compare_variant(*(const long *)*state, 4, SPLIT_SHADOW);
}

/* test_shade_simd [CASES]: CASES random cases per variant and flat mode (a seventh of them for
 * per-pixel lighting), CASES_PER_FLAT by default; the emulated AArch64 run asks for fewer. */
int main(int argc, char **argv) {
    long cases = argc > 1 ? strtol(argv[1], NULL, 10) : CASES_PER_FLAT;
    if (cases < 700) {
        fprintf(stderr, "test_shade_simd: CASES must be 700 or more\n");
        return 2;
    }
    const struct CMUnitTest tests[] = {
        cmocka_unit_test_prestate(vertex_colour, &cases),
        cmocka_unit_test_prestate(nearest_repeat, &cases),
        cmocka_unit_test_prestate(nearest_clamp, &cases),
        cmocka_unit_test_prestate(bilinear_repeat, &cases),
        cmocka_unit_test_prestate(bilinear_clamp, &cases),
        cmocka_unit_test_prestate(vertex_colour_secondary, &cases),
        cmocka_unit_test_prestate(nearest_repeat_secondary, &cases),
        cmocka_unit_test_prestate(nearest_clamp_secondary, &cases),
        cmocka_unit_test_prestate(bilinear_repeat_secondary, &cases),
        cmocka_unit_test_prestate(bilinear_clamp_secondary, &cases),
        cmocka_unit_test_prestate(vertex_colour_phong, &cases),
        cmocka_unit_test_prestate(nearest_repeat_phong, &cases),
        cmocka_unit_test_prestate(nearest_clamp_phong, &cases),
        cmocka_unit_test_prestate(bilinear_repeat_phong, &cases),
        cmocka_unit_test_prestate(bilinear_clamp_phong, &cases),
        cmocka_unit_test_prestate(vertex_colour_phong_shadow, &cases),
        cmocka_unit_test_prestate(vertex_colour_unlit_shadow, &cases),
        cmocka_unit_test_prestate(nearest_repeat_phong_shadow, &cases),
        cmocka_unit_test_prestate(nearest_repeat_unlit_shadow, &cases),
        cmocka_unit_test_prestate(nearest_clamp_phong_shadow, &cases),
        cmocka_unit_test_prestate(nearest_clamp_unlit_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_repeat_phong_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_repeat_unlit_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_clamp_phong_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_clamp_unlit_shadow, &cases),
        cmocka_unit_test_prestate(vertex_colour_split_shadow, &cases),
        cmocka_unit_test_prestate(nearest_repeat_split_shadow, &cases),
        cmocka_unit_test_prestate(nearest_clamp_split_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_repeat_split_shadow, &cases),
        cmocka_unit_test_prestate(bilinear_clamp_split_shadow, &cases),
        cmocka_unit_test(mip_nearest_level),
        cmocka_unit_test(mip_linear),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
