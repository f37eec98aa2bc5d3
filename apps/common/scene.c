/* scene.c - scene file parsing (JSON) and loading of the meshes and textures the draws name.
 *
 * Every value is validated here, so a renderer can map the result to its API without checks of
 * its own; errors name the file, the scene and draw, and what is wrong.
 */
#define _POSIX_C_SOURCE 200809L /* stat */

#include "scene.h"
#include "cli.h"
#include "scene_keys.h"
#include "shadow.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include <cJSON.h>
#include <sgapi/sgapi_util.h>
#include <strings.h>

#include "model.h"
#include "off.h"

/* Where in the file an error is: -1 (NULL) for "not inside one". */
typedef struct loc {
    int scene, draw, light;
    const char *scene_name;
    const char *object; /* a named object of the scene or top level, such as "shadow" */
} loc;

#define NOWHERE ((loc){.scene = -1, .draw = -1, .light = -1, .scene_name = NULL, .object = NULL})

enum { MESH_OBJ, MESH_HEIGHTMAP, MESH_SHAPE };

typedef struct ctx {
    const char *path;
    char *dir; /* folder of the scene file with its trailing '/', or "" */
    sc_msg *err;
    sc_file *f;
    unsigned char *mesh_kinds; /* MESH_OBJ or MESH_HEIGHTMAP per mesh, to tell sources apart */
    size_t cap_meshes, cap_textures;
} ctx;

static bool fail(ctx *c, const loc *l, const char *fmt, ...) SC_PRINTF_LIKE(3, 4);

/* Formats "file: scenes[i] ('name'), draws[j]: message" (or ", lights[k]" for a light of the
 * scene, or "lights[k]" for one of the top level, and likewise ", shadow"); always returns
 * false. */
static bool fail(ctx *c, const loc *l, const char *fmt, ...) {
    if (!c->err) return false;
    /* The arguments never point into the message: it is replaced below. */
    sc_msg_set(c->err, "%s: ", c->path);
    if (l && l->scene >= 0) {
        sc_msg_append(c->err, "scenes[%d]", l->scene);
        if (l->scene_name) sc_msg_append(c->err, " ('%s')", l->scene_name);
        if (l->draw >= 0) sc_msg_append(c->err, ", draws[%d]", l->draw);
    }
    if (l && l->light >= 0)
        sc_msg_append(c->err, "%slights[%d]", l->scene >= 0 ? ", " : "", l->light);
    if (l && l->object)
        sc_msg_append(c->err, "%s%s", l->scene >= 0 || l->light >= 0 ? ", " : "", l->object);
    if (l && (l->scene >= 0 || l->light >= 0 || l->object)) sc_msg_append(c->err, ": ");
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vappend(c->err, fmt, ap);
    va_end(ap);
    return false;
}

static char *dup_str(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* The capacity after growing from cap to hold need elements (doubling); 0 on overflow. */
static size_t next_cap(size_t cap, size_t need) {
    size_t n = cap ? cap : 8;
    while (n < need) {
        if (n > SIZE_MAX / 2) return 0;
        n *= 2;
    }
    return n;
}

/* Reallocates *ptr to n elements of elem bytes; on failure *ptr is unchanged. */
static bool resize(void **ptr, size_t n, size_t elem) {
    if (n == 0 || n > SIZE_MAX / elem) return false;
    void *q = realloc(*ptr, n * elem);
    if (!q) return false;
    *ptr = q;
    return true;
}

/* A path from the file, made relative to the scene file's folder unless it is absolute. */
static char *resolve_path(const ctx *c, const char *rel) {
    if (rel[0] == '/') return dup_str(rel);
    size_t a = strlen(c->dir), b = strlen(rel);
    char *p = malloc(a + b + 1);
    if (!p) return NULL;
    memcpy(p, c->dir, a);
    memcpy(p + a, rel, b + 1);
    return p;
}

/* A mesh or texture path must not name a device, FIFO or folder: /dev/zero would be read until
 * memory runs out, and opening a FIFO blocks forever. A missing file passes, for the loader to
 * report. */
static bool check_regular(ctx *c, const loc *l, const char *what, const char *path) {
    struct stat st;
    if (stat(path, &st) == 0 && !S_ISREG(st.st_mode))
        return fail(c, l, "%s: '%s' is not a regular file", what, path);
    return true;
}

/* ---- values ---------------------------------------------------------------------------------- */

static bool get_int(ctx *c, const loc *l, const cJSON *obj, const char *key, int lo, int hi,
                    int *out, bool *present) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    *present = v != NULL;
    if (!v) return true;
    double d = cJSON_IsNumber(v) ? v->valuedouble : NAN;
    if (!(d >= lo && d <= hi) || d != floor(d)) {
        if (cJSON_IsNumber(v))
            return fail(c, l, "'%s' must be an integer in %d..%d (got %g)", key, lo, hi, d);
        return fail(c, l, "'%s' must be an integer in %d..%d", key, lo, hi);
    }
    *out = (int)d;
    return true;
}

/* "samples": 1 or 4 (sgPassDesc.samples); *out is left as it is when the key is absent. */
static bool get_samples(ctx *c, const loc *l, const cJSON *obj, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "samples");
    if (!v) return true;
    if (!cJSON_IsNumber(v) || (v->valuedouble != 1.0 && v->valuedouble != 4.0))
        return fail(c, l, "'samples' must be 1 or 4 (samples a pixel)");
    *out = (int)v->valuedouble;
    return true;
}

/* An array of exactly n finite numbers, each in [lo, hi]. */
static bool get_floats(ctx *c, const loc *l, const cJSON *obj, const char *key, int n, double lo,
                       double hi, float *out, bool *present) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    *present = v != NULL;
    if (!v) return true;
    if (!cJSON_IsArray(v) || cJSON_GetArraySize(v) != n)
        return fail(c, l, "'%s' must be an array of %d numbers", key, n);
    int i = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, v) {
        if (!cJSON_IsNumber(e)) return fail(c, l, "'%s'[%d] is not a number", key, i);
        double d = e->valuedouble;
        float f = (float)d;
        if (!isfinite(f)) return fail(c, l, "'%s'[%d] = %g does not fit a float", key, i, d);
        if (d < lo && hi == HUGE_VAL)
            return fail(c, l, "'%s'[%d] = %g must be >= %g", key, i, d, lo);
        if (d < lo || d > hi)
            return fail(c, l, "'%s'[%d] = %g is out of range (%g..%g)", key, i, d, lo, hi);
        out[i++] = f;
    }
    return true;
}

