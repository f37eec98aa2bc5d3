/* shapes.c - standard shapes (cube, tetrahedron, octahedron, icosphere, UV sphere, cylinder, cone,
 * torus, plane) as indexed triangle lists with normals and texture coordinates, into arrays the
 * caller owns. Every shape is centred on the origin, counter-clockwise seen from outside.
 */
#include <sgapi/sgapi_util.h>

#include <math.h>
#include <stddef.h>

#define PI 3.14159265358979323846

/* Largest segment, ring and subdivision counts: they keep every count far inside an int. */
#define MAX_SEGMENTS     1024
#define MAX_SUBDIVISIONS 7

typedef struct out {
    float *pos, *nrm, *uv;
    uint32_t *idx;
    int nv, ni;
} out;

static void vert(out *o, double x, double y, double z, double nx, double ny, double nz, double s,
                 double t) {
    int i = o->nv++;
    o->pos[i * 4] = (float)x, o->pos[i * 4 + 1] = (float)y, o->pos[i * 4 + 2] = (float)z;
    o->pos[i * 4 + 3] = 1.0f;
    double l = sqrt(nx * nx + ny * ny + nz * nz);
    if (l > 0) nx /= l, ny /= l, nz /= l;
    o->nrm[i * 3] = (float)nx, o->nrm[i * 3 + 1] = (float)ny, o->nrm[i * 3 + 2] = (float)nz;
    o->uv[i * 2] = (float)s, o->uv[i * 2 + 1] = (float)t;
}

static void tri(out *o, int a, int b, int c) {
    o->idx[o->ni++] = (uint32_t)a, o->idx[o->ni++] = (uint32_t)b, o->idx[o->ni++] = (uint32_t)c;
}

/* A grid of (cols + 1) x (rows + 1) vertices from vertex `base`, two triangles per cell, with
 * vertex (i, j) at base + j * (cols + 1) + i; (i, j) -> (i + 1, j) -> (i, j + 1) is
 * counter-clockwise from outside. */
static void grid(out *o, int base, int cols, int rows) {
    for (int j = 0; j < rows; j++)
        for (int i = 0; i < cols; i++) {
            int a = base + j * (cols + 1) + i, b = a + 1, c = a + cols + 1, d = c + 1;
            tri(o, a, b, d);
            tri(o, a, d, c);
        }
}

/* A flat triangle with its own vertices and face normal, texture (0,0) (1,0) (0.5,1). */
static void flat_tri(out *o, const double *a, const double *b, const double *c) {
    double u[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    double v[3] = {c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    double n[3] = {u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]};
    int i = o->nv;
    vert(o, a[0], a[1], a[2], n[0], n[1], n[2], 0, 0);
    vert(o, b[0], b[1], b[2], n[0], n[1], n[2], 1, 0);
    vert(o, c[0], c[1], c[2], n[0], n[1], n[2], 0.5, 1);
    tri(o, i, i + 1, i + 2);
}

static void cube(out *o, double h) {
    /* Per face: its normal and two axes (u, v) with u x v = normal, so (0,0) (1,0) (1,1) (0,1)
     * runs counter-clockwise from outside. */
    static const int f[6][3][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}}, {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}},
    };
    for (int k = 0; k < 6; k++) {
        int base = o->nv;
        for (int j = 0; j < 2; j++)
            for (int i = 0; i < 2; i++) {
                double s = i * 2 - 1, t = j * 2 - 1, p[3];
                for (int c = 0; c < 3; c++)
                    p[c] = h * (f[k][0][c] + s * f[k][1][c] + t * f[k][2][c]);
                vert(o, p[0], p[1], p[2], f[k][0][0], f[k][0][1], f[k][0][2], i, j);
            }
        grid(o, base, 1, 1);
    }
}

static void tetrahedron(out *o, double r) {
    double k = r / sqrt(3.0);
    double v[4][3] = {{k, k, k}, {k, -k, -k}, {-k, k, -k}, {-k, -k, k}};
    flat_tri(o, v[0], v[2], v[3]);
    flat_tri(o, v[0], v[3], v[1]);
    flat_tri(o, v[0], v[1], v[2]);
    flat_tri(o, v[1], v[3], v[2]);
}

static void octahedron(out *o, double r) {
    for (int k = 0; k < 8; k++) {
        double sx = k & 1 ? -r : r, sy = k & 2 ? -r : r, sz = k & 4 ? -r : r;
        double a[3] = {sx, 0, 0}, b[3] = {0, sy, 0}, c[3] = {0, 0, sz};
        /* An odd number of negative axes flips the winding. */
        int neg = (sx < 0) + (sy < 0) + (sz < 0);
        if (neg % 2 == 0)
            flat_tri(o, a, b, c);
        else
            flat_tri(o, a, c, b);
    }
}

static void sphere_vert(out *o, double x, double y, double z, double r) {
    double l = sqrt(x * x + y * y + z * z);
    x /= l, y /= l, z /= l;
    double s = atan2(x, z) / (2 * PI) + 0.5, t = asin(y < -1 ? -1 : y > 1 ? 1 : y) / PI + 0.5;
    vert(o, x * r, y * r, z * r, x, y, z, s, t);
}

