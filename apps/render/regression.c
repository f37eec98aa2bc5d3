/* regression.c - judging compared scenes, their order, and golden updates (see regression.h). */
#define _POSIX_C_SOURCE 200809L
#include "regression.h"

#include <errno.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const char *rg_format_psnr(double db, char *buf, size_t len) {
    if (isinf(db))
        snprintf(buf, len, "inf dB (identical)");
    else
        snprintf(buf, len, "%.2f dB", db);
    return buf;
}

/* Adds a figure past its target to the reason, after "; " when there is one before. */
static void append(sc_msg *reason, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);
static void append(sc_msg *reason, const char *fmt, ...) {
    if (reason->text) sc_msg_append(reason, "; ");
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vappend(reason, fmt, ap);
    va_end(ap);
}

void rg_judge(rg_scene *s) {
    const sc_diff *d = &s->diff;
    const rg_limits *l = &s->limits;
    char psnr[32];
    sc_msg_free(&s->reason);
    if (d->psnr_db < l->min_psnr)
        append(&s->reason, "PSNR %s < %g dB", rg_format_psnr(d->psnr_db, psnr, sizeof psnr),
               l->min_psnr);
    if (d->pct_over[0] > l->max_over2)
        append(&s->reason, "%.4f %% of pixels over 2/255 > %g %%", d->pct_over[0], l->max_over2);
    if (d->pct_coverage > l->max_coverage)
        append(&s->reason, "coverage mismatch %.4f %% > %g %%", d->pct_coverage, l->max_coverage);
    s->passed = s->reason.text == NULL;
}

void rg_fail_golden(rg_scene *s, const char *fmt, ...) {
    s->compared = false;
    s->passed = false;
    va_list ap;
    va_start(ap, fmt);
    sc_msg_vset(&s->reason, fmt, ap);
    va_end(ap);
}

static char *dup_string(const char *s) {
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

bool rg_compare(rg_scene *s, const unsigned char *pixels, const unsigned char background[4],
                const char *golden_dir, const char *actual, const char *out_dir, sc_png_writer *png,
                sc_msg *err) {
    char *path = sc_format("%s/%s.png", golden_dir, s->name);
    unsigned char *heat = malloc((size_t)s->width * (size_t)s->height * 4);
    s->actual = dup_string(actual);
    if (!path || !heat || !s->actual) {
        sc_msg_set(err, "out of memory");
        free(path);
        free(heat);
        return false;
    }
    sc_msg why = {0};
    sc_image ref = {0};
    bool ok = true;
    if (!sc_image_load(path, &ref, &why)) {
        rg_fail_golden(s, "golden image unreadable or missing: %s", why.text);
    } else if (ref.width != s->width || ref.height != s->height) {
        rg_fail_golden(s, "golden image %s is %dx%d, the scene %dx%d", path, ref.width, ref.height,
                       s->width, s->height);
        s->expected = dup_string(path);
    } else {
        s->expected = dup_string(path);
        s->diff = sc_image_diff(pixels, ref.pixels, s->width, s->height, background, heat);
        s->compared = true;
        rg_judge(s);
        free(path);
        path = sc_format("%s/%s-heat.png", out_dir, s->name);
        ok = path && sc_png_writer_write(png, path, s->width, s->height, heat, err);
        if (ok) s->heat = dup_string(path);
        if (!path) sc_msg_set(err, "out of memory");
    }
    /* The golden's copy in a report is optional; the heat map's path is needed (JUnit). */
    if (ok && s->compared && !s->heat) {
        sc_msg_set(err, "out of memory");
        ok = false;
    }
    sc_msg_free(&why);
    sc_image_free(&ref);
    free(heat);
    free(path);
    return ok;
}

/* Orders failing scenes: those without figures, then by PSNR rising; ties in run order. */
static bool worse(const rg_scene *a, size_t ia, const rg_scene *b, size_t ib) {
    if (a->passed != b->passed) return !a->passed;
    if (!a->passed) {
        if (a->compared != b->compared) return !a->compared;
        if (a->compared && a->diff.psnr_db != b->diff.psnr_db)
            return a->diff.psnr_db < b->diff.psnr_db;
    }
    return ia < ib;
}

void rg_sort(const rg_scene *scenes, size_t n, size_t *order) {
    /* Insertion sort: stable, and a run's scenes are at most a few thousand. */
    for (size_t i = 0; i < n; i++) {
        size_t j = i;
        while (j > 0 && worse(&scenes[i], i, &scenes[order[j - 1]], order[j - 1])) {
            order[j] = order[j - 1];
            j--;
        }
        order[j] = i;
    }
}

bool rg_copy_file(const char *src, const char *dst, sc_msg *err) {
    char *part = sc_format("%s.part", dst);
    if (!part) {
        sc_msg_set(err, "out of memory");
        return false;
    }
    FILE *in = fopen(src, "rb");
    FILE *out = in ? fopen(part, "wb") : NULL;
    bool ok = in && out;
    if (!ok) sc_msg_set(err, "%s: %s", in ? part : src, strerror(errno));
    char buf[1 << 16];
    while (ok) {
        size_t n = fread(buf, 1, sizeof buf, in);
        if (n && fwrite(buf, 1, n, out) != n) {
            sc_msg_set(err, "%s: %s", part, strerror(errno));
            ok = false;
        }
        if (n < sizeof buf) {
            if (ferror(in)) {
                sc_msg_set(err, "%s: read error", src);
                ok = false;
            }
            break;
        }
    }
    if (in) fclose(in);
    if (out && fclose(out) != 0 && ok) {
        sc_msg_set(err, "%s: %s", part, strerror(errno));
        ok = false;
    }
    if (ok && rename(part, dst) != 0) {
        sc_msg_set(err, "%s: %s", dst, strerror(errno));
        ok = false;
    }
    if (!ok && out) remove(part);
    free(part);
    return ok;
}

bool rg_update_golden(rg_scene *scenes, size_t n, const char *golden_dir) {
    bool ok = true;
    for (size_t i = 0; i < n; i++) {
        rg_scene *s = &scenes[i];
        if (s->passed || !s->actual) continue;
        char *path = sc_format("%s/%s.png", golden_dir, s->name);
        sc_msg err = {0};
        if (!path) {
            fprintf(stderr, "sgapi-render: out of memory\n");
            return false;
        }
        FILE *probe = fopen(path, "rb");
        bool existed = probe != NULL;
        if (probe) fclose(probe);
        if (rg_copy_file(s->actual, path, &err)) {
            printf("%s %s (%s)\n", existed ? "replaced" : "added   ", path,
                   sc_msg_text(&s->reason));
        } else {
            fprintf(stderr, "sgapi-render: --update-golden: %s\n", err.text);
            s->golden_updated = false;
            ok = false;
        }
        sc_msg_free(&err);
        free(path);
    }
    fflush(stdout);
    return ok;
}

void rg_scenes_free(rg_scene *scenes, size_t n) {
    for (size_t i = 0; i < n; i++) {
        free(scenes[i].suite);
        free(scenes[i].name);
        free(scenes[i].expected);
        free(scenes[i].actual);
        free(scenes[i].heat);
        sc_msg_free(&scenes[i].reason);
    }
}
