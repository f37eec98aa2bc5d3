/* thresholds.c - per-scene accuracy targets from a CSV file (see thresholds.h). */
#include "thresholds.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void rg_thresholds_init(rg_thresholds *t) {
    memset(t, 0, sizeof *t);
    t->overrides = (rg_limits){NAN, NAN, NAN};
}

void rg_thresholds_free(rg_thresholds *t) {
    for (size_t i = 0; i < t->count; i++) {
        free(t->rows[i].suite);
        free(t->rows[i].scene);
    }
    free(t->rows);
    t->rows = NULL;
    t->count = 0;
}

static char *trim(char *s) {
    while (*s == ' ' || *s == '\t') s++;
    size_t n = strlen(s);
    while (n > 0 && (s[n - 1] == ' ' || s[n - 1] == '\t' || s[n - 1] == '\r' || s[n - 1] == '\n'))
        s[--n] = '\0';
    return s;
}

static char *dup(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

/* A figure: empty keeps the default (NAN); otherwise a finite number >= 0. */
static bool parse_figure(const char *s, double *out) {
    if (*s == '\0') {
        *out = NAN;
        return true;
    }
    char *end;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end != '\0' || !isfinite(v) || v < 0) return false;
    *out = v;
    return true;
}

static const char *const COLUMNS[5] = {"suite", "scene", "min_psnr_db", "max_pct_over_2",
                                       "max_coverage_pct"};

/* Splits a line at commas into at most 6 fields (6 means too many); returns the count. */
static int split(char *line, char *fields[6]) {
    int n = 0;
    char *p = line;
    for (;;) {
        char *comma = strchr(p, ',');
        if (n == 6) return 6;
        if (comma) *comma = '\0';
        fields[n++] = trim(p);
        if (!comma) return n;
        p = comma + 1;
    }
}

bool rg_thresholds_load(rg_thresholds *t, const char *path, sc_msg *err) {
    FILE *f = fopen(path, "r");
    if (!f) {
        sc_msg_set(err, "%s: %s", path, strerror(errno));
        return false;
    }
    char line[4096];
    int lineno = 0;
    bool ok = true, first = true;
    while (ok && fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            sc_msg_set(err, "%s:%d: line longer than %zu characters", path, lineno,
                       sizeof line - 2);
            ok = false;
            break;
        }
        char *s = trim(line);
        if (*s == '\0' || *s == '#') continue;
        char *fields[6];
        int n = split(s, fields);
        bool header = first && !strcmp(fields[0], "suite");
        first = false;
        if (header) {
            for (int i = 0; i < n && ok; i++) {
                if (i >= 5 || strcmp(fields[i], COLUMNS[i])) {
                    sc_msg_set(err,
                               "%s:%d: the header's columns are "
                               "suite,scene,min_psnr_db,max_pct_over_2,max_coverage_pct",
                               path, lineno);
                    ok = false;
                }
            }
            continue;
        }
        if (n < 2 || n > 5) {
            sc_msg_set(err,
                       "%s:%d: %d fields; a row is suite,scene[,min_psnr_db[,max_pct_over_2[,"
                       "max_coverage_pct]]]",
                       path, lineno, n > 5 ? 6 : n);
            ok = false;
            break;
        }
        if (*fields[0] == '\0' || *fields[1] == '\0') {
            sc_msg_set(err, "%s:%d: empty %s name", path, lineno,
                       *fields[0] == '\0' ? "suite" : "scene");
            ok = false;
            break;
        }
        double v[3] = {NAN, NAN, NAN};
        for (int i = 2; i < n; i++) {
            if (!parse_figure(fields[i], &v[i - 2])) {
                sc_msg_set(err, "%s:%d: %s is '%s', not a number >= 0", path, lineno, COLUMNS[i],
                           fields[i]);
                ok = false;
                break;
            }
        }
        if (!ok) break;
        for (size_t i = 0; i < t->count; i++) {
            if (!strcmp(t->rows[i].suite, fields[0]) && !strcmp(t->rows[i].scene, fields[1])) {
                sc_msg_set(err, "%s:%d: a second row for suite '%s', scene '%s'", path, lineno,
                           fields[0], fields[1]);
                ok = false;
                break;
            }
        }
        if (!ok) break;
        rg_row *rows = realloc(t->rows, (t->count + 1) * sizeof *rows);
        if (!rows) {
            sc_msg_set(err, "%s:%d: out of memory", path, lineno);
            ok = false;
            break;
        }
        t->rows = rows;
        rg_row *r = &rows[t->count];
        r->suite = dup(fields[0]);
        r->scene = dup(fields[1]);
        r->limits = (rg_limits){v[0], v[1], v[2]};
        t->count++;
        if (!r->suite || !r->scene) {
            sc_msg_set(err, "%s:%d: out of memory", path, lineno);
            ok = false;
        }
    }
    if (ok && ferror(f)) {
        sc_msg_set(err, "%s: read error", path);
        ok = false;
    }
    fclose(f);
    return ok;
}

/* The stem of a file path as a span of it: [*start, *start + return value). */
static size_t stem_span(const char *path, const char **start) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    *start = base;
    return dot && dot != base ? (size_t)(dot - base) : strlen(base);
}

char *rg_file_stem(const char *path) {
    const char *start;
    size_t n = stem_span(path, &start);
    return sc_format("%.*s", (int)n, start);
}

/* The name of the folder holding a file as a span of it ("scenes/hard/x.json" -> "hard"); 0 when
 * none. */
static size_t folder_span(const char *path, const char **start) {
    const char *slash = strrchr(path, '/');
    *start = path;
    if (!slash) return 0;
    const char *s = slash;
    while (s > path && s[-1] != '/') s--;
    *start = s;
    return (size_t)(slash - s);
}

/* The row of a suite, given as the n bytes at suite, and a scene. */
static const rg_row *find(const rg_thresholds *t, const char *suite, size_t n, const char *scene) {
    for (size_t i = 0; i < t->count; i++)
        if (strlen(t->rows[i].suite) == n && !memcmp(t->rows[i].suite, suite, n) &&
            !strcmp(t->rows[i].scene, scene))
            return &t->rows[i];
    return NULL;
}

static double pick(double override, double row, double dflt) {
    return !isnan(override) ? override : !isnan(row) ? row : dflt;
}

rg_limits rg_thresholds_for(const rg_thresholds *t, const char *file_path, const char *scene) {
    const char *stem, *folder;
    size_t stem_len = stem_span(file_path, &stem), folder_len = folder_span(file_path, &folder);
    const rg_row *r = find(t, stem, stem_len, scene);
    if (!r && folder_len) r = find(t, folder, folder_len, scene);
    if (!r) r = find(t, "*", 1, scene);
    rg_limits none = {NAN, NAN, NAN};
    const rg_limits *l = r ? &r->limits : &none;
    return (rg_limits){pick(t->overrides.min_psnr, l->min_psnr, RG_DEFAULT_MIN_PSNR),
                       pick(t->overrides.max_over2, l->max_over2, RG_DEFAULT_MAX_OVER2),
                       pick(t->overrides.max_coverage, l->max_coverage, RG_DEFAULT_MAX_COVERAGE)};
}
