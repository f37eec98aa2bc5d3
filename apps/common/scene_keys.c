/* scene_keys.c - unknown keys of a scene file: a warning each, naming the file, the key's line and
 * its path (scenes[2].draws[0].lightning), with "did you mean" when a known key is one edit away.
 * A misspelt optional key would otherwise take its default in silence. */
#include "scene_keys.h"

#include "json_lines.h"

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The keys each object may hold (docs/scene-format.md). A light may hold the keys of either type:
 * the other type's are ignored, as documented. */
static const char *const root_keys[] = {"scenes", "width",  "height",  "clear_color", "ambient",
                                        "lights", "shadow", "samples", NULL};
static const char *const scene_keys[] = {"name",   "width",  "height", "clear_color", "ambient",
                                         "lights", "shadow", "draws",  "samples",     NULL};
static const char *const draw_keys[] = {
    "mesh",         "texture",    "mode",          "filter",      "mipmap",       "wrap",
    "cull",         "front_face", "depth_compare", "depth_write", "blend",        "color",
    "sort",         "lighting",   "specular",      "shininess",   "casts_shadow", "receives_shadow",
    "polygon_mode", "worldView",  "proj",          "shader",      "uniforms",     "textures",
    "instances",    NULL};
/* A mesh object is a heightmap or a shape (with the parameters of every shape). */
static const char *const mesh_keys[] = {"heightmap", "height_scale", "shape",       "size",
                                        "radius",    "height",       "tube_radius", "segments",
                                        "rings",     "subdivisions", NULL};
static const char *const light_keys[] = {"type",  "direction",   "position",
                                         "color", "attenuation", NULL};
static const char *const shadow_keys[] = {"light", "size", "bias", "slope_bias", "pcf", NULL};

/* Whether a becomes b by one insertion, deletion, substitution or swap of neighbours. */
static bool one_edit(const char *a, const char *b) {
    size_t la = strlen(a), lb = strlen(b);
    if (la > lb + 1 || lb > la + 1) return false;
    size_t i = 0;
    while (i < la && i < lb && a[i] == b[i]) i++;
    if (i == la && i == lb) return false; /* equal */
    if (la == lb) {
        if (!strcmp(a + i + 1, b + i + 1)) return true; /* substitution */
        return i + 1 < la && a[i] == b[i + 1] && a[i + 1] == b[i] && !strcmp(a + i + 2, b + i + 2);
    }
    return la > lb ? !strcmp(a + i + 1, b + i) : !strcmp(a + i, b + i + 1);
}

typedef struct walk {
    sc_file *f;
    const sc_json_lines *lines;
    char *path; /* the path of the object being walked, e.g. "scenes[2].draws[0]" */
    size_t cap;
    bool failed; /* out of memory */
} walk;

static bool add_warning(walk *w, const char *fmt, ...) {
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(NULL, 0, fmt, ap);
    va_end(ap);
    char *msg = n >= 0 ? malloc((size_t)n + 1) : NULL;
    char **list = msg ? realloc(w->f->warnings, (w->f->warning_count + 1) * sizeof *list) : NULL;
    if (!list) {
        free(msg);
        w->failed = true;
        return false;
    }
    w->f->warnings = list;
    va_start(ap, fmt);
    vsnprintf(msg, (size_t)n + 1, fmt, ap);
    va_end(ap);
    list[w->f->warning_count++] = msg;
    return true;
}

/* Appends ".key" or "[i]" to the path; returns the old length, to cut back to. */
static size_t push(walk *w, const char *key, int index) {
    size_t len = strlen(w->path);
    int n = key ? snprintf(NULL, 0, "%s%s", len ? "." : "", key) : snprintf(NULL, 0, "[%d]", index);
    if (n < 0 || len + (size_t)n + 1 > w->cap) {
        size_t cap = (len + (size_t)(n < 0 ? 0 : n) + 1) * 2;
        char *p = realloc(w->path, cap);
        if (!p || n < 0) {
            if (p) w->path = p;
            w->failed = true;
            return len;
        }
        w->path = p;
        w->cap = cap;
    }
    if (key)
        snprintf(w->path + len, w->cap - len, "%s%s", len ? "." : "", key);
    else
        snprintf(w->path + len, w->cap - len, "[%d]", index);
    return len;
}

