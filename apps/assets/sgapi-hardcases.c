/* sgapi-hardcases - writes the hard-case scenes: the situations that break rasterisers, each a
 * scene file in OUTDIR (scenes/hard/ in the repo) with its meshes and textures in OUTDIR/assets.
 *
 *   sgapi-hardcases OUTDIR
 *
 * Deterministic (own PRNG, fixed seeds): two runs write the same bytes. Most 2D cases place
 * vertices in pixel units with identity matrices, so clip space is the pixel position scaled to
 * [-1, 1]; flat per-triangle colours (k / 255) make any difference in which triangle covers a
 * pixel show up as a colour difference, not only as coverage.
 */
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <stb_image_write.h>

#ifndef M_PI
#define M_PI 3.14159265358979323846
#endif

/* ---- small helpers --------------------------------------------------------------------------- */

typedef struct rng {
    uint64_t s;
} rng;

static uint32_t next_u32(rng *r) {
    r->s = r->s * 6364136223846793005ull + 1442695040888963407ull;
    return (uint32_t)(r->s >> 33);
}

static double uniform(rng *r) {
    return next_u32(r) / 2147483648.0;
} /* [0, 1) */

static void die(const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    fprintf(stderr, "sgapi-hardcases: ");
    vfprintf(stderr, fmt, ap);
    fprintf(stderr, "\n");
    va_end(ap);
    exit(1);
}

/* dir + middle + name as a new string of its length; exits when out of memory. */
static char *path_of(const char *dir, const char *middle, const char *name) {
    size_t n = strlen(dir) + strlen(middle) + strlen(name) + 1;
    char *p = malloc(n);
    if (!p) die("out of memory");
    snprintf(p, n, "%s%s%s", dir, middle, name);
    return p;
}

/* A mesh being written: OBJ text with positions, colours, texcoords, triangle faces. */
typedef struct mesh {
    FILE *f;
    int vertices;
    int textured;
} mesh;

static mesh mesh_open(const char *dir, const char *name, int textured) {
    char *path = path_of(dir, "/assets/", name);
    mesh m = {fopen(path, "w"), 0, textured};
    if (!m.f) die("cannot write %s", path);
    free(path);
    fprintf(m.f, "# %s, made by sgapi-hardcases\n", name);
    return m;
}

/* One vertex: position (x, y, z) and colour; texcoord when the mesh has them. Floats are printed
 * with 9 significant digits so the loader reads back exactly these float values. */
static int vtx(mesh *m, double x, double y, double z, const float c[3], double s, double t) {
    fprintf(m->f, "v %.9g %.9g %.9g %.9g %.9g %.9g\n", (float)x, (float)y, (float)z, c[0], c[1],
            c[2]);
    if (m->textured) fprintf(m->f, "vt %.9g %.9g\n", (float)s, (float)t);
    return ++m->vertices;
}

static void tri(mesh *m, int a, int b, int c) {
    if (m->textured)
        fprintf(m->f, "f %d/%d %d/%d %d/%d\n", a, a, b, b, c, c);
    else
        fprintf(m->f, "f %d %d %d\n", a, b, c);
}

static void mesh_close(mesh *m) {
    if (fclose(m->f) != 0) die("write failed");
}

/* Flat colour number k (k / 255 steps, well apart) for triangle i. */
static void flat_colour(unsigned i, float c[3]) {
    uint32_t h = (i + 1) * 2654435761u;
    c[0] = (float)(40 + (h & 0xff) % 200) / 255.0f;
    c[1] = (float)(40 + (h >> 8 & 0xff) % 200) / 255.0f;
    c[2] = (float)(40 + (h >> 16 & 0xff) % 200) / 255.0f;
}

/* Pixel position (y down) of a W x H target to clip space with w = 1. */
typedef struct px_space {
    double w, h;
} px_space;

static double ndc_x(px_space p, double x) {
    return 2.0 * x / p.w - 1.0;
}
static double ndc_y(px_space p, double y) {
    return 1.0 - 2.0 * y / p.h;
}

