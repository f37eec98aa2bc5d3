/* model.c - model files and standard shapes as scenes: an OBJ file split into one mesh per
 * material, an OFF file as one mesh, a camera framed on their bounding sphere and a default light.
 */
#include "model.h"

#include <ctype.h>
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "mtl.h"
#include "off.h"

#define PI 3.14159265358979323846

/* The default light: a white directional light from over the camera's right shoulder, and an
 * ambient light that keeps the faces it misses readable. */
static const float LIGHT_DIRECTION[3] = {-0.35f, -0.45f, -1.0f};
static const float LIGHT_COLOR[3] = {0.8f, 0.8f, 0.8f};
static const float AMBIENT[3] = {0.3f, 0.3f, 0.3f};
/* The camera's vertical field of view, and where it stands: in front, above and to the right. */
#define FOVY_DEGREES 40.0
static const double VIEW_DIRECTION[3] = {0.45, 0.35, 1.0};

bool sc_shape_mesh(const sguShapeDesc *desc, sc_mesh *out, sc_msg *err) {
    int nv, ni;
    memset(out, 0, sizeof *out);
    if (sgu_shape_counts(desc, &nv, &ni) != 0) {
        sc_msg_set(err, "bad shape parameters");
        return false;
    }
    sc_mesh m = {0};
    m.vertex_count = (uint32_t)nv;
    m.index_count = (uint32_t)ni;
    m.positions = malloc((size_t)nv * 4 * sizeof(float));
    m.colors = malloc((size_t)nv * 4 * sizeof(float));
    m.normals = malloc((size_t)nv * 3 * sizeof(float));
    m.texcoords = malloc((size_t)nv * 2 * sizeof(float));
    m.indices = malloc((size_t)ni * sizeof(uint32_t));
    if (!m.positions || !m.colors || !m.normals || !m.texcoords || !m.indices) {
        sc_mesh_free(&m);
        sc_msg_set(err, "out of memory for a shape");
        return false;
    }
    sgu_shape_build(desc, m.positions, m.normals, m.texcoords, m.indices);
    for (size_t i = 0; i < (size_t)nv * 4; i++) m.colors[i] = 1.0f;
    *out = m;
    return true;
}

static bool has_suffix(const char *s, const char *suffix) {
    size_t n = strlen(s), k = strlen(suffix);
    if (n < k) return false;
    for (size_t i = 0; i < k; i++)
        if (tolower((unsigned char)s[n - k + i]) != suffix[i]) return false;
    return true;
}

bool sc_is_model_path(const char *path) {
    return has_suffix(path, ".obj") || has_suffix(path, ".off");
}

static char *dup_str(const char *s) {
    size_t n = strlen(s) + 1;
    char *r = malloc(n);
    if (r) memcpy(r, s, n);
    return r;
}

/* dir of `base` (up to its last '/') joined with rel; rel alone when it is absolute. */
static char *join_dir(const char *base, const char *rel) {
    if (rel[0] == '/') return dup_str(rel);
    const char *slash = strrchr(base, '/');
    size_t d = slash ? (size_t)(slash - base) + 1 : 0, n = strlen(rel);
    char *r = malloc(d + n + 1);
    if (!r) return NULL;
    memcpy(r, base, d);
    memcpy(r + d, rel, n + 1);
    return r;
}

static bool is_regular(const char *path) {
    struct stat st;
    return stat(path, &st) == 0 && S_ISREG(st.st_mode);
}

bool sc_file_add_mesh(sc_file *f, sc_mesh *mesh, const char *source, int *index) {
    char *src = dup_str(source);
    sc_mesh *m = realloc(f->meshes, (f->mesh_count + 1) * sizeof *m);
    if (m) f->meshes = m;
    char **s = realloc(f->mesh_sources, (f->mesh_count + 1) * sizeof *s);
    if (s) f->mesh_sources = s;
    if (!src || !m || !s || f->mesh_count >= INT32_MAX) {
        free(src);
        sc_mesh_free(mesh);
        return false;
    }
    f->meshes[f->mesh_count] = *mesh;
    f->mesh_sources[f->mesh_count] = src;
    *index = (int)f->mesh_count++;
    memset(mesh, 0, sizeof *mesh);
    return true;
}

