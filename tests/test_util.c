/* test_util.c - the helpers of sgapi_util: smooth vertex normals, tangents. */
#include <math.h>
#include <stdbool.h>
#include <stdlib.h>
#include <string.h>

#include "test_common.h"

#include <sgapi/sgapi_util.h>

static void set4(float *p, float x, float y, float z, float w) {
    p[0] = x, p[1] = y, p[2] = z, p[3] = w;
}

static bool any_nan(const float *v, int n) {
    for (int i = 0; i < n; i++)
        if (isnan(v[i])) return true;
    return false;
}

/* ---- a cube whose vertices are not shared between faces ------------------------------------- */

enum { CUBE_VERTS = 24 };

/* Corner c (bits x, y, z) of the cube [-1, 1]^3. */
static void corner(int c, float *p) {
    set4(p, c & 1 ? 1.0f : -1.0f, c & 2 ? 1.0f : -1.0f, c & 4 ? 1.0f : -1.0f, 1.0f);
}

static int parity(int c) {
    return ((c & 1) + (c >> 1 & 1) + (c >> 2 & 1)) & 1;
}

/* Four vertices of its own per face, counter-clockwise from outside. Each face starts at a corner
 * of even parity, so the diagonal a-c of every quad is an edge of the tetrahedron inscribed in
 * the cube: the even corners then touch both triangles of each of their three faces, the odd ones
 * one triangle of each, and every corner's sum points along the corner's diagonal. */
static void make_cube(float *pos, uint32_t *quads) {
    int v = 0;
    for (int axis = 0; axis < 3; axis++) {
        for (int side = 0; side < 2; side++) {
            const int u = (axis + 1) % 3, w = (axis + 2) % 3;
            const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
            int cyc[4];
            for (int k = 0; k < 4; k++) cyc[k] = side << axis | uv[k][0] << u | uv[k][1] << w;
            /* (u, w) is counter-clockwise seen from +axis; reverse it on the -axis side. */
            if (!side) {
                int t = cyc[1];
                cyc[1] = cyc[3];
                cyc[3] = t;
            }
            int start = parity(cyc[0]) == 0 ? 0 : 1;
            for (int k = 0; k < 4; k++) {
                corner(cyc[(start + k) % 4], pos + (v + k) * 4);
                quads[v + k] = (uint32_t)(v + k);
            }
            v += 4;
        }
    }
}

static void check_cube_normals(const float *pos, const float *n) {
    const float third = (float)(1.0 / sqrt(3.0));
    for (int v = 0; v < CUBE_VERTS; v++)
        for (int c = 0; c < 3; c++)
            assert_float_equal(n[v * 3 + c], pos[v * 4 + c] > 0 ? third : -third, 1e-7);
}

static void cube_unshared_gets_corner_normals(void **state) {
    (void)state;
    float pos[CUBE_VERTS * 4], n[CUBE_VERTS * 3];
    uint32_t quads[CUBE_VERTS], tris[36];
    make_cube(pos, quads);
    assert_int_equal(sgu_compute_normals(pos, CUBE_VERTS, quads, CUBE_VERTS, 1, n), 0);
    check_cube_normals(pos, n);

    /* The same as triangles a b c, a c d. */
    for (int q = 0; q < 6; q++) {
        const uint32_t *s = quads + q * 4;
        const uint32_t t[6] = {s[0], s[1], s[2], s[0], s[2], s[3]};
        memcpy(tris + q * 6, t, sizeof t);
    }
    memset(n, 0, sizeof n);
    assert_int_equal(sgu_compute_normals(pos, CUBE_VERTS, tris, 36, 0, n), 0);
    check_cube_normals(pos, n);
}

