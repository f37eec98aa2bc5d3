/* junit.c - JUnit XML of a regression run (see junit.h). */
#define _POSIX_C_SOURCE 200809L
#include "junit.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "markup.h"
#include "report.h"

/* The path an attachment line names: the report's copy, or the file as written. */
static void put_attachment(FILE *f, const rg_scene *s, const char *report_dir, const char *kind,
                           const char *path) {
    if (!path) return;
    fputs("[[ATTACHMENT|", f);
    if (report_dir) {
        /* The report's name of it (rg_report_image_name), written in its parts. */
        rg_put_markup(f, report_dir, RG_MARKUP_XML);
        fputs("/img/", f);
        rg_put_markup(f, s->name, RG_MARKUP_XML);
        fputc('.', f);
        rg_put_markup(f, kind, RG_MARKUP_XML);
        fputs(".png", f);
    } else {
        rg_put_markup(f, path, RG_MARKUP_XML);
    }
    fputs("]]\n", f);
}

bool rg_write_junit(const char *path, const rg_scene *scenes, size_t n, const char *report_dir,
                    sc_msg *err) {
    char *part = sc_format("%s.part", path);
    if (!part) {
        sc_msg_set(err, "out of memory");
        return false;
    }
    FILE *f = fopen(part, "w");
    if (!f) {
        sc_msg_set(err, "%s: %s", part, strerror(errno));
        free(part);
        return false;
    }
    size_t failures = 0;
    double total = 0;
    for (size_t i = 0; i < n; i++) {
        failures += !scenes[i].passed;
        total += scenes[i].time_s;
    }
    char stamp[32];
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(stamp, sizeof stamp, "%Y-%m-%dT%H:%M:%S", &tm);
    fprintf(f, "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n");
    fprintf(f,
            "<testsuites name=\"sgapi-render\" tests=\"%zu\" failures=\"%zu\" errors=\"0\" "
            "time=\"%.6f\">\n",
            n, failures, total);
    /* One testsuite per suite, in the order suites first appear; a run's scenes of one file are
     * consecutive, but nothing here depends on it. */
    for (size_t i = 0; i < n; i++) {
        bool first = true;
        for (size_t k = 0; k < i && first; k++) first = strcmp(scenes[k].suite, scenes[i].suite);
        if (!first) continue;
        size_t tests = 0, failed = 0;
        double time_s = 0;
        for (size_t k = i; k < n; k++) {
            if (strcmp(scenes[k].suite, scenes[i].suite)) continue;
            tests++;
            failed += !scenes[k].passed;
            time_s += scenes[k].time_s;
        }
        fputs("  <testsuite name=\"", f);
        rg_put_markup(f, scenes[i].suite, RG_MARKUP_XML);
        fprintf(f,
                "\" tests=\"%zu\" failures=\"%zu\" errors=\"0\" skipped=\"0\" time=\"%.6f\" "
                "timestamp=\"%s\">\n",
                tests, failed, time_s, stamp);
        for (size_t k = i; k < n; k++) {
            const rg_scene *s = &scenes[k];
            if (strcmp(s->suite, scenes[i].suite)) continue;
            fputs("    <testcase classname=\"", f);
            rg_put_markup(f, s->suite, RG_MARKUP_XML);
            fputs("\" name=\"", f);
            rg_put_markup(f, s->name, RG_MARKUP_XML);
            fprintf(f, "\" time=\"%.6f\">\n", s->time_s);
            if (!s->passed) {
                fputs("      <failure type=\"image regression\" message=\"", f);
                rg_put_markup(f, sc_msg_text(&s->reason), RG_MARKUP_XML);
                fputs("\">", f);
                rg_put_markup(f, s->name, RG_MARKUP_XML);
                fputs(": ", f);
                rg_put_markup(f, sc_msg_text(&s->reason), RG_MARKUP_XML);
                if (s->golden_updated) fputs(" (golden image updated from this run)", f);
                fputs("</failure>\n", f);
            }
            if (s->actual || s->heat) {
                fputs("      <system-out>", f);
                put_attachment(f, s, report_dir, "actual", s->actual);
                put_attachment(f, s, report_dir, "heat", s->heat);
                fputs("</system-out>\n", f);
            }
            fputs("    </testcase>\n", f);
        }
        fputs("  </testsuite>\n", f);
    }
    fputs("</testsuites>\n", f);
    bool ok = !ferror(f);
    if (fclose(f) != 0) ok = false;
    if (!ok) sc_msg_set(err, "%s: write error", part);
    if (ok && rename(part, path) != 0) {
        sc_msg_set(err, "%s: %s", path, strerror(errno));
        ok = false;
    }
    if (!ok) remove(part);
    free(part);
    return ok;
}
