/* mtl.c - Wavefront material library parser: newmtl, Kd, Ks, Ns, d, Tr and map_Kd (with its
 * options skipped). Untrusted input: values are checked, names are copied with their length.
 */
#include "mtl.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "obj.h"
#include "text_scan.h"

typedef struct parser {
    ts_source src; /* its line is never 0 when an error is reported: messages always name one */
    sc_warnings *warnings;
    sc_mtl *out;
    size_t cap;
} parser;

/* One finite number token. */
static bool parse_float(parser *p, const char *tb, const char *te, const char *what, float *out) {
    char buf[64];
    size_t n = (size_t)(te - tb);
    if (n >= sizeof buf) return ts_fail(&p->src, "'%s': number too long", what);
    memcpy(buf, tb, n);
    buf[n] = '\0';
    char *end;
    float f = strtof(buf, &end);
    if (end != buf + n || !isfinite(f))
        return ts_fail(&p->src, "'%s': not a finite number: '%s'", what, buf);
    *out = f;
    return true;
}

/* r g b, each finite and >= 0; "Kd r" alone means r r r (the format allows it). */
static bool parse_rgb(parser *p, const char *s, const char *e, const char *what, float out[3]) {
    const char *tb, *te;
    int n = 0;
    float f[3];
    while (ts_next_token(&s, e, &tb, &te)) {
        if (ts_token_is(tb, te, "spectral") || ts_token_is(tb, te, "xyz")) {
            sc_warn(p->warnings, SC_WARN_MTL_UNKNOWN, "%s:%zu: '%s %.*s' colours are ignored",
                    p->src.name, p->src.line, what, (int)(te - tb), tb);
            return true;
        }
        if (n == 3) return ts_fail(&p->src, "'%s' needs 3 numbers (got more)", what);
        if (!parse_float(p, tb, te, what, &f[n])) return false;
        if (f[n] < 0) return ts_fail(&p->src, "'%s': negative value", what);
        n++;
    }
    if (n != 1 && n != 3) return ts_fail(&p->src, "'%s' needs 3 numbers (got %d)", what, n);
    for (int i = 0; i < 3; i++) out[i] = f[n == 1 ? 0 : i];
    return true;
}

/* One number in [lo, hi] after options such as d's -halo. */
static bool parse_one(parser *p, const char *s, const char *e, const char *what, float lo, float hi,
                      float *out) {
    const char *tb, *te;
    bool got = false;
    while (ts_next_token(&s, e, &tb, &te)) {
        if (tb[0] == '-' && te - tb > 1 && (tb[1] < '0' || tb[1] > '9') && tb[1] != '.')
            continue; /* an option word */
        if (got) return ts_fail(&p->src, "'%s' needs one number (got more)", what);
        if (!parse_float(p, tb, te, what, out)) return false;
        got = true;
    }
    if (!got) return ts_fail(&p->src, "'%s' needs a number", what);
    if (*out < lo || *out > hi)
        return ts_fail(&p->src, "'%s' %g outside %g..%g", what, *out, lo, hi);
    return true;
}

/* How many arguments each texture option takes (the MTL spec's list); -1: not an option. */
static int option_args(const char *tb, const char *te) {
    static const struct {
        const char *name;
        int args;
    } opts[] = {{"-blendu", 1}, {"-blendv", 1},  {"-bm", 1},  {"-boost", 1}, {"-cc", 1},
                {"-clamp", 1},  {"-imfchan", 1}, {"-mm", 2},  {"-o", 3},     {"-s", 3},
                {"-t", 3},      {"-texres", 1},  {"-type", 1}};
    for (size_t i = 0; i < sizeof opts / sizeof opts[0]; i++)
        if (ts_token_is(tb, te, opts[i].name)) return opts[i].args;
    return -1;
}

/* map_Kd [options] file: the file name is what follows the options (it may hold spaces). */
static bool parse_map(parser *p, const char *s, const char *e, char **out) {
    const char *tb, *te;
    for (;;) {
        const char *save = s;
        if (!ts_next_token(&s, e, &tb, &te)) return ts_fail(&p->src, "'map_Kd' needs a file name");
        int k = option_args(tb, te);
        if (k < 0) {
            s = save;
            break;
        }
        /* -o, -s and -t take 1 to 3 numbers: skip as many as there are. */
        for (int i = 0; i < k; i++) {
            const char *s2 = s;
            if (!ts_next_token(&s2, e, &tb, &te))
                return ts_fail(&p->src, "'map_Kd': option without value");
            if (k == 3 && i > 0 &&
                !(tb[0] == '-' || tb[0] == '.' || (tb[0] >= '0' && tb[0] <= '9')))
                break;
            if (k == 3 && i > 0 && option_args(tb, te) >= 0) break;
            s = s2;
        }
    }
    char *name = ts_copy_trimmed(s, e);
    if (!name) return ts_fail(&p->src, "out of memory");
    /* Files written on Windows say .\\dir\\tex.jpg. */
    for (char *q = name; *q; q++)
        if (*q == '\\') *q = '/';
    free(*out);
    *out = name;
    return true;
}