/* Same position whatever the sign of a zero and whatever w: (2, 0, -0, 2) is (1, 0, 0). */
static void zero_sign_and_w(void **state) {
    (void)state;
    float pos[6 * 4], n[6 * 3];
    /* Two triangles, one in the plane z = 0 facing +z, one in x = 1 facing +x, sharing the
     * position (1, 0, 0) through vertices written differently. */
    set4(pos + 0, 0, 0, 0, 1);
    set4(pos + 4, 1, 0, 0, 1);
    set4(pos + 8, 0, 1, 0, 1);
    set4(pos + 12, 2, 0, -0.0f, 2);
    set4(pos + 16, 1, 1, 0, 1);
    set4(pos + 20, 1, 0, 1, 1);
    const uint32_t idx[6] = {0, 1, 2, 3, 4, 5};
    assert_int_equal(sgu_compute_normals(pos, 6, idx, 6, 0, n), 0);
    /* Both crosses have length 1: the shared vertices get (1, 0, 1) / sqrt 2. */
    const float h = (float)(1.0 / sqrt(2.0));
    for (int v = 1; v <= 3; v += 2) {
        assert_float_equal(n[v * 3 + 0], h, 1e-7);
        assert_float_equal(n[v * 3 + 1], 0.0f, 0);
        assert_float_equal(n[v * 3 + 2], h, 1e-7);
    }
    assert_float_equal(n[0 * 3 + 2], 1.0f, 0);
    assert_float_equal(n[4 * 3 + 0], 1.0f, 0);
}

static void flat_quad_faces_plus_z(void **state) {
    (void)state;
    float pos[4 * 4], n[4 * 3];
    set4(pos + 0, -1, -1, 0.5f, 1);
    set4(pos + 4, 3, -1, 0.5f, 1);
    set4(pos + 8, 3, 2, 0.5f, 1);
    set4(pos + 12, -1, 2, 0.5f, 1);
    const uint32_t quad[4] = {0, 1, 2, 3}, tris[6] = {0, 1, 2, 0, 2, 3};
    assert_int_equal(sgu_compute_normals(pos, 4, quad, 4, 1, n), 0);
    for (int v = 0; v < 4; v++) {
        assert_float_equal(n[v * 3 + 0], 0.0f, 0);
        assert_float_equal(n[v * 3 + 1], 0.0f, 0);
        assert_float_equal(n[v * 3 + 2], 1.0f, 0);
    }
    memset(n, 0xff, sizeof n);
    assert_int_equal(sgu_compute_normals(pos, 4, tris, 6, 0, n), 0);
    for (int v = 0; v < 4; v++) assert_float_equal(n[v * 3 + 2], 1.0f, 0);
}

/* A larger triangle weighs more: the sum is of unnormalised face normals. */
static void area_weighted(void **state) {
    (void)state;
    float pos[4 * 4], n[4 * 3];
    set4(pos + 0, 0, 0, 0, 1);
    set4(pos + 4, 2, 0, 0, 1); /* in z = 0: cross (0, 0, 2) */
    set4(pos + 8, 0, 1, 0, 1);
    set4(pos + 12, 0, 0, 3, 1); /* 0 3 1: the plane y = 0, cross (0, 6, 0) */
    const uint32_t idx[6] = {0, 1, 2, 0, 3, 1};
    assert_int_equal(sgu_compute_normals(pos, 4, idx, 6, 0, n), 0);
    /* Vertices 0 and 1 sum (0, 6, 2). */
    for (int v = 0; v < 2; v++) {
        assert_float_equal(n[v * 3 + 0], 0.0f, 0);
        assert_float_equal(n[v * 3 + 1], (float)(6.0 / sqrt(40.0)), 1e-7);
        assert_float_equal(n[v * 3 + 2], (float)(2.0 / sqrt(40.0)), 1e-7);
    }
    /* Vertex 2 touches only the first triangle, vertex 3 only the second. */
    assert_float_equal(n[2 * 3 + 2], 1.0f, 0);
    assert_float_equal(n[3 * 3 + 1], 1.0f, 0);
}

/* Vertex sharing does not matter: a bumpy grid with shared vertices and the same grid with
 * three vertices of its own per triangle get bit-identical normals. */
