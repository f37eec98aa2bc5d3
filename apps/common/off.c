/* off.c - Geomview OFF loader: the [ST][C][N]OFF header, vertices with optional normal, colour and
 * texture coordinate, and polygons of any size with an optional face colour, fanned into
 * triangles.
 *
 * Input is untrusted. The header's counts are checked against the file's size before anything is
 * allocated (every vertex and face takes at least a few bytes), so a header that claims more than
 * the data holds is an error, never a large allocation.
 */
#include "off.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "text_scan.h"

/* Most numbers on one line: a vertex has at most 3 + 3 + 4 + 2, a face's count is separate. */
#define MAX_VERTEX_NUMBERS 12

typedef struct reader {
    ts_source src;       /* its line: of the line last returned */
    const char *s, *end; /* what is left of the text */
} reader;

/* The next line holding anything but blanks and a comment, as [*b, *e) without the comment;
 * false at the end of the text. */
static bool next_line(reader *r, const char **b, const char **e) {
    while (r->s < r->end) {
        const char *eol = memchr(r->s, '\n', (size_t)(r->end - r->s));
        if (!eol) eol = r->end;
        const char *hash = memchr(r->s, '#', (size_t)(eol - r->s));
        const char *q = r->s, *qe = hash ? hash : eol;
        r->src.line++;
        r->s = eol < r->end ? eol + 1 : r->end;
        while (q < qe && ts_is_space(*q)) q++;
        if (q < qe) {
            *b = q;
            *e = qe;
            return true;
        }
    }
    return false;
}

/* Up to max numbers of a line; *n gets how many there were, or max + 1 when there are more. */
static bool parse_numbers(reader *r, const char *s, const char *e, float *out, bool *integer,
                          int max, int *n) {
    const char *tb, *te;
    int k = 0;
    while (ts_next_token(&s, e, &tb, &te)) {
        if (k == max) {
            *n = max + 1;
            return true;
        }
        if (!ts_parse_number(&r->src, tb, te, &out[k], integer ? &integer[k] : NULL)) return false;
        k++;
    }
    *n = k;
    return true;
}

/* A non-negative integer count token. */
static bool parse_count(reader *r, const char *tb, const char *te, const char *what, size_t *out) {
    size_t v = 0;
    if (tb == te) return ts_fail(&r->src, "missing %s", what);
    for (const char *q = tb; q < te; q++) {
        if (*q < '0' || *q > '9')
            return ts_fail(&r->src, "%s is not a count: '%.*s'", what,
                           (int)(te - tb < 20 ? te - tb : 20), tb);
        if (v > SC_MESH_MAX_COUNT) return ts_fail(&r->src, "%s too large", what);
        v = v * 10 + (size_t)(*q - '0');
    }
    if (v > SC_MESH_MAX_COUNT) return ts_fail(&r->src, "%s too large", what);
    *out = v;
    return true;
}

/* Colours written as integers are 0..255, as floats 0..1 (Geomview's rule); mixed: floats. */
static void to_color(const float *f, const bool *integer, int n, float out[4]) {
    bool ints = true;
    for (int i = 0; i < n; i++) ints &= integer[i];
    for (int i = 0; i < 4; i++) out[i] = i < n ? (ints ? f[i] / 255.0f : f[i]) : 1.0f;
}

typedef struct header {
    bool st, c, n;
} header;

/* The keyword [ST][C][N]OFF, with what other tools add refused by name. */
static bool parse_keyword(reader *r, const char *tb, const char *te, header *h, bool *is_kw) {
    size_t n = (size_t)(te - tb);
    *is_kw = false;
    if (n < 3 || memcmp(te - 3, "OFF", 3) != 0) return true;
    *is_kw = true;
    const char *q = tb, *qe = te - 3;
    if (qe - q >= 2 && q[0] == 'S' && q[1] == 'T') h->st = true, q += 2;
    if (q < qe && *q == 'C') h->c = true, q++;
    if (q < qe && *q == 'N') h->n = true, q++;
    if (q < qe && *q == '4') return ts_fail(&r->src, "4-dimensional OFF (4OFF) is not supported");
    if (q < qe && *q == 'n') return ts_fail(&r->src, "n-dimensional OFF (nOFF) is not supported");
    if (q != qe) return ts_fail(&r->src, "unknown OFF keyword '%.*s'", (int)(n < 20 ? n : 20), tb);
    return true;
}