/* A finite number in [lo, hi]; absent keeps *out (the default). */
static bool get_number(ctx *c, const loc *l, const cJSON *obj, const char *key, double lo,
                       double hi, float *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return true;
    if (!cJSON_IsNumber(v)) return fail(c, l, "'%s' must be a number in %g..%g", key, lo, hi);
    double d = v->valuedouble;
    if (!(d >= lo && d <= hi))
        return fail(c, l, "'%s' must be a number in %g..%g (got %g)", key, lo, hi, d);
    *out = (float)d;
    return true;
}

/* A finite number (one a float holds); absent keeps *out (the default). */
static bool get_finite(ctx *c, const loc *l, const cJSON *obj, const char *key, float *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return true;
    if (!cJSON_IsNumber(v)) return fail(c, l, "'%s' must be a number", key);
    float f = (float)v->valuedouble;
    if (!isfinite(f)) return fail(c, l, "'%s' = %g does not fit a float", key, v->valuedouble);
    *out = f;
    return true;
}

/* true or false; absent keeps *out (the default). */
static bool get_bool(ctx *c, const loc *l, const cJSON *obj, const char *key, bool *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return true;
    if (!cJSON_IsBool(v)) return fail(c, l, "'%s' must be true or false", key);
    *out = cJSON_IsTrue(v);
    return true;
}

typedef struct enum_name {
    const char *name;
    int value;
} enum_name;

static const enum_name modes[] = {
    {"vertex_color", SC_MODE_VERTEX_COLOR}, {"texture", SC_MODE_TEXTURE}, {NULL, 0}};
static const enum_name filters[] = {
    {"bilinear", SC_FILTER_BILINEAR}, {"nearest", SC_FILTER_NEAREST}, {NULL, 0}};
static const enum_name mipmaps[] = {{"none", SC_MIPMAP_NONE},
                                    {"nearest", SC_MIPMAP_NEAREST},
                                    {"linear", SC_MIPMAP_LINEAR},
                                    {NULL, 0}};
static const enum_name wraps[] = {{"repeat", SC_WRAP_REPEAT}, {"clamp", SC_WRAP_CLAMP}, {NULL, 0}};
static const enum_name culls[] = {
    {"none", SC_CULL_NONE}, {"back", SC_CULL_BACK}, {"front", SC_CULL_FRONT}, {NULL, 0}};
static const enum_name front_faces[] = {
    {"ccw", SC_FRONT_FACE_CCW}, {"cw", SC_FRONT_FACE_CW}, {NULL, 0}};
static const enum_name compares[] = {{"less", SC_COMPARE_LESS},
                                     {"never", SC_COMPARE_NEVER},
                                     {"equal", SC_COMPARE_EQUAL},
                                     {"less_equal", SC_COMPARE_LESS_EQUAL},
                                     {"greater", SC_COMPARE_GREATER},
                                     {"not_equal", SC_COMPARE_NOT_EQUAL},
                                     {"greater_equal", SC_COMPARE_GREATER_EQUAL},
                                     {"always", SC_COMPARE_ALWAYS},
                                     {NULL, 0}};

static const enum_name blends[] = {
    {"opaque", SC_BLEND_OPAQUE}, {"alpha", SC_BLEND_ALPHA}, {NULL, 0}};
static const enum_name sorts[] = {
    {"none", SC_SORT_NONE}, {"back_to_front", SC_SORT_BACK_TO_FRONT}, {NULL, 0}};
static const enum_name lightings[] = {{"none", SC_LIGHTING_NONE},
                                      {"flat", SC_LIGHTING_FLAT},
                                      {"gouraud", SC_LIGHTING_GOURAUD},
                                      {"phong", SC_LIGHTING_PHONG},
                                      {NULL, 0}};
static const enum_name polygon_modes[] = {
    {"fill", SC_POLYGON_MODE_FILL}, {"line", SC_POLYGON_MODE_LINE}, {NULL, 0}};
static const enum_name light_types[] = {
    {"directional", SC_LIGHT_DIRECTIONAL}, {"point", SC_LIGHT_POINT}, {NULL, 0}};

/* A string naming one of the table's values; absent keeps *out (the default). */
static bool get_enum(ctx *c, const loc *l, const cJSON *obj, const char *key,
                     const enum_name *table, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!v) return true;
    if (cJSON_IsString(v)) {
        for (const enum_name *e = table; e->name; e++) {
            if (strcmp(e->name, v->valuestring) == 0) {
                *out = e->value;
                return true;
            }
        }
    }
    char names[160] = "";
    for (const enum_name *e = table; e->name; e++) {
        size_t n = strlen(names);
        snprintf(names + n, sizeof names - n, "%s%s", n ? ", " : "", e->name);
    }
    if (cJSON_IsString(v))
        return fail(c, l, "'%s' must be one of %s (got '%.60s')", key, names, v->valuestring);
    return fail(c, l, "'%s' must be a string, one of %s", key, names);
}

static bool valid_name(const char *s) {
    size_t n = 0;
    for (; s[n]; n++) {
        char ch = s[n];
        bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') ||
                  (ch >= '0' && ch <= '9') || ch == '_' || ch == '.' || ch == '-';
        if (!ok) return false;
    }
    return n >= 1 && n <= SC_MAX_NAME_LENGTH;
}

/* ---- meshes and textures --------------------------------------------------------------------- */

