/* sgapi-render - renders every scene of scene files with sgapi and writes one PNG per scene.
 *
 *   sgapi-render [--frames N] [--scene NAME]... [--threads T] [--simd SET] SCENE.json... -o DIR
 *
 * Writes DIR/<scene name>.png and prints, per scene, the wall-clock time of one frame: the time
 * from sgBeginRenderPass to the return of sgEndRenderPass, of the shadow's depth-only pass and the
 * scene's pass together when the scene has a shadow (loading and uploads are not counted), the
 * median over N frames.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>

#include <sgapi/sgapi.h>

#include "cli.h"
#include "image_diff.h"
#include "image_io.h"
#include "scene_sgapi.h"
#include "scene.h"

typedef struct options {
    const char *out_dir;
    int frames;
    int threads;
    sgSimd simd;
    const char **files;
    int file_count;
    const char **scenes; /* --scene filters; none: every scene */
    int scene_count;
    const char *compare_dir; /* --compare: reference images, one DIR/<scene>.png per scene */
    double min_psnr, max_over2, max_coverage; /* thresholds of --compare; < 0: none */
    bool depth_only; /* --depth-only: the scene's pass without its colour target */
} options;

static void usage(FILE *f) {
    fprintf(f, "usage: sgapi-render [options] SCENE.json... -o DIR\n"
               "Renders every scene of the files to DIR/<scene name>.png and prints each scene's\n"
               "time per frame (render passes only).\n"
               "  -o DIR          output folder, created if missing (required)\n"
               "  --frames N      render each scene N times and print the median (default 1)\n"
               "  --scene NAME    render only scenes of that name (repeatable)\n"
               "  --threads T     worker threads for the device (default 0: all cores)\n"
               "  --simd SET      instruction set of the raster: scalar, sse2, avx2 or avx512\n"
               "                  (default: the best this CPU runs; all give the same images)\n"
               "  --compare DIR   compare each image with DIR/<scene name>.png: print PSNR,\n"
               "                  %% of pixels over 2/255 and coverage mismatch next to the time,\n"
               "                  and write DIR_OUT/<scene name>-heat.png\n"
               "  --min-psnr DB, --max-over2 PCT, --max-coverage PCT\n"
               "                  with --compare: fail (exit 1) when a scene is past a threshold\n"
               "  --depth-only    render each scene's pass with its depth target alone (a\n"
               "                  depth-only pass, no shadow pass) and write the depth as a grey\n"
               "                  image, white near, black at the far plane: the time of\n"
               "                  visibility alone\n"
               "  -h, --help      show this help\n");
}

/* 0: parsed; 1: help was printed; 2: bad arguments (already reported). */
static int parse_args(int argc, char **argv, options *o) {
    o->frames = 1;
    o->min_psnr = o->max_over2 = o->max_coverage = -1;
    o->files = calloc((size_t)argc, sizeof *o->files);
    o->scenes = calloc((size_t)argc, sizeof *o->scenes);
    if (!o->files || !o->scenes) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        return 2;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool threshold =
            !strcmp(a, "--min-psnr") || !strcmp(a, "--max-over2") || !strcmp(a, "--max-coverage");
        bool takes_value = !strcmp(a, "-o") || !strcmp(a, "--frames") || !strcmp(a, "--scene") ||
                           !strcmp(a, "--threads") || !strcmp(a, "--simd") ||
                           !strcmp(a, "--compare") || threshold;
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 1;
        }
        if (takes_value && !value) {
            fprintf(stderr, "sgapi-render: %s needs a value\n", a);
            return 2;
        }
        if (!strcmp(a, "-o")) {
            o->out_dir = value;
        } else if (!strcmp(a, "--frames")) {
            if (!sc_parse_int(value, 1, 1000000, &o->frames)) {
                fprintf(stderr, "sgapi-render: --frames needs a whole number >= 1, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--threads")) {
            if (!sc_parse_int(value, 0, 4096, &o->threads)) {
                fprintf(stderr, "sgapi-render: --threads needs a whole number >= 0, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--simd")) {
            if (!strcmp(value, "scalar")) {
                o->simd = SG_SIMD_SCALAR;
            } else if (!strcmp(value, "sse2")) {
                o->simd = SG_SIMD_SSE2;
            } else if (!strcmp(value, "avx2")) {
                o->simd = SG_SIMD_AVX2;
            } else if (!strcmp(value, "avx512")) {
                o->simd = SG_SIMD_AVX512;
            } else {
                fprintf(stderr, "sgapi-render: --simd is scalar, sse2, avx2 or avx512, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--depth-only")) {
            o->depth_only = true;
        } else if (!strcmp(a, "--scene")) {
            o->scenes[o->scene_count++] = value;
        } else if (!strcmp(a, "--compare")) {
            o->compare_dir = value;
        } else if (threshold) {
            double v;
            if (!sc_parse_double(value, 0.0, &v)) {
                fprintf(stderr, "sgapi-render: %s needs a number >= 0, not '%s'\n", a, value);
                return 2;
            }
            *(!strcmp(a, "--min-psnr")    ? &o->min_psnr
              : !strcmp(a, "--max-over2") ? &o->max_over2
                                          : &o->max_coverage) = v;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "sgapi-render: unknown option '%s' (see --help)\n", a);
            return 2;
        } else {
            o->files[o->file_count++] = a;
        }
        if (takes_value) i++;
    }
    if (o->file_count == 0 || !o->out_dir) {
        fprintf(stderr, "sgapi-render: %s\n",
                o->file_count == 0 ? "no scene file given" : "no output folder (-o DIR)");
        usage(stderr);
        return 2;
    }
    return 0;
}