/* A flat-coloured triangle given in pixels. */
static void px_tri(mesh *m, px_space p, double x0, double y0, double x1, double y1, double x2,
                   double y2, unsigned colour) {
    float c[3];
    flat_colour(colour, c);
    int a = vtx(m, ndc_x(p, x0), ndc_y(p, y0), 0, c, 0, 0);
    int b = vtx(m, ndc_x(p, x1), ndc_y(p, y1), 0, c, 0, 0);
    int d = vtx(m, ndc_x(p, x2), ndc_y(p, y2), 0, c, 0, 0);
    tri(m, a, b, d);
}

/* ---- scene files ----------------------------------------------------------------------------- */

static const char *IDENTITY = "[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]";

/* The OpenGL perspective matrix, row-major, as the scene format wants it. */
static void perspective(char *out, size_t n, double fovy_deg, double near, double far) {
    double f = 1.0 / tan(fovy_deg * M_PI / 360.0);
    snprintf(out, n, "[%.9g,0,0,0, 0,%.9g,0,0, 0,0,%.9g,%.9g, 0,0,-1,0]", f, f,
             (far + near) / (near - far), 2.0 * far * near / (near - far));
}

typedef struct scene_file {
    FILE *f;
    int draws;
} scene_file;

/* Opens OUTDIR/<name>.json; the scene is called `name` up to its first dot, so that a reference
 * twin (<scene>.reference.json) renders under the scene's own name. */
static scene_file scene_open(const char *dir, const char *name, int w, int h, const char *clear) {
    char *path = path_of(dir, "/", name);
    char *file = path_of(path, "", ".json");
    free(path);
    scene_file s = {fopen(file, "w"), 0};
    if (!s.f) die("cannot write %s", file);
    free(file);
    fprintf(s.f,
            "{\n \"width\": %d, \"height\": %d, \"clear_color\": %s,\n \"scenes\": [{\n"
            "  \"name\": \"%.*s\",\n  \"draws\": [\n",
            w, h, clear ? clear : "[0,0,0,0]", (int)strcspn(name, "."), name);
    return s;
}

/* A draw: mesh file, then the rest of the draw's JSON members (state, texture, matrices). */
static void draw(scene_file *s, const char *mesh_name, const char *members) {
    fprintf(s->f, "%s   {\"mesh\": \"assets/%s\", %s}", s->draws ? ",\n" : "", mesh_name, members);
    s->draws++;
}

static void scene_close(scene_file *s) {
    fprintf(s->f, "\n  ]\n }]\n}\n");
    if (fclose(s->f) != 0) die("write failed");
}

/* A scene file with a single draw. */
static void one_draw_scene(const char *dir, const char *name, int w, int h, const char *mesh_name,
                           const char *members) {
    scene_file s = scene_open(dir, name, w, h, NULL);
    draw(&s, mesh_name, members);
    scene_close(&s);
}

/* Members of a vertex-colour draw with identity matrices and the given extra state. */
static void members_2d(char *out, size_t n, const char *extra) {
    snprintf(out, n, "\"mode\": \"vertex_color\",%s \"worldView\": %s, \"proj\": %s",
             extra ? extra : "", IDENTITY, IDENTITY);
}

/* ---- the cases ------------------------------------------------------------------------------- */

/* 90 triangles 0.01 px thin and 2000 px long at angles over 180 degrees, around (c, c) in a
 * target of `size` pixels, written to `name`. */
static void sliver_mesh(const char *dir, const char *name, double size, double c) {
    px_space p = {size, size};
    mesh m = mesh_open(dir, name, 0);
    for (int i = 0; i < 90; i++) {
        double a = i * (M_PI / 90.0) + 0.0123;
        double cx = c + 10.0 * cos(i * 1.7), cy = c + 10.0 * sin(i * 2.3);
        double dx = cos(a), dy = sin(a);
        double x0 = cx - 1000 * dx, y0 = cy - 1000 * dy, x1 = cx + 1000 * dx, y1 = cy + 1000 * dy;
        /* 0.01 px wide at the far end: the two long edges almost coincide. */
        px_tri(&m, p, x0, y0, x1, y1, x1 - 0.01 * dy, y1 + 0.01 * dx, (unsigned)i);
    }
    mesh_close(&m);
}