bool sc_scene_add_draw(sc_scene *scene, const sc_draw *draw) {
    sc_draw *d = realloc(scene->draws, (scene->draw_count + 1) * sizeof *d);
    if (!d) return false;
    scene->draws = d;
    scene->draws[scene->draw_count++] = *draw;
    return true;
}

/* The texture of a path, loaded once per file; -1 (with one warning) when it cannot be read. */
static int get_texture(sc_file *f, const char *path, const char *who, sc_warnings *w) {
    for (size_t i = 0; i < f->texture_count; i++)
        if (strcmp(f->texture_sources[i], path) == 0) return (int)i;
    sc_image img;
    if (!is_regular(path)) {
        sc_warn(w, SC_WARN_TEXTURE_MISSING, "%s: texture '%s' not found: drawn without it", who,
                path);
        return -1;
    }
    sc_msg why = {0};
    if (!sc_image_load(path, &img, &why)) {
        sc_warn(w, SC_WARN_TEXTURE_MISSING,
                "%s: texture '%s' cannot be read (%s): drawn without it", who, path, why.text);
        sc_msg_free(&why);
        return -1;
    }
    if (img.width > SC_MAX_IMAGE_SIZE || img.height > SC_MAX_IMAGE_SIZE) {
        sc_warn(w, SC_WARN_TEXTURE_MISSING,
                "%s: texture '%s' is larger than %d on a side: drawn "
                "without it",
                who, path, SC_MAX_IMAGE_SIZE);
        sc_image_free(&img);
        return -1;
    }
    char *src = dup_str(path);
    sc_image *t = realloc(f->textures, (f->texture_count + 1) * sizeof *t);
    if (t) f->textures = t;
    char **s = realloc(f->texture_sources, (f->texture_count + 1) * sizeof *s);
    if (s) f->texture_sources = s;
    if (!src || !t || !s) {
        free(src);
        sc_image_free(&img);
        return -1;
    }
    f->textures[f->texture_count] = img;
    f->texture_sources[f->texture_count] = src;
    return (int)f->texture_count++;
}

/* The triangles of `mesh` listed by ranges (first index, count) as a mesh of their own, with only
 * the vertices they use. */
static bool sub_mesh(const sc_mesh *mesh, const uint32_t *ranges, size_t nranges, sc_mesh *out) {
    memset(out, 0, sizeof *out);
    uint32_t *map = malloc((size_t)mesh->vertex_count * sizeof *map);
    if (!map) return false;
    memset(map, 0xff, (size_t)mesh->vertex_count * sizeof *map);
    size_t ni = 0, nv = 0;
    for (size_t r = 0; r < nranges; r++) ni += ranges[r * 2 + 1];
    for (size_t r = 0; r < nranges; r++)
        for (uint32_t i = 0; i < ranges[r * 2 + 1]; i++) {
            uint32_t v = mesh->indices[ranges[r * 2] + i];
            if (map[v] == UINT32_MAX) map[v] = (uint32_t)nv++;
        }
    sc_mesh m = {0};
    m.vertex_count = (uint32_t)nv;
    m.index_count = (uint32_t)ni;
    m.positions = malloc(nv * 4 * sizeof(float));
    m.colors = malloc(nv * 4 * sizeof(float));
    m.texcoords = mesh->texcoords ? malloc(nv * 2 * sizeof(float)) : NULL;
    m.normals = mesh->normals ? malloc(nv * 3 * sizeof(float)) : NULL;
    m.indices = malloc(ni * sizeof(uint32_t));
    if (!m.positions || !m.colors || (mesh->texcoords && !m.texcoords) ||
        (mesh->normals && !m.normals) || !m.indices) {
        free(map);
        sc_mesh_free(&m);
        return false;
    }
    size_t k = 0;
    for (size_t r = 0; r < nranges; r++)
        for (uint32_t i = 0; i < ranges[r * 2 + 1]; i++)
            m.indices[k++] = map[mesh->indices[ranges[r * 2] + i]];
    for (uint32_t v = 0; v < mesh->vertex_count; v++) {
        uint32_t o = map[v];
        if (o == UINT32_MAX) continue;
        memcpy(m.positions + (size_t)o * 4, mesh->positions + (size_t)v * 4, 16);
        memcpy(m.colors + (size_t)o * 4, mesh->colors + (size_t)v * 4, 16);
        if (m.texcoords) memcpy(m.texcoords + (size_t)o * 2, mesh->texcoords + (size_t)v * 2, 8);
        if (m.normals) memcpy(m.normals + (size_t)o * 3, mesh->normals + (size_t)v * 3, 12);
    }
    free(map);
    *out = m;
    return true;
}

