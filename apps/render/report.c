/* report.c - the HTML report and results.json of a regression run (see report.h).
 *
 * The page is plain HTML first: every scene's expected, actual and heat-map images side by side,
 * failures on top, passing scenes in a collapsed <details>, so it reads without JavaScript. A small
 * inline script adds, per scene, a switch view (one image, flipped between expected and actual by
 * a click: the eye catches a one-pixel shift), a swipe slider and pixel-exact zoom, and a filter.
 * Images load lazily and carry their size, so a page of a thousand scenes lays out at once and
 * fetches only what is on screen. */
#define _POSIX_C_SOURCE 200809L
#include "report.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <cJSON.h>

#include "markup.h"

/* Creates one folder; an existing one is fine. */
static int mkdir_p_one(const char *path) {
    struct stat st;
    if (mkdir(path, 0777) == 0) return 0;
    if (errno == EEXIST && stat(path, &st) == 0 && S_ISDIR(st.st_mode)) return 0;
    if (errno == EEXIST) errno = ENOTDIR;
    return -1;
}

char *rg_report_image_name(const char *scene, const char *kind) {
    return sc_format("img/%s.%s.png", scene, kind);
}

/* A relative URL: every byte but the unreserved ones and '/' percent-encoded. */
static void put_url(FILE *f, const char *s) {
    for (; *s; s++) {
        unsigned char c = (unsigned char)*s;
        if ((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') ||
            c == '-' || c == '.' || c == '_' || c == '~' || c == '/')
            fputc(c, f);
        else
            fprintf(f, "%%%02X", c);
    }
}

/* The URL of a scene's image in the report (rg_report_image_name), written in its parts. */
static void put_image_url(FILE *f, const char *scene, const char *kind) {
    put_url(f, "img/");
    put_url(f, scene);
    fputc('.', f);
    put_url(f, kind);
    fputs(".png", f);
}

static const char STYLE[] =
    ":root{color-scheme:light dark;font-family:system-ui,-apple-system,'Segoe "
    "UI',sans-serif;font-size:15px}\n"
    "body{margin:0 auto;max-width:1500px;padding:0 1em 2em}\n"
    "header{padding:.5em 0;border-bottom:1px solid #8886}\n"
    "h1{font-size:1.4em;margin:.2em 0}\n"
    ".nfail{color:#c62828}.npass{color:#2e7d32}\n"
    "code{font-size:.9em;word-break:break-all}\n"
    ".meta{margin:.2em 0;font-size:.9em}\n"
    ".legend span{display:inline-block;width:1em;height:1em;vertical-align:middle;border:1px "
    "solid #8888}\n"
    ".filter{display:none;gap:1em;align-items:center;margin:.4em 0}\n"
    ".js .filter{display:flex}\n"
    ".scene{border:1px solid #8885;border-left:6px solid #c62828;border-radius:4px;margin:1em "
    "0;padding:.4em 1em .8em}\n"
    ".scene.pass{border-left-color:#2e7d32}\n"
    ".scene h3{margin:.2em 0;font-size:1.1em}\n"
    ".scene h3 small{font-weight:normal;opacity:.7}\n"
    ".reason{color:#c62828;font-weight:600;margin:.2em 0}\n"
    ".updated{color:#8a6d00;font-weight:600}\n"
    "table.fig{border-collapse:collapse;font-size:.9em;margin:.3em 0}\n"
    "table.fig td,table.fig th{padding:1px 12px 1px 0;text-align:right}\n"
    "table.fig td:first-child,table.fig th:first-child{text-align:left}\n"
    "table.fig tr.bad td{color:#c62828;font-weight:600}\n"
    ".tools{display:none;gap:.4em;align-items:center;margin:.4em 0;font-size:.9em}\n"
    ".js .tools{display:flex}\n"
    ".tools button[aria-pressed=true]{font-weight:700;outline:2px solid #1565c0}\n"
    ".view{overflow:auto;max-height:90vh}\n"
    ".images{display:flex;flex-wrap:wrap;gap:10px;align-items:flex-start}\n"
    "figure{margin:0}\n"
    "figcaption{font-size:.85em;text-align:center;margin-top:2px}\n"
    "img{image-rendering:pixelated;display:block;background:repeating-conic-gradient(#bbb 0 "
    "25%,#eee 0 50%) 0 0/16px 16px}\n"
    ".scene:not(.zoomed) .view img{width:360px;height:auto}\n"
    ".flip{cursor:pointer}\n"
    "[hidden]{display:none!important}\n"
    ".alt figure{display:inline-block}\n"
    ".swipe{position:relative}\n"
    ".swipe img.top{position:absolute;left:0;top:0;clip-path:inset(0 50% 0 0)}\n"
    ".swipe+input{display:block;width:100%;margin:4px 0}\n"
    ".missing{width:360px;max-width:100%;height:120px;display:flex;align-items:center;justify-"
    "content:center;"
    "border:2px dashed #c62828;text-align:center;padding:4px}\n"
    "details>summary{cursor:pointer;font-size:1.15em;font-weight:600;margin:1em 0}\n";

/* Adds the views and the filter; everything it needs is in the page's data- attributes. */
static const char SCRIPT[] =
    "'use strict';\n"
    "document.documentElement.classList.add('js');\n"
    "function el(tag, attrs, kids) {\n"
    "  const e = document.createElement(tag);\n"
    "  for (const k in attrs) e.setAttribute(k, attrs[k]);\n"
    "  for (const c of kids || []) e.append(c);\n"
    "  return e;\n"
    "}\n"
    "function image(src, w, h, cls) {\n"
    "  const a = {src: src, width: w, height: h, alt: ''};\n"
    "  if (cls) a.class = cls;\n"
    "  return el('img', a);\n"
    "}\n"
    "function applyZoom(scene) {\n"
    "  const z = Number(scene.dataset.zoom || 0);\n"
    "  scene.classList.toggle('zoomed', z > 0);\n"
    "  for (const img of scene.querySelectorAll('.view img'))\n"
    "    img.style.width = z > 0 ? (img.getAttribute('width') * z) + 'px' : '';\n"
    "}\n"
    "function show(scene, mode) {\n"
    "  const d = scene.dataset, w = d.width, h = d.height;\n"
    "  const side = scene.querySelector('.images'), alt = scene.querySelector('.alt');\n"
    "  for (const b of scene.querySelectorAll('.tools button'))\n"
    "    b.setAttribute('aria-pressed', String(b.dataset.mode === mode));\n"
    "  side.hidden = mode !== 'side';\n"
    "  alt.hidden = mode === 'side';\n"
    "  alt.replaceChildren();\n"
    "  if (mode === 'switch') {\n"
    "    const img = image(d.expected, w, h, 'flip');\n"
    "    const cap = el('figcaption', {}, ['expected (click the image to flip to actual)']);\n"
    "    img.title = 'click to flip between expected and actual';\n"
    "    img.dataset.showing = 'expected';\n"
    "    img.addEventListener('click', () => {\n"
    "      const next = img.dataset.showing === 'expected' ? 'actual' : 'expected';\n"
    "      img.dataset.showing = next;\n"
    "      img.src = d[next];\n"
    "      cap.textContent = next + ' (click the image to flip to ' +\n"
    "          (next === 'expected' ? 'actual' : 'expected') + ')';\n"
    "    });\n"
    "    alt.append(el('figure', {}, [img, cap]));\n"
    "  } else if (mode === 'swipe') {\n"
    "    const top = image(d.actual, w, h, 'top');\n"
    "    const range = el('input', {type: 'range', min: 0, max: 100, value: 50,\n"
    "                              'aria-label': 'expected | actual'});\n"
    "    range.addEventListener('input', () => {\n"
    "      top.style.clipPath = 'inset(0 ' + (100 - range.value) + '% 0 0)';\n"
    "    });\n"
    "    alt.append(el('figure', {}, [el('div', {class: 'swipe'}, [image(d.expected, w, h), "
    "top]),\n"
    "                                  range, el('figcaption', {}, ['actual | expected: drag "
    "the slider'])]));\n"
    "  }\n"
    "  applyZoom(scene);\n"
    "}\n"
    "for (const scene of document.querySelectorAll('.scene')) {\n"
    "  const both = scene.dataset.expected && scene.dataset.actual;\n"
    "  const tools = scene.querySelector('.tools');\n"
    "  for (const [mode, label] of [['side', 'side by side'], ['switch', 'switch'],\n"
    "                               ['swipe', 'swipe']]) {\n"
    "    const b = el('button', {type: 'button', 'data-mode': mode}, [label]);\n"
    "    if (mode !== 'side' && !both) b.disabled = true;\n"
    "    b.addEventListener('click', () => show(scene, mode));\n"
    "    tools.append(b);\n"
    "  }\n"
    "  const zoom = el('select', {'aria-label': 'zoom'}, [['0', 'fit'], ['1', '1:1'], ['2', "
    "'2x'],\n"
    "      ['4', '4x'], ['8', '8x']].map(([v, t]) => el('option', {value: v}, [t])));\n"
    "  zoom.addEventListener('change', () => { scene.dataset.zoom = zoom.value; "
    "applyZoom(scene); });\n"
    "  tools.append(' zoom ', zoom);\n"
    "  tools.querySelector('button').setAttribute('aria-pressed', 'true');\n"
    "}\n"
    "const text = document.getElementById('filter-text');\n"
    "const failedOnly = document.getElementById('filter-failed');\n"
    "function filter() {\n"
    "  const q = text.value.trim().toLowerCase();\n"
    "  for (const scene of document.querySelectorAll('.scene'))\n"
    "    scene.hidden = q !== '' && !scene.dataset.key.includes(q);\n"
    "  const passed = document.getElementById('passed');\n"
    "  if (passed) {\n"
    "    passed.hidden = failedOnly.checked;\n"
    "    if (q !== '' && !failedOnly.checked) passed.open = true;\n"
    "  }\n"
    "}\n"
    "text.addEventListener('input', filter);\n"
    "failedOnly.addEventListener('change', filter);\n";

/* A figure against its target: one row of the scene's table. */
static void put_row(FILE *f, const char *what, const char *value, const char *target, bool bad) {
    fprintf(f, "<tr%s><td>%s</td><td>%s</td><td>%s</td></tr>\n", bad ? " class=\"bad\"" : "", what,
            value, target);
}

static void put_figures(FILE *f, const rg_scene *s) {
    char v[64], t[64];
    fputs("<table class=\"fig\"><tr><th></th><th>value</th><th>target</th></tr>\n", f);
    if (s->compared) {
        const sc_diff *d = &s->diff;
        rg_format_psnr(d->psnr_db, v, sizeof v);
        snprintf(t, sizeof t, "&ge; %g dB", s->limits.min_psnr);
        put_row(f, "PSNR", v, t, d->psnr_db < s->limits.min_psnr);
        snprintf(v, sizeof v, "%.4f %%", d->pct_over[0]);
        snprintf(t, sizeof t, "&le; %g %%", s->limits.max_over2);
        put_row(f, "pixels over 2/255", v, t, d->pct_over[0] > s->limits.max_over2);
        snprintf(v, sizeof v, "%.4f %%", d->pct_coverage);
        snprintf(t, sizeof t, "&le; %g %%", s->limits.max_coverage);
        put_row(f, "coverage mismatch", v, t, d->pct_coverage > s->limits.max_coverage);
        snprintf(v, sizeof v, "%.4f %%", d->pct_over[1]);
        put_row(f, "pixels over 8/255", v, "", false);
        snprintf(v, sizeof v, "%d / 255", d->max_error);
        put_row(f, "largest difference", v, "", false);
    } else {
        snprintf(t, sizeof t, "&ge; %g dB, &le; %g %%, &le; %g %%", s->limits.min_psnr,
                 s->limits.max_over2, s->limits.max_coverage);
        put_row(f, "targets (not compared)", "", t, false);
    }
    snprintf(v, sizeof v, "%.3f ms", s->time_s * 1e3);
    put_row(f, "render time", v, "", false);
    fputs("</table>\n", f);
}

/* One image of the side-by-side view, or a box saying why there is none. */
static void put_image(FILE *f, const rg_scene *s, const char *kind, const char *caption,
                      const char *src, int w, int h) {
    fputs("<figure>", f);
    if (src) {
        fputs("<img loading=\"lazy\" src=\"", f);
        put_image_url(f, s->name, kind);
        fprintf(f, "\" width=\"%d\" height=\"%d\" alt=\"%s\">", w, h, caption);
    } else {
        fprintf(f, "<div class=\"missing\">no %s image</div>", caption);
    }
    fprintf(f, "<figcaption>%s</figcaption></figure>\n", caption);
}

static void put_scene(FILE *f, const rg_scene *s, const int expected_size[2]) {
    fprintf(f, "<article class=\"scene %s\" id=\"scene-", s->passed ? "pass" : "fail");
    rg_put_markup(f, s->name, RG_MARKUP_HTML);
    fprintf(f, "\" data-width=\"%d\" data-height=\"%d\" data-key=\"", s->width, s->height);
    rg_put_markup(f, s->suite, RG_MARKUP_HTML);
    fputc('/', f);
    rg_put_markup(f, s->name, RG_MARKUP_HTML);
    fputc('"', f);
    /* The switch and swipe views lay the two images over each other: same size only. */
    bool overlay =
        s->expected && s->actual && expected_size[0] == s->width && expected_size[1] == s->height;
    if (overlay) {
        fputs(" data-expected=\"", f);
        put_image_url(f, s->name, "expected");
        fputs("\" data-actual=\"", f);
        put_image_url(f, s->name, "actual");
        fputc('"', f);
    }
    fputs(">\n<h3>", f);
    rg_put_markup(f, s->name, RG_MARKUP_HTML);
    fputs(" <small>", f);
    rg_put_markup(f, s->suite, RG_MARKUP_HTML);
    fprintf(f, " &middot; %d &times; %d</small></h3>\n", s->width, s->height);
    if (!s->passed) {
        fputs("<p class=\"reason\">", f);
        rg_put_markup(f, sc_msg_text(&s->reason), RG_MARKUP_HTML);
        fputs("</p>\n", f);
    }
    if (s->golden_updated)
        fputs("<p class=\"updated\">golden image replaced by this run's image</p>\n", f);
    put_figures(f, s);
    fputs("<div class=\"tools\"></div>\n<div class=\"view\"><div class=\"images\">\n", f);
    put_image(f, s, "expected", "expected", s->expected, expected_size[0], expected_size[1]);
    put_image(f, s, "actual", "actual", s->actual, s->width, s->height);
    put_image(f, s, "heat", "heat map", s->heat, s->width, s->height);
    fputs("</div><div class=\"alt\" hidden></div></div>\n</article>\n", f);
}

/* The size of a golden image, read from its PNG header (0 x 0 when it is not a PNG): the page
 * gives every image its size so that it lays out before it loads. */
static void png_size(const char *path, int size[2]) {
    size[0] = size[1] = 0;
    FILE *f = path ? fopen(path, "rb") : NULL;
    unsigned char h[24];
    if (!f) return;
    if (fread(h, 1, sizeof h, f) == sizeof h && !memcmp(h, "\x89PNG\r\n\x1a\n", 8) &&
        !memcmp(h + 12, "IHDR", 4)) {
        unsigned long w = (unsigned long)h[16] << 24 | (unsigned long)h[17] << 16 |
                          (unsigned long)h[18] << 8 | h[19];
        unsigned long ht = (unsigned long)h[20] << 24 | (unsigned long)h[21] << 16 |
                           (unsigned long)h[22] << 8 | h[23];
        if (w <= 1u << 20 && ht <= 1u << 20) {
            size[0] = (int)w;
            size[1] = (int)ht;
        }
    }
    fclose(f);
}

static bool write_html(const char *path, const rg_scene *scenes, size_t n, const size_t *order,
                       const int (*sizes)[2], const char *command, const char *golden) {
    FILE *f = fopen(path, "w");
    if (!f) return false;
    size_t failed = 0;
    for (size_t i = 0; i < n; i++) failed += !scenes[i].passed;
    char stamp[32];
    time_t now = time(NULL);
    struct tm tm;
    gmtime_r(&now, &tm);
    strftime(stamp, sizeof stamp, "%Y-%m-%d %H:%M:%S UTC", &tm);
    fprintf(f,
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            "<link rel=\"icon\" href=\"data:,\">\n"
            "<title>%s: %zu failed, %zu passed</title>\n<style>\n%s</style>\n</head>\n<body>\n",
            failed ? "FAILED" : "passed", failed, n - failed, STYLE);
    fprintf(f,
            "<header>\n<h1>Image regression: <span class=\"nfail\" id=\"failed-count\">%zu "
            "failed</span>, <span class=\"npass\" id=\"passed-count\">%zu passed</span> of %zu "
            "scenes</h1>\n",
            failed, n - failed, n);
    fputs("<p class=\"meta\">Command: <code id=\"command\">", f);
    rg_put_markup(f, command, RG_MARKUP_HTML);
    fputs("</code></p>\n<p class=\"meta legend\">Golden images: <code>", f);
    rg_put_markup(f, golden, RG_MARKUP_HTML);
    fprintf(f,
            "</code> &middot; written %s &middot; heat map: "
            "<span style=\"background:#000\"></span> equal, "
            "<span style=\"background:#00f\"></span> 1/255, "
            "<span style=\"background:#f00\"></span> 8/255, "
            "<span style=\"background:#ff0\"></span> 32/255, "
            "<span style=\"background:#fff\"></span> 128/255 and more</p>\n",
            stamp);
    fputs("<div class=\"filter\"><label>filter <input id=\"filter-text\" type=\"search\" "
          "placeholder=\"suite or scene\"></label><label><input id=\"filter-failed\" "
          "type=\"checkbox\"> failures only</label></div>\n</header>\n<main>\n",
          f);
    fprintf(f, "<section id=\"failed\">\n<h2>Failed (%zu)</h2>\n", failed);
    for (size_t i = 0; i < failed; i++) put_scene(f, &scenes[order[i]], sizes[order[i]]);
    fputs("</section>\n", f);
    if (n > failed) {
        fprintf(f, "<details id=\"passed\"%s>\n<summary>Passed (%zu)</summary>\n",
                failed ? "" : " open", n - failed);
        for (size_t i = failed; i < n; i++) put_scene(f, &scenes[order[i]], sizes[order[i]]);
        fputs("</details>\n", f);
    }
    fprintf(f, "</main>\n<script>\n%s</script>\n</body>\n</html>\n", SCRIPT);
    bool ok = !ferror(f);
    return fclose(f) == 0 && ok;
}

char *rg_command_line(int argc, char **argv) {
    static const char plain_chars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ"
                                      "0123456789-_./=,:+@%";
    size_t len = 1;
    for (int i = 0; i < argc; i++) len += strlen(argv[i]) * 4 + 3;
    char *out = malloc(len), *p = out;
    if (!out) return NULL;
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        bool plain = *a != '\0' && strspn(a, plain_chars) == strlen(a);
        if (i) *p++ = ' ';
        if (plain) {
            p += sprintf(p, "%s", a);
            continue;
        }
        /* Single quotes; a quote inside becomes '\'' (close, escaped quote, reopen). */
        *p++ = '\'';
        for (const char *c = a; *c; c++) {
            if (*c == '\'') {
                memcpy(p, "'\\''", 4);
                p += 4;
            } else {
                *p++ = *c;
            }
        }
        *p++ = '\'';
    }
    *p = '\0';
    return out;
}