/* Creates a folder and its missing parents, like mkdir -p. */
static bool make_dirs(const char *path) {
    size_t n = strlen(path);
    char *p = malloc(n + 1);
    if (!p) return false;
    memcpy(p, path, n + 1);
    bool ok = true;
    for (size_t i = 1; i <= n && ok; i++) {
        if (p[i] != '/' && p[i] != '\0') continue;
        char saved = p[i];
        p[i] = '\0';
        struct stat st;
        if (mkdir(p, 0777) != 0 && errno != EEXIST)
            ok = false;
        else if (stat(p, &st) != 0 || !S_ISDIR(st.st_mode))
            ok = false;
        if (!ok)
            fprintf(stderr, "sgapi-render: cannot create folder '%s': %s\n", p,
                    errno == EEXIST ? "a file of that name exists" : strerror(errno));
        p[i] = saved;
    }
    free(p);
    return ok;
}

static bool selected(const options *o, const char *name) {
    if (o->scene_count == 0) return true;
    for (int i = 0; i < o->scene_count; i++)
        if (!strcmp(o->scenes[i], name)) return true;
    return false;
}

#define PROG         "sgapi-render"
#define sg_fail(...) ss_fail(PROG, __VA_ARGS__)

/* ---- rendering ------------------------------------------------------------------------------- */

/* Compares a rendered scene with its reference image: appends the figures to the scene's line
 * (without its newline), writes the heat map, and checks the thresholds. */
static bool compare_scene(const options *o, const sc_scene *s, const unsigned char *pixels) {
    size_t len = strlen(o->compare_dir) + strlen(o->out_dir) + strlen(s->name) + 16;
    char *path = malloc(len);
    char err[1024];
    sc_image ref = {0};
    bool ok = path != NULL;
    if (ok) snprintf(path, len, "%s/%s.png", o->compare_dir, s->name);
    ok = ok && sc_image_load(path, &ref, err, sizeof err);
    if (!ok) {
        printf("\n");
        fprintf(stderr, "sgapi-render: --compare: %s\n", path ? err : "out of memory");
        free(path);
        return false;
    }
    if (ref.width != s->width || ref.height != s->height) {
        printf("\n");
        fprintf(stderr, "sgapi-render: --compare: %s is %dx%d, the scene %dx%d\n", path, ref.width,
                ref.height, s->width, s->height);
        sc_image_free(&ref);
        free(path);
        return false;
    }
    /* Background, for the coverage figure, is the scene's clear colour as stored. */
    unsigned char bg[4];
    for (int c = 0; c < 4; c++) bg[c] = (unsigned char)lroundf(s->clear_color[c] * 255.0f);
    unsigned char *heat = malloc((size_t)s->width * (size_t)s->height * 4);
    sc_diff d = sc_image_diff(pixels, ref.pixels, s->width, s->height, bg, heat);
    printf("  psnr %6.2f dB  >2/255 %7.4f %%  >8/255 %7.4f %%  max %3d  coverage %7.4f %%",
           d.psnr_db, d.pct_over[0], d.pct_over[1], d.max_error, d.pct_coverage);
    if (o->min_psnr >= 0 && d.psnr_db < o->min_psnr) ok = false;
    if (o->max_over2 >= 0 && d.pct_over[0] > o->max_over2) ok = false;
    if (o->max_coverage >= 0 && d.pct_coverage > o->max_coverage) ok = false;
    printf("%s\n", ok ? "" : "  FAIL");
    snprintf(path, len, "%s/%s-heat.png", o->out_dir, s->name);
    if (heat && !sc_image_write_png(path, s->width, s->height, heat, err, sizeof err))
        fprintf(stderr, "sgapi-render: %s\n", err);
    free(heat);
    sc_image_free(&ref);
    free(path);
    return ok;
}