/* The lines of a mesh as a mesh of their own (drawn unlit: a line has no face to light). */
static bool line_mesh(const sc_mesh *mesh, sc_mesh *out) {
    memset(out, 0, sizeof *out);
    sc_mesh m = {0};
    size_t nv = mesh->vertex_count;
    m.vertex_count = mesh->vertex_count;
    m.positions = malloc(nv * 16);
    m.colors = malloc(nv * 16);
    m.line_index_count = mesh->line_index_count;
    m.line_indices = malloc((size_t)mesh->line_index_count * 4);
    if (!m.positions || !m.colors || !m.line_indices) {
        sc_mesh_free(&m);
        return false;
    }
    memcpy(m.positions, mesh->positions, nv * 16);
    memcpy(m.colors, mesh->colors, nv * 16);
    memcpy(m.line_indices, mesh->line_indices, (size_t)mesh->line_index_count * 4);
    *out = m;
    return true;
}

/* A draw of a model's mesh with the defaults of model scenes. */
static sc_draw model_draw(int mesh, bool file_normals) {
    sc_draw d = {0};
    d.mesh = mesh;
    d.texture = -1;
    d.mode = SC_MODE_VERTEX_COLOR;
    d.depth_write = true;
    for (int i = 0; i < 4; i++) d.color[i] = 1.0f;
    /* A file's own normals are lit per pixel; without them its faces are lit flat, as they are
     * (the polyhedra of OFF files above all): smooth normals would round their edges. */
    d.lighting = file_normals ? SC_LIGHTING_PHONG : SC_LIGHTING_FLAT;
    d.casts_shadow = false;
    d.receives_shadow = false;
    return d;
}

/* Gives a mesh without normals smooth ones (so that shapes and files light alike). */
static bool add_normals(sc_mesh *m) {
    if (m->normals || m->index_count == 0) return true;
    m->normals = calloc(m->vertex_count, 3 * sizeof(float));
    return m->normals && sgu_compute_normals(m->positions, (int)m->vertex_count, m->indices,
                                             (int)m->index_count, 0, m->normals) == 0;
}

/* A mesh lit flat takes its faces' normals from their winding. Many files wind every face
 * clockwise seen from outside, which would light the far side of the model: a mesh whose signed
 * volume (the sum of a . (b x c) over its triangles) is negative is turned inside out. */
static void orient_outward(sc_mesh *m) {
    double vol = 0;
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        const float *a = m->positions + (size_t)m->indices[i] * 4;
        const float *b = m->positions + (size_t)m->indices[i + 1] * 4;
        const float *c = m->positions + (size_t)m->indices[i + 2] * 4;
        double t = (double)a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
                   (double)a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
                   (double)a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0]);
        if (isfinite(t)) vol += t;
    }
    if (!(vol < 0)) return;
    for (uint32_t i = 0; i + 2 < m->index_count; i += 3) {
        uint32_t t = m->indices[i + 1];
        m->indices[i + 1] = m->indices[i + 2];
        m->indices[i + 2] = t;
    }
}

/* Adds a mesh and its draw; the mesh is taken over. */
static bool add_part(sc_file *f, sc_scene *sc, sc_mesh *mesh, const char *source,
                     const sc_draw *proto, sc_msg *err) {
    if (!add_normals(mesh)) {
        sc_mesh_free(mesh);
        sc_msg_set(err, "%s: out of memory", source);
        return false;
    }
    sc_draw d = *proto;
    if (!sc_file_add_mesh(f, mesh, source, &d.mesh) || !sc_scene_add_draw(sc, &d)) {
        sc_msg_set(err, "%s: out of memory", source);
        return false;
    }
    return true;
}