typedef struct face_list {
    uint32_t *idx; /* every face's vertex indices, one after the other */
    size_t nidx, capidx;
    size_t *start; /* per kept face, its first entry in idx; plus one past the last */
    float *color;  /* per kept face, r g b a (meaningful when has_color) */
    unsigned char *has_color;
    size_t nfaces;
} face_list;

static bool grow(void **p, size_t *cap, size_t need, size_t elem) {
    if (need <= *cap) return true;
    size_t n = *cap ? *cap : 64;
    while (n < need) {
        if (n > SIZE_MAX / 2) return false;
        n *= 2;
    }
    if (n > SIZE_MAX / elem) return false;
    void *q = realloc(*p, n * elem);
    if (!q) return false;
    *p = q;
    *cap = n;
    return true;
}

bool sc_off_parse(const char *name, const char *text, size_t len, sc_mesh *out,
                  sc_warnings *warnings, sc_msg *err) {
    reader r = {.src = {.name = name ? name : "(off)", .err = err}, .s = text, .end = text + len};
    memset(out, 0, sizeof *out);
    if (!text) return ts_fail(&r.src, "empty file");
    if (memchr(text, '\0', len))
        return ts_fail(&r.src, "NUL byte in the file (binary OFF is not supported)");
    r.s += ts_bom_length(text, len);

    header h = {0};
    const char *b = NULL, *e = NULL, *tb = NULL, *te = NULL;
    if (!next_line(&r, &b, &e)) return ts_fail(&r.src, "empty file: no OFF header");
    const char *s = b;
    ts_next_token(&s, e, &tb, &te);
    bool is_kw;
    if (!parse_keyword(&r, tb, te, &h, &is_kw)) return false;
    /* The keyword may be left out, and the counts may follow it on the same line. */
    if (!is_kw) s = b;
    if (is_kw && ts_next_token(&s, e, &tb, &te)) {
        if (te - tb == 6 && memcmp(tb, "BINARY", 6) == 0)
            return ts_fail(&r.src, "binary OFF is not supported");
        s = tb;
    } else if (is_kw) {
        if (!next_line(&r, &b, &e)) return ts_fail(&r.src, "missing the vertex and face counts");
        s = b;
    }
    size_t nv, nf, ne;
    if (!ts_next_token(&s, e, &tb, &te)) return ts_fail(&r.src, "missing the vertex count");
    if (!parse_count(&r, tb, te, "vertex count", &nv)) return false;
    if (!ts_next_token(&s, e, &tb, &te)) return ts_fail(&r.src, "missing the face count");
    if (!parse_count(&r, tb, te, "face count", &nf)) return false;
    if (ts_next_token(&s, e, &tb, &te) && !parse_count(&r, tb, te, "edge count", &ne)) return false;
    if (ts_next_token(&s, e, &tb, &te)) return ts_fail(&r.src, "more than 3 counts");
    /* Each vertex takes at least "0 0 0\n" and each face at least "3 0 1 2\n": a header that
     * claims more than the rest of the file could hold is refused before allocating for it. */
    size_t left = (size_t)(r.end - r.s);
    if (nv > left / 6 || nf > left / 8)
        return ts_fail(&r.src,
                       "the header claims %zu vertices and %zu faces, more than the %zu bytes "
                       "after it can hold",
                       nv, nf, left);
    if (nv == 0) return ts_fail(&r.src, "no vertices");
    if (nf == 0) return ts_fail(&r.src, "no faces");

    bool ok = false;
    float *pos = malloc(nv * 3 * sizeof(float));
    float *col = malloc(nv * 4 * sizeof(float));
    float *nrm = h.n ? malloc(nv * 3 * sizeof(float)) : NULL;
    float *st = h.st ? malloc(nv * 2 * sizeof(float)) : NULL;
    face_list fl = {0};
    fl.start = malloc((nf + 1) * sizeof(size_t));
    fl.color = malloc(nf * 4 * sizeof(float));
    fl.has_color = malloc(nf);
    sc_mesh m = {0};
    if (!pos || !col || (h.n && !nrm) || (h.st && !st) || !fl.start || !fl.color || !fl.has_color) {
        ts_fail(&r.src, "out of memory");
        goto done;
    }

    /* Vertices: x y z [nx ny nz] [r g b [a]] [s t]. A plain OFF vertex with 3 or 4 more numbers
     * is read as coloured too: several tools write colours without saying COFF. */
    for (size_t i = 0; i < nv; i++) {
        if (!next_line(&r, &b, &e)) {
            ts_fail(&r.src, "the file ends after %zu of its %zu vertices", i, nv);
            goto done;
        }
        float f[MAX_VERTEX_NUMBERS];
        bool in[MAX_VERTEX_NUMBERS];
        int n;
        if (!parse_numbers(&r, b, e, f, in, MAX_VERTEX_NUMBERS, &n)) goto done;
        int fixed = 3 + (h.n ? 3 : 0) + (h.st ? 2 : 0);
        int ncol = n - fixed;
        bool good = h.c ? (ncol == 3 || ncol == 4) : (ncol == 0 || ncol == 3 || ncol == 4);
        if (!good) {
            ts_fail(&r.src, "vertex %zu has %d numbers; %s expects x y z%s%s%s", i, n,
                    h.st ? (h.c ? (h.n ? "STCNOFF" : "STCOFF") : (h.n ? "STNOFF" : "STOFF"))
                         : (h.c ? (h.n ? "CNOFF" : "COFF") : (h.n ? "NOFF" : "OFF")),
                    h.n ? " nx ny nz" : "", h.c ? " r g b [a]" : "", h.st ? " s t" : "");
            goto done;
        }
        memcpy(pos + i * 3, f, 3 * sizeof(float));
        int k = 3;
        if (h.n) memcpy(nrm + i * 3, f + k, 3 * sizeof(float)), k += 3;
        if (ncol > 0) {
            to_color(f + k, in + k, ncol, col + i * 4);
            k += ncol;
        } else {
            for (int c = 0; c < 4; c++) col[i * 4 + c] = 1.0f;
        }
        if (h.st) memcpy(st + i * 2, f + k, 2 * sizeof(float));
    }

    /* Faces: n v1 .. vn [colour], the colour 3 or 4 numbers (or a colour-map index, ignored). */
    bool any_face_color = false;
    for (size_t i = 0; i < nf; i++) {
        if (!next_line(&r, &b, &e)) {
            ts_fail(&r.src, "the file ends after %zu of its %zu faces", i, nf);
            goto done;
        }
        s = b;
        size_t k;
        ts_next_token(&s, e, &tb, &te);
        if (!parse_count(&r, tb, te, "face vertex count", &k)) goto done;
        size_t first = fl.nidx;
        for (size_t j = 0; j < k; j++) {
            size_t vi;
            if (!ts_next_token(&s, e, &tb, &te)) {
                ts_fail(&r.src, "face %zu names %zu vertices but lists %zu", i, k, j);
                goto done;
            }
            if (!parse_count(&r, tb, te, "vertex index", &vi)) goto done;
            if (vi >= nv) {
                ts_fail(&r.src, "vertex index %zu out of range (%zu vertices; indices start at 0)",
                        vi, nv);
                goto done;
            }
            if (!grow((void **)&fl.idx, &fl.capidx, fl.nidx + 1, sizeof(uint32_t))) {
                ts_fail(&r.src, "out of memory");
                goto done;
            }
            fl.idx[fl.nidx++] = (uint32_t)vi;
        }
        float f[5];
        bool in[5];
        int n;
        if (!parse_numbers(&r, s, e, f, in, 4, &n)) goto done;
        if (n == 2 || n > 4) {
            ts_fail(&r.src,
                    "face %zu: a face colour is 3 or 4 numbers (or a colour-map index), got %d", i,
                    n);
            goto done;
        }
        if (k < 3) {
            sc_warn(warnings, SC_WARN_OFF_SMALL_FACE,
                    "%s:%zu: faces of fewer than 3 vertices (points, edges) are not drawn",
                    r.src.name, r.src.line);
            fl.nidx = first;
            continue;
        }
        if (n == 1)
            sc_warn(warnings, SC_WARN_OFF_COLORMAP,
                    "%s:%zu: colour-map indices as face colours are ignored", r.src.name,
                    r.src.line);
        size_t fi = fl.nfaces++;
        fl.start[fi] = first;
        fl.has_color[fi] = n >= 3;
        if (n >= 3) {
            to_color(f, in, n, fl.color + fi * 4);
            any_face_color = true;
        }
    }
    fl.start[fl.nfaces] = fl.nidx;
    r.src.line = 0;
    if (fl.nfaces == 0) {
        ts_fail(&r.src, "no face of 3 or more vertices");
        goto done;
    }

    /* Triangles. With face colours every face gets vertices of its own (a vertex carries one
     * colour); otherwise the file's vertices are shared. */
    size_t ntri = 0;
    for (size_t i = 0; i < fl.nfaces; i++) ntri += fl.start[i + 1] - fl.start[i] - 2;
    size_t nout = any_face_color ? fl.nidx : nv;
    if (ntri > SC_MESH_MAX_COUNT / 3 || nout > SC_MESH_MAX_COUNT) {
        ts_fail(&r.src, "too many triangles");
        goto done;
    }
    m.vertex_count = (uint32_t)nout;
    m.positions = malloc(nout * 4 * sizeof(float));
    m.colors = malloc(nout * 4 * sizeof(float));
    m.normals = h.n ? malloc(nout * 3 * sizeof(float)) : NULL;
    m.texcoords = h.st ? malloc(nout * 2 * sizeof(float)) : NULL;
    m.index_count = (uint32_t)(ntri * 3);
    m.indices = malloc(ntri * 3 * sizeof(uint32_t));
    if (!m.positions || !m.colors || (h.n && !m.normals) || (h.st && !m.texcoords) || !m.indices) {
        ts_fail(&r.src, "out of memory");
        goto done;
    }
    for (size_t o = 0; o < nout; o++) {
        size_t v = any_face_color ? fl.idx[o] : o;
        memcpy(m.positions + o * 4, pos + v * 3, 3 * sizeof(float));
        m.positions[o * 4 + 3] = 1.0f;
        memcpy(m.colors + o * 4, col + v * 4, 4 * sizeof(float));
        if (h.n) memcpy(m.normals + o * 3, nrm + v * 3, 3 * sizeof(float));
        if (h.st) memcpy(m.texcoords + o * 2, st + v * 2, 2 * sizeof(float));
    }
    size_t t = 0;
    for (size_t i = 0; i < fl.nfaces; i++) {
        size_t a = fl.start[i], z = fl.start[i + 1];
        if (any_face_color && fl.has_color[i]) {
            for (size_t j = a; j < z; j++) memcpy(m.colors + j * 4, fl.color + i * 4, 16);
        }
        for (size_t j = a + 2; j < z; j++) {
            /* Shared vertices are named by the file's index, own ones by their place in idx. */
            m.indices[t++] = any_face_color ? (uint32_t)a : fl.idx[a];
            m.indices[t++] = any_face_color ? (uint32_t)(j - 1) : fl.idx[j - 1];
            m.indices[t++] = any_face_color ? (uint32_t)j : fl.idx[j];
        }
    }
    *out = m;
    memset(&m, 0, sizeof m);
    ok = true;
done:
    sc_mesh_free(&m);
    free(pos);
    free(col);
    free(nrm);
    free(st);
    free(fl.idx);
    free(fl.start);
    free(fl.color);
    free(fl.has_color);
    return ok;
}

bool sc_off_load(const char *path, sc_mesh *out, sc_warnings *warnings, sc_msg *err) {
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &text, &len, err)) return false;
    bool ok = sc_off_parse(path, text, len, out, warnings, err);
    free(text);
    return ok;
}