bool sc_heightmap_mesh(const sc_image *image, float height_scale, sc_mesh *out, sc_msg *err) {
    memset(out, 0, sizeof *out);
    const int w = image->width, h = image->height;
    if (w < 2 || h < 2 || !image->pixels) {
        sc_msg_set(err, "a heightmap needs at least 2x2 pixels (got %dx%d)", w, h);
        return false;
    }
    if (!isfinite(height_scale)) {
        sc_msg_set(err, "height_scale is not finite");
        return false;
    }
    uint64_t nv = (uint64_t)w * (uint64_t)h, ni = 6 * (uint64_t)(w - 1) * (uint64_t)(h - 1);
    if (nv > SC_MESH_MAX_COUNT || ni > SC_MESH_MAX_COUNT || nv > SIZE_MAX / (4 * sizeof(float)) ||
        ni > SIZE_MAX / sizeof(uint32_t)) {
        sc_msg_set(err, "heightmap of %dx%d pixels is too large", w, h);
        return false;
    }
    sc_mesh m = {0};
    m.positions = malloc((size_t)nv * 4 * sizeof(float));
    m.colors = malloc((size_t)nv * 4 * sizeof(float));
    m.texcoords = malloc((size_t)nv * 2 * sizeof(float));
    m.indices = malloc((size_t)ni * sizeof(uint32_t));
    if (!m.positions || !m.colors || !m.texcoords || !m.indices) {
        sc_mesh_free(&m);
        sc_msg_set(err, "out of memory for a heightmap of %dx%d pixels", w, h);
        return false;
    }
    for (int y = 0; y < h; y++) {
        for (int x = 0; x < w; x++) {
            size_t i = (size_t)y * (size_t)w + (size_t)x;
            /* Row y counts from the bottom of the image as displayed, as texcoord t does: the
             * vertex at t = y / H sits on the height of the texel row t samples. */
            size_t row = (size_t)(h - 1 - y);
            const unsigned char *px = image->pixels + (row * (size_t)w + (size_t)x) * 4;
            float *p = m.positions + i * 4, *col = m.colors + i * 4, *t = m.texcoords + i * 2;
            p[0] = (float)(x - w / 2.0);
            p[1] = (float)(height_scale * (double)(px[0] + px[1] + px[2]) / 765.0);
            p[2] = (float)(y - h / 2.0);
            p[3] = 1.0f;
            col[0] = col[1] = col[2] = col[3] = 1.0f;
            t[0] = (float)((double)x / w);
            t[1] = (float)((double)y / h);
        }
    }
    uint32_t *idx = m.indices;
    for (int y = 0; y + 1 < h; y++) {
        for (int x = 0; x + 1 < w; x++) {
            uint32_t i = (uint32_t)y * (uint32_t)w + (uint32_t)x, W = (uint32_t)w;
            *idx++ = i, *idx++ = i + W, *idx++ = i + 1;
            *idx++ = i + 1, *idx++ = i + W, *idx++ = i + W + 1;
        }
    }
    m.vertex_count = (uint32_t)nv;
    m.index_count = (uint32_t)ni;
    *out = m;
    return true;
}

static bool check_image_size(ctx *c, const loc *l, const char *path, const sc_image *img) {
    if (img->width > SC_MAX_IMAGE_SIZE || img->height > SC_MAX_IMAGE_SIZE)
        return fail(c, l, "image '%s' is %dx%d, larger than %d on a side", path, img->width,
                    img->height, SC_MAX_IMAGE_SIZE);
    return true;
}

/* Gives a mesh without normals smooth ones, so every renderer lights the same normals. */
static bool add_normals(sc_mesh *m) {
    if (m->normals) return true;
    m->normals = calloc(m->vertex_count, 3 * sizeof(float)); /* calloc checks the product */
    /* Both counts are at most SC_MESH_MAX_COUNT, so they fit an int. */
    return m->normals && sgu_compute_normals(m->positions, (int)m->vertex_count, m->indices,
                                             (int)m->index_count, 0, m->normals) == 0;
}

/* Appends a mesh with its source and kind; takes ownership of source and mesh, even on failure. */
static bool add_mesh(ctx *c, const loc *l, char *source, int kind, sc_mesh *mesh, int *out) {
    sc_file *f = c->f;
    if (f->mesh_count == c->cap_meshes) {
        /* Arrays that grew before a later one failed are merely larger than cap_meshes says. */
        size_t n = f->mesh_count < INT_MAX ? next_cap(c->cap_meshes, f->mesh_count + 1) : 0;
        if (!n || !resize((void **)&f->meshes, n, sizeof *f->meshes) ||
            !resize((void **)&f->mesh_sources, n, sizeof *f->mesh_sources) ||
            !resize((void **)&c->mesh_kinds, n, 1)) {
            free(source);
            sc_mesh_free(mesh);
            return fail(c, l, "out of memory");
        }
        c->cap_meshes = n;
    }
    f->meshes[f->mesh_count] = *mesh;
    f->mesh_sources[f->mesh_count] = source;
    c->mesh_kinds[f->mesh_count] = (unsigned char)kind;
    *out = (int)f->mesh_count++;
    return true;
}

/* {"shape": name, parameters...}: a standard shape of sgapi_util, made once per distinct
 * description. */
static bool get_shape(ctx *c, const loc *l, const cJSON *v, int *out) {
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(v, "shape");
    sguShapeDesc d = {0};
    if (!cJSON_IsString(name) || sgu_shape_from_name(name->valuestring, &d.shape) != 0)
        return fail(c, l,
                    "'shape' must be one of \"cube\", \"tetrahedron\", \"octahedron\", "
                    "\"icosphere\", \"sphere\", \"cylinder\", \"cone\", \"torus\", "
                    "\"plane\"");
    bool present;
    if (!get_int(c, l, v, "segments", d.shape == SGU_SHAPE_PLANE ? 1 : 3, 1024, &d.segments,
                 &present) ||
        !get_int(c, l, v, "rings", 2, 1024, &d.rings, &present) ||
        !get_int(c, l, v, "subdivisions", 0, 7, &d.subdivisions, &present))
        return false;
    static const char *const sizes[] = {"size", "radius", "height", "tube_radius"};
    float *fields[] = {&d.size, &d.radius, &d.height, &d.tube_radius};
    for (int i = 0; i < 4; i++) {
        const cJSON *n = cJSON_GetObjectItemCaseSensitive(v, sizes[i]);
        if (!n) continue;
        float x = cJSON_IsNumber(n) ? (float)n->valuedouble : 0;
        if (!cJSON_IsNumber(n) || !isfinite(x) || !(x > 0) || x > 1e6f)
            return fail(c, l, "'%s' must be a number in (0, 1e6]", sizes[i]);
        *fields[i] = x;
    }
    char *source = sc_format(
        "shape %s (segments %d, rings %d, subdivisions %d, size %.9g, radius %.9g, height "
        "%.9g, tube_radius %.9g)",
        name->valuestring, d.segments, d.rings, d.subdivisions, d.size, d.radius, d.height,
        d.tube_radius);
    if (!source) return fail(c, l, "out of memory");
    for (size_t i = 0; i < c->f->mesh_count; i++) {
        if (c->mesh_kinds[i] == MESH_SHAPE && strcmp(c->f->mesh_sources[i], source) == 0) {
            free(source);
            *out = (int)i;
            return true;
        }
    }
    sc_mesh mesh;
    sc_msg why = {0};
    if (!sc_shape_mesh(&d, &mesh, &why)) {
        free(source);
        fail(c, l, "mesh: %s", why.text);
        sc_msg_free(&why);
        return false;
    }
    return add_mesh(c, l, source, MESH_SHAPE, &mesh, out);
}