static void icosphere(out *o, double r, int subdivisions) {
    const double g = (1 + sqrt(5.0)) / 2;
    const double v[12][3] = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0},
                             {0, -1, g}, {0, 1, g}, {0, -1, -g}, {0, 1, -g},
                             {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
    static const int f[20][3] = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                 {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                 {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                 {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
    int n = 1 << subdivisions;
    /* Each face split into n x n triangles on its own vertices, projected onto the sphere. */
    for (int k = 0; k < 20; k++) {
        const double *a = v[f[k][0]], *b = v[f[k][1]], *c = v[f[k][2]];
        int base = o->nv;
        for (int j = 0; j <= n; j++)
            for (int i = 0; i <= n - j; i++) {
                double wb = (double)i / n, wc = (double)j / n, wa = 1 - wb - wc;
                sphere_vert(o, wa * a[0] + wb * b[0] + wc * c[0], wa * a[1] + wb * b[1] + wc * c[1],
                            wa * a[2] + wb * b[2] + wc * c[2], r);
            }
        /* Row j starts at base + j * (n + 1) - j * (j - 1) / 2. */
        for (int j = 0; j < n; j++) {
            int row = base + j * (n + 1) - j * (j - 1) / 2, next = row + (n + 1 - j);
            for (int i = 0; i < n - j; i++) {
                tri(o, row + i, row + i + 1, next + i);
                if (i < n - j - 1) tri(o, row + i + 1, next + i + 1, next + i);
            }
        }
    }
}

static void uv_sphere(out *o, double r, int seg, int rings) {
    int base = o->nv;
    for (int j = 0; j <= rings; j++) {
        double phi = PI * j / rings - PI / 2; /* from the south pole up */
        for (int i = 0; i <= seg; i++) {
            double th = 2 * PI * i / seg;
            double x = cos(phi) * sin(th), y = sin(phi), z = cos(phi) * cos(th);
            vert(o, x * r, y * r, z * r, x, y, z, (double)i / seg, (double)j / rings);
        }
    }
    grid(o, base, seg, rings);
}

/* A disc of radius r at height y facing up (+1) or down (-1): a centre and a ring. */
static void disc(out *o, double r, double y, int up, int seg) {
    int c = o->nv;
    vert(o, 0, y, 0, 0, up, 0, 0.5, 0.5);
    for (int i = 0; i <= seg; i++) {
        double th = 2 * PI * i / seg, x = sin(th), z = cos(th);
        vert(o, x * r, y, z * r, 0, up, 0, 0.5 + 0.5 * x, 0.5 - 0.5 * z * up);
    }
    for (int i = 0; i < seg; i++) {
        if (up > 0)
            tri(o, c, c + 1 + i, c + 2 + i);
        else
            tri(o, c, c + 2 + i, c + 1 + i);
    }
}

/* The side of a cylinder (r0 = r1) or cone (r1 = 0) from y = -h/2 to h/2. */
static void side(out *o, double r0, double r1, double h, int seg) {
    int base = o->nv;
    /* The normal leans by the slope: (x, (r0 - r1) / h, z). */
    double ny = (r0 - r1) / h;
    for (int j = 0; j <= 1; j++)
        for (int i = 0; i <= seg; i++) {
            /* The apex of a cone takes each segment's middle direction, so its shading is even. */
            double th = 2 * PI * (i + (j && r1 == 0 ? 0.5 : 0)) / seg, x = sin(th), z = cos(th);
            double r = j ? r1 : r0;
            vert(o, x * r, j ? h / 2 : -h / 2, z * r, x, ny, z, (double)i / seg, j);
        }
    grid(o, base, seg, 1);
}

static void torus(out *o, double big, double small, int seg, int rings) {
    int base = o->nv;
    for (int j = 0; j <= rings; j++) {
        double ph = 2 * PI * j / rings, cp = cos(ph), sp = sin(ph);
        for (int i = 0; i <= seg; i++) {
            double th = 2 * PI * i / seg, x = sin(th), z = cos(th);
            /* The tube's circle, starting outside and going over the top. */
            double d = big + small * cp;
            vert(o, x * d, small * sp, z * d, x * cp, sp, z * cp, (double)i / seg,
                 (double)j / rings);
        }
    }
    grid(o, base, seg, rings);
}

static void plane(out *o, double size, int seg) {
    int base = o->nv;
    for (int j = 0; j <= seg; j++)
        for (int i = 0; i <= seg; i++) {
            double s = (double)i / seg, t = (double)j / seg;
            vert(o, (s - 0.5) * size, 0, (0.5 - t) * size, 0, 1, 0, s, t);
        }
    grid(o, base, seg, seg);
}

/* The description with defaults filled in, or -1 if a value is out of range. */
static int resolve(const sguShapeDesc *d, sguShapeDesc *r) {
    if (!d) return -1;
    *r = *d;
    if (r->segments == 0) r->segments = r->shape == SGU_SHAPE_PLANE ? 1 : 32;
    if (r->rings == 0) r->rings = 16;
    if (r->size == 0) r->size = 1;
    if (r->radius == 0) r->radius = r->shape == SGU_SHAPE_TORUS ? 0.35f : 0.5f;
    if (r->height == 0) r->height = 1;
    if (r->tube_radius == 0) r->tube_radius = 0.15f;
    if ((unsigned)r->shape > SGU_SHAPE_PLANE) return -1;
    if (r->segments < 3 && r->shape != SGU_SHAPE_PLANE) return -1;
    if (r->segments < 1 || r->segments > MAX_SEGMENTS || r->rings < 2 || r->rings > MAX_SEGMENTS)
        return -1;
    if (r->subdivisions < 0 || r->subdivisions > MAX_SUBDIVISIONS) return -1;
    if (!(r->size > 0 && r->radius > 0 && r->height > 0 && r->tube_radius > 0)) return -1;
    if (!isfinite(r->size) || !isfinite(r->radius) || !isfinite(r->height) ||
        !isfinite(r->tube_radius))
        return -1;
    return 0;
}

int sgu_shape_counts(const sguShapeDesc *desc, int *vertex_count, int *index_count) {
    sguShapeDesc d;
    if (resolve(desc, &d) != 0 || !vertex_count || !index_count) return -1;
    int s = d.segments, r = d.rings, n = 1 << d.subdivisions, v = 0, t = 0;
    switch (d.shape) {
    case SGU_SHAPE_CUBE:
        v = 24, t = 12;
        break;
    case SGU_SHAPE_TETRAHEDRON:
        v = 12, t = 4;
        break;
    case SGU_SHAPE_OCTAHEDRON:
        v = 24, t = 8;
        break;
    case SGU_SHAPE_ICOSPHERE:
        v = 20 * (n + 1) * (n + 2) / 2, t = 20 * n * n;
        break;
    case SGU_SHAPE_UV_SPHERE:
        v = (s + 1) * (r + 1), t = 2 * s * r;
        break;
    case SGU_SHAPE_CYLINDER:
        v = 2 * (s + 1) + 2 * (s + 2), t = 2 * s + 2 * s;
        break;
    case SGU_SHAPE_CONE:
        v = 2 * (s + 1) + (s + 2), t = 2 * s + s;
        break;
    case SGU_SHAPE_TORUS:
        v = (s + 1) * (r + 1), t = 2 * s * r;
        break;
    case SGU_SHAPE_PLANE:
        v = (s + 1) * (s + 1), t = 2 * s * s;
        break;
    }
    *vertex_count = v;
    *index_count = 3 * t;
    return 0;
}

int sgu_shape_build(const sguShapeDesc *desc, float *positions, float *normals, float *texcoords,
                    uint32_t *indices) {
    sguShapeDesc d;
    if (resolve(desc, &d) != 0 || !positions || !normals || !texcoords || !indices) return -1;
    out o = {positions, normals, texcoords, indices, 0, 0};
    switch (d.shape) {
    case SGU_SHAPE_CUBE:
        cube(&o, d.size / 2.0);
        break;
    case SGU_SHAPE_TETRAHEDRON:
        tetrahedron(&o, d.radius);
        break;
    case SGU_SHAPE_OCTAHEDRON:
        octahedron(&o, d.radius);
        break;
    case SGU_SHAPE_ICOSPHERE:
        icosphere(&o, d.radius, d.subdivisions);
        break;
    case SGU_SHAPE_UV_SPHERE:
        uv_sphere(&o, d.radius, d.segments, d.rings);
        break;
    case SGU_SHAPE_CYLINDER:
        side(&o, d.radius, d.radius, d.height, d.segments);
        disc(&o, d.radius, d.height / 2, 1, d.segments);
        disc(&o, d.radius, -d.height / 2, -1, d.segments);
        break;
    case SGU_SHAPE_CONE:
        side(&o, d.radius, 0, d.height, d.segments);
        disc(&o, d.radius, -d.height / 2, -1, d.segments);
        break;
    case SGU_SHAPE_TORUS:
        torus(&o, d.radius, d.tube_radius, d.segments, d.rings);
        break;
    case SGU_SHAPE_PLANE:
        plane(&o, d.size, d.segments);
        break;
    }
    return 0;
}

int sgu_shape_from_name(const char *name, sguShape *out) {
    static const char *const names[] = {"cube",      "tetrahedron", "octahedron",
                                        "icosphere", "sphere",      "cylinder",
                                        "cone",      "torus",       "plane"};
    if (!name || !out) return -1;
    for (int i = 0; i < (int)(sizeof names / sizeof names[0]); i++) {
        const char *a = names[i], *b = name;
        while (*a && *a == *b) a++, b++;
        if (!*a && !*b) {
            *out = (sguShape)i;
            return 0;
        }
    }
    return -1;
}
