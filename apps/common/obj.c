/* obj.c - Wavefront OBJ loader: positions (with the "v x y z r g b [a]" colour extension), texture
 * coordinates, normals, polygonal faces and polylines, turned into an indexed triangle list and an
 * indexed line list over the same vertices.
 *
 * Input is untrusted: every index is checked, every size is checked against overflow, and any
 * malformed line is an error naming its line number.
 */
#include "obj.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "text_scan.h"

#define NONE UINT32_MAX /* a face or line vertex without texture coordinate or normal */

/* A face or line vertex after resolving its indices: one output vertex per distinct key. */
typedef struct key3 {
    uint32_t v, vt, vn;
} key3;

typedef struct parser {
    ts_source src;

    float *v; /* 7 floats per position: x, y, z, r, g, b, a */
    size_t nv, capv;
    float *vt; /* 2 per texture coordinate */
    size_t nvt, capvt;
    float *vn; /* 3 per normal */
    size_t nvn, capvn;

    key3 *keys; /* the output vertices */
    size_t nkeys, capkeys;
    uint32_t *table; /* open addressing: key index + 1, 0 = empty slot */
    size_t tablecap; /* a power of two */

    uint32_t *idx; /* triangles, 3 each */
    size_t nidx, capidx;
    uint32_t *lidx; /* line segments, 2 each */
    size_t nlidx, caplidx;

    sc_obj_extra *extra; /* materials: NULL when the caller does not want them */
    size_t capgroups, capmtllibs;
    sc_warnings *warnings; /* may be NULL */
} parser;

/* Makes room for need elements of elem bytes, doubling; false on overflow or no memory. */
static bool grow(void **ptr, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return true;
    size_t n = *cap ? *cap : 256;
    while (n < need) {
        if (n > SIZE_MAX / 2) return false;
        n *= 2;
    }
    if (n > SIZE_MAX / elem) return false;
    void *q = realloc(*ptr, n * elem);
    if (!q) return false;
    *ptr = q;
    *cap = n;
    return true;
}

/* Next token before a comment: in OBJ a '#' starts one only where a token would start. */
static bool next_token(const char **s, const char *e, const char **tb, const char **te) {
    return ts_next_token(s, e, tb, te) && **tb != '#';
}

/* Reads up to max numbers of the rest of the line; more than max is an error. */
static bool parse_floats(parser *p, const char *s, const char *e, float *out, int max, int *count,
                         const char *what) {
    const char *tb, *te;
    int n = 0;
    while (next_token(&s, e, &tb, &te)) {
        if (n == max) return ts_fail(&p->src, "too many numbers after '%s'", what);
        if (!ts_parse_number(&p->src, tb, te, &out[n], NULL)) return false;
        n++;
    }
    *count = n;
    return true;
}

static bool add_position(parser *p, const char *s, const char *e) {
    float f[7] = {0};
    int n = 0;
    if (!parse_floats(p, s, e, f, 7, &n, "v")) return false;
    if (n != 3 && n != 4 && n != 6 && n != 7)
        return ts_fail(&p->src,
                       "'v' needs x y z, optionally followed by w, by r g b or by r g b a (got %d "
                       "numbers)",
                       n);
    if (p->nv >= SC_MESH_MAX_COUNT) return ts_fail(&p->src, "too many positions");
    if (!grow((void **)&p->v, &p->capv, p->nv + 1, 7 * sizeof(float)))
        return ts_fail(&p->src, "out of memory");
    float *d = p->v + p->nv * 7;
    d[0] = f[0], d[1] = f[1], d[2] = f[2];
    /* The fourth number of the OBJ spec is a weight for rational curves: not a colour, unused. */
    bool rgb = n >= 6;
    d[3] = rgb ? f[3] : 1.0f;
    d[4] = rgb ? f[4] : 1.0f;
    d[5] = rgb ? f[5] : 1.0f;
    d[6] = n == 7 ? f[6] : 1.0f;
    p->nv++;
    return true;
}

static bool add_texcoord(parser *p, const char *s, const char *e) {
    float f[3] = {0};
    int n = 0;
    if (!parse_floats(p, s, e, f, 3, &n, "vt")) return false;
    if (n < 1) return ts_fail(&p->src, "'vt' needs at least one number");
    if (p->nvt >= SC_MESH_MAX_COUNT) return ts_fail(&p->src, "too many texture coordinates");
    if (!grow((void **)&p->vt, &p->capvt, p->nvt + 1, 2 * sizeof(float)))
        return ts_fail(&p->src, "out of memory");
    p->vt[p->nvt * 2] = f[0];
    p->vt[p->nvt * 2 + 1] = n >= 2 ? f[1] : 0.0f;
    p->nvt++;
    return true;
}