/* The draw's "mesh": an OBJ or OFF path, {"heightmap": path, "height_scale": number} or
 * {"shape": name, ...}. */
static bool get_mesh(ctx *c, const loc *l, const cJSON *draw, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(draw, "mesh");
    const char *rel;
    double scale = 1.0;
    int kind;
    if (!v) return fail(c, l, "missing 'mesh'");
    if (cJSON_IsObject(v) && cJSON_GetObjectItemCaseSensitive(v, "shape"))
        return get_shape(c, l, v, out);
    if (cJSON_IsString(v)) {
        kind = MESH_OBJ;
        rel = v->valuestring;
    } else if (cJSON_IsObject(v)) {
        kind = MESH_HEIGHTMAP;
        const cJSON *hm = cJSON_GetObjectItemCaseSensitive(v, "heightmap");
        const cJSON *hs = cJSON_GetObjectItemCaseSensitive(v, "height_scale");
        if (!cJSON_IsString(hm)) return fail(c, l, "'mesh' object needs a 'heightmap' path");
        if (hs && (!cJSON_IsNumber(hs) || !isfinite((float)hs->valuedouble)))
            return fail(c, l, "'height_scale' must be a finite number");
        rel = hm->valuestring;
        if (hs) scale = hs->valuedouble;
    } else {
        return fail(c, l,
                    "'mesh' must be a path, a {\"heightmap\": ...} or a {\"shape\": ...} "
                    "object");
    }
    if (rel[0] == '\0') return fail(c, l, "'mesh' names an empty path");

    char *path = resolve_path(c, rel);
    if (!path) return fail(c, l, "out of memory");
    char *source = path;
    if (kind == MESH_HEIGHTMAP) {
        source = sc_format("%s (heightmap, height_scale %.9g)", path, (float)scale);
        if (!source) {
            free(path);
            return fail(c, l, "out of memory");
        }
    }
    /* Loaded once per file: later draws naming the same mesh share it. */
    for (size_t i = 0; i < c->f->mesh_count; i++) {
        if (c->mesh_kinds[i] == kind && strcmp(c->f->mesh_sources[i], source) == 0) {
            if (source != path) free(source);
            free(path);
            *out = (int)i;
            return true;
        }
    }

    if (!check_regular(c, l, "mesh", path)) {
        if (source != path) free(source);
        free(path);
        return false;
    }
    sc_msg why = {0};
    sc_mesh mesh;
    bool ok;
    if (kind == MESH_OBJ) {
        /* OFF files by their extension, anything else as OBJ (as before OFF was read). */
        size_t pl = strlen(path);
        if (pl >= 4 && strcasecmp(path + pl - 4, ".off") == 0)
            ok = sc_off_load(path, &mesh, NULL, &why);
        else
            ok = sc_obj_load(path, &mesh, &why);
    } else {
        sc_image img;
        ok = sc_image_load(path, &img, &why);
        if (ok && !check_image_size(c, l, path, &img)) {
            sc_image_free(&img);
            if (source != path) free(source);
            free(path);
            return false;
        }
        if (ok) ok = sc_heightmap_mesh(&img, (float)scale, &mesh, &why);
        sc_image_free(&img);
    }
    if (source != path) free(path);
    if (!ok) {
        free(source);
        fail(c, l, "mesh: %s", why.text);
        sc_msg_free(&why);
        return false;
    }
    if (!add_normals(&mesh)) {
        fail(c, l, "mesh '%s': out of memory for its normals", source);
        free(source);
        sc_mesh_free(&mesh);
        return false;
    }
    return add_mesh(c, l, source, kind, &mesh, out);
}

/* A texture path of the file, loaded once per file: *out is its index in f->textures. key names
 * the value in messages ("'texture'", "'textures'[2]"). */
static bool load_texture(ctx *c, const loc *l, const char *key, const char *rel, int *out) {
    if (rel[0] == '\0') return fail(c, l, "%s names an empty path", key);
    char *path = resolve_path(c, rel);
    if (!path) return fail(c, l, "out of memory");
    sc_file *f = c->f;
    for (size_t i = 0; i < f->texture_count; i++) {
        if (strcmp(f->texture_sources[i], path) == 0) {
            free(path);
            *out = (int)i;
            return true;
        }
    }
    if (!check_regular(c, l, "texture", path)) {
        free(path);
        return false;
    }
    sc_msg why = {0};
    sc_image img;
    if (!sc_image_load(path, &img, &why)) {
        free(path);
        fail(c, l, "%s: %s", strcmp(key, "'texture'") == 0 ? "texture" : key, why.text);
        sc_msg_free(&why);
        return false;
    }
    if (!check_image_size(c, l, path, &img)) {
        sc_image_free(&img);
        free(path);
        return false;
    }
    if (f->texture_count == c->cap_textures) {
        size_t n = f->texture_count < INT_MAX ? next_cap(c->cap_textures, f->texture_count + 1) : 0;
        if (!n || !resize((void **)&f->textures, n, sizeof *f->textures) ||
            !resize((void **)&f->texture_sources, n, sizeof *f->texture_sources)) {
            sc_image_free(&img);
            free(path);
            return fail(c, l, "out of memory");
        }
        c->cap_textures = n;
    }
    f->textures[f->texture_count] = img;
    f->texture_sources[f->texture_count] = path;
    *out = (int)f->texture_count++;
    return true;
}

/* The draw's "texture": a path, null or absent (-1). */
static bool get_texture(ctx *c, const loc *l, const cJSON *draw, int *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(draw, "texture");
    *out = -1;
    if (!v || cJSON_IsNull(v)) return true;
    if (!cJSON_IsString(v)) return fail(c, l, "'texture' must be a path or null");
    return load_texture(c, l, "'texture'", v->valuestring, out);
}

/* ---- scenes and draws ------------------------------------------------------------------------ */

/* What a draw of a mesh with lines cannot do (docs/scene-format.md, "Lines"): flat lighting needs a
 * face, Gouraud and Phong a normal at every line vertex, which only faces give; back-to-front
 * sorting orders triangles. */
