/* sgapi-assets - writes the project's default scenes and every asset they use, all made from code.
 *
 *   sgapi-assets OUTDIR
 *
 * Writes OUTDIR/default.json (eight scenes, format in docs/scene-format.md), the feature files
 * (transparency.json, lighting.json, shadows.json, lines.json) and OUTDIR/assets/: OBJ meshes
 * (triangles, quad, plane, pyramid, cubes, the Utah teapot tessellated from its Bezier patches,
 * line sets) and PNG textures (checker, mosaic, brick, terrain height map and colour). Every value
 * comes from code and fixed seeds, never from the clock or the C library's rand(), so two runs
 * give byte-identical files: the assets_reproducible test compares a fresh run with the committed
 * scenes/ folder. Meshes that scenes draw with culling are checked for outward winding before
 * anything is written.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <math.h>
#include <stdbool.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/types.h>

#include <stb_image_write.h>

#include "teapot_patches.h"

static const double PI = 3.14159265358979323846;

/* Height of the terrain's brightest height-map pixel in height-map pixels (the terrain is 256
 * pixels wide): used by the scene and by the colour texture's baked shading, which must agree. */
static const double TERRAIN_HEIGHT_SCALE = 36.0;

/* ---------------------------------------------------------------------------------------------
 * Small vector and matrix maths. Everything is double: outputs are rounded to a few decimals or
 * to 8 bits, so last-bit differences between compilers (contracted multiply-adds, libm) almost
 * never reach the files, and the committed scenes stay reproducible elsewhere.
 */

typedef struct vec3 {
    double x, y, z;
} vec3;

static vec3 v3(double x, double y, double z) {
    return (vec3){x, y, z};
}
static vec3 v3_add(vec3 a, vec3 b) {
    return v3(a.x + b.x, a.y + b.y, a.z + b.z);
}
static vec3 v3_sub(vec3 a, vec3 b) {
    return v3(a.x - b.x, a.y - b.y, a.z - b.z);
}
static vec3 v3_scale(vec3 a, double s) {
    return v3(a.x * s, a.y * s, a.z * s);
}
static double v3_dot(vec3 a, vec3 b) {
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
static vec3 v3_cross(vec3 a, vec3 b) {
    return v3(a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x);
}
static double v3_len(vec3 a) {
    return sqrt(v3_dot(a, a));
}
static vec3 v3_norm(vec3 a) {
    double l = v3_len(a);
    return l > 0.0 ? v3_scale(a, 1.0 / l) : a;
}

/* Row-major like the scene format (m[r * 4 + c]), acting on column vectors. */
typedef struct mat4 {
    double m[16];
} mat4;

static mat4 mat_identity(void) {
    mat4 r = {{0}};
    r.m[0] = r.m[5] = r.m[10] = r.m[15] = 1.0;
    return r;
}

static mat4 mat_mul(mat4 a, mat4 b) {
    mat4 r;
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += a.m[i * 4 + k] * b.m[k * 4 + j];
            r.m[i * 4 + j] = s;
        }
    }
    return r;
}

static mat4 mat_translate(double x, double y, double z) {
    mat4 r = mat_identity();
    r.m[3] = x;
    r.m[7] = y;
    r.m[11] = z;
    return r;
}

static mat4 mat_scale(double x, double y, double z) {
    mat4 r = mat_identity();
    r.m[0] = x;
    r.m[5] = y;
    r.m[10] = z;
    return r;
}

/* Exact values for multiples of 90 degrees, so such rotations print as plain 0 and 1. */
static void sin_cos_deg(double deg, double *s, double *c) {
    double q = deg / 90.0;
    if (q == floor(q)) {
        static const double qs[4] = {0, 1, 0, -1};
        long k = ((long)q % 4 + 4) % 4;
        *s = qs[k];
        *c = qs[(k + 1) % 4];
        return;
    }
    *s = sin(deg * PI / 180.0);
    *c = cos(deg * PI / 180.0);
}

static mat4 mat_rotate_x(double deg) {
    double s, c;
    sin_cos_deg(deg, &s, &c);
    mat4 r = mat_identity();
    r.m[5] = c;
    r.m[6] = -s;
    r.m[9] = s;
    r.m[10] = c;
    return r;
}

static mat4 mat_rotate_y(double deg) {
    double s, c;
    sin_cos_deg(deg, &s, &c);
    mat4 r = mat_identity();
    r.m[0] = c;
    r.m[2] = s;
    r.m[8] = -s;
    r.m[10] = c;
    return r;
}

static mat4 mat_rotate_z(double deg) {
    double s, c;
    sin_cos_deg(deg, &s, &c);
    mat4 r = mat_identity();
    r.m[0] = c;
    r.m[1] = -s;
    r.m[4] = s;
    r.m[5] = c;
    return r;
}

/* OpenGL's gluPerspective: camera looks down -z, clip z in [-w, w]. */
static mat4 mat_perspective(double fovy_deg, double aspect, double znear, double zfar) {
    double f = 1.0 / tan(fovy_deg * PI / 360.0);
    mat4 r = {{0}};
    r.m[0] = f / aspect;
    r.m[5] = f;
    r.m[10] = (zfar + znear) / (znear - zfar);
    r.m[11] = 2.0 * zfar * znear / (znear - zfar);
    r.m[14] = -1.0;
    return r;
}

/* A camera at eye looking at target: a rotation (rows right, up, back) times a translation. */
static mat4 mat_look_at(vec3 eye, vec3 target, vec3 up) {
    vec3 back = v3_norm(v3_sub(eye, target));
    vec3 right = v3_norm(v3_cross(up, back));
    vec3 true_up = v3_cross(back, right);
    mat4 r = mat_identity();
    const vec3 rows[3] = {right, true_up, back};
    for (int i = 0; i < 3; i++) {
        r.m[i * 4 + 0] = rows[i].x;
        r.m[i * 4 + 1] = rows[i].y;
        r.m[i * 4 + 2] = rows[i].z;
        r.m[i * 4 + 3] = -v3_dot(rows[i], eye);
    }
    return r;
}

static vec3 mat_apply(mat4 a, vec3 p) {
    return v3(a.m[0] * p.x + a.m[1] * p.y + a.m[2] * p.z + a.m[3],
              a.m[4] * p.x + a.m[5] * p.y + a.m[6] * p.z + a.m[7],
              a.m[8] * p.x + a.m[9] * p.y + a.m[10] * p.z + a.m[11]);
}

/* ---------------------------------------------------------------------------------------------
 * Randomness: a seeded PRNG for layouts and an integer hash for value noise. Both are our own
 * so the sequence never depends on the platform.
 */

typedef struct rng {
    uint64_t state;
} rng;

