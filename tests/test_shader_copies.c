/* test_shader_copies.c - the compilations of the built-in shaders (apps/shaders/library.c: the
 * baseline, AVX2 and AVX-512 copies) give the same bits: every shader's vertex and fragment stages
 * on the same random batches, each copy this CPU runs against the baseline, outputs compared
 * byte for byte. Some lanes hold zeros of both signs, infinities and NaN, so that the copies'
 * comparisons and square roots meet them too. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "test_common.h"

#include "builtin.h"

static uint32_t next(uint32_t *s) {
    *s = *s * 1664525u + 1013904223u;
    return *s;
}

static float rnd(uint32_t *s, float lo, float hi) {
    return lo + (hi - lo) * (float)(next(s) >> 8) * (1.0f / 16777216.0f);
}

/* Mostly a value in [lo, hi]; one time in 16 a special one. */
static float value(uint32_t *s, float lo, float hi) {
    static const float special[] = {0.0f, -0.0f, 1.0f, -1.0f, 1e30f, -1e30f, 1e-40f};
    if (next(s) >> 28) return rnd(s, lo, hi);
    const uint32_t k = next(s) >> 24;
    if (k < 16) return (float)(k & 1 ? -INFINITY : INFINITY);
    if (k < 32) return NAN;
    return special[k % (sizeof special / sizeof special[0])];
}

/* The first of n floats whose bits differ, -1 if none. Any NaN equals any other: which operand's
 * NaN an operation passes on depends on the order the compiler gives a commutative operation's
 * operands, and sgapi reads every NaN alike (a colour as 0, a clip position drops its triangle). */
static int first_difference(const float *a, const float *b, int n) {
    for (int i = 0; i < n; i++)
        if (memcmp(&a[i], &b[i], sizeof a[i]) && !(isnan(a[i]) && isnan(b[i]))) return i;
    return -1;
}

static void fill(uint32_t *s, float *p, size_t n, float lo, float hi) {
    for (size_t i = 0; i < n; i++) p[i] = value(s, lo, hi);
}

enum { ROUNDS = 400 };

/* A shader of a copy against the baseline's, on ROUNDS batches of each stage. */
static void compare(const sgShaderInfo *base, const sgShaderInfo *copy, const char *set) {
    uint32_t s = 12345u;
    float uniforms[256];
    assert_true(base->uniform_count <= (int)(sizeof uniforms / sizeof uniforms[0]));
    for (int round = 0; round < ROUNDS; round++) {
        fill(&s, uniforms, (size_t)base->uniform_count, -2.0f, 2.0f);
        if (round % 2) /* plausible uniforms too: counts and switches in range */
            for (int k = 0; k < base->uniform_count; k++) uniforms[k] = rnd(&s, 0.0f, 3.0f);
        float world_view[16], proj[16];
        fill(&s, world_view, 16, -1.0f, 1.0f);
        fill(&s, proj, 16, -1.0f, 1.0f);

        static sgVertexBatch v[2];
        memset(&v[0], 0x55, sizeof v[0]);
        v[0].count = 1 + (int)(next(&s) % SG_SHADER_LANES);
        v[0].instance = (int)(next(&s) % 5000u);
        for (int i = 0; i < SG_SHADER_LANES; i++) v[0].index[i] = next(&s) % 100000u;
        fill(&s, &v[0].position[0][0], 4 * SG_SHADER_LANES, -3.0f, 3.0f);
        fill(&s, &v[0].color[0][0], 4 * SG_SHADER_LANES, 0.0f, 1.0f);
        fill(&s, &v[0].normal[0][0], 3 * SG_SHADER_LANES, -1.0f, 1.0f);
        fill(&s, &v[0].texcoord[0][0], 2 * SG_SHADER_LANES, -2.0f, 2.0f);
        fill(&s, &v[0].attribute[0][0][0], SG_MAX_ATTRIBUTES * 4 * SG_SHADER_LANES, -2.0f, 2.0f);
        v[0].world_view = world_view;
        v[0].proj = proj;
        v[1] = v[0];
        base->desc.vertex(&v[0], uniforms);
        copy->desc.vertex(&v[1], uniforms);
        const int vc = first_difference(&v[0].clip[0][0], &v[1].clip[0][0], 4 * SG_SHADER_LANES);
        const int vv = first_difference(&v[0].varying[0][0], &v[1].varying[0][0],
                                        SG_MAX_VARYINGS * SG_SHADER_LANES);
        if (vc >= 0)
            fail_msg("%s: the %s copy's vertex stage differs from the baseline's (round %d, clip "
                     "%d lane %d: %a against %a)",
                     base->name, set, round, vc / SG_SHADER_LANES, vc % SG_SHADER_LANES,
                     (double)v[1].clip[0][vc], (double)v[0].clip[0][vc]);
        if (vv >= 0)
            fail_msg("%s: the %s copy's vertex stage differs from the baseline's (round %d, "
                     "varying %d lane %d: %a against %a)",
                     base->name, set, round, vv / SG_SHADER_LANES, vv % SG_SHADER_LANES,
                     (double)v[1].varying[0][vv], (double)v[0].varying[0][vv]);

        static sgFragmentBatch f[2];
        memset(&f[0], 0x55, sizeof f[0]);
        f[0].mask = next(&s) >> 16 | 1u;
        f[0].x = (int)(next(&s) % 1024u) & ~3;
        f[0].y = (int)(next(&s) % 1024u) & ~3;
        fill(&s, f[0].z, SG_SHADER_LANES, 0.0f, 1.0f);
        f[0].front_facing = next(&s) >> 31;
        f[0].primitive = (int)(next(&s) % 100000u);
        f[0].instance = (int)(next(&s) % 5000u);
        fill(&s, &f[0].varying[0][0], SG_MAX_VARYINGS * SG_SHADER_LANES, -2.0f, 2.0f);
        f[0].discard = 0;
        f[0].internal = NULL; /* sgSample gives (0, 0, 0, 1) */
        f[1] = f[0];
        base->desc.fragment(&f[0], uniforms);
        copy->desc.fragment(&f[1], uniforms);
        const int fc = first_difference(&f[0].color[0][0], &f[1].color[0][0], 4 * SG_SHADER_LANES);
        if (fc >= 0)
            fail_msg("%s: the %s copy's fragment stage differs from the baseline's (round %d, "
                     "colour %d lane %d: %a against %a)",
                     base->name, set, round, fc / SG_SHADER_LANES, fc % SG_SHADER_LANES,
                     (double)f[1].color[0][fc], (double)f[0].color[0][fc]);
        if (f[0].discard != f[1].discard)
            fail_msg("%s: the %s copy's discards %#x, the baseline's %#x (round %d)", base->name,
                     set, (unsigned)f[1].discard, (unsigned)f[0].discard, round);
    }
}