/* The material libraries of an OBJ file, merged into one (later definitions win). */
static void load_mtllibs(const char *obj_path, const sc_obj_extra *x, sc_mtl *all, char ***dirs,
                         sc_warnings *w, bool *ok, sc_msg *err) {
    *ok = true;
    for (size_t i = 0; i < x->mtllib_count; i++) {
        char *path = join_dir(obj_path, x->mtllibs[i]);
        if (!path) continue;
        for (char *q = path; *q; q++)
            if (*q == '\\') *q = '/';
        if (!is_regular(path)) {
            sc_warn(w, SC_WARN_MTL_MISSING,
                    "%s: material library '%s' not found: default "
                    "material",
                    obj_path, path);
            free(path);
            continue;
        }
        sc_mtl lib;
        if (!sc_mtl_load(path, &lib, w, err)) {
            free(path);
            *ok = false;
            return;
        }
        /* Every material remembers its library's folder, for the paths of its textures. */
        size_t n = all->count + lib.count;
        sc_material *m = realloc(all->materials, (n ? n : 1) * sizeof *m);
        char **d = realloc(*dirs, (n ? n : 1) * sizeof *d);
        if (m) all->materials = m;
        if (d) *dirs = d;
        if (!m || !d) {
            sc_mtl_free(&lib);
            free(path);
            sc_msg_set(err, "%s: out of memory", obj_path);
            *ok = false;
            return;
        }
        for (size_t k = 0; k < lib.count; k++) {
            all->materials[all->count] = lib.materials[k];
            (*dirs)[all->count] = dup_str(path);
            all->count++;
        }
        free(lib.materials);
        free(path);
    }
}

static bool load_obj(sc_file *f, sc_scene *sc, const char *path, sc_warnings *w, sc_msg *err) {
    char *text;
    size_t len;
    if (!sc_read_file(path, &text, &len, err)) return false;
    sc_mesh mesh;
    sc_obj_extra x;
    bool ok = sc_obj_parse_ex(path, text, len, &mesh, &x, w, err);
    free(text);
    if (!ok) return false;
    bool file_normals = mesh.normals != NULL;
    sc_mtl mtl = {0};
    char **dirs = NULL;
    load_mtllibs(path, &x, &mtl, &dirs, w, &ok, err);
    if (ok && mesh.line_index_count) {
        sc_mesh lm;
        sc_draw d = model_draw(0, false);
        d.lighting = SC_LIGHTING_NONE;
        ok = line_mesh(&mesh, &lm);
        if (!ok) sc_msg_set(err, "%s: out of memory", path);
        if (ok) ok = add_part(f, sc, &lm, path, &d, err);
    }
    if (ok && mesh.index_count) {
        /* Ranges of triangles per material: index 0 for no material (or an unknown one). */
        size_t ng = x.group_count;
        int *mat_of = calloc(ng + 1, sizeof *mat_of);
        uint32_t *ranges = malloc((ng + 1) * 2 * sizeof *ranges);
        if (!mat_of || !ranges) {
            sc_msg_set(err, "%s: out of memory", path);
            ok = false;
        }
        for (size_t g = 0; ok && g < ng; g++) {
            const sc_material *m = sc_mtl_find(&mtl, x.groups[g].material);
            if (!m) {
                sc_warn(w, SC_WARN_MTL_NO_MATERIAL,
                        "%s: material '%s' is not defined: default "
                        "material",
                        path, x.groups[g].material);
                mat_of[g + 1] = -1;
            } else {
                mat_of[g + 1] = (int)(m - mtl.materials);
            }
        }
        /* The ungrouped start: triangles before the first usemtl. */
        uint32_t start_count = ng ? x.groups[0].first_index : mesh.index_count;
        /* One draw per material, opaque ones first, translucent ones after with their triangles
         * sorted; a material used by several groups is one draw. */
        for (int pass = 0; ok && pass < 2; pass++) {
            for (long mi = -1; ok && mi < (long)mtl.count; mi++) {
                const sc_material *m = mi >= 0 ? &mtl.materials[mi] : NULL;
                bool translucent = m && m->alpha < 1.0f;
                if (translucent != (pass == 1)) continue;
                size_t nr = 0;
                if (mi == -1 && start_count) {
                    ranges[0] = 0, ranges[1] = start_count;
                    nr = 1;
                }
                for (size_t g = 0; g < ng; g++)
                    if (mat_of[g + 1] == mi) {
                        ranges[nr * 2] = x.groups[g].first_index;
                        ranges[nr * 2 + 1] = x.groups[g].index_count;
                        nr++;
                    }
                if (nr == 0) continue;
                sc_mesh part;
                if (!sub_mesh(&mesh, ranges, nr, &part)) {
                    sc_msg_set(err, "%s: out of memory", path);
                    ok = false;
                    break;
                }
                sc_draw d = model_draw(0, file_normals);
                char *source = sc_format("%s (material %s)", path, m ? m->name : "default");
                char *who = m && m->diffuse_map && part.texcoords
                                ? sc_format("%s, material '%s' (%s)", path, m->name, dirs[mi])
                                : NULL;
                if (!source || (m && m->diffuse_map && part.texcoords && !who)) {
                    free(source);
                    free(who);
                    sc_mesh_free(&part);
                    sc_msg_set(err, "%s: out of memory", path);
                    ok = false;
                    break;
                }
                if (m) {
                    memcpy(d.color, m->diffuse, 12);
                    for (int c = 0; c < 3; c++) d.color[c] = d.color[c] > 1 ? 1 : d.color[c];
                    d.color[3] = m->alpha;
                    memcpy(d.specular, m->specular, 12);
                    d.shininess = m->shininess;
                    if (m->diffuse_map && part.texcoords) {
                        char *tp = join_dir(dirs[mi], m->diffuse_map);
                        if (tp) d.texture = get_texture(f, tp, who, w);
                        free(tp);
                        if (d.texture >= 0) d.mode = SC_MODE_TEXTURE;
                    }
                }
                if (translucent) {
                    d.blend = SC_BLEND_ALPHA;
                    d.depth_write = false;
                    d.sort = SC_SORT_BACK_TO_FRONT;
                }
                if (d.lighting == SC_LIGHTING_FLAT) orient_outward(&part);
                ok = add_part(f, sc, &part, source, &d, err);
                free(source);
                free(who);
            }
        }
        free(mat_of);
        free(ranges);
    }
    for (size_t i = 0; i < mtl.count; i++) free(dirs[i]);
    free(dirs);
    sc_mtl_free(&mtl);
    sc_obj_extra_free(&x);
    sc_mesh_free(&mesh);
    return ok;
}