static bool add_normal(parser *p, const char *s, const char *e) {
    float f[3] = {0};
    int n = 0;
    if (!parse_floats(p, s, e, f, 3, &n, "vn")) return false;
    if (n != 3) return ts_fail(&p->src, "'vn' needs 3 numbers (got %d)", n);
    if (p->nvn >= SC_MESH_MAX_COUNT) return ts_fail(&p->src, "too many normals");
    if (!grow((void **)&p->vn, &p->capvn, p->nvn + 1, 3 * sizeof(float)))
        return ts_fail(&p->src, "out of memory");
    memcpy(p->vn + p->nvn * 3, f, sizeof f);
    p->nvn++;
    return true;
}

/* An optionally negative decimal integer at *s (before e); false if there is none. */
static bool parse_int(const char **s, const char *e, long long *out) {
    const char *q = *s;
    bool neg = q < e && *q == '-';
    if (neg) q++;
    if (q == e || *q < '0' || *q > '9') return false;
    long long v = 0;
    for (; q < e && *q >= '0' && *q <= '9'; q++) {
        /* Anything this large is out of range anyway; stop before it could overflow. */
        if (v < 1000000000000LL) v = v * 10 + (*q - '0');
    }
    *out = neg ? -v : v;
    *s = q;
    return true;
}

/* OBJ indices are 1-based; negative ones count back from the last element defined so far. */
static bool resolve(parser *p, long long i, size_t count, const char *what, uint32_t *out) {
    if (i > 0 && (unsigned long long)i <= count) {
        *out = (uint32_t)(i - 1);
        return true;
    }
    if (i < 0 && (unsigned long long)-i <= count) {
        *out = (uint32_t)((long long)count + i);
        return true;
    }
    if (i == 0) return ts_fail(&p->src, "%s index 0 is invalid (indices start at 1)", what);
    return ts_fail(&p->src, "%s index %lld out of range (%zu defined so far)", what, i, count);
}

static uint64_t hash_key(key3 k) {
    uint64_t h = ((uint64_t)k.v << 32 | k.vt) * 0x9E3779B97F4A7C15ull;
    h ^= (uint64_t)k.vn * 0xC2B2AE3D27D4EB4Full;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    return h ^ (h >> 29);
}

static bool rehash(parser *p, size_t cap) {
    if (cap > SIZE_MAX / sizeof(uint32_t)) return false;
    uint32_t *t = calloc(cap, sizeof *t);
    if (!t) return false;
    for (size_t i = 0; i < p->nkeys; i++) {
        size_t j = (size_t)hash_key(p->keys[i]) & (cap - 1);
        while (t[j]) j = (j + 1) & (cap - 1);
        t[j] = (uint32_t)(i + 1);
    }
    free(p->table);
    p->table = t;
    p->tablecap = cap;
    return true;
}

/* The output vertex of a key: the existing one, or a new one. */
static bool vertex_of(parser *p, key3 k, uint32_t *out) {
    if ((p->nkeys + 1) * 2 > p->tablecap) {
        if (p->tablecap > SIZE_MAX / 2 || !rehash(p, p->tablecap ? p->tablecap * 2 : 1024))
            return ts_fail(&p->src, "out of memory");
    }
    size_t mask = p->tablecap - 1, j = (size_t)hash_key(k) & mask;
    for (; p->table[j]; j = (j + 1) & mask) {
        const key3 *o = &p->keys[p->table[j] - 1];
        if (o->v == k.v && o->vt == k.vt && o->vn == k.vn) {
            *out = p->table[j] - 1;
            return true;
        }
    }
    if (p->nkeys >= SC_MESH_MAX_COUNT) return ts_fail(&p->src, "too many vertices");
    if (!grow((void **)&p->keys, &p->capkeys, p->nkeys + 1, sizeof(key3)))
        return ts_fail(&p->src, "out of memory");
    p->keys[p->nkeys] = k;
    p->table[j] = (uint32_t)(p->nkeys + 1);
    *out = (uint32_t)p->nkeys++;
    return true;
}