static bool check_lines(ctx *c, const loc *l, const sc_draw *d) {
    const sc_mesh *m = &c->f->meshes[d->mesh];
    const char *src = c->f->mesh_sources[d->mesh];
    if (m->line_index_count == 0) return true;
    if (d->sort == SC_SORT_BACK_TO_FRONT)
        return fail(c, l,
                    "'sort' 'back_to_front' orders triangles, and mesh '%s' has lines ('l'): draw "
                    "them from a mesh of their own",
                    src);
    if (d->lighting == SC_LIGHTING_FLAT)
        return fail(c, l,
                    "'lighting' 'flat' lights faces, and mesh '%s' has lines ('l'), which have "
                    "none: light it 'gouraud' or 'phong', or draw the lines from a mesh of their "
                    "own",
                    src);
    if (d->lighting == SC_LIGHTING_NONE) return true;
    for (uint32_t i = 0; i < m->line_index_count; i++) {
        const float *n = m->normals + (size_t)m->line_indices[i] * 3;
        if (n[0] != 0.0f || n[1] != 0.0f || n[2] != 0.0f) continue;
        const float *p = m->positions + (size_t)m->line_indices[i] * 4;
        return fail(c, l,
                    "'lighting' '%s' needs a normal at every line vertex, and line vertex (%g, %g, "
                    "%g) of mesh '%s' has none: an 'l' vertex gets one only from the faces at its "
                    "position, in a file without 'vn'",
                    d->lighting == SC_LIGHTING_GOURAUD ? "gouraud" : "phong", (double)p[0],
                    (double)p[1], (double)p[2], src);
    }
    return true;
}

/* Most instances of one draw: the instance index stays exact in a float (a twin may compute with
 * it so). */
#define SC_MAX_INSTANCES (1 << 24)

bool sc_shader_name_valid(const char *s) {
    size_t n = 0;
    for (; s[n]; n++) {
        char ch = s[n];
        bool ok = (ch >= 'A' && ch <= 'Z') || (ch >= 'a' && ch <= 'z') ||
                  (ch >= '0' && ch <= '9') || ch == '_';
        if (!ok) return false;
    }
    return n >= 1 && n <= SC_MAX_SHADER_NAME;
}

/* "uniforms": an array of finite numbers (a float each), any length the API takes. */
static bool get_uniforms(ctx *c, const loc *l, const cJSON *v, sc_draw *d) {
    const int max = SC_MAX_UNIFORMS;
    if (!cJSON_IsArray(v)) return fail(c, l, "'uniforms' must be an array of numbers");
    int n = cJSON_GetArraySize(v);
    if (n > max)
        return fail(c, l, "'uniforms' holds %d numbers, more than the %d a draw takes", n, max);
    if (n == 0) return true;
    d->uniforms = malloc((size_t)n * sizeof *d->uniforms);
    if (!d->uniforms) return fail(c, l, "out of memory");
    int i = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, v) {
        if (!cJSON_IsNumber(e)) return fail(c, l, "'uniforms'[%d] is not a number", i);
        float f = (float)e->valuedouble;
        if (!isfinite(f))
            return fail(c, l, "'uniforms'[%d] = %g does not fit a float", i, e->valuedouble);
        d->uniforms[i++] = f;
    }
    d->uniform_count = n;
    return true;
}

/* "textures": an array of paths, each loaded as "texture" is. */
static bool get_shader_textures(ctx *c, const loc *l, const cJSON *v, sc_draw *d) {
    if (!cJSON_IsArray(v)) return fail(c, l, "'textures' must be an array of paths");
    int n = cJSON_GetArraySize(v);
    if (n > SC_MAX_DRAW_TEXTURES)
        return fail(c, l, "'textures' names %d textures, more than the %d a draw binds", n,
                    SC_MAX_DRAW_TEXTURES);
    int i = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, v) {
        char key[32];
        snprintf(key, sizeof key, "'textures'[%d]", i);
        if (!cJSON_IsString(e)) return fail(c, l, "%s must be a path", key);
        if (!load_texture(c, l, key, e->valuestring, &d->shader_textures[i])) return false;
        d->shader_texture_count = ++i;
    }
    return true;
}

/* The keys of programmable stages (docs/scene-format.md, "Shaders"): "shader" and what only a
 * shader draw takes. A shader replaces the fixed colour, texture, lighting and shadows, so a draw
 * asking for both is refused rather than silently drawn one way. The name itself is checked by
 * the program, which knows its shaders (sc_shaders_check). */
static bool parse_shader_keys(ctx *c, const loc *l, const cJSON *v, sc_draw *d) {
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(v, "shader");
    const cJSON *uniforms = cJSON_GetObjectItemCaseSensitive(v, "uniforms");
    const cJSON *textures = cJSON_GetObjectItemCaseSensitive(v, "textures");
    bool has_instances;
    d->instances = 1;
    if (!get_int(c, l, v, "instances", 1, SC_MAX_INSTANCES, &d->instances, &has_instances))
        return false;
    if (!name) {
        const char *key = uniforms ? "uniforms" : textures ? "textures" : "instances";
        if (uniforms || textures || has_instances)
            return fail(c, l, "'%s' is for shader draws, and the draw names no 'shader'", key);
        return true;
    }
    if (!cJSON_IsString(name) || !sc_shader_name_valid(name->valuestring))
        return fail(c, l, "'shader' must be a shader's name (1 to 64 of A-Z a-z 0-9 _)");
    static const char *const replaced[] = {"the shader replaces the fixed shading",
                                           "the shader samples the draw's 'textures'",
                                           "a shader draw is not lit: the shader computes its "
                                           "own light",
                                           "a shader draw neither casts nor receives the "
                                           "scene's shadow (a shader may sample a shadow map "
                                           "given in 'textures')"};
    const cJSON *mode = cJSON_GetObjectItemCaseSensitive(v, "mode");
    if (mode && d->mode != SC_MODE_VERTEX_COLOR)
        return fail(c, l, "'mode' 'texture' with a 'shader': %s", replaced[0]);
    if (d->texture >= 0) return fail(c, l, "'texture' with a 'shader': %s", replaced[1]);
    if (d->lighting != SC_LIGHTING_NONE)
        return fail(c, l, "'lighting' with a 'shader': %s", replaced[2]);
    if (d->color[0] != 1.0f || d->color[1] != 1.0f || d->color[2] != 1.0f || d->color[3] != 1.0f)
        return fail(c, l, "'color' with a 'shader': %s (give the colour in 'uniforms')",
                    replaced[0]);
    if (d->specular[0] != 0.0f || d->specular[1] != 0.0f || d->specular[2] != 0.0f ||
        d->shininess != 0.0f)
        return fail(c, l, "'%s' with a 'shader': %s",
                    d->shininess != 0.0f ? "shininess" : "specular", replaced[2]);
    const cJSON *cs = cJSON_GetObjectItemCaseSensitive(v, "casts_shadow");
    const cJSON *rs = cJSON_GetObjectItemCaseSensitive(v, "receives_shadow");
    if (cJSON_IsTrue(cs) || cJSON_IsTrue(rs))
        return fail(c, l, "'%s' true with a 'shader': %s",
                    cJSON_IsTrue(cs) ? "casts_shadow" : "receives_shadow", replaced[3]);
    d->casts_shadow = false;
    d->receives_shadow = false;
    if (uniforms && !get_uniforms(c, l, uniforms, d)) return false;
    if (textures && !get_shader_textures(c, l, textures, d)) return false;
    d->shader = dup_str(name->valuestring);
    if (!d->shader) return fail(c, l, "out of memory");
    return true;
}