static void shared_and_unshared_agree(void **state) {
    (void)state;
    enum { W = 9, H = 7, TRIS = (W - 1) * (H - 1) * 2 };
    float shared[W * H * 4], alone[TRIS * 3 * 4], ns[W * H * 3], na[TRIS * 3 * 3];
    uint32_t idx[TRIS * 3], idx_alone[TRIS * 3];
    uint32_t seed = 99;
    for (int y = 0; y < H; y++)
        for (int x = 0; x < W; x++) {
            seed = seed * 1664525u + 1013904223u;
            set4(shared + (y * W + x) * 4, (float)x, (float)y, (float)(seed >> 20) / 4096.0f, 1);
        }
    int k = 0;
    for (int y = 0; y + 1 < H; y++)
        for (int x = 0; x + 1 < W; x++) {
            uint32_t i = (uint32_t)(y * W + x);
            const uint32_t t[6] = {i, i + 1, i + W, i + 1, i + W + 1, i + W};
            memcpy(idx + k, t, sizeof t);
            k += 6;
        }
    for (int i = 0; i < TRIS * 3; i++) {
        memcpy(alone + i * 4, shared + idx[i] * 4, 4 * sizeof(float));
        idx_alone[i] = (uint32_t)i;
    }
    assert_int_equal(sgu_compute_normals(shared, W * H, idx, TRIS * 3, 0, ns), 0);
    assert_int_equal(sgu_compute_normals(alone, TRIS * 3, idx_alone, TRIS * 3, 0, na), 0);
    for (int i = 0; i < TRIS * 3; i++) {
        assert_memory_equal(na + i * 3, ns + idx[i] * 3, 3 * sizeof(float));
        double len = sqrt((double)na[i * 3] * na[i * 3] + (double)na[i * 3 + 1] * na[i * 3 + 1] +
                          (double)na[i * 3 + 2] * na[i * 3 + 2]);
        assert_float_equal(len, 1.0, 1e-6);
        assert_true(na[i * 3 + 2] > 0.0f);
    }
}

/* Degenerate triangles, NaN and infinite positions, w = 0: zeros, never NaN. */
static void degenerate_gives_zero_not_nan(void **state) {
    (void)state;
    float pos[10 * 4], n[10 * 3];
    set4(pos + 0, 1, 1, 1, 1);
    set4(pos + 4, 1, 1, 1, 1);
    set4(pos + 8, 2, 2, 2, 1); /* 0 1 2: two equal corners */
    set4(pos + 12, 0, 0, 0, 1);
    set4(pos + 16, 5, 5, 5, 1); /* 3 4 2: collinear */
    set4(pos + 20, NAN, 0, 0, 1);
    set4(pos + 24, 7, 0, 0, 1);
    set4(pos + 28, 7, 1, 0, 1); /* 5 6 7: a NaN corner */
    set4(pos + 32, INFINITY, 0, 0, 1);
    set4(pos + 36, 3, 3, 3, 0); /* 8 6 9: infinite, and w = 0 */
    const uint32_t idx[12] = {0, 1, 2, 3, 4, 2, 5, 6, 7, 8, 6, 9};
    memset(n, 0x7f, sizeof n);
    assert_int_equal(sgu_compute_normals(pos, 10, idx, 12, 0, n), 0);
    assert_false(any_nan(n, 30));
    for (int i = 0; i < 30; i++) assert_float_equal(n[i], 0.0f, 0);

    /* A vertex no triangle uses gets zeros too. */
    const uint32_t one[3] = {3, 6, 7};
    assert_int_equal(sgu_compute_normals(pos, 10, one, 3, 0, n), 0);
    assert_float_equal(n[0], 0.0f, 0);
    assert_float_equal(n[3 * 3 + 2], 1.0f, 0);
    assert_false(any_nan(n, 30));
}