/* One face vertex: a, a/b, a//c or a/b/c; or one line vertex: a or a/b (the OBJ format gives line
 * vertices no normal). */
static bool obj_vertex(parser *p, bool line, const char *tb, const char *te, uint32_t *out) {
    const char *s = tb;
    long long a, b = 0, c = 0;
    bool has_b = false, has_c = false;
    if (!parse_int(&s, te, &a)) goto bad;
    if (s < te && *s == '/') {
        s++;
        if (s < te && *s != '/') {
            if (!parse_int(&s, te, &b)) goto bad;
            has_b = true;
        }
        if (s < te && *s == '/') {
            s++;
            if (line || !parse_int(&s, te, &c)) goto bad;
            has_c = true;
        }
        if (!has_b && !has_c) goto bad;
    }
    if (s != te) goto bad;

    key3 k = {0, NONE, NONE};
    if (!resolve(p, a, p->nv, "position", &k.v)) return false;
    if (has_b && !resolve(p, b, p->nvt, "texture coordinate", &k.vt)) return false;
    if (has_c && !resolve(p, c, p->nvn, "normal", &k.vn)) return false;
    return vertex_of(p, k, out);
bad:
    return ts_fail(&p->src, "bad %s vertex '%.*s' (expected %s)", line ? "line" : "face",
                   (int)(te - tb < 40 ? te - tb : 40), tb,
                   line ? "a or a/b" : "a, a/b, a//c or a/b/c");
}

static bool emit(parser *p, uint32_t a, uint32_t b, uint32_t c) {
    if (p->nidx > SC_MESH_MAX_COUNT - 3) return ts_fail(&p->src, "too many triangles");
    if (!grow((void **)&p->idx, &p->capidx, p->nidx + 3, sizeof(uint32_t)))
        return ts_fail(&p->src, "out of memory");
    p->idx[p->nidx++] = a;
    p->idx[p->nidx++] = b;
    p->idx[p->nidx++] = c;
    return true;
}

/* A polygon of any size, split into the fan (0 1 2), (0 2 3), ... */
static bool add_face(parser *p, const char *s, const char *e) {
    const char *tb, *te;
    uint32_t first = 0, prev = 0;
    size_t n = 0;
    while (next_token(&s, e, &tb, &te)) {
        uint32_t cur = 0;
        if (!obj_vertex(p, false, tb, te, &cur)) return false;
        if (n == 0) first = cur;
        if (n >= 2 && !emit(p, first, prev, cur)) return false;
        prev = cur;
        n++;
    }
    if (n < 3) return ts_fail(&p->src, "a face needs at least 3 vertices (got %zu)", n);
    return true;
}

/* A polyline a b c ...: the segments a-b, b-c, ..., each as its two indices. */
static bool add_line(parser *p, const char *s, const char *e) {
    const char *tb, *te;
    uint32_t prev = 0;
    size_t n = 0;
    while (next_token(&s, e, &tb, &te)) {
        uint32_t cur = 0;
        if (!obj_vertex(p, true, tb, te, &cur)) return false;
        if (n >= 1) {
            if (p->nlidx > SC_MESH_MAX_COUNT - 2) return ts_fail(&p->src, "too many line segments");
            if (!grow((void **)&p->lidx, &p->caplidx, p->nlidx + 2, sizeof(uint32_t)))
                return ts_fail(&p->src, "out of memory");
            p->lidx[p->nlidx++] = prev;
            p->lidx[p->nlidx++] = cur;
        }
        prev = cur;
        n++;
    }
    if (n < 2) return ts_fail(&p->src, "a line needs at least 2 vertices (got %zu)", n);
    return true;
}

/* usemtl: the triangles from here on take the named material. */
static bool use_material(parser *p, const char *s, const char *e) {
    sc_obj_extra *x = p->extra;
    if (!x) return true;
    if (!grow((void **)&x->groups, &p->capgroups, x->group_count + 1, sizeof *x->groups))
        return ts_fail(&p->src, "out of memory");
    char *name = ts_copy_trimmed(s, e);
    if (!name) return ts_fail(&p->src, "out of memory");
    x->groups[x->group_count++] =
        (sc_obj_group){.material = name, .first_index = (uint32_t)p->nidx};
    return true;
}