/* Slivers wholly on screen (a 2048 x 2048 target) and the same slivers in a 512 x 512 target,
 * reaching far off screen; and a fan of 1000 triangles around one pixel centre. */
static void case_slivers(const char *dir) {
    sliver_mesh(dir, "slivers.obj", 2048, 1024);
    sliver_mesh(dir, "slivers_offscreen.obj", 512, 256);
    px_space p = {512, 512};
    mesh fan = mesh_open(dir, "fan1000.obj", 0);
    double cx = 255.5, cy = 255.5, r = 200.0; /* the centre is a pixel centre */
    for (int i = 0; i < 1000; i++) {
        double a0 = 2 * M_PI * i / 1000, a1 = 2 * M_PI * (i + 1) / 1000;
        px_tri(&fan, p, cx, cy, cx + r * cos(a0), cy + r * sin(a0), cx + r * cos(a1),
               cy + r * sin(a1), (unsigned)i);
    }
    mesh_close(&fan);
    char mem[512];
    members_2d(mem, sizeof mem, NULL);
    one_draw_scene(dir, "slivers", 2048, 2048, "slivers.obj", mem);
    one_draw_scene(dir, "slivers_offscreen", 512, 512, "slivers_offscreen.obj", mem);
    one_draw_scene(dir, "fan_1000", 512, 512, "fan1000.obj", mem);
}

/* Shared edges: a jittered 64 x 64 grid, split both ways, flat colours per triangle. */
static void case_grid(const char *dir) {
    px_space p = {256, 256};
    enum { N = 65 };
    static double gx[N][N], gy[N][N];
    rng r = {7};
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            double jx = (i == 0 || i == N - 1) ? 0 : uniform(&r) - 0.5;
            double jy = (j == 0 || j == N - 1) ? 0 : uniform(&r) - 0.5;
            gx[j][i] = 8.0 + i * 3.75 + jx * 2.5;
            gy[j][i] = 8.0 + j * 3.75 + jy * 2.5;
        }
    mesh m = mesh_open(dir, "grid64.obj", 0);
    unsigned k = 0;
    for (int j = 0; j + 1 < N; j++)
        for (int i = 0; i + 1 < N; i++) {
            if ((i + j) & 1) {
                px_tri(&m, p, gx[j][i], gy[j][i], gx[j][i + 1], gy[j][i + 1], gx[j + 1][i + 1],
                       gy[j + 1][i + 1], k++);
                px_tri(&m, p, gx[j][i], gy[j][i], gx[j + 1][i + 1], gy[j + 1][i + 1], gx[j + 1][i],
                       gy[j + 1][i], k++);
            } else {
                px_tri(&m, p, gx[j][i], gy[j][i], gx[j][i + 1], gy[j][i + 1], gx[j + 1][i],
                       gy[j + 1][i], k++);
                px_tri(&m, p, gx[j][i + 1], gy[j][i + 1], gx[j + 1][i + 1], gy[j + 1][i + 1],
                       gx[j + 1][i], gy[j + 1][i], k++);
            }
        }
    mesh_close(&m);
    char mem[512];
    members_2d(mem, sizeof mem, NULL);
    one_draw_scene(dir, "grid_64", 256, 256, "grid64.obj", mem);
}