static bool new_material(parser *p, const char *s, const char *e) {
    sc_mtl *m = p->out;
    if (m->count == p->cap) {
        size_t n = p->cap ? p->cap * 2 : 8;
        if (n > SIZE_MAX / sizeof *m->materials) return ts_fail(&p->src, "out of memory");
        sc_material *q = realloc(m->materials, n * sizeof *q);
        if (!q) return ts_fail(&p->src, "out of memory");
        m->materials = q;
        p->cap = n;
    }
    char *name = ts_copy_trimmed(s, e);
    if (!name) return ts_fail(&p->src, "out of memory");
    m->materials[m->count++] = (sc_material){.name = name,
                                             .diffuse = {1, 1, 1},
                                             .alpha = 1,
                                             .specular = {0, 0, 0},
                                             .shininess = 0,
                                             .diffuse_map = NULL};
    return true;
}

static bool parse_line(parser *p, const char *s, const char *e) {
    const char *tb, *te;
    if (memchr(s, '\0', (size_t)(e - s))) return ts_fail(&p->src, "NUL byte in the line");
    const char *hash = memchr(s, '#', (size_t)(e - s));
    if (hash) e = hash;
    if (!ts_next_token(&s, e, &tb, &te)) return true;
    if (ts_token_is(tb, te, "newmtl")) return new_material(p, s, e);
    sc_material *cur = p->out->count ? &p->out->materials[p->out->count - 1] : NULL;
    bool known = ts_token_is(tb, te, "Kd") || ts_token_is(tb, te, "Ks") ||
                 ts_token_is(tb, te, "Ns") || ts_token_is(tb, te, "d") ||
                 ts_token_is(tb, te, "Tr") || ts_token_is(tb, te, "map_Kd");
    if (!known) {
        sc_warn(p->warnings, SC_WARN_MTL_UNKNOWN,
                "%s:%zu: '%.*s' (and other statements but "
                "Kd, Ks, Ns, d, Tr, map_Kd) ignored",
                p->src.name, p->src.line, (int)(te - tb < 20 ? te - tb : 20), tb);
        return true;
    }
    if (!cur) return ts_fail(&p->src, "'%.*s' before any newmtl", (int)(te - tb), tb);
    if (ts_token_is(tb, te, "Kd")) return parse_rgb(p, s, e, "Kd", cur->diffuse);
    if (ts_token_is(tb, te, "Ks")) return parse_rgb(p, s, e, "Ks", cur->specular);
    if (ts_token_is(tb, te, "Ns")) {
        /* Exporters write up to 1000; the fixed-function exponent stops at 128. */
        float ns;
        if (!parse_one(p, s, e, "Ns", 0, 1e6f, &ns)) return false;
        cur->shininess = ns > 128 ? 128 : ns;
        return true;
    }
    if (ts_token_is(tb, te, "d")) return parse_one(p, s, e, "d", 0, 1, &cur->alpha);
    if (ts_token_is(tb, te, "Tr")) {
        float tr;
        if (!parse_one(p, s, e, "Tr", 0, 1, &tr)) return false;
        cur->alpha = 1 - tr;
        return true;
    }
    return parse_map(p, s, e, &cur->diffuse_map);
}

bool sc_mtl_parse(const char *name, const char *text, size_t len, sc_mtl *out,
                  sc_warnings *warnings, sc_msg *err) {
    parser p = {
        .src = {.name = name ? name : "(mtl)", .err = err}, .warnings = warnings, .out = out};
    memset(out, 0, sizeof *out);
    const char *s = text, *end = text ? text + len : text;
    s += ts_bom_length(text, len);
    bool ok = true;
    while (ok && s < end) {
        const char *eol = memchr(s, '\n', (size_t)(end - s));
        if (!eol) eol = end;
        p.src.line++;
        ok = parse_line(&p, s, eol);
        s = eol < end ? eol + 1 : end;
    }
    if (!ok) sc_mtl_free(out);
    return ok;
}

bool sc_mtl_load(const char *path, sc_mtl *out, sc_warnings *warnings, sc_msg *err) {
    char *text;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &text, &len, err)) return false;
    bool ok = sc_mtl_parse(path, text, len, out, warnings, err);
    free(text);
    return ok;
}

const sc_material *sc_mtl_find(const sc_mtl *mtl, const char *name) {
    /* The last definition wins, as a later newmtl of the same name replaces the earlier. */
    for (size_t i = mtl->count; i-- > 0;)
        if (strcmp(mtl->materials[i].name, name) == 0) return &mtl->materials[i];
    return NULL;
}

void sc_mtl_free(sc_mtl *mtl) {
    if (!mtl) return;
    for (size_t i = 0; i < mtl->count; i++) {
        free(mtl->materials[i].name);
        free(mtl->materials[i].diffuse_map);
    }
    free(mtl->materials);
    memset(mtl, 0, sizeof *mtl);
}