void sc_draw_free(sc_draw *d) {
    free(d->shader);
    free(d->uniforms);
    d->shader = NULL;
    d->uniforms = NULL;
    d->uniform_count = 0;
}

static bool parse_draw_fields(ctx *c, const loc *l, const cJSON *v, sc_draw *d) {
    if (!cJSON_IsObject(v)) return fail(c, l, "a draw must be an object");
    if (!get_mesh(c, l, v, &d->mesh)) return false;
    if (!get_texture(c, l, v, &d->texture)) return false;

    /* Without "mode", a draw that names a texture is textured. */
    int mode = d->texture >= 0 ? SC_MODE_TEXTURE : SC_MODE_VERTEX_COLOR;
    int filter = SC_FILTER_BILINEAR, wrap = SC_WRAP_REPEAT, cull = SC_CULL_NONE;
    int front = SC_FRONT_FACE_CCW, compare = SC_COMPARE_LESS;
    int blend = SC_BLEND_OPAQUE, sort = SC_SORT_NONE, lighting = SC_LIGHTING_NONE;
    int polygon_mode = SC_POLYGON_MODE_FILL, mipmap = SC_MIPMAP_NONE;
    if (!get_enum(c, l, v, "mode", modes, &mode) ||
        !get_enum(c, l, v, "filter", filters, &filter) ||
        !get_enum(c, l, v, "mipmap", mipmaps, &mipmap) ||
        !get_enum(c, l, v, "wrap", wraps, &wrap) || !get_enum(c, l, v, "cull", culls, &cull) ||
        !get_enum(c, l, v, "front_face", front_faces, &front) ||
        !get_enum(c, l, v, "depth_compare", compares, &compare) ||
        !get_enum(c, l, v, "blend", blends, &blend) || !get_enum(c, l, v, "sort", sorts, &sort) ||
        !get_enum(c, l, v, "lighting", lightings, &lighting) ||
        !get_enum(c, l, v, "polygon_mode", polygon_modes, &polygon_mode))
        return false;
    d->mode = (sc_mode)mode;
    d->filter = (sc_filter)filter;
    d->mipmap = (sc_mipmap)mipmap;
    d->wrap = (sc_wrap)wrap;
    d->cull = (sc_cull)cull;
    d->front_face = (sc_front_face)front;
    d->depth_compare = (sc_compare)compare;
    d->blend = (sc_blend)blend;
    d->sort = (sc_sort)sort;
    d->lighting = (sc_lighting)lighting;
    d->polygon_mode = (sc_polygon_mode)polygon_mode;
    if (!check_lines(c, l, d)) return false;

    const cJSON *dw = cJSON_GetObjectItemCaseSensitive(v, "depth_write");
    if (dw && !cJSON_IsBool(dw)) return fail(c, l, "'depth_write' must be true or false");
    d->depth_write = !dw || cJSON_IsTrue(dw);
    d->casts_shadow = true;
    d->receives_shadow = true;
    if (!get_bool(c, l, v, "casts_shadow", &d->casts_shadow) ||
        !get_bool(c, l, v, "receives_shadow", &d->receives_shadow))
        return false;
    bool present;
    for (int i = 0; i < 4; i++) d->color[i] = 1.0f;
    if (!get_floats(c, l, v, "color", 4, 0.0, 1.0, d->color, &present)) return false;
    if (!get_floats(c, l, v, "specular", 3, 0.0, HUGE_VAL, d->specular, &present) ||
        !get_number(c, l, v, "shininess", 0.0, 128.0, &d->shininess))
        return false;
    if (!get_floats(c, l, v, "worldView", 16, -HUGE_VAL, HUGE_VAL, d->world_view, &present))
        return false;
    if (!present) return fail(c, l, "missing 'worldView' (16 numbers, row-major)");
    if (!get_floats(c, l, v, "proj", 16, -HUGE_VAL, HUGE_VAL, d->proj, &present)) return false;
    if (!present) return fail(c, l, "missing 'proj' (16 numbers, row-major)");
    return parse_shader_keys(c, l, v, d);
}

/* One draw; on failure it holds nothing (the scene counts only the draws parsed). */
static bool parse_draw(ctx *c, const loc *l, const cJSON *v, sc_draw *d) {
    if (parse_draw_fields(c, l, v, d)) return true;
    sc_draw_free(d);
    return false;
}

/* One light object; l names it in messages. */
static bool parse_light(ctx *c, const loc *l, const cJSON *v, sc_light *out) {
    if (!cJSON_IsObject(v)) return fail(c, l, "a light must be an object");
    if (!cJSON_GetObjectItemCaseSensitive(v, "type"))
        return fail(c, l, "missing 'type' (directional or point)");
    int type = SC_LIGHT_DIRECTIONAL;
    if (!get_enum(c, l, v, "type", light_types, &type)) return false;
    memset(out, 0, sizeof *out);
    out->type = (sc_light_type)type;
    bool present;
    if (out->type == SC_LIGHT_DIRECTIONAL) {
        if (!get_floats(c, l, v, "direction", 3, -HUGE_VAL, HUGE_VAL, out->direction, &present))
            return false;
        if (!present) return fail(c, l, "missing 'direction' (3 numbers) of a directional light");
        if (out->direction[0] == 0.0f && out->direction[1] == 0.0f && out->direction[2] == 0.0f)
            return fail(c, l, "'direction' is (0, 0, 0): a directional light needs a direction");
    } else {
        if (!get_floats(c, l, v, "position", 3, -HUGE_VAL, HUGE_VAL, out->position, &present))
            return false;
        if (!present) return fail(c, l, "missing 'position' (3 numbers) of a point light");
        out->attenuation[0] = 1.0f;
        if (!get_floats(c, l, v, "attenuation", 3, 0.0, HUGE_VAL, out->attenuation, &present))
            return false;
        /* sgapi reads (0, 0, 0) as "no attenuation"; spelled out here, every renderer agrees. */
        if (out->attenuation[0] == 0.0f && out->attenuation[1] == 0.0f &&
            out->attenuation[2] == 0.0f)
            out->attenuation[0] = 1.0f;
    }
    if (!get_floats(c, l, v, "color", 3, 0.0, HUGE_VAL, out->color, &present)) return false;
    if (!present) return fail(c, l, "missing 'color' (3 numbers >= 0) of a light");
    return true;
}