/* A UV sphere in perspective: shared edges, no T-junctions, flat colours. */
static void case_sphere(const char *dir) {
    enum { SLICES = 48, STACKS = 24 };
    mesh m = mesh_open(dir, "sphere.obj", 0);
    unsigned k = 0;
    for (int j = 0; j < STACKS; j++)
        for (int i = 0; i < SLICES; i++) {
            double t0 = M_PI * j / STACKS, t1 = M_PI * (j + 1) / STACKS;
            double p0 = 2 * M_PI * i / SLICES, p1 = 2 * M_PI * (i + 1) / SLICES;
#define SP(t, ph) sin(t) * cos(ph), cos(t), sin(t) * sin(ph)
            float c[3];
            flat_colour(k++, c);
            int a = vtx(&m, SP(t0, p0), c, 0, 0), b = vtx(&m, SP(t1, p0), c, 0, 0);
            int d = vtx(&m, SP(t1, p1), c, 0, 0);
            tri(&m, a, b, d);
            flat_colour(k++, c);
            a = vtx(&m, SP(t0, p0), c, 0, 0);
            b = vtx(&m, SP(t1, p1), c, 0, 0);
            d = vtx(&m, SP(t0, p1), c, 0, 0);
            tri(&m, a, b, d);
#undef SP
        }
    mesh_close(&m);
    char proj[256], mem[1024];
    perspective(proj, sizeof proj, 45, 0.1, 100);
    snprintf(mem, sizeof mem,
             "\"mode\": \"vertex_color\", \"worldView\": [0.8,0,0.6,0, 0.1,0.98,-0.13,0, "
             "-0.59,0.16,0.79,-3.2, 0,0,0,1], \"proj\": %s",
             proj);
    one_draw_scene(dir, "sphere", 256, 256, "sphere.obj", mem);
}

/* Vertices on pixel centres, on tile (4 px) and bin (64 px) borders and on the screen border;
 * edges through pixel centres in each fill-rule case (horizontal top and bottom, vertical left and
 * right, and diagonals). */
static void case_pixel_centres(const char *dir) {
    px_space p = {256, 256};
    mesh m = mesh_open(dir, "pixel_centres.obj", 0);
    unsigned k = 0;
    /* Squares with corners on pixel centres, split along either diagonal. */
    for (int i = 0; i < 6; i++) {
        double x = 4.5 + 40 * i, y = 4.5, s = 7 + 5 * i;
        px_tri(&m, p, x, y, x + s, y, x + s, y + s, k++);
        px_tri(&m, p, x, y, x + s, y + s, x, y + s, k++);
        y = 64.5;
        px_tri(&m, p, x, y, x + s, y, x, y + s, k++);
        px_tri(&m, p, x + s, y, x + s, y + s, x, y + s, k++);
    }
    /* Corners on tile and bin borders (integer positions are pixel corners). */
    for (int i = 0; i < 4; i++) {
        double x = 64.0 * i, y = 128.0, s = 64.0;
        px_tri(&m, p, x, y, x + s, y, x + s, y + s, k++);
        px_tri(&m, p, x, y, x + s, y + s, x, y + s, k++);
    }
    /* Edges along the screen border. */
    px_tri(&m, p, 0, 200, 40, 200, 0, 256, k++);
    px_tri(&m, p, 256, 200, 256, 256, 200, 256, k++);
    /* Diagonals through pixel centres at 1:1, 1:2 and 2:1 slopes, both orientations. */
    px_tri(&m, p, 100.5, 200.5, 140.5, 240.5, 100.5, 240.5, k++);
    px_tri(&m, p, 100.5, 200.5, 140.5, 200.5, 140.5, 240.5, k++);
    px_tri(&m, p, 150.5, 200.5, 170.5, 240.5, 150.5, 240.5, k++);
    px_tri(&m, p, 150.5, 200.5, 190.5, 200.5, 190.5, 220.5, k++);
    mesh_close(&m);
    char mem[512];
    members_2d(mem, sizeof mem, NULL);
    one_draw_scene(dir, "pixel_centres", 256, 256, "pixel_centres.obj", mem);
}

/* Huge and ill-placed triangles: vertices at +-1e6 in NDC, across the eye plane, w close to 0 on
 * either side, and the eye inside a closed mesh. */