/* mtllib: a material library, its name as written (the caller resolves it). */
static bool add_mtllib(parser *p, const char *s, const char *e) {
    sc_obj_extra *x = p->extra;
    if (!x) return true;
    if (!grow((void **)&x->mtllibs, &p->capmtllibs, x->mtllib_count + 1, sizeof *x->mtllibs))
        return ts_fail(&p->src, "out of memory");
    char *name = ts_copy_trimmed(s, e);
    if (!name) return ts_fail(&p->src, "out of memory");
    if (name[0] == '\0') {
        free(name);
        return ts_fail(&p->src, "'mtllib' needs a file name");
    }
    x->mtllibs[x->mtllib_count++] = name;
    return true;
}

static bool parse_line(parser *p, const char *s, const char *e) {
    const char *tb, *te;
    if (memchr(s, '\0', (size_t)(e - s))) return ts_fail(&p->src, "NUL byte in the line");
    if (!next_token(&s, e, &tb, &te)) return true; /* blank or comment */
    size_t n = (size_t)(te - tb);
    if (n == 1 && tb[0] == 'v') return add_position(p, s, e);
    if (n == 2 && tb[0] == 'v' && tb[1] == 't') return add_texcoord(p, s, e);
    if (n == 2 && tb[0] == 'v' && tb[1] == 'n') return add_normal(p, s, e);
    if (n == 1 && tb[0] == 'f') return add_face(p, s, e);
    if (n == 1 && tb[0] == 'l') return add_line(p, s, e);
    if (ts_token_is(tb, te, "usemtl")) return use_material(p, s, e);
    if (ts_token_is(tb, te, "mtllib")) return add_mtllib(p, s, e);
    if (n == 1 && tb[0] == 'p') {
        sc_warn(p->warnings, SC_WARN_OBJ_POINTS, "%s:%zu: points (p) are not drawn", p->src.name,
                p->src.line);
        return true;
    }
    /* Names, groups and smoothing groups change nothing drawn; free-form geometry (curves,
     * surfaces) is not supported and said so once. */
    if (ts_token_is(tb, te, "o") || ts_token_is(tb, te, "g") || ts_token_is(tb, te, "s") ||
        ts_token_is(tb, te, "mg"))
        return true;
    sc_warn(p->warnings, SC_WARN_OBJ_UNKNOWN, "%s:%zu: '%.*s' statements are ignored", p->src.name,
            p->src.line, (int)(n < 20 ? n : 20), tb);
    return true;
}

/* n elements of elem bytes, or NULL on overflow or no memory. */
static void *alloc_array(size_t n, size_t elem) {
    if (n == 0 || n > SIZE_MAX / elem) return NULL;
    return malloc(n * elem);
}

/* Builds the output arrays from the keys. */
static bool finish(parser *p, sc_mesh *out) {
    p->src.line = 0;
    if (p->nidx == 0 && p->nlidx == 0) return ts_fail(&p->src, "no faces or lines");
    bool any_vt = false, any_vn = false;
    for (size_t i = 0; i < p->nkeys; i++) {
        any_vt |= p->keys[i].vt != NONE;
        any_vn |= p->keys[i].vn != NONE;
    }
    size_t n = p->nkeys;
    sc_mesh m = {0};
    m.positions = alloc_array(n, 4 * sizeof(float));
    m.colors = alloc_array(n, 4 * sizeof(float));
    m.texcoords = any_vt ? alloc_array(n, 2 * sizeof(float)) : NULL;
    m.normals = any_vn ? alloc_array(n, 3 * sizeof(float)) : NULL;
    if (!m.positions || !m.colors || (any_vt && !m.texcoords) || (any_vn && !m.normals)) {
        sc_mesh_free(&m);
        return ts_fail(&p->src, "out of memory");
    }
    for (size_t i = 0; i < n; i++) {
        const key3 k = p->keys[i];
        const float *v = p->v + (size_t)k.v * 7;
        float *pos = m.positions + i * 4, *col = m.colors + i * 4;
        pos[0] = v[0], pos[1] = v[1], pos[2] = v[2], pos[3] = 1.0f;
        col[0] = v[3], col[1] = v[4], col[2] = v[5], col[3] = v[6];
        /* A vertex without one, in a mesh where others have one, gets zeros. */
        if (any_vt) {
            m.texcoords[i * 2] = k.vt != NONE ? p->vt[(size_t)k.vt * 2] : 0.0f;
            m.texcoords[i * 2 + 1] = k.vt != NONE ? p->vt[(size_t)k.vt * 2 + 1] : 0.0f;
        }
        if (any_vn) {
            for (int c = 0; c < 3; c++)
                m.normals[i * 3 + c] = k.vn != NONE ? p->vn[(size_t)k.vn * 3 + c] : 0.0f;
        }
    }
    m.vertex_count = (uint32_t)n;
    m.index_count = (uint32_t)p->nidx;
    m.indices = p->idx; /* handed over; NULL when there are no faces */
    p->idx = NULL;
    m.line_index_count = (uint32_t)p->nlidx;
    m.line_indices = p->lidx; /* likewise */
    p->lidx = NULL;
    *out = m;
    if (p->extra) {
        /* Each group runs to the next one's start; empty groups go. */
        sc_obj_extra *x = p->extra;
        size_t k = 0;
        for (size_t i = 0; i < x->group_count; i++) {
            uint32_t end = i + 1 < x->group_count ? x->groups[i + 1].first_index : m.index_count;
            x->groups[i].index_count = end - x->groups[i].first_index;
            if (x->groups[i].index_count == 0)
                free(x->groups[i].material);
            else
                x->groups[k++] = x->groups[i];
        }
        x->group_count = k;
    }
    return true;
}