/* "ambient" and "lights" of the top level or of a scene; absent keys keep what is there. */
static bool parse_lighting(ctx *c, const loc *l, const cJSON *obj, float ambient[3],
                           sc_light lights[SC_MAX_LIGHTS], int *light_count) {
    bool present;
    if (!get_floats(c, l, obj, "ambient", 3, 0.0, HUGE_VAL, ambient, &present)) return false;
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "lights");
    if (!v) return true;
    if (!cJSON_IsArray(v)) return fail(c, l, "'lights' must be an array of light objects");
    int n = cJSON_GetArraySize(v);
    if (n > SC_MAX_LIGHTS)
        return fail(c, l, "'lights' holds %d lights, more than the %d allowed", n, SC_MAX_LIGHTS);
    loc ll = *l;
    ll.light = 0;
    const cJSON *e;
    cJSON_ArrayForEach(e, v) {
        if (!parse_light(c, &ll, e, &lights[ll.light])) return false;
        ll.light++;
    }
    *light_count = n;
    return true;
}

/* A "shadow" object, or null (none), into *has and *out; absent keeps both. Its light is checked
 * against the scene's lights by the scene. */
static bool parse_shadow(ctx *c, const loc *where, const cJSON *obj, bool *has, sc_shadow *out) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, "shadow");
    if (!v) return true;
    if (cJSON_IsNull(v)) {
        *has = false;
        return true;
    }
    loc l = *where;
    l.object = "shadow";
    if (!cJSON_IsObject(v)) return fail(c, where, "'shadow' must be an object or null");
    sc_shadow s = {.light = 0,
                   .size = SC_SHADOW_SIZE,
                   .bias = SC_SHADOW_BIAS,
                   .slope_bias = SC_SHADOW_SLOPE_BIAS,
                   .pcf = SC_SHADOW_PCF};
    bool present;
    if (!get_int(c, &l, v, "light", 0, SC_MAX_LIGHTS - 1, &s.light, &present)) return false;
    if (!present) return fail(c, &l, "missing 'light' (the index of the light in 'lights')");
    if (!get_int(c, &l, v, "size", 1, SC_MAX_IMAGE_SIZE, &s.size, &present) ||
        !get_finite(c, &l, v, "bias", &s.bias) ||
        !get_finite(c, &l, v, "slope_bias", &s.slope_bias) || !get_bool(c, &l, v, "pcf", &s.pcf))
        return false;
    *has = true;
    *out = s;
    return true;
}

/* File-level values every scene starts from. */
typedef struct defaults {
    int width, height;
    bool has_width, has_height;
    float clear_color[4];
    int samples;
    float ambient[3];
    int light_count;
    sc_light lights[SC_MAX_LIGHTS];
    bool has_shadow;
    sc_shadow shadow;
} defaults;

static bool parse_scene(ctx *c, int index, const cJSON *v, const defaults *def, sc_scene *s) {
    loc l = NOWHERE;
    l.scene = index;
    if (!cJSON_IsObject(v)) return fail(c, &l, "a scene must be an object");
    const cJSON *name = cJSON_GetObjectItemCaseSensitive(v, "name");
    if (!name) return fail(c, &l, "missing 'name'");
    if (!cJSON_IsString(name) || !valid_name(name->valuestring))
        return fail(c, &l, "'name' must be 1 to %d characters of A-Z a-z 0-9 _ . -",
                    SC_MAX_NAME_LENGTH);
    for (int i = 0; i < index; i++) {
        if (strcmp(c->f->scenes[i].name, name->valuestring) == 0)
            return fail(c, &l, "scene name '%s' is already used by scenes[%d]", name->valuestring,
                        i);
    }
    s->name = dup_str(name->valuestring);
    if (!s->name) return fail(c, &l, "out of memory");
    l.scene_name = s->name;

    bool has_w = def->has_width, has_h = def->has_height, present;
    s->width = def->width;
    s->height = def->height;
    if (!get_int(c, &l, v, "width", 1, SC_MAX_IMAGE_SIZE, &s->width, &present)) return false;
    has_w |= present;
    if (!get_int(c, &l, v, "height", 1, SC_MAX_IMAGE_SIZE, &s->height, &present)) return false;
    has_h |= present;
    if (!has_w || !has_h)
        return fail(c, &l, "no '%s': set it in the scene or at the top of the file",
                    has_w ? "height" : "width");
    memcpy(s->clear_color, def->clear_color, sizeof s->clear_color);
    if (!get_floats(c, &l, v, "clear_color", 4, 0.0, 1.0, s->clear_color, &present)) return false;
    s->samples = def->samples;
    if (!get_samples(c, &l, v, &s->samples)) return false;
    /* A scene's "lights" replaces the top level's list as a whole. */
    memcpy(s->ambient, def->ambient, sizeof s->ambient);
    memcpy(s->lights, def->lights, sizeof s->lights);
    s->light_count = def->light_count;
    if (!parse_lighting(c, &l, v, s->ambient, s->lights, &s->light_count)) return false;
    s->has_shadow = def->has_shadow;
    s->shadow = def->shadow;
    if (!parse_shadow(c, &l, v, &s->has_shadow, &s->shadow)) return false;
    if (s->has_shadow && s->shadow.light >= s->light_count) {
        loc ls = l;
        ls.object = "shadow";
        if (s->light_count == 0)
            return fail(c, &ls, "'light' is %d, but the scene has no lights", s->shadow.light);
        return fail(c, &ls, "'light' is %d, but the scene has %d light%s (0..%d)", s->shadow.light,
                    s->light_count, s->light_count == 1 ? "" : "s", s->light_count - 1);
    }

    const cJSON *draws = cJSON_GetObjectItemCaseSensitive(v, "draws");
    if (!draws) return fail(c, &l, "missing 'draws'");
    if (!cJSON_IsArray(draws)) return fail(c, &l, "'draws' must be an array");
    int n = cJSON_GetArraySize(draws);
    if (n > 0) {
        s->draws = calloc((size_t)n, sizeof *s->draws);
        if (!s->draws) return fail(c, &l, "out of memory");
    }
    const cJSON *d;
    cJSON_ArrayForEach(d, draws) {
        l.draw = (int)s->draw_count;
        if (!parse_draw(c, &l, d, &s->draws[s->draw_count])) return false;
        s->draw_count++;
    }
    if (!s->has_shadow) return true;
    /* Without a caster there is nothing to see from the light: no map, no pass. */
    bool casters = false;
    for (size_t i = 0; i < s->draw_count; i++) casters |= s->draws[i].casts_shadow;
    if (!casters) {
        s->has_shadow = false;
        return true;
    }
    /* Fitted here once, so that a renderer never meets a scene whose light cannot be fitted. */
    double view[16], proj[16];
    l.draw = -1;
    l.object = "shadow";
    if (!sc_shadow_light(c->f, s, view, proj))
        return fail(c, &l,
                    "the light cannot be fitted to the casters: they have no finite vertex, or "
                    "they span no area as seen from the light");
    return true;
}