static void case_huge(const char *dir) {
    mesh m = mesh_open(dir, "huge_ndc.obj", 0);
    float c[3];
    flat_colour(1, c);
    /* Identity matrices: NDC = the positions; the triangle covers the whole target. */
    int a = vtx(&m, -1e6, -1e6, 0.5, c, 0, 0), b = vtx(&m, 1e6, -1e6, 0.5, c, 0, 0);
    int d = vtx(&m, 0, 1e6, 0.5, c, 0, 0);
    tri(&m, a, b, d);
    flat_colour(2, c);
    a = vtx(&m, -0.5, -0.5, 0, c, 0, 0);
    b = vtx(&m, 1e6, 0.25, 0, c, 0, 0);
    d = vtx(&m, -0.5, 0.5, 0, c, 0, 0);
    tri(&m, a, b, d);
    mesh_close(&m);

    /* Perspective: a floor from behind the eye to far ahead, a wall crossing the eye plane, and
     * triangles whose vertices sit at w = +-1e-6 next to the eye. */
    mesh q = mesh_open(dir, "huge_eye.obj", 0);
    flat_colour(3, c);
    a = vtx(&q, -50, -1, 10, c, 0, 0);
    b = vtx(&q, 50, -1, 10, c, 0, 0);
    d = vtx(&q, 0, -1, -90, c, 0, 0);
    tri(&q, a, b, d);
    flat_colour(4, c);
    a = vtx(&q, 1, -0.5, 5, c, 0, 0);
    b = vtx(&q, 1, 0.8, -20, c, 0, 0);
    d = vtx(&q, 3, -0.5, -20, c, 0, 0);
    tri(&q, a, b, d);
    flat_colour(5, c);
    a = vtx(&q, -1.5, 0.2, -1e-6, c, 0, 0);
    b = vtx(&q, -0.5, 0.9, -4, c, 0, 0);
    d = vtx(&q, -2.5, 0.9, -4, c, 0, 0);
    tri(&q, a, b, d);
    flat_colour(6, c);
    a = vtx(&q, -0.3, 0.3, 1e-6, c, 0, 0);
    b = vtx(&q, 0.2, 0.1, -3, c, 0, 0);
    d = vtx(&q, -0.6, 0.1, -3, c, 0, 0);
    tri(&q, a, b, d);
    mesh_close(&q);

    /* The eye inside a box: every face crosses or surrounds the view. */
    mesh box = mesh_open(dir, "huge_box.obj", 0);
    static const int faces[6][4] = {{0, 1, 3, 2}, {4, 6, 7, 5}, {0, 4, 5, 1},
                                    {2, 3, 7, 6}, {0, 2, 6, 4}, {1, 5, 7, 3}};
    for (int f = 0; f < 6; f++) {
        int v[4];
        flat_colour(10 + (unsigned)f, c);
        for (int k = 0; k < 4; k++) {
            int n = faces[f][k];
            v[k] = vtx(&box, (n & 1) ? 2 : -2, (n & 2) ? 1.5 : -1.5, (n & 4) ? 3 : -3, c, 0, 0);
        }
        tri(&box, v[0], v[1], v[2]);
        tri(&box, v[0], v[2], v[3]);
    }
    mesh_close(&box);

    char proj[256], mem[1024], mem2d[512];
    perspective(proj, sizeof proj, 60, 0.05, 200);
    members_2d(mem2d, sizeof mem2d, NULL);
    snprintf(mem, sizeof mem, "\"mode\": \"vertex_color\", \"worldView\": %s, \"proj\": %s",
             IDENTITY, proj);
    one_draw_scene(dir, "huge_ndc", 256, 256, "huge_ndc.obj", mem2d);
    one_draw_scene(dir, "huge_eye_plane", 256, 256, "huge_eye.obj", mem);
    one_draw_scene(dir, "huge_eye_inside", 256, 256, "huge_box.obj", mem);
}

/* Depth: coplanar overlapping triangles under several compare ops, a 1e-4 / 1e5 near/far ratio,
 * and fragments whose depth equals the clear value. */
