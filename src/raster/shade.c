/* shade.c - the portable scalar shading functions, the reference every SIMD variant must match
 * byte for byte (see shade.h), and the choice of variant. */
#include "raster/shade.h"

#include <stdio.h>
#include <string.h>

#include "raster/framebuffer.h"

/* The one body every variant is made from; the constant arguments fold away per variant, and
 * `flat` (a per-triangle constant, see sg_tri) is split off at the top into its own loops. */
static inline __attribute__((always_inline)) void
shade_rows(const sg_shade_ctx *c, const sg_tri *t, const sg_tri_ext *ext, int x0, int y0,
           uint32_t mask, uint32_t *dst, const int textured, const int bilinear, const int repeat,
           const int flat, const int sec) {
    float ox = (float)(x0 - t->minx), oy = (float)(y0 - t->miny);
    const int e = SG_LIT_SEC - SG_TRI_ATTRS; /* the secondary colour in ext */
    while (mask) {
        int bit = __builtin_ctz(mask);
        mask &= mask - 1;
        float dx = ox + (float)(bit & 3), dy = oy + (float)(bit >> 2);
        float w = 0.0f;
        if (textured || flat == SG_FLAT_NONE) w = 1.0f / (t->q + t->q_dx * dx + t->q_dy * dy);
        float col[4];
        for (int k = 0; k < 4; k++)
            col[k] = flat != SG_FLAT_NONE ? t->color[k]
                                          : (t->a[k] + t->a_dx[k] * dx + t->a_dy[k] * dy) * w;
        if (textured) {
            float s = (t->a[4] + t->a_dx[4] * dx + t->a_dy[4] * dy) * w;
            float u = (t->a[5] + t->a_dx[5] * dx + t->a_dy[5] * dy) * w;
            sg_texel tx = bilinear ? sg_sample_bilinear(&c->tex, s, u, repeat)
                                   : sg_sample_nearest(&c->tex, s, u, repeat);
            if (flat == SG_FLAT_WHITE && !sec) { /* 1 * texel / 255, back to unorm8: the texel */
                dst[bit] = sg_pack_rgba8((uint32_t)tx.c[0], (uint32_t)tx.c[1], (uint32_t)tx.c[2],
                                         (uint32_t)tx.c[3]);
                continue;
            }
            for (int k = 0; k < 4; k++) col[k] *= (float)tx.c[k] * (1.0f / 255.0f);
        }
        if (sec)
            for (int k = 0; k < 3; k++)
                col[k] += flat != SG_FLAT_NONE
                              ? ext->a[e + k]
                              : (ext->a[e + k] + ext->a_dx[e + k] * dx + ext->a_dy[e + k] * dy) * w;
        dst[bit] = sg_pack_rgba8(sg_to_unorm8(col[0]), sg_to_unorm8(col[1]), sg_to_unorm8(col[2]),
                                 sg_to_unorm8(col[3]));
    }
}

#define SG_SHADE_TABLE sg_shade_scalar
#include "raster/shade_variants.h"

int sg_shade_variant(sgShade shade, sgFilter filter, sgWrap wrap) {
    if (shade != SG_SHADE_TEXTURE_MODULATE) return 0;
    return 1 + (filter == SG_FILTER_BILINEAR ? 2 : 0) + (wrap == SG_WRAP_REPEAT ? 0 : 1);
}

sg_shade_fn sg_shade_select(sgShade shade, sgFilter filter, sgWrap wrap, sg_isa isa) {
    return sg_shade_select_variant(sg_shade_variant(shade, filter, wrap), isa);
}

sg_shade_fn sg_shade_select_variant(int variant, sg_isa isa) {
    sg_shade_fn fn = NULL;
    if (isa == SG_ISA_NEON) fn = sg_shade_neon(variant);
    if (fn || isa == SG_ISA_NEON) return fn ? fn : sg_shade_scalar(variant);
    /* The best set the ISA allows that is built: AVX-512, AVX2, SSE2, scalar. */
    if (isa >= SG_ISA_AVX512) fn = sg_shade_avx512(variant);
    if (!fn && isa >= SG_ISA_AVX2) fn = sg_shade_avx2(variant);
    if (!fn && isa >= SG_ISA_SSE2) fn = sg_shade_sse2(variant);
    return fn ? fn : sg_shade_scalar(variant);
}

sg_shade2_fn sg_shade2_select_variant(int variant, sg_isa isa) {
    if (isa == SG_ISA_AVX512) return sg_shade2_avx512(variant);
    return isa == SG_ISA_AVX2 ? sg_shade2_avx2(variant) : NULL;
}

sg_shade_runs_fn sg_shade_runs_select_variant(int variant, sg_isa isa) {
    if (isa == SG_ISA_AVX512) return sg_shade_runs_avx512(variant);
    return isa == SG_ISA_AVX2 ? sg_shade_runs_avx2(variant) : NULL;
}

sg_shade_mixed_fn sg_shade_mixed_select_variant(int variant, sg_isa isa) {
    if (variant >= SG_SHADE_VARIANTS) return NULL;
    if (isa == SG_ISA_AVX512) return sg_shade_mixed_avx512(variant);
    return isa == SG_ISA_AVX2 ? sg_shade_mixed_avx2(variant) : NULL;
}

int sg_shade_attr_count(sgShade shade) {
    return shade == SG_SHADE_TEXTURE_MODULATE ? 6 : 4;
}

sg_isa sg_isa_detect(void) {
#if defined(__x86_64__) || defined(__i386__)
    __builtin_cpu_init();
    /* libgcc and compiler-rt also check that the OS saves the AVX-512 state. */
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512vl") && __builtin_cpu_supports("avx512dq"))
        return SG_ISA_AVX512;
    if (__builtin_cpu_supports("avx2")) return SG_ISA_AVX2;
    if (__builtin_cpu_supports("sse2")) return SG_ISA_SSE2;
#elif defined(__aarch64__) && defined(__ARM_NEON)
    return SG_ISA_NEON; /* Advanced SIMD is part of every AArch64 CPU */
#endif
    return SG_ISA_SCALAR;
}

bool sg_texel_window_detect(void) {
#if defined(__x86_64__) || defined(__i386__)
    /* The window replaces gathers by row loads, permutes and a test, which fails on about half
     * the mipmapped lookups and is then mispredicted. Where gathers are slow (AMD's Zen 4) it
     * pays; on an Intel Xeon with AMX gathers alone are quicker (docs/performance.md, "Texel
     * windows"), unless the microcode's mitigation of gather data sampling, which the Linux
     * kernel reports here, slows every gather. */
    __builtin_cpu_init();
    if (!__builtin_cpu_is("intel")) return true;
#if defined(__linux__)
    FILE *f = fopen("/sys/devices/system/cpu/vulnerabilities/gather_data_sampling", "r");
    if (!f) return true; /* not known: gathers may be slowed */
    char line[64] = "";
    const bool read = fgets(line, sizeof line, f) != NULL;
    fclose(f);
    return !read ||
           !(strncmp(line, "Not affected", 12) == 0 || strncmp(line, "Vulnerable", 10) == 0);
#else
    return true;
#endif
#else
    /* no window in the other sets' lookups */
    return true;
#endif
}

bool sg_isa_runs(sg_isa isa) {
    sg_isa best = sg_isa_detect();
    if (isa == SG_ISA_SCALAR) return true;
    /* NEON and the x86 sets exclude each other: neither is "more" than the other. */
    if (isa == SG_ISA_NEON || best == SG_ISA_NEON) return isa == best;
    return isa <= best;
}