static bool parse_root(ctx *c, const cJSON *root) {
    loc none = NOWHERE;
    if (!cJSON_IsObject(root)) return fail(c, &none, "the top level must be a JSON object");
    defaults def = {0};
    if (!get_int(c, &none, root, "width", 1, SC_MAX_IMAGE_SIZE, &def.width, &def.has_width) ||
        !get_int(c, &none, root, "height", 1, SC_MAX_IMAGE_SIZE, &def.height, &def.has_height))
        return false;
    bool present;
    def.samples = 1;
    if (!get_samples(c, &none, root, &def.samples) ||
        !get_floats(c, &none, root, "clear_color", 4, 0.0, 1.0, def.clear_color, &present) ||
        !parse_lighting(c, &none, root, def.ambient, def.lights, &def.light_count) ||
        !parse_shadow(c, &none, root, &def.has_shadow, &def.shadow))
        return false;

    const cJSON *scenes = cJSON_GetObjectItemCaseSensitive(root, "scenes");
    if (!scenes) return fail(c, &none, "missing 'scenes'");
    if (!cJSON_IsArray(scenes)) return fail(c, &none, "'scenes' must be an array");
    int n = cJSON_GetArraySize(scenes);
    if (n == 0) return fail(c, &none, "'scenes' is empty");
    c->f->scenes = calloc((size_t)n, sizeof *c->f->scenes);
    if (!c->f->scenes) return fail(c, &none, "out of memory");
    const cJSON *s;
    cJSON_ArrayForEach(s, scenes) {
        /* Counted before parsing, so sc_free also frees a half-parsed scene. */
        size_t i = c->f->scene_count++;
        if (!parse_scene(c, (int)i, s, &def, &c->f->scenes[i])) return false;
    }
    return true;
}

bool sc_parse(const char *path, const char *json, size_t len, sc_file *out, sc_msg *err) {
    memset(out, 0, sizeof *out);
    ctx c = {.path = path, .err = err, .f = out};
    loc none = NOWHERE;
    bool ok = false;
    cJSON *root = NULL;

    out->path = dup_str(path);
    const char *slash = strrchr(path, '/');
    size_t dirlen = slash ? (size_t)(slash - path) + 1 : 0;
    c.dir = malloc(dirlen + 1);
    if (!out->path || !c.dir) {
        fail(&c, &none, "out of memory");
        goto done;
    }
    memcpy(c.dir, path, dirlen);
    c.dir[dirlen] = '\0';

    const char *end = NULL;
    root = cJSON_ParseWithLengthOpts(json, len, &end, false);
    if (!root) {
        /* The parser reports where it stopped; a line number is what an editor needs. */
        size_t line = 1, at = end && end >= json && end <= json + len ? (size_t)(end - json) : 0;
        for (size_t i = 0; i < at; i++) line += json[i] == '\n';
        fail(&c, &none, "invalid JSON (line %zu)", line);
        goto done;
    }
    ok = parse_root(&c, root);
    if (ok && !sc_check_keys(json, len, root, out)) ok = fail(&c, &none, "out of memory");
done:
    cJSON_Delete(root);
    free(c.dir);
    free(c.mesh_kinds);
    if (!ok) sc_free(out);
    return ok;
}

bool sc_load(const char *path, sc_file *out, sc_msg *err) {
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &text, &len, err)) return false;
    bool ok = sc_parse(path, text, len, out, err);
    free(text);
    return ok;
}

void sc_free(sc_file *file) {
    if (!file) return;
    for (size_t i = 0; i < file->scene_count; i++) {
        free(file->scenes[i].name);
        for (size_t j = 0; j < file->scenes[i].draw_count; j++)
            sc_draw_free(&file->scenes[i].draws[j]);
        free(file->scenes[i].draws);
    }
    free(file->scenes);
    for (size_t i = 0; i < file->mesh_count; i++) {
        sc_mesh_free(&file->meshes[i]);
        free(file->mesh_sources[i]);
    }
    free(file->meshes);
    free(file->mesh_sources);
    for (size_t i = 0; i < file->texture_count; i++) {
        sc_image_free(&file->textures[i]);
        free(file->texture_sources[i]);
    }
    free(file->textures);
    free(file->texture_sources);
    for (size_t i = 0; i < file->warning_count; i++) free(file->warnings[i]);
    free(file->warnings);
    free(file->path);
    memset(file, 0, sizeof *file);
}

void sc_set_samples(sc_file *file, int samples) {
    for (size_t i = 0; i < file->scene_count; i++) file->scenes[i].samples = samples;
}

bool sc_parse_samples(const char *s, int *out) {
    int n = 0;
    if (!sc_parse_int(s, 1, 4, &n) || (n != 1 && n != 4)) return false;
    *out = n;
    return true;
}

bool sc_mipmap_from_name(const char *name, sc_mipmap *out) {
    for (const enum_name *e = mipmaps; e->name; e++)
        if (!strcmp(e->name, name)) {
            *out = (sc_mipmap)e->value;
            return true;
        }
    return false;
}

void sc_override_mipmap(sc_file *f, sc_mipmap mode) {
    for (size_t i = 0; i < f->scene_count; i++)
        for (size_t j = 0; j < f->scenes[i].draw_count; j++) f->scenes[i].draws[j].mipmap = mode;
}

bool sc_texture_mipmapped(const sc_file *f, size_t texture) {
    for (size_t i = 0; i < f->scene_count; i++)
        for (size_t j = 0; j < f->scenes[i].draw_count; j++) {
            const sc_draw *d = &f->scenes[i].draws[j];
            if (d->mipmap == SC_MIPMAP_NONE) continue;
            if (d->texture == (int)texture) return true;
            for (int k = 0; k < d->shader_texture_count; k++)
                if (d->shader_textures[k] == (int)texture) return true;
        }
    return false;
}