static bool opaque_triangle(const sc_mesh *m, const uint32_t *t) {
    for (int c = 0; c < 3; c++)
        if (m->colors[(size_t)t[c] * 4 + 3] < 1.0f) return false;
    return true;
}

/* Puts the triangles whose vertices are all opaque (alpha 1) before the others, each group in
 * file order; *opaque gets the number of indices the opaque ones take. False when out of memory. */
static bool opaque_first(sc_mesh *m, uint32_t *opaque) {
    uint32_t n = m->index_count, solid = 0;
    for (uint32_t i = 0; i < n; i += 3) solid += opaque_triangle(m, m->indices + i) ? 3 : 0;
    *opaque = solid;
    if (solid == n || solid == 0) return true;
    uint32_t *sorted = malloc((size_t)n * sizeof *sorted);
    if (!sorted) return false;
    uint32_t front = 0, back = solid;
    for (uint32_t i = 0; i < n; i += 3) {
        uint32_t *at = opaque_triangle(m, m->indices + i) ? &front : &back;
        memcpy(sorted + *at, m->indices + i, 3 * sizeof *sorted);
        *at += 3;
    }
    free(m->indices);
    m->indices = sorted;
    return true;
}

static bool load_off(sc_file *f, sc_scene *sc, const char *path, sc_warnings *w, sc_msg *err) {
    sc_mesh mesh;
    if (!sc_off_load(path, &mesh, w, err)) return false;
    sc_draw d = model_draw(0, mesh.normals != NULL);
    /* Oriented whole: a part alone (the translucent faces of a cube) has no inside. */
    if (d.lighting == SC_LIGHTING_FLAT) orient_outward(&mesh);
    uint32_t opaque;
    if (!opaque_first(&mesh, &opaque)) {
        sc_mesh_free(&mesh);
        sc_msg_set(err, "%s: out of memory", path);
        return false;
    }
    if (opaque == mesh.index_count) return add_part(f, sc, &mesh, path, &d, err);
    /* Colours with alpha below 1 are drawn as an MTL 'd' below 1 is: after the opaque faces,
     * blended, sorted back to front, without depth writes. */
    uint32_t ranges[4] = {0, opaque, opaque, mesh.index_count - opaque};
    bool ok = true;
    for (int k = 0; ok && k < 2; k++) {
        if (!ranges[k * 2 + 1]) continue;
        sc_mesh part;
        if (!sub_mesh(&mesh, ranges + k * 2, 1, &part)) {
            sc_msg_set(err, "%s: out of memory", path);
            ok = false;
            break;
        }
        sc_draw pd = d;
        if (k == 1) {
            pd.blend = SC_BLEND_ALPHA;
            pd.depth_write = false;
            pd.sort = SC_SORT_BACK_TO_FRONT;
        }
        ok = add_part(f, sc, &part, path, &pd, err);
    }
    sc_mesh_free(&mesh);
    return ok;
}