/* A figure as JSON: null for an identical image's PSNR (JSON has no infinity). */
static void add_number(cJSON *o, const char *key, double v) {
    if (isfinite(v))
        cJSON_AddNumberToObject(o, key, v);
    else
        cJSON_AddNullToObject(o, key);
}

static bool write_json(const char *path, const rg_scene *scenes, size_t n, const size_t *order,
                       const char *command, const char *golden) {
    cJSON *root = cJSON_CreateObject();
    if (!root) return false;
    size_t failed = 0;
    for (size_t i = 0; i < n; i++) failed += !scenes[i].passed;
    cJSON_AddStringToObject(root, "command", command);
    cJSON_AddStringToObject(root, "golden", golden);
    cJSON_AddNumberToObject(root, "scenes", (double)n);
    cJSON_AddNumberToObject(root, "passed", (double)(n - failed));
    cJSON_AddNumberToObject(root, "failed", (double)failed);
    cJSON *list = cJSON_AddArrayToObject(root, "results");
    bool named = true; /* every image's name was made */
    for (size_t k = 0; list && named && k < n; k++) {
        const rg_scene *s = &scenes[order[k]];
        cJSON *o = cJSON_CreateObject();
        if (!o) break;
        cJSON_AddItemToArray(list, o);
        cJSON_AddStringToObject(o, "suite", s->suite);
        cJSON_AddStringToObject(o, "scene", s->name);
        cJSON_AddStringToObject(o, "status", s->passed ? "passed" : "failed");
        if (!s->passed) cJSON_AddStringToObject(o, "reason", sc_msg_text(&s->reason));
        cJSON_AddBoolToObject(o, "golden_updated", s->golden_updated);
        cJSON_AddNumberToObject(o, "time_s", s->time_s);
        cJSON_AddNumberToObject(o, "width", s->width);
        cJSON_AddNumberToObject(o, "height", s->height);
        cJSON *t = cJSON_AddObjectToObject(o, "thresholds");
        if (t) {
            cJSON_AddNumberToObject(t, "min_psnr_db", s->limits.min_psnr);
            cJSON_AddNumberToObject(t, "max_pct_over_2", s->limits.max_over2);
            cJSON_AddNumberToObject(t, "max_coverage_pct", s->limits.max_coverage);
        }
        if (s->compared) {
            cJSON *d = cJSON_AddObjectToObject(o, "figures");
            if (d) {
                add_number(d, "psnr_db", s->diff.psnr_db);
                cJSON_AddNumberToObject(d, "pct_over_2", s->diff.pct_over[0]);
                cJSON_AddNumberToObject(d, "pct_over_8", s->diff.pct_over[1]);
                cJSON_AddNumberToObject(d, "pct_over_32", s->diff.pct_over[2]);
                cJSON_AddNumberToObject(d, "coverage_pct", s->diff.pct_coverage);
                cJSON_AddNumberToObject(d, "max_error", s->diff.max_error);
                cJSON_AddNumberToObject(d, "mean_abs_error", s->diff.mean_abs_error);
            }
        } else {
            cJSON_AddNullToObject(o, "figures");
        }
        cJSON *img = cJSON_AddObjectToObject(o, "images");
        const char *kinds[3] = {"expected", "actual", "heat"};
        const char *have[3] = {s->expected, s->actual, s->heat};
        for (int i = 0; img && i < 3; i++) {
            if (have[i]) {
                char *rel = rg_report_image_name(s->name, kinds[i]);
                named = rel != NULL;
                if (rel) cJSON_AddStringToObject(img, kinds[i], rel);
                free(rel);
            } else {
                cJSON_AddNullToObject(img, kinds[i]);
            }
        }
    }
    char *text = named ? cJSON_Print(root) : NULL;
    cJSON_Delete(root);
    if (!text) return false;
    FILE *f = fopen(path, "w");
    bool ok = f && fputs(text, f) >= 0 && fputc('\n', f) != EOF;
    if (f && fclose(f) != 0) ok = false;
    free(text);
    return ok;
}