bool sc_obj_parse(const char *name, const char *text, size_t len, sc_mesh *out, sc_msg *err) {
    return sc_obj_parse_ex(name, text, len, out, NULL, NULL, err);
}

bool sc_obj_parse_ex(const char *name, const char *text, size_t len, sc_mesh *out,
                     sc_obj_extra *extra, sc_warnings *warnings, sc_msg *err) {
    parser p = {
        .src = {.name = name ? name : "(obj)", .err = err}, .extra = extra, .warnings = warnings};
    memset(out, 0, sizeof *out);
    if (extra) memset(extra, 0, sizeof *extra);
    bool ok = true;
    const char *s = text, *end = text ? text + len : text;
    s += ts_bom_length(text, len);
    while (ok && s < end) {
        const char *eol = memchr(s, '\n', (size_t)(end - s));
        if (!eol) eol = end;
        p.src.line++;
        ok = parse_line(&p, s, eol);
        s = eol < end ? eol + 1 : end;
    }
    if (ok) ok = finish(&p, out);
    free(p.v);
    free(p.vt);
    free(p.vn);
    free(p.keys);
    free(p.table);
    free(p.idx);
    free(p.lidx);
    if (!ok) sc_obj_extra_free(extra);
    return ok;
}

void sc_obj_extra_free(sc_obj_extra *extra) {
    if (!extra) return;
    for (size_t i = 0; i < extra->group_count; i++) free(extra->groups[i].material);
    for (size_t i = 0; i < extra->mtllib_count; i++) free(extra->mtllibs[i]);
    free(extra->groups);
    free(extra->mtllibs);
    memset(extra, 0, sizeof *extra);
}

bool sc_read_file(const char *path, char **out_data, size_t *out_len, sc_msg *err) {
    *out_data = NULL;
    *out_len = 0;
    FILE *f = fopen(path, "rb");
    if (!f) {
        sc_msg_set(err, "cannot open '%s': %s", path, strerror(errno));
        return false;
    }
    char *buf = NULL;
    size_t len = 0, cap = 0;
    for (;;) {
        /* Keep one spare byte for the terminating NUL. */
        if (!grow((void **)&buf, &cap, len + 65536 + 1, 1)) {
            sc_msg_set(err, "cannot read '%s': out of memory", path);
            goto error;
        }
        size_t got = fread(buf + len, 1, cap - len - 1, f);
        len += got;
        if (got == 0) break;
    }
    if (ferror(f)) {
        sc_msg_set(err, "cannot read '%s': %s", path, strerror(errno));
        goto error;
    }
    fclose(f);
    buf[len] = '\0';
    *out_data = buf;
    *out_len = len;
    return true;
error:
    free(buf);
    fclose(f);
    return false;
}

bool sc_obj_load(const char *path, sc_mesh *out, sc_msg *err) {
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &text, &len, err)) return false;
    bool ok = sc_obj_parse(path, text, len, out, err);
    free(text);
    return ok;
}

void sc_mesh_free(sc_mesh *mesh) {
    if (!mesh) return;
    free(mesh->positions);
    free(mesh->colors);
    free(mesh->texcoords);
    free(mesh->normals);
    free(mesh->indices);
    free(mesh->line_indices);
    memset(mesh, 0, sizeof *mesh);
}