/* SplitMix64: tiny, full period, good enough for picking colours and positions. */
static uint64_t rng_next(rng *r) {
    uint64_t z = (r->state += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

/* Uniform in [0, 1) from the top 53 bits, exact in a double. */
static double rng_unit(rng *r) {
    return (double)(rng_next(r) >> 11) * (1.0 / 9007199254740992.0);
}

static double rng_range(rng *r, double lo, double hi) {
    return lo + (hi - lo) * rng_unit(r);
}

/* Mixes lattice coordinates and a seed into 32 well-spread bits (ends with murmur3's mixer). */
static uint32_t hash2(uint32_t x, uint32_t y, uint32_t seed) {
    uint32_t h = seed * 0x9E3779B1u;
    h ^= x * 0x85EBCA6Bu;
    h = (h << 13) | (h >> 19);
    h = h * 5u + 0xE6546B64u;
    h ^= y * 0xC2B2AE35u;
    h = (h << 17) | (h >> 15);
    h = h * 0x1B873593u;
    h ^= h >> 16;
    h *= 0x85EBCA6Bu;
    h ^= h >> 13;
    h *= 0xC2B2AE35u;
    h ^= h >> 16;
    return h;
}

static int wrap_int(int v, int period) {
    return ((v % period) + period) % period;
}

/* Value noise in [0, 1] on an integer lattice that repeats every `period` cells, so textures built
 * from it tile seamlessly under repeat wrapping. Quintic fade keeps the slope continuous. */
static double value_noise(double x, double y, int period, uint32_t seed) {
    double fx = floor(x), fy = floor(y);
    int ix = (int)fx, iy = (int)fy;
    double tx = x - fx, ty = y - fy;
    double sx = tx * tx * tx * (tx * (tx * 6.0 - 15.0) + 10.0);
    double sy = ty * ty * ty * (ty * (ty * 6.0 - 15.0) + 10.0);
    int x0 = wrap_int(ix, period), x1 = wrap_int(ix + 1, period);
    int y0 = wrap_int(iy, period), y1 = wrap_int(iy + 1, period);
    const double inv = 1.0 / 4294967295.0;
    double a = hash2((uint32_t)x0, (uint32_t)y0, seed) * inv;
    double b = hash2((uint32_t)x1, (uint32_t)y0, seed) * inv;
    double c = hash2((uint32_t)x0, (uint32_t)y1, seed) * inv;
    double d = hash2((uint32_t)x1, (uint32_t)y1, seed) * inv;
    double top = a + (b - a) * sx, bottom = c + (d - c) * sx;
    return top + (bottom - top) * sy;
}

/* Sum of octaves at texture coordinates (u, v) in [0, 1): octave k has period base << k cells and
 * half the previous amplitude. The result is normalised back to [0, 1]. */
static double fbm(double u, double v, int base_period, int octaves, uint32_t seed) {
    double sum = 0.0, amp = 1.0, total = 0.0;
    int period = base_period;
    for (int k = 0; k < octaves; k++) {
        sum += amp * value_noise(u * period, v * period, period, seed + (uint32_t)k * 7919u);
        total += amp;
        amp *= 0.5;
        period *= 2;
    }
    return sum / total;
}

/* ---------------------------------------------------------------------------------------------
 * Images and colours.
 */

typedef struct image {
    int w, h, comp;
    unsigned char *px; /* top row first, as PNG stores it */
} image;

static void *xmalloc(size_t n) {
    void *p = calloc(1, n);
    if (!p) {
        fputs("sgapi-assets: out of memory\n", stderr);
        exit(1);
    }
    return p;
}

static image image_new(int w, int h, int comp) {
    image im = {w, h, comp, xmalloc((size_t)w * (size_t)h * (size_t)comp)};
    return im;
}

/* Round to nearest after clamping: the same rule the renderer uses for its output. */
static unsigned char to_u8(double v) {
    if (!(v > 0.0)) return 0;
    if (v >= 1.0) return 255;
    return (unsigned char)floor(v * 255.0 + 0.5);
}

static void put_rgb(image *im, int x, int y, vec3 c) {
    unsigned char *p = im->px + ((size_t)y * (size_t)im->w + (size_t)x) * (size_t)im->comp;
    p[0] = to_u8(c.x);
    p[1] = to_u8(c.y);
    p[2] = to_u8(c.z);
}

static bool image_write(const image *im, const char *path) {
    if (!stbi_write_png(path, im->w, im->h, im->comp, im->px, im->w * im->comp)) {
        fprintf(stderr, "sgapi-assets: cannot write %s\n", path);
        return false;
    }
    return true;
}

static vec3 mix3(vec3 a, vec3 b, double t) {
    return v3_add(a, v3_scale(v3_sub(b, a), t));
}

static double clamp01(double v) {
    return v < 0.0 ? 0.0 : v > 1.0 ? 1.0 : v;
}

static double smoothstep(double e0, double e1, double x) {
    double t = clamp01((x - e0) / (e1 - e0));
    return t * t * (3.0 - 2.0 * t);
}

static vec3 hsv(double h, double s, double v) {
    h = (h - floor(h)) * 6.0;
    int i = (int)h;
    double f = h - i, p = v * (1.0 - s), q = v * (1.0 - s * f), t = v * (1.0 - s * (1.0 - f));
    switch (i) {
    case 0:
        return v3(v, t, p);
    case 1:
        return v3(q, v, p);
    case 2:
        return v3(p, v, t);
    case 3:
        return v3(p, q, v);
    case 4:
        return v3(t, p, v);
    default:
        return v3(v, p, q);
    }
}

/* ---------------------------------------------------------------------------------------------
 * Textures. Pixel (x, y) counts rows from the top of the image as displayed; texcoord t = 0 is the
 * bottom row.
 */

/* 8 x 8 checker with thin grid lines. The cell at texcoord (0, 0) (bottom left) is red so a
 * mirrored or rotated mapping shows at a glance. */
static bool make_checker(const char *path) {
    enum { N = 256, CELL = 32 };
    image im = image_new(N, N, 3);
    const vec3 light = v3(0.92, 0.90, 0.84), dark = v3(0.20, 0.32, 0.47);
    const vec3 line = v3(0.08, 0.09, 0.12), marker = v3(0.85, 0.18, 0.12);
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            int cx = x / CELL, cy = y / CELL;
            vec3 c = ((cx + cy) & 1) ? dark : light;
            if (cx == 0 && cy == N / CELL - 1) c = marker;
            /* One pixel on each side of every cell border, so the repeat seam looks like any
             * other grid line. */
            int mx = x % CELL, my = y % CELL;
            if (mx == 0 || mx == CELL - 1 || my == 0 || my == CELL - 1) c = line;
            put_rgb(&im, x, y, c);
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* Voronoi tiles in varied colours with dark grout; distances wrap around so the texture tiles. */
static bool make_mosaic(const char *path) {
    enum { N = 128, SEEDS = 22 };
    rng r = {0x5EED0002u};
    double sx[SEEDS], sy[SEEDS];
    vec3 col[SEEDS];
    for (int i = 0; i < SEEDS; i++) {
        sx[i] = rng_range(&r, 0.0, N);
        sy[i] = rng_range(&r, 0.0, N);
        /* Hues spread by the golden ratio so neighbours rarely look alike. */
        double hue = 0.13 + i * 0.618034 + rng_range(&r, -0.05, 0.05);
        /* One draw per statement: the order of a call's arguments is unspecified. */
        double sat = rng_range(&r, 0.45, 0.85);
        double val = rng_range(&r, 0.70, 0.95);
        col[i] = hsv(hue, sat, val);
    }
    image im = image_new(N, N, 3);
    const vec3 grout = v3(0.13, 0.11, 0.10);
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            double px = x + 0.5, py = y + 0.5;
            double d1 = 1e30, d2 = 1e30;
            int best = 0;
            for (int i = 0; i < SEEDS; i++) {
                double dx = fabs(px - sx[i]), dy = fabs(py - sy[i]);
                if (dx > N / 2) dx = N - dx;
                if (dy > N / 2) dy = N - dy;
                double d = sqrt(dx * dx + dy * dy);
                if (d < d1) {
                    d2 = d1;
                    d1 = d;
                    best = i;
                } else if (d < d2) {
                    d2 = d;
                }
            }
            vec3 c = col[best];
            /* Slightly darker towards a tile's rim, like a glazed tile. */
            c = v3_scale(c, 1.0 - 0.18 * smoothstep(2.0, 9.0, 9.0 - (d2 - d1)));
            if (d2 - d1 < 1.6) c = grout;
            put_rgb(&im, x, y, c);
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* Running-bond bricks, each with its own shade, on light mortar; tiles in both directions. */
static bool make_brick(const char *path) {
    enum { N = 256, BW = 64, BH = 32, MORTAR = 2 };
    image im = image_new(N, N, 3);
    const vec3 base = v3(0.60, 0.26, 0.17), mortar = v3(0.74, 0.72, 0.67);
    for (int y = 0; y < N; y++) {
        int row = y / BH;
        for (int x = 0; x < N; x++) {
            int shifted = x + ((row & 1) ? BW / 2 : 0);
            int col = (shifted / BW) % (N / BW);
            int mx = shifted % BW, my = y % BH;
            double u = (x + 0.5) / N, v = (y + 0.5) / N;
            double grain = fbm(u, v, 32, 3, 0xB41Cu);
            vec3 c;
            if (mx < MORTAR || mx >= BW - MORTAR || my < MORTAR || my >= BH - MORTAR) {
                c = v3_scale(mortar, 0.92 + 0.16 * grain);
            } else {
                uint32_t h = hash2((uint32_t)col, (uint32_t)row, 0xB41Cu);
                double shade = 0.80 + 0.35 * ((h & 0xFFu) / 255.0);
                double warm = ((h >> 8) & 0xFFu) / 255.0;
                c = v3_scale(mix3(base, v3(0.55, 0.32, 0.22), warm), shade);
                c = v3_scale(c, 0.88 + 0.24 * grain);
            }
            put_rgb(&im, x, y, c);
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* The bricks of make_brick as a tangent-space normal map (the `normal_map` shader's texture 0):
 * each brick a raised block whose edges slope down over 4 texels to the mortar, with a little
 * grain. r, g, b = x, y, z of the unit normal mapped from [-1, 1] to [0, 1], x along s (to the
 * right) and y along t (up the image as displayed). */
static double brick_relief(int x, int y) {
    enum { N = 256, BW = 64, BH = 32, MORTAR = 2, SLOPE = 4 };
    x = wrap_int(x, N), y = wrap_int(y, N);
    int row = y / BH;
    int shifted = x + ((row & 1) ? BW / 2 : 0);
    int mx = shifted % BW, my = y % BH;
    int dx = mx - MORTAR < BW - MORTAR - 1 - mx ? mx - MORTAR : BW - MORTAR - 1 - mx;
    int dy = my - MORTAR < BH - MORTAR - 1 - my ? my - MORTAR : BH - MORTAR - 1 - my;
    int d = dx < dy ? dx : dy; /* texels inside the brick's edge; < 0 in the mortar */
    double grain = fbm((x + 0.5) / N, (y + 0.5) / N, 32, 3, 0xB41Du);
    double h = d < 0 ? 0.0 : smoothstep(0.0, SLOPE, d + 1.0);
    return h + 0.15 * grain;
}

static bool make_brick_normal(const char *path) {
    enum { N = 256 };
    const double strength = 1.5; /* height units per texel of slope */
    image im = image_new(N, N, 3);
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            double dhdx = 0.5 * (brick_relief(x + 1, y) - brick_relief(x - 1, y));
            /* t grows up the image, y down it */
            double dhdt = 0.5 * (brick_relief(x, y - 1) - brick_relief(x, y + 1));
            vec3 n = v3_norm(v3(-strength * dhdx, -strength * dhdt, 1.0));
            put_rgb(&im, x, y, v3(0.5 + 0.5 * n.x, 0.5 + 0.5 * n.y, 0.5 + 0.5 * n.z));
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* RGBA: a round lattice window. Its bars are opaque and shaded by hue; the panes are cut out
 * (alpha 0) in a ring and glazed with alpha falling from 0.9 at the top to 0.1 at the bottom
 * elsewhere, so one texture shows a hard cut-out edge and a smooth alpha gradient. */
static bool make_cutout(const char *path) {
    enum { N = 256, CELL = 32, BAR = 5 };
    image im = image_new(N, N, 4);
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            unsigned char *p = im.px + ((size_t)y * N + (size_t)x) * 4;
            double u = (x + 0.5) / N - 0.5, v = (y + 0.5) / N - 0.5;
            double r = sqrt(u * u + v * v);
            int mx = x % CELL, my = y % CELL;
            bool bar = mx < BAR || my < BAR || r > 0.47;
            vec3 c;
            double alpha;
            if (bar) {
                c = v3_scale(hsv(0.08 + 0.5 * r, 0.55, 0.85), 0.75 + 0.5 * (0.5 - v) * 0.5);
                alpha = 1.0;
            } else if (r > 0.28 && r < 0.38) {
                c = v3(0, 0, 0);
                alpha = 0.0;
            } else {
                c = hsv(0.55 + 0.25 * u, 0.6, 0.95);
                alpha = 0.1 + 0.8 * (1.0 - (y + 0.5) / N);
            }
            put_rgb(&im, x, y, c);
            p[3] = to_u8(alpha);
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

enum { HEIGHT_N = 256, TERRAIN_COLOR_N = 512 };

/* Ridged octave noise: 1 - |2n - 1| per octave turns smooth bumps into sharp crests. Each octave's
 * lattice is turned by another angle, or the crests would line up with the lattice axes. */
static double ridged(double u, double v, double base_freq, int octaves, uint32_t seed) {
    enum { NO_WRAP = 1 << 20 };
    double sum = 0.0, amp = 1.0, total = 0.0, freq = base_freq;
    for (int k = 0; k < octaves; k++) {
        double a = 0.61 * (k + 1), c = cos(a), s = sin(a);
        double x = (c * u - s * v) * freq + 1000.0, y = (s * u + c * v) * freq + 1000.0;
        double n = value_noise(x, y, NO_WRAP, seed + (uint32_t)k * 104729u);
        double r = 1.0 - fabs(2.0 * n - 1.0);
        sum += amp * r * r;
        total += amp;
        amp *= 0.5;
        freq *= 2.0;
    }
    return sum / total;
}

/* Rolling hills from octave value noise, a range of ridged mountains winding across, and
 * everything below a water line flattened into lakes. Grey, 0..255; kept in `out` for the colour
 * texture. */
static bool make_height(const char *path, unsigned char *out) {
    enum { N = HEIGHT_N };
    double *h = xmalloc(sizeof(double) * N * N);
    double lo = 1e30, hi = -1e30;
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            double u = (x + 0.5) / N, v = (y + 0.5) / N;
            double hills = fbm(u, v, 4, 6, 0x7E22A1u);
            /* A mountain range winds across the map; its width wobbles with low noise. */
            double range_v = 0.45 + 0.17 * sin(2.0 * PI * (1.1 * u + 0.1));
            double off = fabs(v - range_v) + 0.25 * (fbm(u, v, 2, 3, 0x21D6Eu) - 0.5);
            double mask = smoothstep(0.30, 0.04, off);
            double e = 0.65 * hills + 0.45 * mask * (0.25 + 0.75 * ridged(u, v, 4.0, 5, 0x4C1Du));
            h[y * N + x] = e;
            if (e < lo) lo = e;
            if (e > hi) hi = e;
        }
    }
    const double water = 0.17;
    image im = image_new(N, N, 1);
    for (int i = 0; i < N * N; i++) {
        double e = (h[i] - lo) / (hi - lo);
        e = e < water ? 0.0 : (e - water) / (1.0 - water);
        e = pow(e, 1.25); /* flatter lowlands, steeper peaks */
        im.px[i] = to_u8(e);
        out[i] = im.px[i];
    }
    free(h);
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* Bilinear read of the height map at continuous pixel coordinates, clamped to the edge. */
static double height_at(const unsigned char *hm, double x, double y) {
    if (x < 0.0) x = 0.0;
    if (y < 0.0) y = 0.0;
    if (x > HEIGHT_N - 1) x = HEIGHT_N - 1;
    if (y > HEIGHT_N - 1) y = HEIGHT_N - 1;
    int x0 = (int)x, y0 = (int)y;
    int x1 = x0 + 1 < HEIGHT_N ? x0 + 1 : x0, y1 = y0 + 1 < HEIGHT_N ? y0 + 1 : y0;
    double fx = x - x0, fy = y - y0;
    double a = hm[y0 * HEIGHT_N + x0], b = hm[y0 * HEIGHT_N + x1];
    double c = hm[y1 * HEIGHT_N + x0], d = hm[y1 * HEIGHT_N + x1];
    return ((a + (b - a) * fx) * (1.0 - fy) + (c + (d - c) * fx) * fy) / 255.0;
}

/* The terrain's colour: a ramp by height (water, sand, grass, forest, rock, snow), rock on steep
 * slopes, a little noise, and baked sun shading, because the pipeline has no lighting of its own
 * and the relief would otherwise be invisible. */
static bool make_terrain_color(const char *path, const unsigned char *hm) {
    enum { N = TERRAIN_COLOR_N };
    static const struct {
        double h;
        vec3 c;
    } ramp[] = {
        {0.00, {0.80, 0.74, 0.52}}, {0.05, {0.72, 0.68, 0.45}}, {0.10, {0.36, 0.56, 0.22}},
        {0.35, {0.27, 0.47, 0.18}}, {0.52, {0.19, 0.34, 0.15}}, {0.62, {0.42, 0.38, 0.32}},
        {0.76, {0.55, 0.52, 0.48}}, {0.82, {0.93, 0.94, 0.96}}, {1.00, {0.98, 0.98, 1.00}},
    };
    const int ramp_n = (int)(sizeof ramp / sizeof ramp[0]);
    const vec3 sun = v3_norm(v3(-0.55, 0.75, 0.35));
    const vec3 rock = v3(0.45, 0.41, 0.36);
    image im = image_new(N, N, 3);
    for (int y = 0; y < N; y++) {
        for (int x = 0; x < N; x++) {
            /* The heightmap mesh counts grid rows from the bottom of the image, as t does: grid
             * vertex (gx, gy) reads height-map pixel (gx, 255 - gy) top-first and gets texcoord
             * (gx / 256, gy / 256). So this texel, at (s, t), lies over height-map pixel
             * (256 s, 255 - 256 t) and the two images line up as displayed. */
            double s = (x + 0.5) / N, t = 1.0 - (y + 0.5) / N;
            double hx = s * HEIGHT_N, hy = (HEIGHT_N - 1) - t * HEIGHT_N;
            double e = height_at(hm, hx, hy);
            /* Slope in world units: one height-map pixel is one unit across; z grows with the
             * grid row, i.e. up the image. */
            double dx = (height_at(hm, hx + 1.0, hy) - height_at(hm, hx - 1.0, hy)) * 0.5;
            double dz = (height_at(hm, hx, hy - 1.0) - height_at(hm, hx, hy + 1.0)) * 0.5;
            vec3 n = v3_norm(v3(-dx * TERRAIN_HEIGHT_SCALE, 1.0, -dz * TERRAIN_HEIGHT_SCALE));
            double grain = fbm(s, t, 128, 2, 0x6A11u) - 0.5;
            vec3 c;
            if (e < 1.5 / 255.0) {
                /* Lakes: deeper-looking blue away from the shore, blending into the sand over the
                 * last height step so the shore line is not a staircase of texels. */
                double shore = height_at(hm, hx + 3.0, hy) + height_at(hm, hx - 3.0, hy) +
                               height_at(hm, hx, hy + 3.0) + height_at(hm, hx, hy - 3.0);
                c = mix3(v3(0.10, 0.26, 0.46), v3(0.22, 0.44, 0.60), clamp01(shore * 20.0));
                c = v3_scale(c, 1.0 + 0.10 * grain);
                c = mix3(c, ramp[0].c, smoothstep(0.5 / 255.0, 1.5 / 255.0, e));
            } else {
                double he = clamp01(e + 0.04 * grain);
                int k = 0;
                while (k + 2 < ramp_n && he > ramp[k + 1].h) k++;
                double f = clamp01((he - ramp[k].h) / (ramp[k + 1].h - ramp[k].h));
                c = mix3(ramp[k].c, ramp[k + 1].c, f);
                double steep = smoothstep(0.70, 0.50, n.y) * (e < 0.80 ? 1.0 : 0.4);
                c = mix3(c, rock, steep);
                double light = 0.40 + 0.75 * fmax(0.0, v3_dot(n, sun));
                c = v3_scale(c, light * (1.0 + 0.12 * grain));
            }
            put_rgb(&im, x, y, c);
        }
    }
    bool ok = image_write(&im, path);
    free(im.px);
    return ok;
}

/* ---------------------------------------------------------------------------------------------
 * Meshes in OBJ terms: separate position (with colour), texcoord and normal lists, and faces and
 * polylines whose corners index each list on its own, so shared data is written once.
 */

typedef struct corner {
    int v, t, n; /* 1-based, 0 = absent */
} corner;

typedef struct face {
    int count; /* 3 or 4 */
    corner c[4];
} face;

typedef struct mesh {
    vec3 *pos, *col;
    size_t nv, cap_v;
    double (*tex)[2];
    size_t nt, cap_t;
    vec3 *nrm;
    size_t nn, cap_n;
    face *faces;
    size_t nf, cap_f;
    corner *lines; /* polylines ("l"), one after the other, each ended by a corner with v = 0 */
    size_t nlc, cap_lc;
    bool exact; /* positions are written exactly (writing fails when they cannot be) */
} mesh;

/* Grows an array to hold `need` elements; a generator has no way round a failed allocation. */
static void *grow(void *p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return p;
    size_t c = *cap ? *cap : 16;
    while (c < need) c *= 2;
    void *q = realloc(p, c * elem);
    if (!q) {
        fputs("sgapi-assets: out of memory\n", stderr);
        exit(1);
    }
    *cap = c;
    return q;
}

static int mesh_v(mesh *m, vec3 p, vec3 c) {
    size_t cap = m->cap_v;
    m->pos = grow(m->pos, &cap, m->nv + 1, sizeof *m->pos);
    cap = m->cap_v;
    m->col = grow(m->col, &cap, m->nv + 1, sizeof *m->col);
    m->cap_v = cap;
    m->pos[m->nv] = p;
    m->col[m->nv] = c;
    return (int)++m->nv;
}

static int mesh_vt(mesh *m, double s, double t) {
    m->tex = grow(m->tex, &m->cap_t, m->nt + 1, sizeof *m->tex);
    m->tex[m->nt][0] = s;
    m->tex[m->nt][1] = t;
    return (int)++m->nt;
}

static int mesh_vn(mesh *m, vec3 n) {
    m->nrm = grow(m->nrm, &m->cap_n, m->nn + 1, sizeof *m->nrm);
    m->nrm[m->nn] = n;
    return (int)++m->nn;
}

static void mesh_face(mesh *m, int count, const corner *c) {
    m->faces = grow(m->faces, &m->cap_f, m->nf + 1, sizeof *m->faces);
    face *f = &m->faces[m->nf++];
    f->count = count;
    for (int i = 0; i < count; i++) f->c[i] = c[i];
}

/* A polyline of count corners (position and texcoord; normals are not part of OBJ lines). */
static void mesh_line(mesh *m, int count, const corner *c) {
    m->lines = grow(m->lines, &m->cap_lc, m->nlc + (size_t)count + 1, sizeof *m->lines);
    for (int i = 0; i < count; i++) m->lines[m->nlc++] = c[i];
    m->lines[m->nlc++] = (corner){0, 0, 0};
}

static void mesh_free(mesh *m) {
    free(m->pos);
    free(m->col);
    free(m->tex);
    free(m->nrm);
    free(m->faces);
    free(m->lines);
    memset(m, 0, sizeof *m);
}

/* Shortest fixed-point form with at most `decimals` decimals: files stay small and readable, and
 * values that round to zero print as 0 (never -0 or 1e-17). */
static const char *fmt_num(char *buf, size_t size, double x, int decimals) {
    if (fabs(x) < 0.5 * pow(10.0, -decimals)) x = 0.0;
    snprintf(buf, size, "%.*f", decimals, x);
    char *dot = strchr(buf, '.');
    if (dot) {
        char *end = buf + strlen(buf) - 1;
        while (end > dot && *end == '0') *end-- = '\0';
        if (end == dot) *end = '\0';
    }
    if (!strcmp(buf, "-0")) strcpy(buf, "0");
    return buf;
}

/* A coordinate of an exact mesh: a float whose decimal expansion is short enough (a dyadic
 * fraction of at most 17 bits after the point, as window coordinates in 1/256 pixel are), written
 * out in full, so the loader reads back the very float. NULL when it is not one. */
static const char *fmt_exact(char *buf, size_t size, double x) {
    fmt_num(buf, size, x, 17);
    if ((double)(float)x != x || strtof(buf, NULL) != (float)x || strtod(buf, NULL) != x)
        return NULL;
    return buf;
}

static bool write_obj(const mesh *m, const char *path, const char *comment) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "sgapi-assets: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    char a[32], b[32], c[32], d[32], e[32], g[32];
    fprintf(f, "# %s\n", comment);
    for (size_t i = 0; i < m->nv; i++) {
        const char *x, *y, *z;
        if (m->exact) {
            x = fmt_exact(a, sizeof a, m->pos[i].x);
            y = fmt_exact(b, sizeof b, m->pos[i].y);
            z = fmt_exact(c, sizeof c, m->pos[i].z);
            if (!x || !y || !z) {
                fprintf(stderr, "sgapi-assets: %s: position %zu cannot be written exactly\n", path,
                        i + 1);
                fclose(f);
                return false;
            }
        } else {
            x = fmt_num(a, sizeof a, m->pos[i].x, 5);
            y = fmt_num(b, sizeof b, m->pos[i].y, 5);
            z = fmt_num(c, sizeof c, m->pos[i].z, 5);
        }
        fprintf(f, "v %s %s %s %s %s %s\n", x, y, z, fmt_num(d, sizeof d, m->col[i].x, 4),
                fmt_num(e, sizeof e, m->col[i].y, 4), fmt_num(g, sizeof g, m->col[i].z, 4));
    }
    for (size_t i = 0; i < m->nt; i++) {
        fprintf(f, "vt %s %s\n", fmt_num(a, sizeof a, m->tex[i][0], 5),
                fmt_num(b, sizeof b, m->tex[i][1], 5));
    }
    for (size_t i = 0; i < m->nn; i++) {
        fprintf(f, "vn %s %s %s\n", fmt_num(a, sizeof a, m->nrm[i].x, 4),
                fmt_num(b, sizeof b, m->nrm[i].y, 4), fmt_num(c, sizeof c, m->nrm[i].z, 4));
    }
    for (size_t i = 0; i < m->nf; i++) {
        fputc('f', f);
        for (int k = 0; k < m->faces[i].count; k++) {
            corner q = m->faces[i].c[k];
            if (q.t && q.n)
                fprintf(f, " %d/%d/%d", q.v, q.t, q.n);
            else if (q.t)
                fprintf(f, " %d/%d", q.v, q.t);
            else if (q.n)
                fprintf(f, " %d//%d", q.v, q.n);
            else
                fprintf(f, " %d", q.v);
        }
        fputc('\n', f);
    }
    for (size_t i = 0; i < m->nlc; i++) {
        corner q = m->lines[i];
        if (q.v == 0) {
            fputc('\n', f);
            continue;
        }
        if (i == 0 || m->lines[i - 1].v == 0) fputc('l', f);
        if (q.t)
            fprintf(f, " %d/%d", q.v, q.t);
        else
            fprintf(f, " %d", q.v);
    }
    bool ok = !ferror(f);
    if (fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "sgapi-assets: error writing %s\n", path);
    return ok;
}

/* Newell's method: the normal of a polygon from its winding, with length twice its area. Points
 * along the side from which the corners run counter-clockwise. */
static vec3 face_normal(const mesh *m, const face *f) {
    vec3 n = v3(0, 0, 0);
    for (int i = 0; i < f->count; i++) {
        vec3 a = m->pos[f->c[i].v - 1], b = m->pos[f->c[(i + 1) % f->count].v - 1];
        n.x += (a.y - b.y) * (a.z + b.z);
        n.y += (a.z - b.z) * (a.x + b.x);
        n.z += (a.x - b.x) * (a.y + b.y);
    }
    return n;
}

static vec3 face_centre(const mesh *m, const face *f) {
    vec3 s = v3(0, 0, 0);
    for (int i = 0; i < f->count; i++) s = v3_add(s, m->pos[f->c[i].v - 1]);
    return v3_scale(s, 1.0 / f->count);
}

/* For a closed convex mesh: every face must wind counter-clockwise seen from outside, i.e. its
 * winding normal must point away from the centroid, or back-face culling would eat it. */
static bool check_outward(const mesh *m, const char *name) {
    vec3 centre = v3(0, 0, 0);
    for (size_t i = 0; i < m->nv; i++) centre = v3_add(centre, m->pos[i]);
    centre = v3_scale(centre, 1.0 / (double)m->nv);
    for (size_t i = 0; i < m->nf; i++) {
        vec3 n = face_normal(m, &m->faces[i]);
        vec3 out = v3_sub(face_centre(m, &m->faces[i]), centre);
        if (v3_dot(n, out) <= 1e-9 * v3_len(n) * v3_len(out)) {
            fprintf(stderr, "sgapi-assets: %s: face %zu winds inward\n", name, i + 1);
            return false;
        }
    }
    return true;
}

/* For a flat mesh: every face must wind counter-clockwise seen from direction `side`. */
static bool check_facing(const mesh *m, vec3 side, const char *name) {
    for (size_t i = 0; i < m->nf; i++) {
        vec3 n = face_normal(m, &m->faces[i]);
        if (v3_dot(n, side) <= 0.99 * v3_len(n) * v3_len(side)) {
            fprintf(stderr, "sgapi-assets: %s: face %zu faces the wrong way\n", name, i + 1);
            return false;
        }
    }
    return true;
}

static const vec3 WHITE = {1, 1, 1};

/* Scene 01's triangle: red, green, blue corners, counter-clockwise, directly in clip space. */
static void build_triangle_rgb(mesh *m) {
    mesh_v(m, v3(-0.70, -0.62, 0), v3(1, 0, 0));
    mesh_v(m, v3(0.78, -0.40, 0), v3(0, 1, 0));
    mesh_v(m, v3(-0.12, 0.76, 0), v3(0, 0, 1));
    mesh_face(m, 3, (corner[]){{1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
}

/* A white equilateral triangle with circumradius 1 around the origin, pointing up. */
static void build_triangle(mesh *m) {
    double h = sqrt(3.0) / 2.0;
    mesh_v(m, v3(0, 1, 0), WHITE);
    mesh_v(m, v3(-h, -0.5, 0), WHITE);
    mesh_v(m, v3(h, -0.5, 0), WHITE);
    mesh_face(m, 3, (corner[]){{1, 0, 0}, {2, 0, 0}, {3, 0, 0}});
}

/* A white square [-1, 1]^2 as one four-corner face, so the loader's polygon split is used. */
static void build_quad(mesh *m) {
    static const double xy[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    corner c[4];
    for (int i = 0; i < 4; i++) {
        int v = mesh_v(m, v3(xy[i][0], xy[i][1], 0), WHITE);
        int t = mesh_vt(m, (xy[i][0] + 1) / 2, (xy[i][1] + 1) / 2);
        c[i] = (corner){v, t, 0};
    }
    mesh_face(m, 4, c);
}

/* Ground: [-1, 1]^2 in x/z at y = 0 as a 4 x 4 grid of quads sharing their corners, facing up,
 * texcoords 0..4 so the texture repeats. Far edge (-z) is the top of the texture. */
static void build_plane(mesh *m) {
    enum { G = 4 };
    int n = mesh_vn(m, v3(0, 1, 0));
    for (int k = 0; k <= G; k++) {
        for (int i = 0; i <= G; i++) {
            mesh_v(m, v3(-1.0 + 2.0 * i / G, 0, -1.0 + 2.0 * k / G), WHITE);
            mesh_vt(m, i, G - k);
        }
    }
    for (int k = 0; k < G; k++) {
        for (int i = 0; i < G; i++) {
            int a = k * (G + 1) + i + 1; /* far left (smaller z) */
            int b = a + 1, c = a + G + 1, d = c + 1;
            /* Near left, near right, far right, far left: counter-clockwise seen from above. */
            mesh_face(m, 4, (corner[]){{c, c, n}, {d, d, n}, {b, b, n}, {a, a, n}});
        }
    }
}

/* The ground as one quad with texcoords 0..16: a texture repeated 16 times each way, for floors
 * stretched far toward the horizon (mipmaps.json). */
static void build_floor_long(mesh *m) {
    enum { R = 16 };
    int n = mesh_vn(m, v3(0, 1, 0));
    int a = mesh_v(m, v3(-1, 0, -1), WHITE), b = mesh_v(m, v3(1, 0, -1), WHITE);
    int c = mesh_v(m, v3(-1, 0, 1), WHITE), d = mesh_v(m, v3(1, 0, 1), WHITE);
    int ta = mesh_vt(m, 0, R), tb = mesh_vt(m, R, R), tc = mesh_vt(m, 0, 0), td = mesh_vt(m, R, 0);
    /* Near left, near right, far right, far left: counter-clockwise seen from above. */
    mesh_face(m, 4, (corner[]){{c, tc, n}, {d, td, n}, {b, tb, n}, {a, ta, n}});
}

/* Square pyramid: base [-1, 1]^2 at y = -1, apex at y = 1. Five shared corners with their own
 * colours, one normal per face (so faces use the v//vn form). */
static void build_pyramid(mesh *m) {
    /* Base corners counter-clockwise seen from above, starting near left. */
    int c0 = mesh_v(m, v3(-1, -1, 1), v3(0.95, 0.20, 0.15));
    int c1 = mesh_v(m, v3(1, -1, 1), v3(0.15, 0.80, 0.25));
    int c2 = mesh_v(m, v3(1, -1, -1), v3(0.15, 0.35, 0.95));
    int c3 = mesh_v(m, v3(-1, -1, -1), v3(0.98, 0.85, 0.15));
    int apex = mesh_v(m, v3(0, 1, 0), v3(1, 1, 1));
    const int base[4] = {c0, c1, c2, c3};
    for (int i = 0; i < 4; i++) {
        int a = base[i], b = base[(i + 1) % 4];
        face tmp = {3, {{a, 0, 0}, {b, 0, 0}, {apex, 0, 0}}};
        int n = mesh_vn(m, v3_norm(face_normal(m, &tmp)));
        mesh_face(m, 3, (corner[]){{a, 0, n}, {b, 0, n}, {apex, 0, n}});
    }
    /* Seen from below the base order reverses. */
    int n = mesh_vn(m, v3(0, -1, 0));
    mesh_face(m, 4, (corner[]){{c3, 0, n}, {c2, 0, n}, {c1, 0, n}, {c0, 0, n}});
}

typedef enum cube_color { CUBE_WHITE, CUBE_RGB } cube_color;

/* Cube [-1, 1]^3: four corners per face (24 positions) so a face can have its own colours, four
 * shared texcoords spanning [lo, hi] per face, upright seen from outside, and one normal per face.
 * CUBE_RGB colours each corner by its position, the classic colour cube. */
static void build_cube(mesh *m, cube_color color, double lo, double hi) {
    /* Per face: outward normal, and the axes that run right and up on it seen from outside. With
     * right x up = normal the corner order below is counter-clockwise from outside. */
    static const double axes[6][3][3] = {
        {{0, 0, 1}, {1, 0, 0}, {0, 1, 0}},   {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},
        {{0, 0, -1}, {-1, 0, 0}, {0, 1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, 1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, -1}},  {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},
    };
    static const double corner_uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    int t[4];
    for (int i = 0; i < 4; i++) {
        t[i] = mesh_vt(m, lo + (hi - lo) * corner_uv[i][0], lo + (hi - lo) * corner_uv[i][1]);
    }
    for (int f = 0; f < 6; f++) {
        vec3 n = v3(axes[f][0][0], axes[f][0][1], axes[f][0][2]);
        vec3 r = v3(axes[f][1][0], axes[f][1][1], axes[f][1][2]);
        vec3 u = v3(axes[f][2][0], axes[f][2][1], axes[f][2][2]);
        int ni = mesh_vn(m, n);
        corner c[4];
        for (int i = 0; i < 4; i++) {
            vec3 p = v3_add(n, v3_add(v3_scale(r, corner_uv[i][0] * 2 - 1),
                                      v3_scale(u, corner_uv[i][1] * 2 - 1)));
            vec3 col = color == CUBE_RGB ? v3((p.x + 1) / 2, (p.y + 1) / 2, (p.z + 1) / 2) : WHITE;
            c[i] = (corner){mesh_v(m, p, col), t[i], ni};
        }
        mesh_face(m, 4, c);
    }
}

/* ---------------------------------------------------------------------------------------------
 * The Utah teapot, tessellated from its bicubic Bezier patches.
 */

enum { TEAPOT_DIV = 8, TEAPOT_GRID = TEAPOT_DIV + 1 };

/* Cubic Bernstein basis and its derivative at t. */
static void bernstein(double t, double b[4], double d[4]) {
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * t * s * s;
    b[2] = 3.0 * t * t * s;
    b[3] = t * t * t;
    d[0] = -3.0 * s * s;
    d[1] = 3.0 * s * s - 6.0 * t * s;
    d[2] = 6.0 * t * s - 3.0 * t * t;
    d[3] = 3.0 * t * t;
}

/* Position and partial derivatives of patch p at (u, v); u runs down the rows of the control
 * grid, v along them. */
static void patch_eval(int p, double u, double v, vec3 *pos, vec3 *du, vec3 *dv) {
    double bu[4], du_b[4], bv[4], dv_b[4];
    bernstein(u, bu, du_b);
    bernstein(v, bv, dv_b);
    *pos = *du = *dv = v3(0, 0, 0);
    for (int i = 0; i < 4; i++) {
        for (int j = 0; j < 4; j++) {
            const double *c = teapot_vertices[teapot_patches[p][i * 4 + j] - 1];
            vec3 cp = v3(c[0], c[1], c[2]);
            *pos = v3_add(*pos, v3_scale(cp, bu[i] * bv[j]));
            *du = v3_add(*du, v3_scale(cp, du_b[i] * bv[j]));
            *dv = v3_add(*dv, v3_scale(cp, bu[i] * dv_b[j]));
        }
    }
}

/* Surface normal du x dv. Where a whole row of control points is one point (the lid knob's top,
 * the bottom's centre) it vanishes, so it is taken a hair inside the patch instead. */
static vec3 patch_normal(int p, double u, double v) {
    static const double nudge[4][2] = {{0, 0}, {1, 0}, {0, 1}, {1, 1}};
    const double eps = 1e-4;
    vec3 pos, du, dv, n = v3(0, 0, 0);
    for (int k = 0; k < 4; k++) {
        double uu = u + nudge[k][0] * (u < 0.5 ? eps : -eps);
        double vv = v + nudge[k][1] * (v < 0.5 ? eps : -eps);
        patch_eval(p, uu, vv, &pos, &du, &dv);
        n = v3_cross(du, dv);
        if (v3_len(n) > 1e-9) break;
    }
    return v3_norm(n);
}

/* Moller-Trumbore: does the ray o + t d (t > tmin) hit triangle abc? */
static bool ray_hits(vec3 o, vec3 d, vec3 a, vec3 b, vec3 c, double tmin) {
    vec3 e1 = v3_sub(b, a), e2 = v3_sub(c, a);
    vec3 pv = v3_cross(d, e2);
    double det = v3_dot(e1, pv);
    if (fabs(det) < 1e-14) return false;
    double inv = 1.0 / det;
    vec3 tv = v3_sub(o, a);
    double u = v3_dot(tv, pv) * inv;
    if (u < 0.0 || u > 1.0) return false;
    vec3 qv = v3_cross(tv, e1);
    double v = v3_dot(d, qv) * inv;
    if (v < 0.0 || u + v > 1.0) return false;
    return v3_dot(e2, qv) * inv > tmin;
}

typedef struct edge {
    int from, to;
} edge;

static int edge_cmp(const void *pa, const void *pb) {
    const edge *a = pa, *b = pb;
    if (a->from != b->from) return a->from < b->from ? -1 : 1;
    return (a->to > b->to) - (a->to < b->to);
}

/* Patches meet along shared boundary curves, where their vertices coincide. With every patch
 * wound the same way round, neighbours run along a shared edge in opposite directions, so once
 * coinciding vertices are merged no directed edge may occur twice. */
static bool check_seams(const mesh *m) {
    int *weld = xmalloc(sizeof(int) * m->nv);
    for (size_t i = 0; i < m->nv; i++) {
        weld[i] = (int)i;
        for (size_t j = 0; j < i; j++) {
            if (v3_len(v3_sub(m->pos[i], m->pos[j])) < 1e-9) {
                weld[i] = weld[j];
                break;
            }
        }
    }
    edge *edges = xmalloc(sizeof(edge) * m->nf * 3);
    size_t n = 0;
    for (size_t f = 0; f < m->nf; f++) {
        int w[3];
        for (int k = 0; k < 3; k++) w[k] = weld[m->faces[f].c[k].v - 1];
        if (w[0] == w[1] || w[1] == w[2] || w[2] == w[0]) continue; /* collapsed at a pole */
        for (int k = 0; k < 3; k++) edges[n++] = (edge){w[k], w[(k + 1) % 3]};
    }
    qsort(edges, n, sizeof *edges, edge_cmp);
    bool ok = true;
    for (size_t i = 1; i < n && ok; i++) {
        if (!edge_cmp(&edges[i - 1], &edges[i])) {
            fprintf(stderr, "sgapi-assets: teapot: neighbouring triangles wind differently\n");
            ok = false;
        }
    }
    free(edges);
    free(weld);
    return ok;
}

/* Builds the teapot: 32 patches of 8 x 8 cells, 2 triangles each (4096 in all, the degenerate ones
 * at the knob and bottom centres included), y up, about [-1, 1] wide and centred at the origin,
 * colour 0.75 grey, texcoords (2u, 2v) per patch. Each patch is turned, if needed, so its normals
 * point outward and its triangles wind counter-clockwise seen from outside. */
static bool build_teapot(mesh *m) {
    enum { PER_PATCH = TEAPOT_GRID * TEAPOT_GRID, TOTAL = TEAPOT_PATCH_COUNT * PER_PATCH };
    vec3 *pos = xmalloc(sizeof(vec3) * TOTAL);
    vec3 *nrm = xmalloc(sizeof(vec3) * TOTAL);
    bool ok = true;

    for (int p = 0; p < TEAPOT_PATCH_COUNT; p++) {
        for (int i = 0; i < TEAPOT_GRID; i++) {
            for (int j = 0; j < TEAPOT_GRID; j++) {
                double u = (double)i / TEAPOT_DIV, v = (double)j / TEAPOT_DIV;
                vec3 du, dv;
                int k = p * PER_PATCH + i * TEAPOT_GRID + j;
                patch_eval(p, u, v, &pos[k], &du, &dv);
                nrm[k] = patch_normal(p, u, v);
            }
        }
    }

    /* Which patches face inward? The data set does not keep one orientation (the bottom was
     * added later). A ray leaving the surface along an outward normal crosses the surface an even
     * number of times; along an inward one, an odd number. The teapot is neither closed nor free
     * of self-intersection (lid gap, open spout, handle and spout pushed into the body), so single
     * rays can be fooled: each patch takes the majority over rays from all its triangles. */
    bool flip[TEAPOT_PATCH_COUNT];
    for (int p = 0; p < TEAPOT_PATCH_COUNT; p++) {
        int inward = 0, outward = 0;
        for (int i = 0; i < TEAPOT_DIV; i++) {
            for (int j = 0; j < TEAPOT_DIV; j++) {
                for (int half = 0; half < 2; half++) {
                    int a = p * PER_PATCH + i * TEAPOT_GRID + j;
                    int b = half ? a + 1 : a + TEAPOT_GRID, c = a + TEAPOT_GRID + 1;
                    vec3 d = v3_cross(v3_sub(pos[b], pos[a]), v3_sub(pos[c], pos[a]));
                    if (v3_len(d) < 1e-12) continue; /* degenerate at a pole */
                    if (half) d = v3_scale(d, -1.0); /* a, e, c runs the other way round */
                    d = v3_norm(d);
                    vec3 o = v3_scale(v3_add(pos[a], v3_add(pos[b], pos[c])), 1.0 / 3.0);
                    int hits = 0;
                    for (int q = 0; q < TEAPOT_PATCH_COUNT * TEAPOT_DIV * TEAPOT_DIV; q++) {
                        int qa = (q / (TEAPOT_DIV * TEAPOT_DIV)) * PER_PATCH +
                                 (q / TEAPOT_DIV % TEAPOT_DIV) * TEAPOT_GRID + q % TEAPOT_DIV;
                        int qb = qa + TEAPOT_GRID, qc = qb + 1, qe = qa + 1;
                        hits += ray_hits(o, d, pos[qa], pos[qb], pos[qc], 1e-7);
                        hits += ray_hits(o, d, pos[qa], pos[qc], pos[qe], 1e-7);
                    }
                    if (hits & 1)
                        inward++;
                    else
                        outward++;
                }
            }
        }
        flip[p] = inward > outward;
    }

    /* The data set has z up; turn it to y up (x stays, y = z, z = -y), then fit it into [-1, 1]
     * on its longest side (spout to handle) with its bounding box centred at the origin. */
    vec3 lo = v3(1e30, 1e30, 1e30), hi = v3(-1e30, -1e30, -1e30);
    for (int k = 0; k < TOTAL; k++) {
        pos[k] = v3(pos[k].x, pos[k].z, -pos[k].y);
        nrm[k] = v3(nrm[k].x, nrm[k].z, -nrm[k].y);
        lo = v3(fmin(lo.x, pos[k].x), fmin(lo.y, pos[k].y), fmin(lo.z, pos[k].z));
        hi = v3(fmax(hi.x, pos[k].x), fmax(hi.y, pos[k].y), fmax(hi.z, pos[k].z));
    }
    vec3 mid = v3_scale(v3_add(lo, hi), 0.5);
    double extent = fmax(hi.x - lo.x, fmax(hi.y - lo.y, hi.z - lo.z));
    double scale = 2.0 / extent;

    const vec3 grey = v3(0.75, 0.75, 0.75);
    for (int p = 0; p < TEAPOT_PATCH_COUNT; p++) {
        int first = (int)m->nv + 1;
        for (int i = 0; i < TEAPOT_GRID; i++) {
            for (int j = 0; j < TEAPOT_GRID; j++) {
                int k = p * PER_PATCH + i * TEAPOT_GRID + j;
                mesh_v(m, v3_scale(v3_sub(pos[k], mid), scale), grey);
                mesh_vt(m, 2.0 * j / TEAPOT_DIV, 2.0 * i / TEAPOT_DIV);
                mesh_vn(m, flip[p] ? v3_scale(nrm[k], -1.0) : nrm[k]);
            }
        }
        /* Corners a (i, j), b (i + 1, j), c (i + 1, j + 1), e (i, j + 1) run counter-clockwise
         * around du x dv; a flipped patch takes them the other way round. */
        for (int i = 0; i < TEAPOT_DIV; i++) {
            for (int j = 0; j < TEAPOT_DIV; j++) {
                int a = first + i * TEAPOT_GRID + j;
                int b = a + TEAPOT_GRID, c = b + 1, e = a + 1;
                if (flip[p]) {
                    mesh_face(m, 3, (corner[]){{a, a, a}, {c, c, c}, {b, b, b}});
                    mesh_face(m, 3, (corner[]){{a, a, a}, {e, e, e}, {c, c, c}});
                } else {
                    mesh_face(m, 3, (corner[]){{a, a, a}, {b, b, b}, {c, c, c}});
                    mesh_face(m, 3, (corner[]){{a, a, a}, {c, c, c}, {e, e, e}});
                }
            }
        }
    }

    /* Every real (non-degenerate) triangle must wind the way its vertex normals point. */
    for (size_t f = 0; f < m->nf && ok; f++) {
        const face *fc = &m->faces[f];
        vec3 n = face_normal(m, fc);
        if (v3_len(n) < 1e-10) continue;
        vec3 vn =
            v3_add(m->nrm[fc->c[0].n - 1], v3_add(m->nrm[fc->c[1].n - 1], m->nrm[fc->c[2].n - 1]));
        if (v3_dot(n, vn) <= 0.0) {
            fprintf(stderr, "sgapi-assets: teapot: triangle %zu winds against its normals\n", f);
            ok = false;
        }
    }
    ok = ok && check_seams(m);
    free(pos);
    free(nrm);
    return ok;
}

/* Lowest y of a mesh under a transform: how far to lift it so it rests on the ground. */
static double mesh_min_y(const mesh *m, mat4 t) {
    double y = 1e30;
    for (size_t i = 0; i < m->nv; i++) y = fmin(y, mat_apply(t, m->pos[i]).y);
    return y;
}

/* ---------------------------------------------------------------------------------------------
 * Scene file writing.
 */

typedef struct draw {
    const char *mesh;      /* OBJ path relative to the scene file, or NULL for the height map */
    const char *heightmap; /* height-map PNG when mesh is NULL */
    double height_scale;
    bool textured;       /* "mode": "texture" */
    const char *texture; /* NULL writes null (vertex colour) */
    bool nearest, clamp;
    const char *cull;          /* NULL: the default, none */
    const char *depth_compare; /* NULL: the default, less */
    bool no_depth_write;
    bool blend; /* "blend": "alpha" */
    bool sort;  /* "sort": "back_to_front" */
    bool has_color;
    double color[4];      /* "color", when has_color */
    const char *lighting; /* NULL: none */
    double specular[3], shininess;
    bool no_cast, no_receive; /* "casts_shadow": false, "receives_shadow": false */
    bool wireframe;           /* "polygon_mode": "line" */
    mat4 world_view, proj;
} draw;

/* A light in world space; written to the scene file in view space. */
typedef struct light {
    bool point;
    vec3 v; /* direction the light travels, or position */
    vec3 color;
    double att[3];
} light;

enum { MAX_DRAWS = 48 };

typedef struct scene {
    const char *name;
    int width, height;   /* 0: the file's default */
    const double *clear; /* NULL: the file's default */
    draw draws[MAX_DRAWS];
    int count;
    /* Lighting: ambient, and lights in world space seen through `view` (light_count > 0). */
    vec3 ambient;
    light lights[8];
    int light_count;
    mat4 view;
    /* The shadow light's index + 1 (0: no shadow); the map's side (0: the default), PCF off. */
    int shadow_light, shadow_size;
    bool shadow_no_pcf;
} scene;

static draw *scene_add(scene *s) {
    if (s->count == MAX_DRAWS) {
        fprintf(stderr, "sgapi-assets: scene %s has too many draws\n", s->name);
        exit(1);
    }
    draw *d = &s->draws[s->count++];
    memset(d, 0, sizeof *d);
    d->proj = mat_identity();
    d->world_view = mat_identity();
    return d;
}

static void write_matrix(FILE *f, const char *key, mat4 m) {
    char buf[32];
    fprintf(f, "\"%s\": [", key);
    for (int i = 0; i < 16; i++) {
        fprintf(f, "%s%s", i ? (i % 4 ? ", " : ",  ") : "", fmt_num(buf, sizeof buf, m.m[i], 6));
    }
    fputc(']', f);
}

static void write_scene(FILE *f, const scene *s, bool last) {
    char a[32];
    fprintf(f, "    {\n      \"name\": \"%s\",\n", s->name);
    if (s->width) fprintf(f, "      \"width\": %d, \"height\": %d,\n", s->width, s->height);
    if (s->clear) {
        fprintf(f, "      \"clear_color\": [");
        for (int i = 0; i < 4; i++)
            fprintf(f, "%s%s", i ? ", " : "", fmt_num(a, sizeof a, s->clear[i], 4));
        fprintf(f, "],\n");
    }
    if (s->light_count) {
        char b[32], c[32];
        fprintf(f, "      \"ambient\": [%s, %s, %s],\n      \"lights\": [\n",
                fmt_num(a, sizeof a, s->ambient.x, 4), fmt_num(b, sizeof b, s->ambient.y, 4),
                fmt_num(c, sizeof c, s->ambient.z, 4));
        for (int i = 0; i < s->light_count; i++) {
            const light *l = &s->lights[i];
            /* World to view: positions by the whole matrix, directions by its 3 x 3. */
            vec3 v = l->point ? mat_apply(s->view, l->v)
                              : v3_sub(mat_apply(s->view, l->v), mat_apply(s->view, v3(0, 0, 0)));
            fprintf(f, "        {\"type\": \"%s\", \"%s\": [%s, %s, %s], \"color\": [",
                    l->point ? "point" : "directional", l->point ? "position" : "direction",
                    fmt_num(a, sizeof a, v.x, 4), fmt_num(b, sizeof b, v.y, 4),
                    fmt_num(c, sizeof c, v.z, 4));
            fprintf(f, "%s, %s, %s]", fmt_num(a, sizeof a, l->color.x, 4),
                    fmt_num(b, sizeof b, l->color.y, 4), fmt_num(c, sizeof c, l->color.z, 4));
            if (l->point)
                fprintf(f, ", \"attenuation\": [%s, %s, %s]", fmt_num(a, sizeof a, l->att[0], 4),
                        fmt_num(b, sizeof b, l->att[1], 4), fmt_num(c, sizeof c, l->att[2], 4));
            fprintf(f, "}%s\n", i + 1 < s->light_count ? "," : "");
        }
        fprintf(f, "      ],\n");
    }
    if (s->shadow_light) {
        fprintf(f, "      \"shadow\": {\"light\": %d", s->shadow_light - 1);
        if (s->shadow_size) fprintf(f, ", \"size\": %d", s->shadow_size);
        if (s->shadow_no_pcf) fprintf(f, ", \"pcf\": false");
        fprintf(f, "},\n");
    }
    fprintf(f, "      \"draws\": [\n");
    for (int i = 0; i < s->count; i++) {
        const draw *d = &s->draws[i];
        fprintf(f, "        {\n          \"mesh\": ");
        if (d->mesh) {
            fprintf(f, "\"%s\",\n", d->mesh);
        } else {
            fprintf(f, "{\"heightmap\": \"%s\", \"height_scale\": %s},\n", d->heightmap,
                    fmt_num(a, sizeof a, d->height_scale, 4));
        }
        if (d->textured) {
            fprintf(f, "          \"mode\": \"texture\",\n");
            if (d->texture)
                fprintf(f, "          \"texture\": \"%s\",\n", d->texture);
            else
                fprintf(f, "          \"texture\": null,\n");
            if (d->texture) {
                fprintf(f, "          \"filter\": \"%s\", \"wrap\": \"%s\",\n",
                        d->nearest ? "nearest" : "bilinear", d->clamp ? "clamp" : "repeat");
            }
        } else {
            fprintf(f, "          \"mode\": \"vertex_color\",\n");
        }
        if (d->cull) fprintf(f, "          \"cull\": \"%s\",\n", d->cull);
        if (d->wireframe) fprintf(f, "          \"polygon_mode\": \"line\",\n");
        if (d->depth_compare)
            fprintf(f, "          \"depth_compare\": \"%s\",\n", d->depth_compare);
        if (d->no_depth_write) fprintf(f, "          \"depth_write\": false,\n");
        if (d->blend) fprintf(f, "          \"blend\": \"alpha\",\n");
        if (d->sort) fprintf(f, "          \"sort\": \"back_to_front\",\n");
        if (d->lighting) {
            char b[32], c[32], e[32];
            fprintf(f, "          \"lighting\": \"%s\"", d->lighting);
            if (d->specular[0] || d->specular[1] || d->specular[2])
                fprintf(f, ", \"specular\": [%s, %s, %s], \"shininess\": %s",
                        fmt_num(a, sizeof a, d->specular[0], 4),
                        fmt_num(b, sizeof b, d->specular[1], 4),
                        fmt_num(c, sizeof c, d->specular[2], 4),
                        fmt_num(e, sizeof e, d->shininess, 2));
            fprintf(f, ",\n");
        }
        if (d->no_cast) fprintf(f, "          \"casts_shadow\": false,\n");
        if (d->no_receive) fprintf(f, "          \"receives_shadow\": false,\n");
        if (d->has_color) {
            fprintf(f, "          \"color\": [");
            for (int k = 0; k < 4; k++)
                fprintf(f, "%s%s", k ? ", " : "", fmt_num(a, sizeof a, d->color[k], 4));
            fprintf(f, "],\n");
        }
        fprintf(f, "          ");
        write_matrix(f, "worldView", d->world_view);
        fprintf(f, ",\n          ");
        write_matrix(f, "proj", d->proj);
        fprintf(f, "\n        }%s\n", i + 1 < s->count ? "," : "");
    }
    fprintf(f, "      ]\n    }%s\n", last ? "" : ",");
}

/* Asset paths as the scene file names them. */
#define A_TRIANGLE_RGB "assets/triangle_rgb.obj"
#define A_TRIANGLE     "assets/triangle.obj"
#define A_QUAD         "assets/quad.obj"
#define A_PLANE        "assets/plane.obj"
#define A_PYRAMID      "assets/pyramid.obj"
#define A_CUBE         "assets/cube.obj"
#define A_CUBE_RGB     "assets/cube_rgb.obj"
#define A_CUBE_WIDE    "assets/cube_wide_uv.obj"
#define A_TEAPOT       "assets/teapot.obj"
#define A_CHECKER      "assets/checker.png"
#define A_MOSAIC       "assets/mosaic.png"
#define A_BRICK        "assets/brick.png"
#define A_BRICK_NORMAL "assets/brick_normal.png"
#define A_HEIGHT       "assets/height.png"
#define A_TERRAIN      "assets/terrain_color.png"
#define A_CUTOUT       "assets/cutout.png"
#define A_LINE_FAN     "assets/line_fan.obj"
#define A_LINE_GRID    "assets/line_grid.obj"
#define A_LINE_RAILS   "assets/line_rails.obj"
#define A_LINE_BURST   "assets/line_burst.obj"

/* Model transform T x Ry(yaw) x Rx(pitch) x Rz(roll) x S: scaled first, then rolled, pitched and
 * turned about the vertical last, then placed. */
static mat4 model(vec3 t, double yaw, double pitch, double roll, double s) {
    mat4 r = mat_mul(mat_rotate_y(yaw), mat_mul(mat_rotate_x(pitch), mat_rotate_z(roll)));
    return mat_mul(mat_translate(t.x, t.y, t.z), mat_mul(r, mat_scale(s, s, s)));
}

/* The textured ground plane, scaled by `scale`, seen through `view`. */
static draw *add_floor(scene *s, mat4 proj, mat4 view, const char *texture, double scale) {
    draw *d = scene_add(s);
    d->mesh = A_PLANE;
    d->textured = true;
    d->texture = texture;
    d->proj = proj;
    d->world_view = mat_mul(view, mat_scale(scale, scale, scale));
    return d;
}

static void scene_01(scene *s) {
    s->name = "01_colored_triangle";
    draw *d = scene_add(s);
    d->mesh = A_TRIANGLE_RGB;
}

/* White shapes laid out in 2D: identity projection, worldView = translate x rotate x scale. */
static void scene_02(scene *s) {
    static const struct {
        bool quad;
        double x, y, sx, sy, rot;
    } shapes[] = {
        {false, -0.62, 0.56, 0.30, 0.30, 0},   {false, 0.00, 0.62, 0.24, 0.30, 180},
        {false, 0.62, 0.58, 0.27, 0.27, 17},   {true, -0.62, 0.00, 0.22, 0.22, 0},
        {true, 0.00, 0.00, 0.30, 0.11, 0},     {true, 0.62, 0.00, 0.20, 0.20, 45},
        {false, -0.60, -0.62, 0.32, 0.14, 90}, {true, -0.04, -0.62, 0.07, 0.27, -12},
        {false, 0.42, -0.52, 0.05, 0.05, 0},   {false, 0.58, -0.66, 0.035, 0.035, 200},
        {false, 0.74, -0.54, 0.02, 0.02, 30},  {true, 0.60, -0.82, 0.15, 0.012, 0},
    };
    s->name = "02_tris_and_quads";
    for (size_t i = 0; i < sizeof shapes / sizeof shapes[0]; i++) {
        draw *d = scene_add(s);
        d->mesh = shapes[i].quad ? A_QUAD : A_TRIANGLE;
        d->world_view =
            mat_mul(mat_translate(shapes[i].x, shapes[i].y, 0),
                    mat_mul(mat_rotate_z(shapes[i].rot), mat_scale(shapes[i].sx, shapes[i].sy, 1)));
    }
}

/* Vertex-coloured pyramid and cube with back faces culled: only outward faces may show. */
static void scene_03(scene *s, mat4 proj) {
    s->name = "03_pyramid_and_cube";
    draw *d = scene_add(s);
    d->mesh = A_PYRAMID;
    d->cull = "back";
    d->proj = proj;
    d->world_view = model(v3(-1.5, -0.2, -7.4), 32, 18, 0, 1.0);
    d = scene_add(s);
    d->mesh = A_CUBE_RGB;
    d->cull = "back";
    d->proj = proj;
    d->world_view = model(v3(1.5, 0.15, -7.4), -38, 26, 0, 0.85);
}

/* Textured cube, nearest filter, clamp: its texcoords run past [0, 1] so clamping shows as
 * stretched edge texels framing each face, and magnified nearest texels show as blocks. */
static void scene_04(scene *s, mat4 proj) {
    s->name = "04_textured_cube";
    draw *d = scene_add(s);
    d->mesh = A_CUBE_WIDE;
    d->textured = true;
    d->texture = A_MOSAIC;
    d->nearest = true;
    d->clamp = true;
    d->proj = proj;
    d->world_view = model(v3(0, 0, -5.2), -36, 27, 0, 1.0);
}

/* A field of textured cubes and vertex-coloured pyramids (texture mode with no texture) on a
 * checkered ground, bilinear and repeat throughout. */
static void scene_05(scene *s, mat4 proj) {
    static const char *const textures[3] = {A_BRICK, A_MOSAIC, A_CHECKER};
    s->name = "05_many_cubes";
    mat4 view = mat_look_at(v3(0, 8.5, 10.5), v3(0, 0, -0.2), v3(0, 1, 0));
    draw *d = add_floor(s, proj, view, A_CHECKER, 8);

    /* A 4 x 4 grid, jittered; every fourth slot a pyramid, two cubes carry a smaller one. */
    rng r = {0x5EED0005u};
    for (int row = 0; row < 4; row++) {
        for (int colm = 0; colm < 4; colm++) {
            int slot = row * 4 + colm;
            double x = -3.45 + 2.3 * colm + rng_range(&r, -0.3, 0.3);
            double z = -4.4 + 2.5 * row + rng_range(&r, -0.3, 0.3);
            double yaw = rng_range(&r, 0, 90);
            double size = rng_range(&r, 0.45, 0.72);
            bool pyramid = slot % 4 == (row & 1 ? 1 : 3);
            d = scene_add(s);
            d->textured = true;
            d->proj = proj;
            /* Both meshes span y in [-1, 1]: lifting by the scale rests them on the ground. */
            d->world_view = mat_mul(view, model(v3(x, size, z), yaw, 0, 0, size));
            if (pyramid) {
                d->mesh = A_PYRAMID;
                d->texture = NULL;
                continue;
            }
            /* Shifting the texture by row keeps equal textures out of the same column. */
            d->mesh = A_CUBE;
            d->texture = textures[(colm + 2 * row) % 3];
            if (slot == 5 || slot == 10) {
                double top = 0.55 * size;
                draw *t = scene_add(s);
                *t = *d;
                t->texture = textures[(colm + 2 * row + 1) % 3];
                t->world_view = mat_mul(view, model(v3(x, 2 * size + top, z), yaw + 30, 0, 0, top));
            }
        }
    }
}

/* The brick floor and one teapot resting on it, checker texture repeating twice per patch, as
 * seen by scenes 06 and the translucent teapots; returns the teapot's draw. */
static draw *teapot_on_floor(scene *s, mat4 proj, const mesh *teapot) {
    mat4 view = mat_look_at(v3(0, 1.55, 2.9), v3(0, 0.32, 0), v3(0, 1, 0));
    draw *d = add_floor(s, proj, view, A_BRICK, 2.5);

    mat4 pose = model(v3(0, 0, 0), -28, 0, 0, 1.0);
    d = scene_add(s);
    d->mesh = A_TEAPOT;
    d->textured = true;
    d->texture = A_CHECKER;
    d->proj = proj;
    d->world_view = mat_mul(view, mat_mul(mat_translate(0, -mesh_min_y(teapot, pose), 0), pose));
    return d;
}

/* One teapot, checker texture repeating twice per patch, resting on a brick floor. */
static void scene_06(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "06_teapot";
    teapot_on_floor(s, proj, teapot);
}

/* Ten teapots in different poses (upright, on their side, upside down, tipped) on the floor. */
static void scene_07(scene *s, mat4 proj, const mesh *teapot) {
    static const char *const textures[3] = {A_CHECKER, A_MOSAIC, A_BRICK};
    static const struct {
        double x, z, yaw, pitch, roll, scale;
    } poses[] = {
        /* Back row, where the view is widest: four. Then three and three. */
        {-3.5, -3.2, 20, 0, 0, 0.95},   {-1.2, -3.4, 150, 0, 0, 1.05},
        {1.3, -3.3, 30, 90, 0, 0.85},   {3.6, -3.1, -60, 0, 0, 0.95},
        {-2.7, -0.4, 200, 0, 0, 0.85},  {0.0, -0.2, 45, 180, 0, 0.9},
        {2.7, -0.3, -120, 24, 0, 0.85}, {-1.9, 2.3, 95, 0, 0, 0.7},
        {0.1, 2.5, -30, -90, 0, 0.72},  {2.0, 2.3, 265, -15, 8, 0.72},
    };
    s->name = "07_many_teapots";
    mat4 view = mat_look_at(v3(0, 5.0, 7.6), v3(0, 0.2, -0.4), v3(0, 1, 0));
    draw *d = add_floor(s, proj, view, A_CHECKER, 7);
    for (size_t i = 0; i < sizeof poses / sizeof poses[0]; i++) {
        mat4 pose = model(v3(0, 0, 0), poses[i].yaw, poses[i].pitch, poses[i].roll, poses[i].scale);
        double lift = -mesh_min_y(teapot, pose);
        d = scene_add(s);
        d->mesh = A_TEAPOT;
        d->textured = true;
        d->texture = textures[i % 3];
        d->proj = proj;
        d->world_view = mat_mul(view, mat_mul(mat_translate(poses[i].x, lift, poses[i].z), pose));
    }
}

/* The height-map terrain from above one edge, lakes in front and the range behind, over a
 * sky-coloured clear: the one scene that overrides the file's clear colour. */
static void scene_08(scene *s, mat4 proj) {
    static const double sky[4] = {0.56, 0.71, 0.86, 1.0};
    s->name = "08_terrain";
    s->clear = sky;
    /* The grid spans +-128 units; 1/16 brings it to +-8 so all of it sits inside the far plane. */
    mat4 view = mat_look_at(v3(0, 10.5, 11.5), v3(0, 0, -1.2), v3(0, 1, 0));
    draw *d = scene_add(s);
    d->heightmap = A_HEIGHT;
    d->height_scale = TERRAIN_HEIGHT_SCALE;
    d->textured = true;
    d->texture = A_TERRAIN;
    /* The colour must not wrap round at the terrain's edges; also the one bilinear clamp draw. */
    d->clamp = true;
    d->proj = proj;
    d->world_view = mat_mul(view, model(v3(0, 0, 0), 200, 0, 0, 1.0 / 16.0));
}

/* ---------------------------------------------------------------------------------------------
 * Transparency scenes (transparency.json).
 */

static void set_color(draw *d, double r, double g, double b, double a) {
    d->has_color = true;
    d->color[0] = r, d->color[1] = g, d->color[2] = b, d->color[3] = a;
}

/* Convex transparent cubes over a checkered floor, each drawn the classic way: back faces first
 * (cull front), then front faces (cull back), without depth writes, farthest cube first. One
 * cube is textured, the texel times a translucent tint. */
static void scene_alpha_cubes(scene *s, mat4 proj) {
    static const struct {
        double x, z, yaw, size, c[4];
        bool textured;
    } cubes[] = {
        {-1.3, -1.6, 20, 0.75, {0.95, 0.25, 0.2, 0.45}, false},
        {1.4, -1.2, -35, 0.7, {1, 1, 1, 0.6}, true},
        {-0.2, 0.6, 50, 0.65, {0.2, 0.45, 0.95, 0.5}, false},
        {1.2, 1.5, 10, 0.45, {0.25, 0.85, 0.3, 0.55}, false},
    };
    s->name = "alpha_cubes";
    mat4 view = mat_look_at(v3(0, 4.2, 6.2), v3(0, 0.3, 0), v3(0, 1, 0));
    draw *d = add_floor(s, proj, view, A_CHECKER, 4);
    for (size_t i = 0; i < sizeof cubes / sizeof cubes[0]; i++) {
        /* Held a little above the floor: a bottom face in the floor's plane would z-fight. */
        double y = 1.04 * cubes[i].size;
        mat4 wv =
            mat_mul(view, model(v3(cubes[i].x, y, cubes[i].z), cubes[i].yaw, 0, 0, cubes[i].size));
        for (int pass = 0; pass < 2; pass++) {
            d = scene_add(s);
            d->mesh = A_CUBE;
            d->textured = cubes[i].textured;
            d->texture = cubes[i].textured ? A_MOSAIC : NULL;
            d->cull = pass == 0 ? "front" : "back";
            d->no_depth_write = true;
            d->blend = true;
            set_color(d, cubes[i].c[0], cubes[i].c[1], cubes[i].c[2], cubes[i].c[3]);
            d->proj = proj;
            d->world_view = wv;
        }
    }
}

/* A translucent teapot on the brick floor, its own faces blended over each other without depth
 * writes: sorted back to front it reads correctly; unsorted the order of the patches shows. */
static void scene_alpha_teapot(scene *s, mat4 proj, const mesh *teapot, bool sorted) {
    s->name = sorted ? "alpha_teapot_sorted" : "alpha_teapot_unsorted";
    draw *d = teapot_on_floor(s, proj, teapot);
    d->no_depth_write = true;
    d->blend = true;
    d->sort = sorted;
    set_color(d, 1.0, 0.9, 0.75, 0.45);
}

/* Window panes with a cut-out ring and an alpha gradient, standing on the checkered floor at
 * different depths and angles, drawn farthest first. */
static void scene_alpha_cutout(scene *s, mat4 proj) {
    static const struct {
        double x, z, yaw, size;
    } panes[] = {{-1.2, -2.0, 25, 1.0}, {1.3, -1.2, -30, 0.9}, {-0.3, 0.4, 10, 0.8}};
    s->name = "alpha_cutout";
    mat4 view = mat_look_at(v3(0, 2.0, 5.5), v3(0, 0.7, 0), v3(0, 1, 0));
    draw *d = add_floor(s, proj, view, A_CHECKER, 4);
    for (size_t i = 0; i < sizeof panes / sizeof panes[0]; i++) {
        d = scene_add(s);
        d->mesh = A_QUAD;
        d->textured = true;
        d->texture = A_CUTOUT;
        d->clamp = true;
        d->no_depth_write = true;
        d->blend = true;
        d->proj = proj;
        d->world_view = mat_mul(view, model(v3(panes[i].x, panes[i].size, panes[i].z), panes[i].yaw,
                                            0, 0, panes[i].size));
    }
}

/* Stacks of coloured squares in screen space over a grey ground: one column per alpha (0, 0.25,
 * 0.5, 1), each square half over the one before, six deep; and a row of sixteen layers of the
 * same colour at alpha 0.25, where the 8-bit rounding of each blend accumulates. */
static void scene_alpha_stack(scene *s) {
    static const double clear[4] = {0.5, 0.5, 0.5, 1.0};
    static const double alphas[4] = {0.0, 0.25, 0.5, 1.0};
    s->name = "alpha_stack";
    s->clear = clear;
    for (int col = 0; col < 4; col++) {
        for (int k = 0; k < 6; k++) {
            draw *d = scene_add(s);
            d->mesh = A_QUAD;
            d->depth_compare = "always";
            d->no_depth_write = true;
            d->blend = true;
            vec3 c = hsv(k / 6.0, 0.8, 0.95);
            set_color(d, c.x, c.y, c.z, alphas[col]);
            double x = -0.82 + 0.46 * col + 0.045 * k, y = 0.72 - 0.075 * k;
            d->world_view = mat_mul(mat_translate(x, y, 0), mat_scale(0.12, 0.12, 1));
        }
    }
    for (int k = 0; k < 16; k++) {
        draw *d = scene_add(s);
        d->mesh = A_QUAD;
        d->depth_compare = "always";
        d->no_depth_write = true;
        d->blend = true;
        set_color(d, 0.9, 0.35, 0.1, 0.25);
        double x0 = -0.9 + 0.1 * k;
        d->world_view =
            mat_mul(mat_translate((x0 + 0.9) / 2, -0.45, 0), mat_scale((0.9 - x0) / 2, 0.2, 1));
    }
}

/* ---------------------------------------------------------------------------------------------
 * Lighting scenes (lighting.json). Lights are placed in world space and written in view space.
 */

static light dir_light(vec3 travel, vec3 color) {
    light l = {false, travel, color, {1, 0, 0}};
    return l;
}

static light point_light(vec3 at, vec3 color, double c, double lin, double q) {
    light l = {true, at, color, {c, lin, q}};
    return l;
}

static void set_lit(draw *d, const char *mode, double spec, double shininess) {
    d->lighting = mode;
    d->specular[0] = d->specular[1] = d->specular[2] = spec;
    d->shininess = shininess;
}

/* A teapot resting on the ground at (x, z), turned by yaw; returns its draw. */
static draw *teapot_at(scene *s, mat4 proj, const mesh *teapot, double x, double z, double yaw,
                       double scale) {
    mat4 pose = model(v3(0, 0, 0), yaw, 0, 0, scale);
    draw *d = scene_add(s);
    d->mesh = A_TEAPOT;
    d->proj = proj;
    d->world_view = mat_mul(s->view, mat_mul(mat_translate(x, -mesh_min_y(teapot, pose), z), pose));
    return d;
}

/* The three modes side by side, flat, Gouraud and Phong, under a directional key light and a
 * warm point light, with a white specular highlight. */
static void scene_lit_modes(scene *s, mat4 proj, const mesh *teapot) {
    static const char *const modes[3] = {"flat", "gouraud", "phong"};
    s->name = "lit_modes";
    s->view = mat_look_at(v3(0, 2.6, 5.2), v3(0, 0.45, 0), v3(0, 1, 0));
    s->ambient = v3(0.12, 0.12, 0.14);
    s->lights[s->light_count++] = dir_light(v3(-0.5, -0.8, -0.6), v3(0.75, 0.75, 0.72));
    s->lights[s->light_count++] = point_light(v3(1.5, 2.0, 2.0), v3(0.6, 0.45, 0.3), 1, 0, 0.05);
    draw *d = add_floor(s, proj, s->view, A_CHECKER, 4);
    set_lit(d, "phong", 0, 0);
    for (int i = 0; i < 3; i++) {
        d = teapot_at(s, proj, teapot, -1.55 + 1.55 * i, 0, -30, 0.62);
        set_color(d, 0.85, 0.4, 0.25, 1);
        set_lit(d, modes[i], 0.8, 40);
    }
}

/* A textured teapot, lit per pixel, with a sharp white highlight on the checker. */
static void scene_lit_textured(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "lit_textured_teapot";
    s->view = mat_look_at(v3(0, 1.55, 2.9), v3(0, 0.32, 0), v3(0, 1, 0));
    s->ambient = v3(0.15, 0.15, 0.15);
    s->lights[s->light_count++] = dir_light(v3(-0.4, -1.0, -0.5), v3(0.85, 0.85, 0.85));
    draw *d = add_floor(s, proj, s->view, A_BRICK, 2.5);
    set_lit(d, "gouraud", 0, 0);
    d = teapot_at(s, proj, teapot, 0, 0, -28, 1.0);
    d->textured = true;
    d->texture = A_CHECKER;
    set_lit(d, "phong", 1.0, 60);
}

/* Cubes around a point light close above the floor: quadratic attenuation makes a pool of light
 * that falls off with distance, and the cube faces turned away from it stay dark. */
static void scene_lit_point(scene *s, mat4 proj) {
    s->name = "lit_point_cubes";
    s->view = mat_look_at(v3(0, 4.5, 6.0), v3(0, 0.2, 0), v3(0, 1, 0));
    s->ambient = v3(0.05, 0.05, 0.06);
    s->lights[s->light_count++] = point_light(v3(0, 1.3, 0), v3(1.0, 0.95, 0.85), 0.2, 0.1, 0.6);
    draw *d = add_floor(s, proj, s->view, A_CHECKER, 5);
    set_lit(d, "phong", 0, 0);
    for (int i = 0; i < 6; i++) {
        double a = i * 60.0 + 15.0, r = 1.6 + 0.5 * (i % 2), size = 0.3 + 0.05 * (i % 3);
        double c, sn;
        sin_cos_deg(a, &sn, &c);
        d = scene_add(s);
        d->mesh = A_CUBE;
        d->proj = proj;
        d->world_view = mat_mul(s->view, model(v3(r * c, size, r * sn), a * 0.7, 0, 0, size));
        vec3 col = hsv(i / 6.0, 0.55, 0.9);
        set_color(d, col.x, col.y, col.z, 1);
        set_lit(d, i % 2 ? "phong" : "gouraud", 0.5, 24);
    }
}

/* A wall between the eye and a point light: its front gets ambient only, and no highlight leaks
 * through it (the specular term needs N.L > 0); the teapot in front is lit by a dim fill light,
 * and the light itself shines on the ground behind the wall's edges. */
static void scene_lit_behind(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "lit_behind_surface";
    s->view = mat_look_at(v3(0.6, 1.6, 4.2), v3(0, 0.6, 0), v3(0, 1, 0));
    s->ambient = v3(0.1, 0.1, 0.12);
    s->lights[s->light_count++] = point_light(v3(0.2, 0.8, -1.2), v3(1.0, 0.9, 0.7), 1, 0, 0.15);
    s->lights[s->light_count++] = dir_light(v3(0.3, -0.5, -1.0), v3(0.25, 0.25, 0.3));
    draw *d = add_floor(s, proj, s->view, A_BRICK, 3);
    set_lit(d, "phong", 0, 0);
    d = scene_add(s);
    d->mesh = A_QUAD;
    d->proj = proj;
    d->world_view =
        mat_mul(s->view, mat_mul(mat_translate(0, 0.8, -0.5), mat_scale(1.1, 0.8, 1.0)));
    set_lit(d, "phong", 1.0, 30);
    d = teapot_at(s, proj, teapot, 0.7, 0.6, 20, 0.45);
    set_color(d, 0.3, 0.6, 0.9, 1);
    set_lit(d, "gouraud", 0.6, 20);
}

/* The ten teapots of 07_many_teapots, textured, lit per pixel by two lights: for speed. */
static void scene_lit_many(scene *s, mat4 proj, const mesh *teapot) {
    scene_07(s, proj, teapot);
    s->name = "lit_many_teapots";
    s->view = mat_look_at(v3(0, 5.0, 7.6), v3(0, 0.2, -0.4), v3(0, 1, 0));
    s->ambient = v3(0.12, 0.12, 0.12);
    s->lights[s->light_count++] = dir_light(v3(-0.6, -1.0, -0.4), v3(0.8, 0.8, 0.78));
    s->lights[s->light_count++] = point_light(v3(2.5, 3.0, 2.5), v3(0.4, 0.35, 0.3), 1, 0.1, 0);
    set_lit(&s->draws[0], "gouraud", 0, 0);
    for (int i = 1; i < s->count; i++) set_lit(&s->draws[i], "phong", 0.7, 32);
}

/* ---------------------------------------------------------------------------------------------
 * Shadow scenes (shadows.json): light 0 casts the scene's shadow.
 */

/* Three teapots on the checker floor under a sun from the left and behind: each teapot's spout,
 * lid and handle shadow its own body, the first teapot's shadow falls on the second, all of them
 * on the floor; a dim unshadowed fill light keeps the shadows from going black. */
static void scene_shadow_teapots(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "shadow_teapots";
    s->view = mat_look_at(v3(0.0, 2.4, 4.3), v3(-0.1, 0.45, -0.35), v3(0, 1, 0));
    s->ambient = v3(0.16, 0.16, 0.18);
    s->lights[s->light_count++] = dir_light(v3(1.0, -0.55, -0.05), v3(1.0, 0.97, 0.9));
    s->lights[s->light_count++] = dir_light(v3(-0.3, -0.4, -1.0), v3(0.16, 0.18, 0.24));
    s->shadow_light = 1;
    draw *d = add_floor(s, proj, s->view, NULL, 4);
    d->textured = false;
    set_color(d, 0.95, 0.93, 0.88, 1);
    set_lit(d, "phong", 0, 0);
    static const struct {
        double x, z, yaw, scale, c[3];
    } pots[3] = {{-1.5, -0.3, 180, 0.75, {0.85, 0.4, 0.25}},
                 {-0.4, -0.3, -35, 0.5, {0.3, 0.55, 0.85}},
                 {1.3, -0.35, 50, 0.62, {0.45, 0.75, 0.35}}};
    for (int i = 0; i < 3; i++) {
        d = teapot_at(s, proj, teapot, pots[i].x, pots[i].z, pots[i].yaw, pots[i].scale);
        set_color(d, pots[i].c[0], pots[i].c[1], pots[i].c[2], 1);
        set_lit(d, "phong", 0.7, 40);
    }
}

/* A point light above and in front of a ring of cubes and a teapot: the shadows spread out from
 * below the light, longer the farther a caster is from it. The floor only receives, so the light's
 * frustum fits the objects alone. */
static void scene_shadow_point(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "shadow_point";
    s->view = mat_look_at(v3(0, 4.2, 5.6), v3(0, 0.3, 0), v3(0, 1, 0));
    s->ambient = v3(0.08, 0.08, 0.1);
    s->lights[s->light_count++] =
        point_light(v3(0.4, 2.0, 0.8), v3(1.0, 0.95, 0.85), 0.6, 0.05, 0.06);
    s->shadow_light = 1;
    draw *d = add_floor(s, proj, s->view, A_BRICK, 4);
    set_lit(d, "phong", 0, 0);
    d->no_cast = true;
    d = teapot_at(s, proj, teapot, 0, 0, -20, 0.6);
    set_color(d, 0.9, 0.85, 0.75, 1);
    set_lit(d, "phong", 0.6, 30);
    for (int i = 0; i < 5; i++) {
        double a = i * 72.0 + 100.0, r = 1.7, size = 0.22 + 0.04 * (i % 3);
        double c, sn;
        sin_cos_deg(a, &sn, &c);
        d = scene_add(s);
        d->mesh = A_CUBE;
        d->proj = proj;
        d->world_view = mat_mul(s->view, model(v3(r * c, size, r * sn), a * 0.6, 0, 0, size));
        vec3 col = hsv(i / 5.0 + 0.05, 0.5, 0.9);
        set_color(d, col.x, col.y, col.z, 1);
        set_lit(d, "phong", 0.4, 20);
    }
}

/* A sun 8 degrees above the horizon: long shadows, and the floor seen by the light at a grazing
 * angle, where too little slope bias shows acne as stripes across the whole floor. The floor is
 * unlit and textured (darkened to half in shadow); a thin slab stands on edge to show that the
 * shadow stays attached to its foot; the one-texel lookup (no PCF) keeps edges hard; a dim fill
 * light from the eye, which casts nothing, shows the objects' shadowed sides. */
static void scene_shadow_grazing(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "shadow_grazing";
    s->view = mat_look_at(v3(0.3, 3.0, 5.0), v3(0.3, 0.1, 0), v3(0, 1, 0));
    s->ambient = v3(0.2, 0.2, 0.22);
    double es, ec;
    sin_cos_deg(8.0, &es, &ec);
    s->lights[s->light_count++] = dir_light(v3(ec * 0.95, -es, ec * 0.3), v3(0.95, 0.85, 0.7));
    s->lights[s->light_count++] = dir_light(v3(0.2, -0.6, -1.0), v3(0.3, 0.3, 0.35));
    s->shadow_light = 1;
    s->shadow_no_pcf = true;
    add_floor(s, proj, s->view, A_CHECKER, 4);
    draw *d = teapot_at(s, proj, teapot, -1.2, 0.5, 30, 0.55);
    set_color(d, 0.8, 0.8, 0.85, 1);
    set_lit(d, "phong", 0.8, 50);
    d = scene_add(s);
    d->mesh = A_CUBE;
    d->proj = proj;
    d->world_view =
        mat_mul(s->view, mat_mul(mat_translate(-1.6, 0.35, -1.0),
                                 mat_mul(mat_rotate_y(45), mat_scale(0.45, 0.35, 0.04))));
    set_color(d, 0.9, 0.5, 0.3, 1);
    set_lit(d, "phong", 0.3, 20);
    d = scene_add(s);
    d->mesh = A_CUBE;
    d->proj = proj;
    d->world_view = mat_mul(s->view, model(v3(-0.2, 0.22, 1.5), 40, 0, 0, 0.22));
    set_color(d, 0.35, 0.6, 0.85, 1);
    set_lit(d, "phong", 0.3, 20);
}

/* Gouraud draws receiving the sun's shadow: a brick floor and two teapots lit per vertex, under a
 * sun (shadowed) and a cool point light to the right (unshadowed). Where the map hides the sun, a
 * pixel keeps the ambient and the point light's pool, and the teapots' highlights of the sun go
 * while the point light's stay. */
static void scene_shadow_gouraud(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "shadow_gouraud";
    s->view = mat_look_at(v3(0.2, 2.6, 4.6), v3(0, 0.4, -0.3), v3(0, 1, 0));
    s->ambient = v3(0.12, 0.12, 0.14);
    s->lights[s->light_count++] = dir_light(v3(0.8, -0.7, -0.35), v3(0.95, 0.88, 0.75));
    s->lights[s->light_count++] =
        point_light(v3(1.8, 1.6, 0.9), v3(0.35, 0.5, 0.75), 0.5, 0.1, 0.15);
    s->shadow_light = 1;
    draw *d = add_floor(s, proj, s->view, A_BRICK, 4);
    set_lit(d, "gouraud", 0, 0);
    d = teapot_at(s, proj, teapot, -1.0, -0.4, 160, 0.7);
    set_color(d, 0.85, 0.5, 0.3, 1);
    set_lit(d, "gouraud", 0.7, 30);
    d = teapot_at(s, proj, teapot, 0.55, -0.2, -30, 0.55);
    set_color(d, 0.4, 0.65, 0.85, 1);
    set_lit(d, "gouraud", 0.7, 30);
}

/* Flat draws receiving the sun's shadow: a checker floor, a teapot and cubes lit once per
 * triangle, under a sun (shadowed) and a dim fill light from the front (unshadowed). The shadow's
 * edge runs through the facets per pixel; a shadowed facet keeps its ambient and fill. */
static void scene_shadow_flat(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "shadow_flat";
    s->view = mat_look_at(v3(-0.3, 2.8, 4.8), v3(0, 0.35, -0.2), v3(0, 1, 0));
    s->ambient = v3(0.14, 0.14, 0.16);
    s->lights[s->light_count++] = dir_light(v3(-0.9, -0.75, -0.25), v3(0.95, 0.9, 0.8));
    s->lights[s->light_count++] = dir_light(v3(0.3, -0.5, -1.0), v3(0.25, 0.22, 0.3));
    s->shadow_light = 1;
    draw *d = add_floor(s, proj, s->view, A_CHECKER, 4);
    set_lit(d, "flat", 0, 0);
    d = teapot_at(s, proj, teapot, 0.6, -0.3, 20, 0.65);
    set_color(d, 0.9, 0.8, 0.55, 1);
    set_lit(d, "flat", 0.6, 25);
    for (int i = 0; i < 3; i++) {
        double size = 0.2 + 0.05 * i;
        d = scene_add(s);
        d->mesh = A_CUBE;
        d->proj = proj;
        d->world_view = mat_mul(
            s->view, model(v3(1.6 - 0.2 * i, size, 0.9 - 0.8 * i), 25.0 * i + 10, 0, 0, size));
        vec3 col = hsv(i / 3.0 + 0.3, 0.55, 0.85);
        set_color(d, col.x, col.y, col.z, 1);
        set_lit(d, "flat", 0, 0);
    }
}

/* ---------------------------------------------------------------------------------------------
 * Line scenes (lines.json) and their line meshes.
 */

/* line_fan is FAN_SIZE pixels square and drawn with identity matrices, so the vertex at window
 * position (x, y) (pixels, y down) is at NDC (x / 512 - 1, 1 - y / 512): exact for any x and y in
 * 1/256 pixel, the grid both rasterisers snap to, so they see the same end points to the bit. */
enum { FAN_SIZE = 1024 };

static int fan_vertex(mesh *m, double x, double y, vec3 color) {
    const double half = FAN_SIZE / 2;
    return mesh_v(m, v3(x / half - 1.0, 1.0 - y / half, 0.0), color);
}

/* One segment, or its reverse: the rule treats a line's first and last pixel differently. */
static void fan_segment(mesh *m, int a, int b, bool reverse) {
    corner c[2] = {{reverse ? b : a, 0, 0}, {reverse ? a : b, 0, 0}};
    mesh_line(m, 2, c);
}

/* 360 segments at 1-degree steps (counter-clockwise as displayed) from (cx, cy), r pixels long,
 * white at the centre and coloured by angle at the far end; even angles drawn outwards, odd ones
 * inwards. The ends are rounded to whole pixels (so they sit on the same kind of point as the
 * centre: pixel centres or pixel corners) or, with subpixel, to 1/256 pixel. The axis-aligned
 * and diagonal ones are exact. */
static void build_fan(mesh *m, double cx, double cy, double r, bool subpixel) {
    int centre = fan_vertex(m, cx, cy, WHITE);
    const double unit = subpixel ? 256.0 : 1.0;
    for (int k = 0; k < 360; k++) {
        double sn, cs;
        sin_cos_deg(k, &sn, &cs);
        if (k % 45 == 0 && k % 90 != 0) {
            /* |cos| = |sin| exactly, whatever the library's last bits. */
            double d = sqrt(0.5);
            cs = cs < 0 ? -d : d;
            sn = sn < 0 ? -d : d;
        }
        double dx = floor(r * cs * unit + 0.5) / unit, dy = floor(-r * sn * unit + 0.5) / unit;
        int end = fan_vertex(m, cx + dx, cy + dy, hsv(k / 360.0, 0.75, 1.0));
        fan_segment(m, centre, end, k % 2 == 1);
    }
}

/* Short segments from one start point (x, y) to its 16 neighbours at (+-1, 0), (0, +-1),
 * (+-1, +-1), (+-2, +-1) and (+-1, +-2) times scale pixels, alternately outwards and inwards: the
 * diamond-exit rule's cases for a line that starts or ends on that kind of point. */
static void build_star(mesh *m, double x, double y, double scale) {
    static const int dirs[16][2] = {{1, 0},   {1, 1},   {0, 1},  {-1, 1}, {-1, 0}, {-1, -1},
                                    {0, -1},  {1, -1},  {2, 1},  {1, 2},  {-1, 2}, {-2, 1},
                                    {-2, -1}, {-1, -2}, {1, -2}, {2, -1}};
    int start = fan_vertex(m, x, y, WHITE);
    for (int k = 0; k < 16; k++) {
        int end =
            fan_vertex(m, x + dirs[k][0] * scale, y + dirs[k][1] * scale, hsv(k / 16.0, 0.8, 1.0));
        fan_segment(m, start, end, k % 2 == 1);
    }
}

/* Two fans around a pixel centre and a pixel corner with whole-pixel ends, two with ends in
 * 1/256 pixel, and rows of short segments from starts at every kind of point of a pixel: its
 * centre, its corner, the diamond's corners and edges, just inside and outside them. */
static void build_line_fan(mesh *m) {
    m->exact = true;
    build_fan(m, 256.5, 256.5, 240, false);
    build_fan(m, 768.0, 256.0, 240, false);
    build_fan(m, 256.5, 672.5, 160, true);
    build_fan(m, 768.0, 672.0, 160, true);
    /* Where a start lies in its pixel, from the pixel's top-left corner. */
    static const double starts[12][2] = {{0.5, 0.5},
                                         {0, 0},
                                         {0.5, 0},
                                         {0, 0.5},
                                         {0.25, 0.75},
                                         {0.75, 0.25},
                                         {0.5 + 1.0 / 256, 0.5},
                                         {0.5, 0.5 - 1.0 / 256},
                                         {1.0 / 256, 0},
                                         {0.125, 0.125},
                                         {0.75, 0.75},
                                         {0.25, 0.5}};
    for (int row = 0; row < 3; row++) {
        double scale = row + 1, y = 872 + 48 * row;
        int i = 0;
        for (double x = 24; x + 2 * scale < FAN_SIZE - 16; x += 4 * scale + 10, i++)
            build_star(m, x + starts[i % 12][0], y + starts[i % 12][1], scale);
    }
}

/* A ground grid of lines across the view at y = 0, from z = 3 to -28.5; the nearest four reach
 * x = +-60, the others +-20; red at the left end, blue at the right. */
static void build_line_grid(mesh *m) {
    for (int j = 0; j < 22; j++) {
        double z = 3.0 - 1.5 * j, half = j < 4 ? 60.0 : 20.0;
        int a = mesh_v(m, v3(-half, 0, z), v3(1.0, 0.45, 0.4));
        int b = mesh_v(m, v3(half, 0, z), v3(0.45, 0.55, 1.0));
        mesh_line(m, 2, (corner[]){{a, 0, 0}, {b, 0, 0}});
    }
}

/* 17 white rails at y = 0 along z, from z = 10 (behind the eye of line_clip) to -30, with
 * texcoord s running along them (a texture repeat every 8 units) and t = 0.3: seen in
 * perspective, textured dashes shorten with distance. */
static void build_line_rails(mesh *m) {
    int near_t = mesh_vt(m, 0.0, 0.3), far_t = mesh_vt(m, 5.0, 0.3);
    for (int i = -8; i <= 8; i++) {
        int a = mesh_v(m, v3(i, 0, 10), WHITE), b = mesh_v(m, v3(i, 0, -30), WHITE);
        mesh_line(m, 2, (corner[]){{a, near_t, 0}, {b, far_t, 0}});
    }
}

/* In view space (drawn with an identity worldView): a burst of 24 segments from a point 6 units
 * ahead to 250 units sideways (some 50000 pixels off the image, beyond the guard band), 8 from it
 * to points behind the eye, and segments that cross the image with both ends beyond the guard
 * band, lie wholly above it, lie wholly behind the eye, or run from behind the eye to far beyond
 * the image. */
static void build_line_burst(mesh *m) {
    const vec3 centre = v3(0.9, 1.1, -6.0);
    int c0 = mesh_v(m, centre, WHITE);
    for (int k = 0; k < 24; k++) {
        /* Each its own colour at the centre: what shows of it is the first percent or two. */
        double sn, cs;
        sin_cos_deg(15.0 * k + 7.5, &sn, &cs);
        int a = mesh_v(m, centre, hsv(k / 24.0, 0.7, 1));
        int e = mesh_v(m, v3_add(centre, v3(250.0 * cs, 250.0 * sn, 0)), v3(0.2, 0.2, 0.2));
        mesh_line(m, 2, (corner[]){{a, 0, 0}, {e, 0, 0}});
    }
    for (int k = 0; k < 8; k++) {
        double sn, cs;
        sin_cos_deg(45.0 * k + 22.5, &sn, &cs);
        int e = mesh_v(m, v3(1.5 * cs, 1.5 * sn, 2.0), hsv(k / 8.0 + 0.5, 0.9, 0.9));
        mesh_line(m, 2, (corner[]){{e, 0, 0}, {c0, 0, 0}});
    }
    static const struct {
        double a[3], b[3], ca[3], cb[3];
    } segs[] = {
        {{-300, -1.0, -6}, {300, -1.6, -6}, {1, 1, 0.2}, {0.2, 1, 1}},   /* across the image */
        {{-1.2, -300, -9}, {-1.0, 300, -9}, {1, 0.3, 1}, {0.3, 1, 0.3}}, /* top to bottom */
        {{-250, 9, -6}, {250, 9.5, -6}, {1, 0, 0}, {1, 0, 0}},           /* above the image */
        {{-1, 0, 1}, {1, 0.5, 2}, {1, 0, 0}, {1, 0, 0}},                 /* behind the eye */
        {{-0.3, -0.4, 0.5}, {400, -60, -30}, {1, 1, 1}, {1, 0.5, 0}},    /* behind to far off */
    };
    for (size_t i = 0; i < sizeof segs / sizeof segs[0]; i++) {
        int a = mesh_v(m, v3(segs[i].a[0], segs[i].a[1], segs[i].a[2]),
                       v3(segs[i].ca[0], segs[i].ca[1], segs[i].ca[2]));
        int b = mesh_v(m, v3(segs[i].b[0], segs[i].b[1], segs[i].b[2]),
                       v3(segs[i].cb[0], segs[i].cb[1], segs[i].cb[2]));
        mesh_line(m, 2, (corner[]){{a, 0, 0}, {b, 0, 0}});
    }
}

/* A lit teapot with its wireframe over it (depth test less-equal, pulled a hair towards the eye),
 * and beside it a wireframe alone with back faces culled, on the checker
 * floor. */
static void scene_wire_teapot(scene *s, mat4 proj, const mesh *teapot) {
    s->name = "wire_teapot";
    s->view = mat_look_at(v3(0, 2.5, 3.3), v3(0, 0.25, 0), v3(0, 1, 0));
    s->ambient = v3(0.15, 0.15, 0.16);
    s->lights[s->light_count++] = dir_light(v3(-0.4, -1.0, -0.6), v3(0.9, 0.88, 0.84));
    add_floor(s, proj, s->view, A_CHECKER, 3);
    draw *d = teapot_at(s, proj, teapot, -0.82, 0.1, -30, 0.72);
    set_color(d, 0.9, 0.55, 0.3, 1);
    set_lit(d, "phong", 0.6, 40);
    draw *w = scene_add(s);
    *w = *d;
    w->lighting = NULL;
    w->wireframe = true;
    w->depth_compare = "less_equal";
    /* A line's depth varies along the line only, its triangle's across it too: at half the
     * pixels the surface would win. Scaling view space about the eye by 0.995 draws the same
     * pixels a hair nearer (x / w and y / w do not change), as a polygon offset would. */
    w->world_view = mat_mul(mat_scale(0.995, 0.995, 0.995), w->world_view);
    set_color(w, 0.12, 0.1, 0.1, 1);
    d = teapot_at(s, proj, teapot, 0.85, -0.1, 35, 0.72);
    d->wireframe = true;
    d->cull = "back";
    set_color(d, 0.35, 1.0, 0.7, 1);
}

/* The fans and short segments of build_line_fan, unlit, no depth test. */
static void scene_line_fan(scene *s) {
    s->name = "line_fan";
    s->width = s->height = FAN_SIZE;
    draw *d = scene_add(s);
    d->mesh = A_LINE_FAN;
    d->depth_compare = "always";
}

/* Lines that leave the view: the ground grid and rails crossing the near plane under the eye, the
 * burst reaching far beyond the image and behind the eye, and two wireframes that the near plane
 * cuts: a colour cube stretched into a beam, and a small triangle just in front of the eye. */
static void scene_line_clip(scene *s, mat4 proj) {
    s->name = "line_clip";
    mat4 view = mat_look_at(v3(0, 1.2, 4.0), v3(0, 0.4, -2.0), v3(0, 1, 0));
    draw *d = scene_add(s);
    d->mesh = A_LINE_GRID;
    d->proj = proj;
    d->world_view = view;
    d = scene_add(s);
    d->mesh = A_LINE_RAILS;
    d->textured = true;
    d->texture = A_CHECKER;
    d->nearest = true;
    d->proj = proj;
    d->world_view = view;
    d = scene_add(s);
    d->mesh = A_LINE_BURST;
    d->proj = proj;
    d = scene_add(s);
    d->mesh = A_CUBE_RGB;
    d->wireframe = true;
    d->proj = proj;
    /* A beam 6 units long from behind the eye into the distance, right of and below the view
     * axis, turned a little. */
    d->world_view =
        mat_mul(mat_translate(0.7, -0.55, -2.4),
                mat_mul(mat_mul(mat_rotate_y(12), mat_rotate_x(8)), mat_scale(0.18, 0.18, 3.0)));
    /* A small triangle tilted through the near plane right in front of the eye: its clipped
     * edges cross the image, and the cut along the near plane is no edge. */
    d = scene_add(s);
    d->mesh = A_TRIANGLE;
    d->wireframe = true;
    set_color(d, 1.0, 0.8, 0.25, 1);
    d->proj = proj;
    d->world_view = mat_mul(mat_translate(0.01, -0.012, -0.12),
                            mat_mul(mat_rotate_x(-70), mat_scale(0.06, 0.06, 0.06)));
}

/* ---------------------------------------------------------------------------------------------
 * Output.
 */

static bool make_dir(const char *path) {
    if (mkdir(path, 0777) == 0 || errno == EEXIST) return true;
    fprintf(stderr, "sgapi-assets: cannot create %s: %s\n", path, strerror(errno));
    return false;
}

/* dir/rel in *buf, grown to its length (one path is in use at a time). Exits when out of
 * memory. */
static const char *join(char **buf, const char *dir, const char *rel) {
    size_t n = strlen(dir) + strlen(rel) + 2;
    char *b = realloc(*buf, n);
    if (!b) {
        fprintf(stderr, "sgapi-assets: out of memory\n");
        exit(1);
    }
    snprintf(b, n, "%s/%s", dir, rel);
    return *buf = b;
}

/* The scenes of each file, in order. */
enum {
    S_01,
    S_02,
    S_03,
    S_04,
    S_05,
    S_06,
    S_07,
    S_08,
    S_ALPHA_CUBES,
    S_ALPHA_TEAPOT_SORTED,
    S_ALPHA_TEAPOT_UNSORTED,
    S_ALPHA_CUTOUT,
    S_ALPHA_STACK,
    S_LIT_MODES,
    S_LIT_TEXTURED,
    S_LIT_POINT,
    S_LIT_BEHIND,
    S_LIT_MANY,
    S_SHADOW_TEAPOTS,
    S_SHADOW_POINT,
    S_SHADOW_GRAZING,
    S_SHADOW_GOURAUD,
    S_SHADOW_FLAT,
    S_WIRE_TEAPOT,
    S_LINE_FAN,
    S_LINE_CLIP,
    S_END = -1
};
static const int DEFAULT_SCENES[] = {S_01, S_02, S_03, S_04, S_05, S_06, S_07, S_08, S_END};
static const int TRANSPARENCY_SCENES[] = {S_ALPHA_CUBES,           S_ALPHA_TEAPOT_SORTED,
                                          S_ALPHA_TEAPOT_UNSORTED, S_ALPHA_CUTOUT,
                                          S_ALPHA_STACK,           S_END};
static const int LIGHTING_SCENES[] = {S_LIT_MODES,  S_LIT_TEXTURED, S_LIT_POINT,
                                      S_LIT_BEHIND, S_LIT_MANY,     S_END};
static const int SHADOW_SCENES[] = {S_SHADOW_TEAPOTS, S_SHADOW_POINT, S_SHADOW_GRAZING,
                                    S_SHADOW_GOURAUD, S_SHADOW_FLAT,  S_END};
static const int LINE_SCENES[] = {S_WIRE_TEAPOT, S_LINE_FAN, S_LINE_CLIP, S_END};

static void build_scene(scene *s, int which, mat4 proj, const mesh *teapot) {
    switch (which) {
    case S_01:
        scene_01(s);
        break;
    case S_02:
        scene_02(s);
        break;
    case S_03:
        scene_03(s, proj);
        break;
    case S_04:
        scene_04(s, proj);
        break;
    case S_05:
        scene_05(s, proj);
        break;
    case S_06:
        scene_06(s, proj, teapot);
        break;
    case S_07:
        scene_07(s, proj, teapot);
        break;
    case S_08:
        scene_08(s, proj);
        break;
    case S_ALPHA_CUBES:
        scene_alpha_cubes(s, proj);
        break;
    case S_ALPHA_TEAPOT_SORTED:
        scene_alpha_teapot(s, proj, teapot, true);
        break;
    case S_ALPHA_TEAPOT_UNSORTED:
        scene_alpha_teapot(s, proj, teapot, false);
        break;
    case S_ALPHA_CUTOUT:
        scene_alpha_cutout(s, proj);
        break;
    case S_ALPHA_STACK:
        scene_alpha_stack(s);
        break;
    case S_LIT_MODES:
        scene_lit_modes(s, proj, teapot);
        break;
    case S_LIT_TEXTURED:
        scene_lit_textured(s, proj, teapot);
        break;
    case S_LIT_POINT:
        scene_lit_point(s, proj);
        break;
    case S_LIT_BEHIND:
        scene_lit_behind(s, proj, teapot);
        break;
    case S_LIT_MANY:
        scene_lit_many(s, proj, teapot);
        break;
    case S_SHADOW_TEAPOTS:
        scene_shadow_teapots(s, proj, teapot);
        break;
    case S_SHADOW_POINT:
        scene_shadow_point(s, proj, teapot);
        break;
    case S_SHADOW_GOURAUD:
        scene_shadow_gouraud(s, proj, teapot);
        break;
    case S_SHADOW_FLAT:
        scene_shadow_flat(s, proj, teapot);
        break;
    case S_WIRE_TEAPOT:
        scene_wire_teapot(s, proj, teapot);
        break;
    case S_LINE_FAN:
        scene_line_fan(s);
        break;
    case S_LINE_CLIP:
        scene_line_clip(s, proj);
        break;
    default:
        scene_shadow_grazing(s, proj, teapot);
        break;
    }
}

/* Writes a scene file of 1024 x 1024 scenes cleared to `clear` (r, g, b, a) unless they say
 * otherwise. */
/* A regular dodecahedron of circumradius 1 as a Geomview OFF file with a colour per face (integers
 * 0..255, Geomview's rule), for model renders of face colours. Each face is the five vertices
 * nearest one of the icosahedron's vertex directions, ordered counter-clockwise about it. */
static bool make_dodecahedron_off(const char *path) {
    const double g = (1 + sqrt(5.0)) / 2, h = 1 / g;
    vec3 v[20];
    int n = 0;
    for (int i = 0; i < 8; i++) v[n++] = v3(i & 1 ? -1 : 1, i & 2 ? -1 : 1, i & 4 ? -1 : 1);
    for (int i = 0; i < 4; i++) {
        double a = i & 1 ? -1 : 1, b = i & 2 ? -1 : 1;
        v[n++] = v3(0, a * h, b * g);
        v[n++] = v3(a * h, b * g, 0);
        v[n++] = v3(a * g, 0, b * h);
    }
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "sgapi-assets: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    fprintf(f, "OFF\n# A regular dodecahedron, circumradius 1, a colour per face (0..255).\n"
               "20 12 30\n");
    for (int i = 0; i < 20; i++) {
        vec3 p = v3_scale(v[i], 1 / sqrt(3.0));
        fprintf(f, "%.6f %.6f %.6f\n", p.x, p.y, p.z);
    }
    for (int k = 0; k < 12; k++) {
        double a = k & 1 ? -1 : 1, b = k & 2 ? -1 : 1;
        vec3 c = k < 4 ? v3(0, a * g, b) : k < 8 ? v3(a * g, b, 0) : v3(a, 0, b * g);
        c = v3_norm(c);
        int face[5] = {0}, m = 0;
        for (int i = 0; i < 20 && m < 5; i++)
            if (v3_dot(v3_norm(v[i]), c) > 0.7) face[m++] = i;
        if (m != 5) {
            fprintf(stderr, "sgapi-assets: dodecahedron face %d has %d vertices\n", k, m);
            fclose(f);
            return false;
        }
        /* Counter-clockwise seen from outside: by angle in a frame (u, w) with u x w = c. */
        vec3 u = v3_norm(v3_sub(v[face[0]], v3_scale(c, v3_dot(v[face[0]], c))));
        vec3 w = v3_cross(c, u);
        double ang[5];
        for (int i = 0; i < 5; i++) ang[i] = atan2(v3_dot(v[face[i]], w), v3_dot(v[face[i]], u));
        for (int i = 1; i < 5; i++)
            for (int j = i; j > 0 && ang[j] < ang[j - 1]; j--) {
                double t = ang[j];
                ang[j] = ang[j - 1], ang[j - 1] = t;
                int q = face[j];
                face[j] = face[j - 1], face[j - 1] = q;
            }
        vec3 col = hsv(k / 12.0, 0.65, 0.95);
        fprintf(f, "5 %d %d %d %d %d %d %d %d\n", face[0], face[1], face[2], face[3], face[4],
                to_u8(col.x), to_u8(col.y), to_u8(col.z));
    }
    bool ok = !ferror(f);
    if (fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "sgapi-assets: error writing %s\n", path);
    return ok;
}

/* scenes/shapes.json: the standard shapes of the scene format's {"shape": ...} meshes on a
 * 3 x 3 grid, lit, and the face-coloured dodecahedron OFF file. */
static bool write_shapes_file(const char *path) {
    static const char *const shapes[9] = {
        "{\"shape\": \"cube\"}",
        "{\"shape\": \"tetrahedron\"}",
        "{\"shape\": \"octahedron\"}",
        "{\"shape\": \"icosphere\", \"subdivisions\": 1}",
        "{\"shape\": \"sphere\", \"segments\": 48, \"rings\": 24}",
        "{\"shape\": \"cylinder\"}",
        "{\"shape\": \"cone\"}",
        "{\"shape\": \"torus\"}",
        "{\"shape\": \"plane\"}"};
    static const char *const textures[9] = {
        "checker.png", NULL, NULL, NULL, "mosaic.png", NULL, NULL, "brick.png", "checker.png"};
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "sgapi-assets: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    const mat4 proj = mat_perspective(40.0, 4.0 / 3.0, 0.5, 50.0);
    const mat4 view = mat_look_at(v3(0, 3.2, 5.8), v3(0, -0.2, 0.2), v3(0, 1, 0));
    char buf[64];
    fprintf(f,
            "{\n  \"width\": 1024,\n  \"height\": 768,\n  \"clear_color\": [0.1, 0.12, 0.16, 1],\n"
            "  \"ambient\": [0.25, 0.25, 0.25],\n"
            "  \"lights\": [{\"type\": \"directional\", \"direction\": [-0.4, -0.6, -1], "
            "\"color\": [0.85, 0.85, 0.85]}],\n  \"scenes\": [\n");
    fprintf(f, "    {\n      \"name\": \"shapes\",\n      \"draws\": [\n");
    for (int i = 0; i < 9; i++) {
        vec3 col = hsv(i / 9.0, textures[i] ? 0.0 : 0.55, 0.95);
        mat4 m = mat_mul(view, mat_mul(mat_translate((i % 3 - 1) * 1.6, 0, (i / 3 - 1) * 1.4),
                                       mat_rotate_y(30.0)));
        fprintf(f, "        {\"mesh\": %s, ", shapes[i]);
        if (textures[i]) fprintf(f, "\"texture\": \"assets/%s\", ", textures[i]);
        fprintf(f, "\"color\": [%s, ", fmt_num(buf, sizeof buf, col.x, 4));
        fprintf(f, "%s, ", fmt_num(buf, sizeof buf, col.y, 4));
        fprintf(f,
                "%s, 1], \"lighting\": \"phong\", \"specular\": [0.4, 0.4, 0.4], "
                "\"shininess\": 32, \"cull\": \"back\",\n         \"worldView\": [",
                fmt_num(buf, sizeof buf, col.z, 4));
        for (int k = 0; k < 16; k++)
            fprintf(f, "%s%s", fmt_num(buf, sizeof buf, m.m[k], 6), k < 15 ? ", " : "");
        fprintf(f, "],\n         \"proj\": [");
        for (int k = 0; k < 16; k++)
            fprintf(f, "%s%s", fmt_num(buf, sizeof buf, proj.m[k], 6), k < 15 ? ", " : "");
        fprintf(f, "]}%s\n", i < 8 ? "," : "");
    }
    fprintf(f, "      ]\n    },\n");
    /* The OFF model, its faces lit flat in their own colours. */
    const mat4 dview = mat_look_at(v3(1.5, 1.2, 3.2), v3(0, 0, 0), v3(0, 1, 0));
    fprintf(f, "    {\n      \"name\": \"dodecahedron_off\",\n      \"draws\": [\n"
               "        {\"mesh\": \"assets/dodecahedron.off\", \"lighting\": \"flat\", "
               "\"cull\": \"back\",\n         \"worldView\": [");
    for (int k = 0; k < 16; k++)
        fprintf(f, "%s%s", fmt_num(buf, sizeof buf, dview.m[k], 6), k < 15 ? ", " : "");
    fprintf(f, "],\n         \"proj\": [");
    for (int k = 0; k < 16; k++)
        fprintf(f, "%s%s", fmt_num(buf, sizeof buf, proj.m[k], 6), k < 15 ? ", " : "");
    fprintf(f, "]}\n      ]\n    }\n  ]\n}\n");
    bool ok = !ferror(f);
    if (fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "sgapi-assets: error writing %s\n", path);
    return ok;
}

static bool write_scene_file(const char *path, const char *clear, const int *which, mat4 proj,
                             const mesh *teapot) {
    FILE *f = fopen(path, "wb");
    if (!f) {
        fprintf(stderr, "sgapi-assets: cannot write %s: %s\n", path, strerror(errno));
        return false;
    }
    scene *s = xmalloc(sizeof *s);
    fprintf(f,
            "{\n  \"width\": 1024,\n  \"height\": 1024,\n  \"clear_color\": [%s],\n"
            "  \"scenes\": [\n",
            clear);
    for (int i = 0; which[i] != S_END; i++) {
        memset(s, 0, sizeof *s);
        build_scene(s, which[i], proj, teapot);
        write_scene(f, s, which[i + 1] == S_END);
    }
    fprintf(f, "  ]\n}\n");
    free(s);
    bool ok = !ferror(f);
    if (fclose(f) != 0) ok = false;
    if (!ok) fprintf(stderr, "sgapi-assets: error writing %s\n", path);
    return ok;
}

typedef void (*mesh_builder)(mesh *m);

static void build_cube_white(mesh *m) {
    build_cube(m, CUBE_WHITE, 0.0, 1.0);
}
static void build_cube_rgb(mesh *m) {
    build_cube(m, CUBE_RGB, 0.0, 1.0);
}
static void build_cube_wide(mesh *m) {
    build_cube(m, CUBE_WHITE, -0.0625, 1.0625);
}

/* Writes every asset and scene file into out; the exit status. */
static int write_assets(const char *out, char **path) {
    if (!make_dir(out) || !make_dir(join(path, out, "assets"))) return 1;

    /* Meshes, each checked before it is written. `facing` is the side a flat mesh must face;
     * a zero vector means a closed mesh whose faces must all face outward. */
    static const struct {
        const char *file, *comment;
        mesh_builder build;
        vec3 facing;
    } meshes[] = {
        {A_TRIANGLE_RGB,
         "One triangle with red, green and blue corners, counter-clockwise.",
         build_triangle_rgb,
         {0, 0, 1}},
        {A_TRIANGLE,
         "White equilateral triangle, circumradius 1, counter-clockwise.",
         build_triangle,
         {0, 0, 1}},
        {A_QUAD, "White square [-1, 1]^2 as one four-corner face.", build_quad, {0, 0, 1}},
        {A_PLANE,
         "Ground [-1, 1]^2 at y = 0, 4 x 4 quads, facing up, texcoords 0..4.",
         build_plane,
         {0, 1, 0}},
        {"assets/floor_long.obj",
         "Ground [-1, 1]^2 at y = 0, one quad facing up, texcoords 0..16 (a texture repeated 16 "
         "times each way), for floors that recede far (mipmaps.json).",
         build_floor_long,
         {0, 1, 0}},
        {A_PYRAMID,
         "Square pyramid, base y = -1, apex y = 1; outward counter-clockwise faces.",
         build_pyramid,
         {0, 0, 0}},
        {A_CUBE,
         "White cube [-1, 1]^3, texcoords 0..1 per face; outward counter-clockwise.",
         build_cube_white,
         {0, 0, 0}},
        {A_CUBE_RGB,
         "Cube [-1, 1]^3 coloured by corner position; outward counter-clockwise.",
         build_cube_rgb,
         {0, 0, 0}},
        {A_CUBE_WIDE,
         "White cube [-1, 1]^3, texcoords -0.0625..1.0625 per face (for clamping).",
         build_cube_wide,
         {0, 0, 0}},
    };
    for (size_t i = 0; i < sizeof meshes / sizeof meshes[0]; i++) {
        mesh m = {0};
        meshes[i].build(&m);
        vec3 f = meshes[i].facing;
        bool ok = (f.x == 0 && f.y == 0 && f.z == 0) ? check_outward(&m, meshes[i].file)
                                                     : check_facing(&m, f, meshes[i].file);
        ok = ok && write_obj(&m, join(path, out, meshes[i].file), meshes[i].comment);
        mesh_free(&m);
        if (!ok) return 1;
    }
    /* Line sets: no faces to check. */
    static const struct {
        const char *file, *comment;
        mesh_builder build;
    } line_meshes[] = {
        {A_LINE_FAN, "Fans and short segments in NDC, exact in 1/256 pixel of a 1024 x 1024 image.",
         build_line_fan},
        {A_LINE_GRID, "Ground grid of coloured lines across the view at y = 0.", build_line_grid},
        {A_LINE_RAILS, "Textured rails at y = 0 along z, reaching behind the eye.",
         build_line_rails},
        {A_LINE_BURST, "Segments in view space, far beyond the image and behind the eye.",
         build_line_burst},
    };
    for (size_t i = 0; i < sizeof line_meshes / sizeof line_meshes[0]; i++) {
        mesh m = {0};
        line_meshes[i].build(&m);
        bool ok = write_obj(&m, join(path, out, line_meshes[i].file), line_meshes[i].comment);
        mesh_free(&m);
        if (!ok) return 1;
    }
    mesh teapot = {0};
    if (!build_teapot(&teapot) ||
        !write_obj(&teapot, join(path, out, A_TEAPOT),
                   "Utah teapot (Newell 1975), 32 Bezier patches x 8 x 8 x 2 triangles, y up.")) {
        mesh_free(&teapot);
        return 1;
    }

    unsigned char *height = xmalloc(HEIGHT_N * HEIGHT_N);
    bool ok = make_checker(join(path, out, A_CHECKER)) && make_mosaic(join(path, out, A_MOSAIC)) &&
              make_brick(join(path, out, A_BRICK)) &&
              make_brick_normal(join(path, out, A_BRICK_NORMAL)) &&
              make_height(join(path, out, A_HEIGHT), height) &&
              make_terrain_color(join(path, out, A_TERRAIN), height) &&
              make_cutout(join(path, out, A_CUTOUT));
    free(height);

    const mat4 proj = mat_perspective(45.0, 1.0, 0.1, 100.0);
    ok = ok && write_scene_file(join(path, out, "default.json"), "0, 0, 0, 0", DEFAULT_SCENES, proj,
                                &teapot);
    ok = ok && write_scene_file(join(path, out, "transparency.json"), "0.62, 0.71, 0.78, 1",
                                TRANSPARENCY_SCENES, proj, &teapot);
    ok = ok && write_scene_file(join(path, out, "lighting.json"), "0.1, 0.12, 0.16, 1",
                                LIGHTING_SCENES, proj, &teapot);
    ok = ok && write_scene_file(join(path, out, "shadows.json"), "0.1, 0.12, 0.16, 1",
                                SHADOW_SCENES, proj, &teapot);
    ok = ok && write_scene_file(join(path, out, "lines.json"), "0.05, 0.06, 0.08, 1", LINE_SCENES,
                                proj, &teapot);
    ok = ok && make_dodecahedron_off(join(path, out, "assets/dodecahedron.off")) &&
         write_shapes_file(join(path, out, "shapes.json"));
    mesh_free(&teapot);
    return ok ? 0 : 1;
}

int main(int argc, char **argv) {
    if (argc != 2 || argv[1][0] == '-') {
        fprintf(stderr, "usage: sgapi-assets OUTDIR\n"
                        "Writes OUTDIR/default.json and the meshes and textures in "
                        "OUTDIR/assets/.\n");
        return 2;
    }
    char *path = NULL; /* every file's, in turn (join) */
    int status = write_assets(argv[1], &path);
    free(path);
    return status;
}