bool sc_scene_bounds(const sc_file *file, const sc_scene *scene, double centre[3], double *radius) {
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    /* Two passes: the box, then the farthest vertex from its centre. */
    for (int pass = 0; pass < 2; pass++) {
        double r2 = 0;
        for (size_t k = 0; k < scene->draw_count; k++) {
            const sc_draw *d = &scene->draws[k];
            const sc_mesh *m = &file->meshes[d->mesh];
            const float *wv = d->world_view;
            for (uint32_t i = 0; i < m->vertex_count; i++) {
                const float *p = m->positions + (size_t)i * 4;
                double v[4];
                for (int r = 0; r < 4; r++)
                    v[r] = (double)wv[r * 4] * p[0] + (double)wv[r * 4 + 1] * p[1] +
                           (double)wv[r * 4 + 2] * p[2] + (double)wv[r * 4 + 3] * p[3];
                if (!(v[3] != 0)) continue;
                double q[3] = {v[0] / v[3], v[1] / v[3], v[2] / v[3]};
                if (!isfinite(q[0]) || !isfinite(q[1]) || !isfinite(q[2])) continue;
                if (pass == 0) {
                    for (int c = 0; c < 3; c++) {
                        lo[c] = q[c] < lo[c] ? q[c] : lo[c];
                        hi[c] = q[c] > hi[c] ? q[c] : hi[c];
                    }
                } else {
                    double dx = q[0] - centre[0], dy = q[1] - centre[1], dz = q[2] - centre[2];
                    double d2 = dx * dx + dy * dy + dz * dz;
                    r2 = d2 > r2 ? d2 : r2;
                }
            }
        }
        if (pass == 0) {
            if (!(lo[0] <= hi[0])) return false;
            for (int c = 0; c < 3; c++) centre[c] = (lo[c] + hi[c]) / 2;
        } else {
            *radius = sqrt(r2);
        }
    }
    return true;
}

void sc_look_at(const double eye[3], const double target[3], float out[16]) {
    double f[3] = {target[0] - eye[0], target[1] - eye[1], target[2] - eye[2]};
    double l = sqrt(f[0] * f[0] + f[1] * f[1] + f[2] * f[2]);
    for (int i = 0; i < 3; i++) f[i] = l > 0 ? f[i] / l : (i == 2 ? -1 : 0);
    /* Up is +y unless the view is along it. */
    double up[3] = {0, 1, 0};
    if (fabs(f[1]) > 0.999) up[1] = 0, up[2] = -1;
    double s[3] = {f[1] * up[2] - f[2] * up[1], f[2] * up[0] - f[0] * up[2],
                   f[0] * up[1] - f[1] * up[0]};
    l = sqrt(s[0] * s[0] + s[1] * s[1] + s[2] * s[2]);
    for (int i = 0; i < 3; i++) s[i] /= l;
    double u[3] = {s[1] * f[2] - s[2] * f[1], s[2] * f[0] - s[0] * f[2], s[0] * f[1] - s[1] * f[0]};
    const double *rows[3] = {s, u, f};
    for (int r = 0; r < 3; r++) {
        double sign = r == 2 ? -1 : 1;
        for (int c = 0; c < 3; c++) out[r * 4 + c] = (float)(sign * rows[r][c]);
        out[r * 4 + 3] =
            (float)(-sign * (rows[r][0] * eye[0] + rows[r][1] * eye[1] + rows[r][2] * eye[2]));
    }
    out[12] = out[13] = out[14] = 0, out[15] = 1;
}

