/* test_turntable.c - the turntable of sgapi-render --turntable and --spin: the centre it turns
 * about, the way it turns (the camera to its right, the scene to the left), the lights turning
 * with the world, and frame 0 as the scene as written, bit for bit. */
#include <math.h>
#include <string.h>

#include "test_common.h"

#include "shadow.h"
#include "turntable.h"

/* Two draws of one mesh: draw 0 moved 10 back, draw 1 moved right and 6 back. The mesh's box is
 * (-1, 0, -1) .. (1, 2, 1); a non-finite vertex, which no box may take, is among them. */
typedef struct fixture {
    sc_mesh mesh;
    sc_draw draws[2];
    sc_scene scene;
    sc_file file;
    float positions[5 * 4];
} fixture;

static void translate(float m[16], float x, float y, float z) {
    memset(m, 0, 16 * sizeof *m);
    m[0] = m[5] = m[10] = m[15] = 1.0f;
    m[3] = x, m[7] = y, m[11] = z;
}

static void setup(fixture *f) {
    memset(f, 0, sizeof *f);
    const float p[5 * 4] = {-1, 0, -1, 1, 1, 2, 1, 1, 0, 1, 0, 1, NAN, 0, 0, 1, 1, 0, 1, 1};
    memcpy(f->positions, p, sizeof p);
    f->mesh.vertex_count = 5;
    f->mesh.positions = f->positions;
    f->file.meshes = &f->mesh;
    f->file.mesh_count = 1;
    translate(f->draws[0].world_view, 0, 0, -10);
    translate(f->draws[1].world_view, 4, 0, -6);
    f->scene.draws = f->draws;
    f->scene.draw_count = 2;
    f->scene.light_count = 2;
    f->scene.lights[0] = (sc_light){.type = SC_LIGHT_DIRECTIONAL, .direction = {1, -1, 0}};
    f->scene.lights[1] = (sc_light){.type = SC_LIGHT_POINT, .position = {2, 5, -8}};
}

/* The view-space position of a mesh vertex under a world-view. */
static void view_pos(const float wv[16], const float p[4], double out[3]) {
    for (int r = 0; r < 3; r++)
        out[r] = (double)wv[r * 4] * p[0] + (double)wv[r * 4 + 1] * p[1] +
                 (double)wv[r * 4 + 2] * p[2] + (double)wv[r * 4 + 3] * p[3];
}

static void bounds_skip_non_finite_vertices(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    double lo[3], hi[3];
    assert_true(sc_view_bounds(&f.file, &f.scene, -1, lo, hi));
    const double all_lo[3] = {-1, 0, -11}, all_hi[3] = {5, 2, -5};
    for (int i = 0; i < 3; i++) {
        assert_true(lo[i] == all_lo[i]);
        assert_true(hi[i] == all_hi[i]);
    }
    assert_true(sc_view_bounds(&f.file, &f.scene, 1, lo, hi));
    assert_true(lo[0] == 3 && hi[0] == 5 && lo[2] == -7 && hi[2] == -5);
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, -1, -1, &t));
    assert_int_equal(t.draw, -1);
    assert_true(t.centre[0] == 2 && t.centre[1] == 1 && t.centre[2] == -8);
    assert_true(sc_turntable_init(&f.file, &f.scene, 1, -1, &t));
    assert_int_equal(t.draw, 1);
    assert_true(t.centre[0] == 4 && t.centre[1] == 1 && t.centre[2] == -6);
}

static void frame_zero_is_the_scene_as_written(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    /* A world-view that a product with an identity rotation would round differently. */
    for (int i = 0; i < 12; i++) f.draws[0].world_view[i] += 0.1f * (float)i / 3.0f;
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, -1, -1, &t));
    sc_draw draws[2];
    sc_scene out;
    for (int turns = 0; turns < 2; turns++) {
        memset(draws, 0xAB, sizeof draws);
        sc_turntable_at(&t, &f.scene, 360.0 * turns, draws, &out);
        assert_ptr_equal(out.draws, draws);
        assert_memory_equal(draws, f.draws, sizeof draws);
        assert_memory_equal(out.lights, f.scene.lights, sizeof out.lights);
    }
}

/* At 90 degrees the camera has gone a quarter turn to its right: what faced it now faces its
 * right, what was on its right is now farthest from it, all about the centre. */
static void orbit_turns_scene_left_about_centre(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, -1, -1, &t));
    sc_draw draws[2];
    sc_scene out;
    sc_turntable_at(&t, &f.scene, 90.0, draws, &out);
    const double *c = t.centre;
    for (int d = 0; d < 2; d++) {
        for (int v = 0; v < 5; v++) {
            if (v == 3) continue; /* the NaN vertex */
            double before[3], after[3];
            view_pos(f.draws[d].world_view, f.positions + v * 4, before);
            view_pos(draws[d].world_view, f.positions + v * 4, after);
            /* Ry(-90): x - cx = -(z - cz) before, z - cz = x - cx before. */
            assert_true(fabs(after[0] - (c[0] - (before[2] - c[2]))) < 1e-5);
            assert_true(fabs(after[1] - before[1]) < 1e-6);
            assert_true(fabs(after[2] - (c[2] + (before[0] - c[0]))) < 1e-5);
        }
    }
    /* The lights go with the world: the direction (1, -1, 0) now travels towards the camera. */
    const float *dir = out.lights[0].direction, *pos = out.lights[1].position;
    assert_true(dir[0] == 0.0f && dir[1] == -1.0f && dir[2] == 1.0f);
    assert_true(pos[0] == 2.0f && pos[1] == 5.0f && pos[2] == -8.0f); /* above the centre */
    /* Half a turn: everything mirrored through the axis, exactly. */
    sc_turntable_at(&t, &f.scene, 180.0, draws, &out);
    assert_true(out.lights[0].direction[0] == -1.0f && out.lights[0].direction[2] == 0.0f);
    float expect[16];
    translate(expect, 4, 0, -6); /* draw 0 at (0, 0, -10) mirrored about (2, _, -8) */
    expect[0] = expect[10] = -1.0f;
    assert_memory_equal(draws[0].world_view, expect, sizeof expect);
}

