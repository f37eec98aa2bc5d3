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

bool rg_thresholds_load(rg_thresholds *t, const char *path, char *err, size_t errlen) {
    FILE *f = fopen(path, "r");
    if (!f) {
        snprintf(err, errlen, "%s: %s", path, strerror(errno));
        return false;
    }
    char line[4096];
    int lineno = 0;
    bool ok = true, first = true;
    while (ok && fgets(line, sizeof line, f)) {
        lineno++;
        size_t len = strlen(line);
        if (len == sizeof line - 1 && line[len - 1] != '\n') {
            snprintf(err, errlen, "%s:%d: line longer than %zu characters", path, lineno,
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
                    snprintf(err, errlen,
                             "%s:%d: the header's columns are "
                             "suite,scene,min_psnr_db,max_pct_over_2,max_coverage_pct",
                             path, lineno);
                    ok = false;
                }
            }
            continue;
        }
        if (n < 2 || n > 5) {
            snprintf(err, errlen,
                     "%s:%d: %d fields; a row is suite,scene[,min_psnr_db[,max_pct_over_2[,"
                     "max_coverage_pct]]]",
                     path, lineno, n > 5 ? 6 : n);
            ok = false;
            break;
        }
        if (*fields[0] == '\0' || *fields[1] == '\0') {
            snprintf(err, errlen, "%s:%d: empty %s name", path, lineno,
                     *fields[0] == '\0' ? "suite" : "scene");
            ok = false;
            break;
        }
        double v[3] = {NAN, NAN, NAN};
        for (int i = 2; i < n; i++) {
            if (!parse_figure(fields[i], &v[i - 2])) {
                snprintf(err, errlen, "%s:%d: %s is '%s', not a number >= 0", path, lineno,
                         COLUMNS[i], fields[i]);
                ok = false;
                break;
            }
        }
        if (!ok) break;
        for (size_t i = 0; i < t->count; i++) {
            if (!strcmp(t->rows[i].suite, fields[0]) && !strcmp(t->rows[i].scene, fields[1])) {
                snprintf(err, errlen, "%s:%d: a second row for suite '%s', scene '%s'", path,
                         lineno, fields[0], fields[1]);
                ok = false;
                break;
            }
        }
        if (!ok) break;
        rg_row *rows = realloc(t->rows, (t->count + 1) * sizeof *rows);
        if (!rows) {
            snprintf(err, errlen, "%s:%d: out of memory", path, lineno);
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
            snprintf(err, errlen, "%s:%d: out of memory", path, lineno);
            ok = false;
        }
    }
    if (ok && ferror(f)) {
        snprintf(err, errlen, "%s: read error", path);
        ok = false;
    }
    fclose(f);
    return ok;
}

void rg_file_stem(const char *path, char *out, size_t outlen) {
    const char *base = strrchr(path, '/');
    base = base ? base + 1 : path;
    const char *dot = strrchr(base, '.');
    size_t n = dot && dot != base ? (size_t)(dot - base) : strlen(base);
    if (n >= outlen) n = outlen - 1;
    memcpy(out, base, n);
    out[n] = '\0';
}

/* The name of the folder holding a file ("scenes/hard/x.json" -> "hard"); "" when none. */
static void folder_name(const char *path, char *out, size_t outlen) {
    out[0] = '\0';
    const char *slash = strrchr(path, '/');
    if (!slash) return;
    const char *start = slash;
    while (start > path && start[-1] != '/') start--;
    size_t n = (size_t)(slash - start);
    if (n >= outlen) n = outlen - 1;
    memcpy(out, start, n);
    out[n] = '\0';
}

static const rg_row *find(const rg_thresholds *t, const char *suite, const char *scene) {
    for (size_t i = 0; i < t->count; i++)
        if (!strcmp(t->rows[i].suite, suite) && !strcmp(t->rows[i].scene, scene))
            return &t->rows[i];
    return NULL;
}

static double pick(double override, double row, double dflt) {
    return !isnan(override) ? override : !isnan(row) ? row : dflt;
}

rg_limits rg_thresholds_for(const rg_thresholds *t, const char *file_path, const char *scene) {
    char stem[256], folder[256];
    rg_file_stem(file_path, stem, sizeof stem);
    folder_name(file_path, folder, sizeof folder);
    const rg_row *r = find(t, stem, scene);
    if (!r && folder[0]) r = find(t, folder, scene);
    if (!r) r = find(t, "*", scene);
    rg_limits none = {NAN, NAN, NAN};
    const rg_limits *l = r ? &r->limits : &none;
    return (rg_limits){pick(t->overrides.min_psnr, l->min_psnr, RG_DEFAULT_MIN_PSNR),
                       pick(t->overrides.max_over2, l->max_over2, RG_DEFAULT_MAX_OVER2),
                       pick(t->overrides.max_coverage, l->max_coverage, RG_DEFAULT_MAX_COVERAGE)};
}