/* The depth target as grey RGBA8: (1 - depth) x 255, opaque. */
static sgResult read_depth(sgDevice *dev, sgImage2D depth, const sc_scene *s,
                           unsigned char *pixels) {
    size_t n = (size_t)s->width * (size_t)s->height;
    float *d = malloc(n * sizeof *d);
    if (!d) return SG_ERROR_OUT_OF_MEMORY;
    sgResult r = sgReadImage2D(dev, depth, d, 0);
    for (size_t i = 0; r == SG_OK && i < n; i++) {
        float v = 1.0f - d[i];
        unsigned char g = (unsigned char)(v <= 0.0f ? 0 : v >= 1.0f ? 255 : lroundf(v * 255.0f));
        pixels[i * 4] = pixels[i * 4 + 1] = pixels[i * 4 + 2] = g;
        pixels[i * 4 + 3] = 255;
    }
    free(d);
    return r;
}

/* Renders one scene frames times, writes its PNG and prints its median time per frame. */
static bool render_scene(sgDevice *dev, const options *o, const sc_file *f, const sc_scene *s,
                         const ss_uploads *u, ss_pso_cache *cache) {
    bool ok = false;
    sgImage2D color = {0}, depth = {0};
    ss_shadow shadow = {0};
    sgPipelineStateObject *psos = calloc(s->draw_count ? s->draw_count : 1, sizeof *psos);
    double *times = calloc((size_t)o->frames, sizeof *times);
    unsigned char *pixels = malloc((size_t)s->width * (size_t)s->height * 4);
    char *png = malloc(strlen(o->out_dir) + strlen(s->name) + 6);
    if (!psos || !times || !pixels || !png) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        goto done;
    }
    for (size_t i = 0; i < s->draw_count; i++) {
        sgPipelineDesc desc = ss_pipeline_desc(&s->draws[i]);
        if (!ss_get_pso(PROG, dev, cache, &desc, &psos[i])) {
            fprintf(stderr, "sgapi-render: in %s, scene '%s', draw %zu\n", f->path, s->name, i);
            goto done;
        }
    }

    sgPassDesc pass;
    if (!ss_create_targets(PROG, dev, s, &color, &depth, &pass) ||
        (!o->depth_only && !ss_create_shadow(PROG, dev, cache, f, s, &shadow)))
        goto done;
    sgResult r;
    if (o->depth_only) {
        pass.color.id = 0;
        pass.depth_store = SG_STORE_STORE;
    }

    for (int frame = 0; frame < o->frames; frame++) {
        double t0 = ss_now_ms();
        if (!ss_draw_frame(PROG, dev, f, s, u, psos, &pass, &shadow)) goto done;
        times[frame] = ss_now_ms() - t0;
    }

    r = o->depth_only ? read_depth(dev, depth, s, pixels) : sgReadImage2D(dev, color, pixels, 0);
    if (r != SG_OK) {
        sg_fail(dev, r, "scene '%s': sgReadImage2D", s->name);
        goto done;
    }
    sprintf(png, "%s/%s.png", o->out_dir, s->name);
    char err[1024];
    if (!sc_image_write_png(png, s->width, s->height, pixels, err, sizeof err)) {
        fprintf(stderr, "sgapi-render: %s\n", err);
        goto done;
    }
    double median = ss_median(times, o->frames);
    if (o->frames > 1)
        printf("%-32s %10.3f ms/frame (median of %d)", s->name, median, o->frames);
    else
        printf("%-32s %10.3f ms/frame", s->name, median);
    ok = o->compare_dir ? compare_scene(o, s, pixels) : (printf("\n"), true);
    fflush(stdout);