/* A small turn moves the point of the scene nearest the camera to the left on screen. */
static void orbit_camera_moves_right(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, -1, -1, &t));
    sc_draw draws[2];
    sc_scene out;
    sc_turntable_at(&t, &f.scene, 10.0, draws, &out);
    const float front[4] = {0, 1, 1, 1}; /* draw 1's vertex nearest the camera... */
    double before[3], after[3];
    view_pos(f.draws[1].world_view, front, before);
    view_pos(draws[1].world_view, front, after);
    assert_true(after[0] < before[0]); /* ...goes left */
    assert_true(after[2] > before[2]); /* and, right of the centre, nearer */
}

static void spin_turns_one_draw_and_no_light(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, 1, -1, &t));
    sc_draw draws[2];
    sc_scene out;
    sc_turntable_at(&t, &f.scene, 90.0, draws, &out);
    assert_memory_equal(&draws[0], &f.draws[0], sizeof draws[0]);
    assert_memory_equal(out.lights, f.scene.lights, sizeof out.lights);
    double lo[3], hi[3];
    assert_true(sc_view_bounds(&f.file, &out, 1, lo, hi));
    /* The draw's box is square in x and z: turned about its own centre it stays where it was. */
    assert_true(fabs(lo[0] - 3) < 1e-6 && fabs(hi[0] - 5) < 1e-6);
    assert_true(fabs(lo[2] + 7) < 1e-6 && fabs(hi[2] + 5) < 1e-6);
    const float corner[4] = {1, 2, 1, 1};
    double after[3];
    view_pos(draws[1].world_view, corner, after);
    assert_true(fabs(after[0] - 3) < 1e-6 && fabs(after[2] + 5) < 1e-6); /* right-front went left */
}

/* --up: the axis is a draw's own +y in view space. Turning about a tilted floor's up keeps the
 * floor in its plane, and the draws' +y (the floor's normal) where it was. */
static void orbit_about_a_draws_up(void **state) {
    (void)state;
    fixture f;
    setup(&f);
    /* Draw 0 tilted towards the camera by 30 degrees about x, as a floor looked down on. */
    const float c = 0.8660254f, s = 0.5f;
    const float tilted[16] = {1, 0, 0, 0, 0, c, -s, -1, 0, s, c, -10, 0, 0, 0, 1};
    memcpy(f.draws[0].world_view, tilted, sizeof tilted);
    sc_turntable t;
    assert_true(sc_turntable_init(&f.file, &f.scene, -1, 0, &t));
    assert_true(fabs(t.axis[0]) < 1e-12 && fabs(t.axis[1] - c) < 1e-7 &&
                fabs(t.axis[2] - s) < 1e-7);
    sc_draw draws[2];
    sc_scene out;
    for (int k = 1; k < 8; k++) {
        sc_turntable_at(&t, &f.scene, 45.0 * k, draws, &out);
        /* The floor's normal (its +y) is the axis: unchanged. */
        const float *wv = draws[0].world_view;
        assert_true(fabs(wv[1]) < 1e-6 && fabs(wv[5] - c) < 1e-6 && fabs(wv[9] - s) < 1e-6);
        /* Every point keeps its height along the axis above the centre. */
        for (int v = 0; v < 5; v++) {
            if (v == 3) continue;
            double before[3], after[3], hb = 0, ha = 0;
            view_pos(f.draws[0].world_view, f.positions + v * 4, before);
            view_pos(wv, f.positions + v * 4, after);
            for (int i = 0; i < 3; i++) {
                hb += (before[i] - t.centre[i]) * t.axis[i];
                ha += (after[i] - t.centre[i]) * t.axis[i];
            }
            assert_true(fabs(ha - hb) < 1e-5);
        }
    }
    /* A draw whose +y is zero has no up. */
    memset(f.draws[1].world_view, 0, sizeof f.draws[1].world_view);
    assert_false(sc_turntable_init(&f.file, &f.scene, -1, 1, &t));
}

int main(void) {
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(bounds_skip_non_finite_vertices),
        cmocka_unit_test(frame_zero_is_the_scene_as_written),
        cmocka_unit_test(orbit_turns_scene_left_about_centre),
        cmocka_unit_test(orbit_camera_moves_right),
        cmocka_unit_test(spin_turns_one_draw_and_no_light),
        cmocka_unit_test(orbit_about_a_draws_up),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