void sc_perspective(double fovy, double aspect, double n, double f, float out[16]) {
    double t = 1 / tan(fovy / 2);
    memset(out, 0, 16 * sizeof *out);
    out[0] = (float)(t / aspect);
    out[5] = (float)t;
    out[10] = (float)((f + n) / (n - f));
    out[11] = (float)(2 * f * n / (n - f));
    out[14] = -1;
}

bool sc_model_scene(const char *const *paths, int count, const char *name, int width, int height,
                    sc_file *out, sc_warnings *warnings, sc_msg *err) {
    memset(out, 0, sizeof *out);
    sc_file f = {0};
    f.path = dup_str(count > 0 ? paths[0] : "(models)");
    f.scenes = calloc(1, sizeof *f.scenes);
    if (!f.path || !f.scenes) {
        sc_free(&f);
        sc_msg_set(err, "out of memory");
        return false;
    }
    f.scene_count = 1;
    sc_scene *sc = &f.scenes[0];
    sc->name = dup_str(name);
    sc->width = width;
    sc->height = height;
    sc->clear_color[0] = 0.16f, sc->clear_color[1] = 0.17f, sc->clear_color[2] = 0.2f;
    sc->clear_color[3] = 1.0f;
    memcpy(sc->ambient, AMBIENT, sizeof AMBIENT);
    sc->light_count = 1;
    sc->lights[0].type = SC_LIGHT_DIRECTIONAL;
    memcpy(sc->lights[0].direction, LIGHT_DIRECTION, sizeof LIGHT_DIRECTION);
    memcpy(sc->lights[0].color, LIGHT_COLOR, sizeof LIGHT_COLOR);
    sc->lights[0].attenuation[0] = 1;
    if (!sc->name) {
        sc_free(&f);
        sc_msg_set(err, "out of memory");
        return false;
    }
    for (int i = 0; i < count; i++) {
        const char *p = paths[i];
        bool ok;
        if (!is_regular(p)) {
            sc_msg_set(err, "%s: not a readable file", p);
            ok = false;
        } else if (has_suffix(p, ".off")) {
            ok = load_off(&f, sc, p, warnings, err);
        } else if (has_suffix(p, ".obj")) {
            ok = load_obj(&f, sc, p, warnings, err);
        } else {
            sc_msg_set(err, "%s: not a model file (.obj or .off)", p);
            ok = false;
        }
        if (!ok) {
            sc_free(&f);
            return false;
        }
    }
    /* Identity world-views first, for the bounds in model space. */
    for (size_t k = 0; k < sc->draw_count; k++) {
        memset(sc->draws[k].world_view, 0, 64);
        for (int c = 0; c < 4; c++) sc->draws[k].world_view[c * 5] = 1;
    }
    double centre[3] = {0, 0, 0}, r = 1;
    if (!sc_scene_bounds(&f, sc, centre, &r) || !(r > 0) || !isfinite(r)) {
        if (!(r > 0) || !isfinite(r)) r = 1;
    }
    /* The distance at which the sphere fits the narrower of the two fields of view. */
    double fovy = FOVY_DEGREES * PI / 180, aspect = (double)width / height;
    double half = aspect < 1 ? atan(tan(fovy / 2) * aspect) : fovy / 2;
    double dist = r / sin(half) * 1.05;
    double l = sqrt(VIEW_DIRECTION[0] * VIEW_DIRECTION[0] + VIEW_DIRECTION[1] * VIEW_DIRECTION[1] +
                    VIEW_DIRECTION[2] * VIEW_DIRECTION[2]);
    double eye[3];
    for (int c = 0; c < 3; c++) eye[c] = centre[c] + VIEW_DIRECTION[c] / l * dist;
    float view[16], proj[16];
    sc_look_at(eye, centre, view);
    sc_perspective(fovy, aspect, dist - r * 1.01 > dist * 0.01 ? dist - r * 1.01 : dist * 0.01,
                   dist + r * 1.01, proj);
    for (size_t k = 0; k < sc->draw_count; k++) {
        memcpy(sc->draws[k].world_view, view, sizeof view);
        memcpy(sc->draws[k].proj, proj, sizeof proj);
    }
    *out = f;
    return true;
}