static void pop(walk *w, size_t len) {
    w->path[len] = '\0';
}

/* Warns about every key of obj not in keys. */
static void check_object(walk *w, const cJSON *obj, const char *const *keys) {
    if (!cJSON_IsObject(obj)) return;
    for (const cJSON *e = obj->child; e && !w->failed; e = e->next) {
        const char *key = e->string ? e->string : "";
        const char *near = NULL;
        bool known = false;
        for (const char *const *k = keys; *k; k++) {
            if (!strcmp(*k, key)) known = true;
            if (!near && one_edit(key, *k)) near = *k;
        }
        if (known) continue;
        size_t len = push(w, key, 0);
        if (w->failed) return;
        /* file:line: as compilers write it, which editors and CI logs turn into links */
        char where[32] = "";
        int line = sc_json_line(w->lines, e);
        if (line > 0) snprintf(where, sizeof where, ":%d", line);
        if (near)
            add_warning(w, "%s%s: unknown key '%s' (did you mean '%s'?)", w->f->path, where,
                        w->path, near);
        else
            add_warning(w, "%s%s: unknown key '%s'", w->f->path, where, w->path);
        pop(w, len);
    }
}

/* Each element of obj[key], an array of objects, against keys. */
static void check_array(walk *w, const cJSON *obj, const char *key, const char *const *keys,
                        void (*inner)(walk *, const cJSON *)) {
    const cJSON *a = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!cJSON_IsArray(a)) return;
    size_t len = push(w, key, 0);
    int i = 0;
    for (const cJSON *e = a->child; e && !w->failed; e = e->next, i++) {
        size_t at = push(w, NULL, i);
        if (w->failed) break;
        check_object(w, e, keys);
        if (inner) inner(w, e);
        pop(w, at);
    }
    pop(w, len);
}

/* obj[key], an object, against keys. */
static void check_member(walk *w, const cJSON *obj, const char *key, const char *const *keys) {
    const cJSON *v = cJSON_GetObjectItemCaseSensitive(obj, key);
    if (!cJSON_IsObject(v) || w->failed) return;
    size_t len = push(w, key, 0);
    if (!w->failed) check_object(w, v, keys);
    pop(w, len);
}

static void check_draw(walk *w, const cJSON *draw) {
    check_member(w, draw, "mesh", mesh_keys);
}

static void check_scene(walk *w, const cJSON *scene) {
    check_array(w, scene, "lights", light_keys, NULL);
    check_member(w, scene, "shadow", shadow_keys);
    check_array(w, scene, "draws", draw_keys, check_draw);
}

bool sc_check_keys(const char *text, size_t len, const cJSON *root, sc_file *f) {
    sc_json_lines lines;
    if (!sc_json_lines_build(text, len, root, &lines)) return false;
    walk w = {.f = f, .lines = &lines, .path = calloc(1, 64), .cap = 64};
    if (!w.path) {
        sc_json_lines_free(&lines);
        return false;
    }
    check_object(&w, root, root_keys);
    check_array(&w, root, "lights", light_keys, NULL);
    check_member(&w, root, "shadow", shadow_keys);
    check_array(&w, root, "scenes", scene_keys, check_scene);
    free(w.path);
    sc_json_lines_free(&lines);
    return !w.failed;
}

bool sc_report_warnings(const sc_file *f, const char *program, bool strict) {
    for (size_t i = 0; i < f->warning_count; i++)
        fprintf(stderr, "%s: %s: %s\n", program, strict ? "error" : "warning", f->warnings[i]);
    if (strict && f->warning_count)
        fprintf(stderr, "%s: %s: %zu unknown key%s, an error with --strict: nothing rendered\n",
                program, f->path, f->warning_count, f->warning_count == 1 ? "" : "s");
    return !(strict && f->warning_count);
}