static void bad_input_is_refused(void **state) {
    (void)state;
    float pos[3 * 4] = {0, 0, 0, 1, 1, 0, 0, 1, 0, 1, 0, 1}, n[3 * 3];
    const uint32_t idx[3] = {0, 1, 2}, bad[3] = {0, 1, 3}, quad[4] = {0, 1, 2, 2};
    const float sentinel = 42.0f;
    for (int i = 0; i < 9; i++) n[i] = sentinel;
    assert_int_equal(sgu_compute_normals(pos, 3, bad, 3, 0, n), -1);
    for (int i = 0; i < 9; i++) assert_float_equal(n[i], sentinel, 0); /* unchanged */
    assert_int_equal(sgu_compute_normals(NULL, 3, idx, 3, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 3, NULL, 3, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 3, idx, 3, 0, NULL), -1);
    assert_int_equal(sgu_compute_normals(pos, 0, idx, 3, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, -1, idx, 3, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 3, idx, -3, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 3, idx, 2, 0, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 3, idx, 3, 1, n), -1); /* not a multiple of 4 */
    assert_int_equal(sgu_compute_normals(pos, 3, quad, 4, 2, n), -1);
    assert_int_equal(sgu_compute_normals(pos, 2, idx, 3, 0, n), -1); /* index 2 >= 2 */
    for (int i = 0; i < 9; i++) assert_float_equal(n[i], sentinel, 0);
    /* No index at all is fine: nothing touches any vertex. */
    assert_int_equal(sgu_compute_normals(pos, 3, NULL, 0, 0, n), 0);
    for (int i = 0; i < 9; i++) assert_float_equal(n[i], 0.0f, 0);
    assert_int_equal(sgu_compute_normals(pos, 3, quad, 4, 1, n), 0);
    assert_float_equal(n[2], 1.0f, 0);
}

/* ---- tangents ---------------------------------------------------------------------------------
 */

/* A unit square in z = 0 as two triangles, its texture coordinates (s, t) = (su * x, tv * y). */
static void square(float pos[16], float nrm[12], float uv[8], float su, float tv) {
    const float xy[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int v = 0; v < 4; v++) {
        set4(pos + v * 4, xy[v][0], xy[v][1], 0, 1);
        nrm[v * 3] = 0, nrm[v * 3 + 1] = 0, nrm[v * 3 + 2] = 1;
        uv[v * 2] = su * xy[v][0], uv[v * 2 + 1] = tv * xy[v][1];
    }
}

static const uint32_t square_idx[6] = {0, 1, 2, 0, 2, 3};

static void tangent_follows_s(void **state) {
    (void)state;
    float pos[16], nrm[12], uv[8], t[16];
    square(pos, nrm, uv, 1, 1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 0, t), 0);
    for (int v = 0; v < 4; v++) {
        assert_float_equal(t[v * 4 + 0], 1.0f, 1e-6);
        assert_float_equal(t[v * 4 + 1], 0.0f, 1e-6);
        assert_float_equal(t[v * 4 + 2], 0.0f, 1e-6);
        assert_float_equal(t[v * 4 + 3], 1.0f, 0);
    }
    /* s mirrored: the tangent turns round and the frame is left-handed. */
    square(pos, nrm, uv, -2, 1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 0, t), 0);
    for (int v = 0; v < 4; v++) {
        assert_float_equal(t[v * 4 + 0], -1.0f, 1e-6);
        assert_float_equal(t[v * 4 + 3], -1.0f, 0);
    }
    /* Quads give what their two triangles give. */
    const uint32_t quad[4] = {0, 1, 2, 3};
    float tq[16];
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, quad, 4, 1, tq), 0);
    assert_memory_equal(t, tq, sizeof t);
}

static void tangent_orthogonal_to_normal(void **state) {
    (void)state;
    float pos[16], nrm[12], uv[8], t[16];
    square(pos, nrm, uv, 1, 1);
    /* Normals tilted towards +x (and not of unit length): Gram-Schmidt keeps the part of +x
     * perpendicular to them, (1, 0, -1) / sqrt(2). */
    for (int v = 0; v < 4; v++) nrm[v * 3] = 3, nrm[v * 3 + 2] = 3;
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 0, t), 0);
    for (int v = 0; v < 4; v++) {
        assert_float_equal(t[v * 4 + 0], 0.70710678f, 1e-6);
        assert_float_equal(t[v * 4 + 1], 0.0f, 1e-6);
        assert_float_equal(t[v * 4 + 2], -0.70710678f, 1e-6);
    }
}

