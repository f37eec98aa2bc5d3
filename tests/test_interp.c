/* test_interp.c - perspective-correct interpolation and depth, against analytic values.
 *
 * A tilted plane is seen through the scenes' perspective matrix; each vertex carries its eye-space
 * x as an attribute. At every covered pixel, the attribute interpolated the way the raster does it
 * (attribute/w and 1/w planes, then a divide) must equal the eye-space x of the point where the
 * pixel's ray meets the plane.
 */
#include "test_common.h"

#include <math.h>
#include <string.h>

#include "pipeline/mat4.h"
#include "pipeline/setup.h"
#include "test_setup.h"

#define W 256
#define H 256
static const double F = 2.41421; /* focal length of the projection below */

/* Eye-space plane: z = -3 - 0.5 x. */
static double plane_z(double x) {
    return -3.0 - 0.5 * x;
}

static sg_cvert eye_vertex(double x, double y) {
    const float proj[16] = {2.41421f, 0, 0,       0,        0, 2.41421f, 0,  0,
                            0,        0, -1.002f, -0.2002f, 0, 0,        -1, 0};
    const float eye[4] = {(float)x, (float)y, (float)plane_z(x), 1};
    sg_cvert v;
    memset(&v, 0, sizeof v);
    sg_mat4_transform(v.pos, proj, eye);
    v.attr[0] = (float)x;
    return v;
}

/* One large triangle of the plane, set up for the raster. */
static void setup_plane_triangle(sg_tri *t) {
    sg_setup_params p = sg_test_params(W, H, 1);
    sg_cvert a = eye_vertex(-1.0, -1.0), b = eye_vertex(1.5, -1.0), c = eye_vertex(-1.0, 1.2);
    assert_true(sg_setup_triangle(&p, &a, &b, &c, t, NULL));
}

static void perspective_correct_matches_ray_cast(void **state) {
    (void)state;
    sg_tri t;
    setup_plane_triangle(&t);
    int checked = 0;
    double worst = 0, worst_affine = 0;
    for (int py = t.miny; py <= t.maxy; py++)
        for (int px = t.minx; px <= t.maxx; px++) {
            int64_t dx = px - t.minx, dy = py - t.miny;
            int in = 1;
            for (int e = 0; e < 3; e++)
                in &= t.edge[e] + dx * t.edge_dx[e] + dy * t.edge_dy[e] >= 0;
            if (!in) continue;
            float fx = (float)dx, fy = (float)dy;
            float q = t.q + t.q_dx * fx + t.q_dy * fy;
            float got = (t.a[0] + t.a_dx[0] * fx + t.a_dy[0] * fy) / q;
            /* The ray through the pixel centre meets the plane at eye z = -3 / (1 - 0.5 xn / F). */
            double xn = (px + 0.5) / W * 2.0 - 1.0;
            double z = -3.0 / (1.0 - 0.5 * xn / F);
            double want = xn * -z / F;
            double err = fabs(got - want);
            if (err > worst) worst = err;
            /* Affine interpolation (attribute planes without the 1/w correction) would be off by
             * far more: the check below proves the test can tell the two apart. */
            double affine = (t.a[0] + t.a_dx[0] * fx + t.a_dy[0] * fy) / t.q;
            if (fabs(affine - want) > worst_affine) worst_affine = fabs(affine - want);
            checked++;
        }
    assert_true(checked > 1000);
    /* Snapping moves vertices by at most 1/512 pixel; the attribute changes by far less than 1e-3.
     */
    assert_true(worst < 1e-3);
    assert_true(worst_affine > 0.05);
}

static void depth_is_linear_in_screen_space(void **state) {
    (void)state;
    sg_tri t;
    setup_plane_triangle(&t);
    /* Window depth at a pixel = (z_ndc + 1) / 2 of the point the ray hits. */
    int px = (t.minx + t.maxx) / 2, py = (t.miny + t.maxy) / 2;
    float fx = (float)(px - t.minx), fy = (float)(py - t.miny);
    float got = t.z + t.z_dx * fx + t.z_dy * fy;
    double xn = (px + 0.5) / W * 2.0 - 1.0;
    double ze = -3.0 / (1.0 - 0.5 * xn / F);
    double zc = -1.002 * ze - 0.2002, wc = -ze;
    assert_float_equal(got, 0.5 * (zc / wc) + 0.5, 1e-5);
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(perspective_correct_matches_ray_cast),
        cmocka_unit_test(depth_is_linear_in_screen_space),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