static void case_depth(const char *dir) {
    px_space p = {256, 256};
    /* Two coplanar triangles in different colours over the same area, drawn in order. */
    for (int layer = 0; layer < 2; layer++) {
        mesh m = mesh_open(dir, layer ? "coplanar_b.obj" : "coplanar_a.obj", 0);
        float c[3];
        flat_colour(20 + (unsigned)layer, c);
        double z = 0.25;
        int a = vtx(&m, ndc_x(p, 20), ndc_y(p, 20), z, c, 0, 0);
        int b = vtx(&m, ndc_x(p, 236), ndc_y(p, 30), z - 0.5, c, 0, 0);
        int d = vtx(&m, ndc_x(p, 40), ndc_y(p, 230), z + 0.5, c, 0, 0);
        tri(&m, a, b, d);
        mesh_close(&m);
    }
    /* Intersecting planes spanning almost the whole depth range of a 1e-4 / 1e5 frustum. */
    mesh far = mesh_open(dir, "near_far.obj", 0);
    float c[3];
    flat_colour(30, c);
    int a = vtx(&far, -1e-4, -1e-4, -1.5e-4, c, 0, 0), b = vtx(&far, 1e4, -1e4, -9e4, c, 0, 0);
    int d = vtx(&far, -1e4, 1e4, -9e4, c, 0, 0);
    tri(&far, a, b, d);
    flat_colour(31, c);
    a = vtx(&far, 1e-4, 1e-4, -1.2e-4, c, 0, 0);
    b = vtx(&far, -1e4, -1e4, -8e4, c, 0, 0);
    d = vtx(&far, 1e4, 0, -9.5e4, c, 0, 0);
    tri(&far, a, b, d);
    mesh_close(&far);
    /* A quad exactly at the far plane (depth 1.0, the clear value). */
    mesh at_far = mesh_open(dir, "at_clear.obj", 0);
    flat_colour(40, c);
    a = vtx(&at_far, -0.8, -0.8, 1, c, 0, 0);
    b = vtx(&at_far, 0.8, -0.8, 1, c, 0, 0);
    d = vtx(&at_far, 0, 0.8, 1, c, 0, 0);
    tri(&at_far, a, b, d);
    mesh_close(&at_far);

    char mem[512];
    static const char *ops[] = {"less", "less_equal", "equal", "greater_equal", "not_equal"};
    for (int i = 0; i < 5; i++) {
        char name[64], extra[96];
        snprintf(name, sizeof name, "depth_coplanar_%s", ops[i]);
        /* The first layer lands with LESS; the second meets the same depths under `op`. */
        scene_file s = scene_open(dir, name, 256, 256, NULL);
        members_2d(mem, sizeof mem, " \"depth_compare\": \"less\",");
        draw(&s, "coplanar_a.obj", mem);
        snprintf(extra, sizeof extra, " \"depth_compare\": \"%s\",", ops[i]);
        members_2d(mem, sizeof mem, extra);
        draw(&s, "coplanar_b.obj", mem);
        scene_close(&s);
    }
    char proj[256], mem3[1024];
    perspective(proj, sizeof proj, 45, 1e-4, 1e5);
    snprintf(mem3, sizeof mem3, "\"mode\": \"vertex_color\", \"worldView\": %s, \"proj\": %s",
             IDENTITY, proj);
    one_draw_scene(dir, "depth_near_far", 256, 256, "near_far.obj", mem3);
    scene_file s = scene_open(dir, "depth_at_clear", 256, 256, NULL);
    members_2d(mem, sizeof mem, " \"depth_compare\": \"less\",");
    draw(&s, "at_clear.obj", mem);
    members_2d(mem, sizeof mem, " \"depth_compare\": \"less_equal\",");
    draw(&s, "at_clear.obj", mem); /* only this one lands */
    scene_close(&s);
}

static void write_png(const char *dir, const char *name, int w, int h, const unsigned char *px) {
    char *path = path_of(dir, "/assets/", name);
    if (!stbi_write_png(path, w, h, 4, px, w * 4)) die("cannot write %s", path);
    free(path);
}

/* A textured quad in pixels with the given texcoords at its corners. */
static void tex_quad(mesh *m, px_space p, double x0, double y0, double x1, double y1, double s0,
                     double t0, double s1, double t1) {
    static const float white[3] = {1, 1, 1};
    int a = vtx(m, ndc_x(p, x0), ndc_y(p, y1), 0, white, s0, t0);
    int b = vtx(m, ndc_x(p, x1), ndc_y(p, y1), 0, white, s1, t0);
    int c = vtx(m, ndc_x(p, x1), ndc_y(p, y0), 0, white, s1, t1);
    int d = vtx(m, ndc_x(p, x0), ndc_y(p, y0), 0, white, s0, t1);
    tri(m, a, b, c);
    tri(m, a, c, d);
}