bool rg_write_report(const char *dir, const rg_scene *scenes, size_t n, const char *command,
                     const char *golden, sc_msg *err) {
    char *path = sc_format("%s/img", dir);
    size_t *order = malloc((n ? n : 1) * sizeof *order);
    int(*sizes)[2] = calloc(n ? n : 1, sizeof *sizes);
    bool ok = path && order && sizes;
    if (!ok) sc_msg_set(err, "out of memory");
    if (ok && mkdir_p_one(path) != 0) {
        sc_msg_set(err, "cannot create folder '%s': %s", path, strerror(errno));
        ok = false;
    }
    /* The images first: the page refers to them. */
    for (size_t i = 0; ok && i < n; i++) {
        const rg_scene *s = &scenes[i];
        const char *kinds[3] = {"expected", "actual", "heat"};
        const char *src[3] = {s->expected, s->actual, s->heat};
        for (int k = 0; ok && k < 3; k++) {
            if (!src[k]) continue;
            free(path);
            path = sc_format("%s/img/%s.%s.png", dir, s->name, kinds[k]);
            ok = path && rg_copy_file(src[k], path, err);
            if (!path) sc_msg_set(err, "out of memory");
        }
        png_size(s->expected, sizes[i]);
    }
    if (ok) {
        rg_sort(scenes, n, order);
        free(path);
        path = sc_format("%s/index.html", dir);
        ok = path && write_html(path, scenes, n, order, (const int(*)[2])sizes, command, golden);
        if (!ok) sc_msg_set(err, "%s: write error", path ? path : dir);
    }
    if (ok) {
        free(path);
        path = sc_format("%s/results.json", dir);
        ok = path && write_json(path, scenes, n, order, command, golden);
        if (!ok) sc_msg_set(err, "%s: write error", path ? path : dir);
    }
    free(path);
    free(order);
    free(sizes);
    return ok;
}