static void copies_identical(void **state) {
    (void)state;
    int n = 0, m = 0;
    const sgShaderInfo *const *base = sg_builtin_shaders_copy(SGS_COPY_BASELINE, &n);
    assert_non_null(base);
    static const char *const names[SGS_COPY_COUNT] = {"baseline", "AVX2", "AVX-512"};
    for (int c = SGS_COPY_BASELINE + 1; c < SGS_COPY_COUNT; c++) {
        const sgShaderInfo *const *list = sg_builtin_shaders_copy((sgs_copy)c, &m);
        if (!list) {
            printf("# the %s copy: not built or not run by this CPU\n", names[c]);
            continue;
        }
        assert_int_equal(m, n);
        for (int i = 0; i < n; i++) {
            assert_string_equal(list[i]->name, base[i]->name);
            compare(base[i], list[i], names[c]);
        }
        printf("# the %s copy: %d shaders, %d batches of each stage, the baseline's bits\n",
               names[c], n, ROUNDS);
    }
    /* sg_builtin_shaders: by default the last copy this CPU runs, for AVX2 and AVX-512 devices
     * their own where it runs, the baseline's for the other sets */
    const sgShaderInfo *const *last = base;
    for (int c = SGS_COPY_BASELINE + 1; c < SGS_COPY_COUNT; c++) {
        const sgShaderInfo *const *l = sg_builtin_shaders_copy((sgs_copy)c, &m);
        if (l) last = l;
    }
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_DEFAULT, &m), last);
    const sgShaderInfo *const *avx2 = sg_builtin_shaders_copy(SGS_COPY_AVX2, &m);
    const sgShaderInfo *const *avx512 = sg_builtin_shaders_copy(SGS_COPY_AVX512, &m);
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_AVX2, &m), avx2 ? avx2 : base);
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_AVX512, &m), avx512 ? avx512 : base);
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_SSE2, &m), base);
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_SCALAR, &m), base);
    assert_ptr_equal(sg_builtin_shaders(SG_SIMD_NEON, &m), base);
}

int main(void) {
    const struct CMUnitTest tests[] = {cmocka_unit_test(copies_identical)};
    return cmocka_run_group_tests(tests, NULL, NULL);
}