/* A mesh file holding one textured quad (see tex_quad). */
static void quad_mesh(const char *dir, const char *name, px_space p, double x0, double y0,
                      double x1, double y1, double s0, double t0, double s1, double t1) {
    mesh m = mesh_open(dir, name, 1);
    tex_quad(&m, p, x0, y0, x1, y1, s0, t0, s1, t1);
    mesh_close(&m);
}

/* A textured draw of a 2D mesh: mesh file, texture file, filter, wrap. */
typedef struct tex_draw {
    const char *mesh, *texture, *filter, *wrap;
} tex_draw;

/* A 256 x 256 scene of textured 2D draws with identity matrices. */
static void texture_scene(const char *dir, const char *name, const tex_draw *draws, int n) {
    scene_file s = scene_open(dir, name, 256, 256, NULL);
    for (int i = 0; i < n; i++) {
        char mem[1024];
        snprintf(mem, sizeof mem,
                 "\"mode\": \"texture\", \"texture\": \"assets/%s\", \"filter\": \"%s\", "
                 "\"wrap\": \"%s\", \"worldView\": %s, \"proj\": %s",
                 draws[i].texture, draws[i].filter, draws[i].wrap, IDENTITY, IDENTITY);
        draw(&s, draws[i].mesh, mem);
    }
    scene_close(&s);
}

/* Textures: coordinates near +-1e4 with repeat, 1x1 and non-power-of-two textures, coordinates on
 * texel edges, extreme minification without mipmaps. */
static void case_textures(const char *dir) {
    px_space p = {256, 256};
    unsigned char one[4] = {200, 120, 40, 255};
    write_png(dir, "one.png", 1, 1, one);
    enum { NW = 37, NH = 23 };
    unsigned char npot[NW * NH * 4];
    for (int y = 0; y < NH; y++)
        for (int x = 0; x < NW; x++) {
            unsigned char *q = npot + (y * NW + x) * 4;
            int on = (x + y) & 1;
            q[0] = (unsigned char)(on ? 230 : 20 + x * 5);
            q[1] = (unsigned char)(on ? 230 : 20 + y * 9);
            q[2] = (unsigned char)(on ? 60 : 200);
            q[3] = 255;
        }
    write_png(dir, "npot.png", NW, NH, npot);
    enum { BIG = 512 };
    unsigned char *big = malloc(BIG * BIG * 4);
    if (!big) die("out of memory");
    for (int y = 0; y < BIG; y++)
        for (int x = 0; x < BIG; x++) {
            unsigned char *q = big + ((size_t)y * BIG + x) * 4;
            int on = ((x >> 1) + (y >> 1)) & 1;
            q[0] = q[1] = q[2] = (unsigned char)(on ? 255 : 0);
            q[3] = 255;
        }
    write_png(dir, "fine_checker.png", BIG, BIG, big);
    free(big);

    /* 16 x 16 texture whose texel edges fall exactly on pixel centres below (dyadic values, so
     * the coordinate at those centres is exactly a whole texel). */
    unsigned char pot[16 * 16 * 4];
    for (int y = 0; y < 16; y++)
        for (int x = 0; x < 16; x++) {
            unsigned char *q = pot + (y * 16 + x) * 4;
            q[0] = (unsigned char)(x * 16);
            q[1] = (unsigned char)(y * 16);
            q[2] = (unsigned char)(((x + y) & 1) ? 255 : 60);
            q[3] = 255;
        }
    write_png(dir, "pot16.png", 16, 16, pot);

    /* Far from the origin, and its twin at the origin: the same image under repeat. */
    quad_mesh(dir, "tex_far.obj", p, 8, 8, 248, 248, 9999.0, -10000.0, 10001.0, -9998.0);
    quad_mesh(dir, "tex_far_twin.obj", p, 8, 8, 248, 248, -1.0, 0.0, 1.0, 2.0);
    quad_mesh(dir, "tex_near.obj", p, 8, 8, 120, 120, 0.0, 0.0, 2.0, 2.0);
    quad_mesh(dir, "tex_one.obj", p, 136, 8, 248, 120, -3.0, 0.2, 4.0, 7.0);
    /* 2 pixels a texel, texel edges on the centres of even pixels from x = 8. */
    quad_mesh(dir, "tex_edges.obj", p, 8, 8, 40, 40, -1.0 / 64, -1.0 / 64, 1.0 - 1.0 / 64,
              1.0 - 1.0 / 64);
    quad_mesh(dir, "tex_minify.obj", p, 8, 8, 248, 248, 0.0, 0.0, 40.0, 40.0);

    static const tex_draw far[] = {{"tex_far.obj", "npot.png", "bilinear", "repeat"}};
    texture_scene(dir, "texture_far_coords", far, 1);
    /* The reference renders the twin: lavapipe interpolates texcoords near 1e4 with a resolution
     * of 1e-3 and drifts (docs/accuracy.md); under repeat the exact image is the twin's. */
    static const tex_draw twin[] = {{"tex_far_twin.obj", "npot.png", "bilinear", "repeat"}};
    texture_scene(dir, "texture_far_coords.reference", twin, 1);
    static const tex_draw npot_draws[] = {{"tex_near.obj", "npot.png", "nearest", "repeat"},
                                          {"tex_one.obj", "one.png", "bilinear", "repeat"}};
    texture_scene(dir, "texture_npot_1x1", npot_draws, 2);
    static const tex_draw edges[] = {{"tex_edges.obj", "pot16.png", "nearest", "clamp"}};
    texture_scene(dir, "texture_texel_edges", edges, 1);
    static const tex_draw minify[] = {{"tex_minify.obj", "fine_checker.png", "bilinear", "repeat"}};
    texture_scene(dir, "texture_minify", minify, 1);
}