done:
    ss_destroy_shadow(dev, &shadow);
    if (depth.id) sgDestroyImage2D(dev, depth);
    if (color.id) sgDestroyImage2D(dev, color);
    free(psos);
    free(times);
    free(pixels);
    free(png);
    return ok;
}

/* ---- main ------------------------------------------------------------------------------------ */

static size_t max_size(size_t a, size_t b) {
    return a > b ? a : b;
}

int main(int argc, char **argv) {
    options o = {0};
    int status = parse_args(argc, argv, &o);
    if (status) {
        free(o.files);
        free(o.scenes);
        return status == 1 ? 0 : 2;
    }

    /* Everything is loaded first, so a bad file stops the run before any rendering. */
    sc_file *files = calloc((size_t)o.file_count, sizeof *files);
    sgDevice *dev = NULL;
    ss_pso_cache cache = {0};
    int loaded = 0;
    status = 1;
    if (!files) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        goto done;
    }
    for (; loaded < o.file_count; loaded++) {
        char err[1024];
        if (!sc_load(o.files[loaded], &files[loaded], err, sizeof err)) {
            fprintf(stderr, "sgapi-render: %s\n", err);
            goto done;
        }
    }

    /* Each name is one output file: two selected scenes of one name would overwrite each other. */
    size_t max_images = 0, max_geoms = 0;
    for (int i = 0; i < o.file_count; i++) {
        const sc_file *f = &files[i];
        max_images = max_size(max_images, f->texture_count);
        max_geoms = max_size(max_geoms, ss_geom_count(f));
        for (size_t j = 0; j < f->scene_count; j++) {
            const char *name = f->scenes[j].name;
            if (!selected(&o, name)) continue;
            for (int k = 0; k <= i; k++) {
                size_t end = k == i ? j : files[k].scene_count;
                for (size_t m = 0; m < end; m++) {
                    if (!strcmp(files[k].scenes[m].name, name)) {
                        fprintf(stderr, "sgapi-render: scene '%s' is in both %s and %s\n", name,
                                files[k].path, f->path);
                        goto done;
                    }
                }
            }
        }
    }
    for (int i = 0; i < o.scene_count; i++) {
        bool found = false;
        for (int k = 0; k < o.file_count && !found; k++)
            for (size_t m = 0; m < files[k].scene_count && !found; m++)
                found = !strcmp(files[k].scenes[m].name, o.scenes[i]);
        if (!found) {
            fprintf(stderr, "sgapi-render: no scene named '%s'\n", o.scenes[i]);
            goto done;
        }
    }
    if (!make_dirs(o.out_dir)) goto done;

    /* Pools big enough for the largest file (its textures plus the two targets and a shadow
     * map) and for every pipeline the files' draws and shadows can need. */
    if (max_images > INT_MAX - 3 || max_geoms > INT_MAX) {
        fprintf(stderr, "sgapi-render: too many meshes or textures in one file\n");
        goto done;
    }
    sgDeviceDesc dd;
    memset(&dd, 0, sizeof dd);
    dd.thread_count = o.threads;
    dd.simd = o.simd;
    if (max_images + 3 > 256) dd.image_pool_size = (int)max_images + 3;
    if (max_geoms > 1024) dd.geom_pool_size = (int)max_geoms;
    dd.pipeline_pool_size = ss_pipeline_pool_size(files, o.file_count, 1);
    sgResult r = sgCreateDevice(&dd, &dev);
    if (r != SG_OK) {
        sg_fail(NULL, r, "sgCreateDevice");
        goto done;
    }

    for (int i = 0; i < o.file_count; i++) {
        const sc_file *f = &files[i];
        ss_uploads u;
        bool ok = ss_upload(PROG, dev, f, &u);
        for (size_t j = 0; ok && j < f->scene_count; j++) {
            if (selected(&o, f->scenes[j].name))
                ok = render_scene(dev, &o, f, &f->scenes[j], &u, &cache);
        }
        ss_destroy_uploads(dev, &u);
        if (!ok) goto done;
    }
    status = 0;
done:
    sgDestroyDevice(dev); /* also destroys the cached pipelines */
    ss_pso_cache_free(&cache);
    for (int i = 0; i < loaded; i++) sc_free(&files[i]);
    free(files);
    free(o.files);
    free(o.scenes);
    return status;
}