static void tangent_sphere_is_unit_and_perpendicular(void **state) {
    (void)state;
    sguShapeDesc d = {.shape = SGU_SHAPE_UV_SPHERE};
    int nv, ni;
    assert_int_equal(sgu_shape_counts(&d, &nv, &ni), 0);
    float *pos = malloc((size_t)nv * 16), *nrm = malloc((size_t)nv * 12);
    float *uv = malloc((size_t)nv * 8), *t = malloc((size_t)nv * 16);
    uint32_t *idx = malloc((size_t)ni * 4);
    assert_non_null(pos && nrm && uv && t && idx);
    assert_int_equal(sgu_shape_build(&d, pos, nrm, uv, idx), 0);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, nv, idx, ni, 0, t), 0);
    assert_false(any_nan(t, nv * 4));
    for (int v = 0; v < nv; v++) {
        const float *a = t + v * 4, *n = nrm + v * 3;
        assert_float_equal(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0f, 1e-5);
        assert_float_equal(a[0] * n[0] + a[1] * n[1] + a[2] * n[2], 0.0f, 1e-5);
        assert_true(a[3] == 1.0f || a[3] == -1.0f);
    }
    free(pos), free(nrm), free(uv), free(t), free(idx);
}

static void tangent_degenerate_never_nan(void **state) {
    (void)state;
    float pos[16], nrm[12], uv[8], t[16];
    square(pos, nrm, uv, 0, 0); /* every vertex at s = t = 0 */
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 0, t), 0);
    assert_false(any_nan(t, 16));
    for (int v = 0; v < 4; v++) {
        const float *a = t + v * 4;
        assert_float_equal(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0f, 1e-6);
        assert_float_equal(a[2], 0.0f, 0); /* perpendicular to the normal (0, 0, 1) */
        assert_float_equal(a[3], 1.0f, 0);
    }
    /* Texture coordinates along one line (no area), then a NaN one; a zero normal; an unused
     * vertex (3): all still finite and of unit length. */
    const uint32_t idx[3] = {0, 1, 2};
    for (int pass = 0; pass < 2; pass++) {
        square(pos, nrm, uv, 1, 1);
        uv[2] = uv[3] = 0.5f; /* vertex 1 halfway between vertex 0 (0, 0) and vertex 2 (1, 1) */
        if (pass) uv[5] = NAN;
        nrm[6] = nrm[7] = nrm[8] = 0;
        assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, idx, 3, 0, t), 0);
        assert_false(any_nan(t, 16));
        for (int v = 0; v < 4; v++) {
            const float *a = t + v * 4;
            assert_float_equal(a[0] * a[0] + a[1] * a[1] + a[2] * a[2], 1.0f, 1e-6);
        }
    }
}

static void tangent_bad_input_is_refused(void **state) {
    (void)state;
    float pos[16], nrm[12], uv[8], t[16];
    square(pos, nrm, uv, 1, 1);
    for (int i = 0; i < 16; i++) t[i] = 42.0f;
    const uint32_t bad[3] = {0, 1, 4};
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, bad, 3, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(NULL, nrm, uv, 4, square_idx, 6, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, NULL, uv, 4, square_idx, 6, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, NULL, 4, square_idx, 6, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, NULL, 6, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 0, NULL), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 0, square_idx, 6, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 5, 0, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 1, t), -1);
    assert_int_equal(sgu_compute_tangents(pos, nrm, uv, 4, square_idx, 6, 2, t), -1);
    for (int i = 0; i < 16; i++) assert_float_equal(t[i], 42.0f, 0); /* unchanged */
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(cube_unshared_gets_corner_normals),
        cmocka_unit_test(zero_sign_and_w),
        cmocka_unit_test(flat_quad_faces_plus_z),
        cmocka_unit_test(area_weighted),
        cmocka_unit_test(shared_and_unshared_agree),
        cmocka_unit_test(degenerate_gives_zero_not_nan),
        cmocka_unit_test(bad_input_is_refused),
        cmocka_unit_test(tangent_follows_s),
        cmocka_unit_test(tangent_orthogonal_to_normal),
        cmocka_unit_test(tangent_sphere_is_unit_and_perpendicular),
        cmocka_unit_test(tangent_degenerate_never_nan),
        cmocka_unit_test(tangent_bad_input_is_refused),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