/* Degenerate input: zero-area, repeated indices, collinear vertices, NaN and infinity. Only the
 * frame of valid triangles may be drawn. */
static void case_degenerate(const char *dir) {
    px_space p = {256, 256};
    char *path = path_of(dir, "/assets/", "degenerate.obj");
    FILE *f = fopen(path, "w");
    if (!f) die("cannot write %s", path);
    free(path);
    fprintf(f, "# degenerate.obj, made by sgapi-hardcases\n");
    /* 1-3: a valid triangle; 4: a point on its edge; 5-7: NaN / inf vertices. */
    fprintf(f, "v %.9g %.9g 0 0.2 0.6 0.9\n", ndc_x(p, 20), ndc_y(p, 20));
    fprintf(f, "v %.9g %.9g 0 0.2 0.6 0.9\n", ndc_x(p, 230), ndc_y(p, 40));
    fprintf(f, "v %.9g %.9g 0 0.2 0.6 0.9\n", ndc_x(p, 60), ndc_y(p, 220));
    fprintf(f, "v %.9g %.9g 0 1 0 0\n", ndc_x(p, 125), ndc_y(p, 30));
    fprintf(f, "v nan 0 0 1 0 0\n");
    fprintf(f, "v 0.5 inf 0 1 0 0\n");
    fprintf(f, "v -inf -inf 0 1 0 0\n");
    fprintf(f, "f 1 2 3\n");
    fprintf(f, "f 1 1 2\nf 2 2 2\nf 1 4 2\n");          /* repeated indices, collinear */
    fprintf(f, "f 1 2 5\nf 5 6 7\nf 3 6 1\nf 7 2 3\n"); /* non-finite */
    if (fclose(f) != 0) die("write failed");
    char mem[512];
    members_2d(mem, sizeof mem, NULL);
    one_draw_scene(dir, "degenerate", 256, 256, "degenerate.obj", mem);
}

int main(int argc, char **argv) {
    if (argc != 2) {
        fprintf(stderr, "usage: sgapi-hardcases OUTDIR\n"
                        "Writes the hard-case scene files to OUTDIR and their assets to "
                        "OUTDIR/assets.\n");
        return 2;
    }
    const char *dir = argv[1];
    char *assets = path_of(dir, "/assets", "");
    mkdir(dir, 0777);
    mkdir(assets, 0777);
    free(assets);
    case_slivers(dir);
    case_grid(dir);
    case_sphere(dir);
    case_pixel_centres(dir);
    case_huge(dir);
    case_depth(dir);
    case_textures(dir);
    case_degenerate(dir);
    return 0;
}
