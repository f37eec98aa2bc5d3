/* sgapi-bench - speed against error: sgapi next to the lavapipe reference, scene by scene.
 *
 *   sgapi-bench SCENE.json... [--frames N] [--rounds R] [--threads T] [--simd SET]
 *               [--csv FILE] [--pareto [--plot OUT.png]] [--quick] [--ref PATH]
 *
 * For every scene of the files it measures:
 *   - sgapi's steady-state time per frame at 1 and at T threads (one device per thread count):
 *     3 warm-up frames, then the median of N frames (default 100), each timed from
 * sgBeginRenderPass to the return of sgEndRenderPass (with a shadow, from the start of its
 * depth-only pass to the end of the scene's pass; loading, uploads and pipeline creation are
 * not counted);
 *   - lavapipe's, at 1 and T threads, by running sgapi-ref (found beside this program) on the
 *     scene and reading the time it prints;
 *   - the error of sgapi's T-thread image against lavapipe's: PSNR and % of pixels over 2/255.
 * A scene's lavapipe and sgapi times are taken back to back, scene after scene, so that a drift
 * of the machine's speed during the run does not favour either side; --rounds R takes them R
 * times in turn and keeps the median of each (a busy moment then moves one round, not the row).
 * --simd picks sgapi's instruction set (default: the best the CPU runs), so that one run gives
 * the whole table for that set; lavapipe is measured as always.
 * It prints a markdown table, the geometric mean of the sgapi/lavapipe ratios, and the floor of
 * the machine: one 1024x1024 colour + depth frame cleared and written by sgapi with no draws.
 *
 * --pareto also measures, at T threads, each setting of the `settings` table below and prints
 * its time and error per scene, writes pareto.csv, and plots time against PSNR with gnuplot when
 * it is installed.
 *
 * Example: sgapi-bench scenes/default.json --csv bench.csv
 * --quick (2 frames, no warm-up) only checks that everything runs; its times mean nothing.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <fcntl.h>
#include <math.h>
#include <stdarg.h>
#include <stdbool.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/types.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include <sgapi/sgapi.h>

#include "cli.h"
#include "image_diff.h"
#include "image_io.h"
#include "scene_sgapi.h"
#include "scene.h"
#include "scene_keys.h"

#define WARMUP_FRAMES 3
#define MIN_FRAMES    20     /* fewer gives no steady-state median */
#define FRAMES        100    /* the default: a median that a busy moment moves little */
#define MAX_FRAMES    100000 /* sgapi-ref's limit */
#define QUICK_FRAMES  2
#define MAX_ROUNDS    25
#define MAX_THREADS   1024 /* sgapi-ref's limit */
#define FLOOR_SIZE    1024

/* ---- settings of --pareto -------------------------------------------------------------------- */

/* One way of drawing every scene: a change to the pipeline state of each draw (NULL: the scene as
 * written). Each row adds one point per scene to the speed/error curve. */
typedef struct setting {
    const char *name;
    void (*adjust)(sgPipelineDesc *desc);
} setting;

static void nearest_filter(sgPipelineDesc *desc) {
    if (desc->shade == SG_SHADE_TEXTURE_MODULATE) desc->filter = SG_FILTER_NEAREST;
}

static const setting settings[] = {
    {"default", NULL}, /* must stay first: the main table's T-thread figures are this row's */
    {"nearest", nearest_filter},
};
#define SETTING_COUNT ((int)(sizeof settings / sizeof settings[0]))

/* ---- options --------------------------------------------------------------------------------- */

typedef struct options {
    const char **files;
    int file_count;
    int frames, warmup, threads;
    int rounds;  /* --rounds: measurements of each scene, in turn; the median is kept */
    sgSimd simd; /* SG_SIMD_DEFAULT: the best the CPU runs */
    int samples; /* --samples: every scene's samples a pixel, sgapi-ref's too (0: the scenes') */
    bool quick, pareto;
    bool strict;              /* --strict: an unknown key in a scene file is an error */
    const char *csv;          /* NULL: no CSV */
    const char *plot;         /* --plot; NULL: pareto.png */
    const char *ref;          /* --ref; NULL: sgapi-ref beside this program */
    const char **shader_libs; /* --shaders: shader libraries, given to sgapi-ref too */
    int shader_lib_count;
    const sc_shaders *shaders; /* the shaders scene files may name, once loaded */
    const char *mipmap; /* --mipmap: every draw's mode (given to sgapi-ref too); NULL: none */
} options;

static void usage(FILE *f) {
    fprintf(f,
            "usage: sgapi-bench SCENE.json... [options]\n"
            "Measures, per scene, sgapi's and lavapipe's (sgapi-ref's) median time per frame at 1\n"
            "and T threads and the error of sgapi's image against lavapipe's, and prints them as\n"
            "a markdown table, with the geometric mean of the time ratios and the time of an\n"
            "empty %dx%d frame (the floor).\n"
            "  --frames N      timed frames per measurement, >= %d (default %d), after %d warm-up\n"
            "                  frames\n"
            "  --rounds R      measure each scene R times, lavapipe and sgapi in turn, and keep\n"
            "                  each side's median (default 1, at most %d)\n"
            "  --threads T     the multi-threaded measurements' thread count (default: all cores)\n"
            "  --samples N     samples a pixel, 1 or 4, for every scene, sgapi's and lavapipe's\n"
            "                  (default: each scene's \"samples\")\n"
            "  --simd SET      sgapi's instruction set: scalar, sse2, avx2, avx512 or neon\n"
            "                  (default: the best this CPU runs)\n"
            "  --csv FILE      also write the table as CSV\n"
            "  --mipmap MODE     every draw's \"mipmap\" (none, nearest, linear), for sgapi and\n"
            "                    sgapi-ref alike, whatever the scenes say\n"
            "  --shaders LIB.so  load the shaders of a shader library (repeatable; sgapi-ref\n"
            "                  gets the same)\n"
            "  --pareto        also measure every setting (default, nearest filter) at T threads:\n"
            "                  print a second table, write pareto.csv (beside --csv FILE, or in\n"
            "                  the current folder) and plot it when gnuplot is installed\n"
            "  --plot OUT.png  with --pareto: the plot's file (default pareto.png)\n"
            "  --quick         %d frames, no warm-up: checks that everything runs; the times mean\n"
            "                  nothing\n"
            "  --ref PATH      the sgapi-ref program (default: the one beside sgapi-bench)\n"
            "  --strict        an unknown key in a scene file is an error (exit 1, nothing\n"
            "                  measured), not a warning\n"
            "  -h, --help      show this help\n",
            FLOOR_SIZE, FLOOR_SIZE, MIN_FRAMES, FRAMES, WARMUP_FRAMES, MAX_ROUNDS, QUICK_FRAMES);
}

static int default_threads(void) {
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n < 1 ? 1 : n > MAX_THREADS ? MAX_THREADS : (int)n;
}

static const struct {
    const char *name;
    sgSimd simd;
} simd_names[] = {{"scalar", SG_SIMD_SCALAR},
                  {"sse2", SG_SIMD_SSE2},
                  {"avx2", SG_SIMD_AVX2},
                  {"avx512", SG_SIMD_AVX512},
                  {"neon", SG_SIMD_NEON}};

static bool parse_simd(const char *s, sgSimd *out) {
    for (size_t i = 0; i < sizeof simd_names / sizeof simd_names[0]; i++)
        if (!strcmp(s, simd_names[i].name)) {
            *out = simd_names[i].simd;
            return true;
        }
    return false;
}

static const char *simd_name(sgSimd simd) {
    for (size_t i = 0; i < sizeof simd_names / sizeof simd_names[0]; i++)
        if (simd_names[i].simd == simd) return simd_names[i].name;
    return "the best this CPU runs";
}

/* 0: parsed; 1: help was printed; 2: bad arguments (already reported). */
static int parse_args(int argc, char **argv, options *o) {
    bool frames_given = false;
    o->frames = FRAMES;
    o->rounds = 1;
    o->warmup = WARMUP_FRAMES;
    o->threads = default_threads();
    o->files = calloc((size_t)argc, sizeof *o->files);
    o->shader_libs = calloc((size_t)argc, sizeof *o->shader_libs);
    if (!o->files || !o->shader_libs) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return 2;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool takes_value = !strcmp(a, "--frames") || !strcmp(a, "--rounds") ||
                           !strcmp(a, "--threads") || !strcmp(a, "--simd") || !strcmp(a, "--csv") ||
                           !strcmp(a, "--plot") || !strcmp(a, "--ref") || !strcmp(a, "--shaders") ||
                           !strcmp(a, "--samples") || !strcmp(a, "--mipmap");
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) {
            usage(stdout);
            return 1;
        }
        if (takes_value && !value) {
            fprintf(stderr, "sgapi-bench: %s needs a value\n", a);
            return 2;
        }
        if (!strcmp(a, "--frames")) {
            if (!sc_parse_int(value, MIN_FRAMES, MAX_FRAMES, &o->frames)) {
                fprintf(stderr, "sgapi-bench: --frames needs a whole number in %d..%d, not '%s'\n",
                        MIN_FRAMES, MAX_FRAMES, value);
                return 2;
            }
            frames_given = true;
        } else if (!strcmp(a, "--rounds")) {
            if (!sc_parse_int(value, 1, MAX_ROUNDS, &o->rounds)) {
                fprintf(stderr, "sgapi-bench: --rounds needs a whole number in 1..%d, not '%s'\n",
                        MAX_ROUNDS, value);
                return 2;
            }
        } else if (!strcmp(a, "--threads")) {
            if (!sc_parse_int(value, 1, MAX_THREADS, &o->threads)) {
                fprintf(stderr, "sgapi-bench: --threads needs a whole number in 1..%d, not '%s'\n",
                        MAX_THREADS, value);
                return 2;
            }
        } else if (!strcmp(a, "--samples")) {
            if (!sc_parse_samples(value, &o->samples)) {
                fprintf(stderr, "sgapi-bench: --samples needs 1 or 4, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--simd")) {
            if (!parse_simd(value, &o->simd)) {
                fprintf(stderr,
                        "sgapi-bench: --simd is scalar, sse2, avx2, avx512 or neon, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--csv")) {
            o->csv = value;
        } else if (!strcmp(a, "--plot")) {
            o->plot = value;
        } else if (!strcmp(a, "--ref")) {
            o->ref = value;
        } else if (!strcmp(a, "--shaders")) {
            o->shader_libs[o->shader_lib_count++] = value;
        } else if (!strcmp(a, "--mipmap")) {
            sc_mipmap m;
            if (!sc_mipmap_from_name(value, &m)) {
                fprintf(stderr, "sgapi-bench: --mipmap needs none, nearest or linear, not '%s'\n",
                        value);
                return 2;
            }
            o->mipmap = value;
        } else if (!strcmp(a, "--pareto")) {
            o->pareto = true;
        } else if (!strcmp(a, "--quick")) {
            o->quick = true;
        } else if (!strcmp(a, "--strict")) {
            o->strict = true;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "sgapi-bench: unknown option '%s' (see --help)\n", a);
            return 2;
        } else {
            o->files[o->file_count++] = a;
        }
        if (takes_value) i++;
    }
    if (o->file_count == 0) {
        fprintf(stderr, "sgapi-bench: no scene file given\n");
        usage(stderr);
        return 2;
    }
    if (o->quick && frames_given) {
        fprintf(stderr, "sgapi-bench: --quick and --frames exclude each other\n");
        return 2;
    }
    if (o->plot && !o->pareto) {
        fprintf(stderr, "sgapi-bench: --plot only works with --pareto\n");
        return 2;
    }
    if (o->quick) {
        o->frames = QUICK_FRAMES;
        o->warmup = 0;
    }
    return 0;
}

/* ---- small helpers --------------------------------------------------------------------------- */

#define PROG         "sgapi-bench"
#define sg_fail(...) ss_fail(PROG, __VA_ARGS__)

/* a + b + c in a new string (free it), or NULL when out of memory. */
static char *concat3(const char *a, const char *b, const char *c) {
    size_t la = strlen(a), lb = strlen(b), lc = strlen(c);
    char *p = malloc(la + lb + lc + 1);
    if (!p) return NULL;
    memcpy(p, a, la);
    memcpy(p + la, b, lb);
    memcpy(p + la + lb, c, lc + 1);
    return p;
}

/* The folder part of a path ("." when it has none), in a new string. */
static char *dir_of(const char *path) {
    const char *slash = strrchr(path, '/');
    if (!slash) return concat3(".", "", "");
    size_t n = slash == path ? 1 : (size_t)(slash - path);
    char *d = malloc(n + 1);
    if (!d) return NULL;
    memcpy(d, path, n);
    d[n] = '\0';
    return d;
}

/* ---- child processes ------------------------------------------------------------------------- */

/* Runs argv[0] (looked up in PATH when it has no '/') and captures its stdout into *out
 * (NUL-terminated; free() it). Its stderr is ours, so its own messages reach the user.
 * Returns 0 when it ran, with *status its exit status (-1: killed by a signal); otherwise the
 * errno of the failure (ENOENT: no such program), with err saying what failed. */
static int run_child(char *const argv[], char **out, int *status, sc_msg *err) {
    int out_pipe[2], exec_pipe[2];
    *out = NULL;
    if (pipe(out_pipe) != 0) {
        int e = errno;
        sc_msg_set(err, "cannot run %s: pipe: %s", argv[0], strerror(e));
        return e;
    }
    /* Closed by a successful exec: the parent then reads nothing from it, and otherwise the
     * errno of the failed exec. */
    if (pipe(exec_pipe) != 0 || fcntl(exec_pipe[1], F_SETFD, FD_CLOEXEC) != 0) {
        int e = errno;
        sc_msg_set(err, "cannot run %s: pipe: %s", argv[0], strerror(e));
        close(out_pipe[0]);
        close(out_pipe[1]);
        return e;
    }
    fflush(stdout);
    fflush(stderr);
    pid_t pid = fork();
    if (pid < 0) {
        int e = errno;
        sc_msg_set(err, "cannot run %s: fork: %s", argv[0], strerror(e));
        close(out_pipe[0]);
        close(out_pipe[1]);
        close(exec_pipe[0]);
        close(exec_pipe[1]);
        return e;
    }
    if (pid == 0) {
        close(out_pipe[0]);
        close(exec_pipe[0]);
        if (dup2(out_pipe[1], STDOUT_FILENO) >= 0) {
            close(out_pipe[1]);
            execvp(argv[0], argv);
        }
        int e = errno;
        ssize_t written = write(exec_pipe[1], &e, sizeof e);
        (void)written;
        _exit(127);
    }
    close(out_pipe[1]);
    close(exec_pipe[1]);
    /* Read to the end even when out of memory, so the child never blocks on a full pipe. */
    size_t len = 0, cap = 4096;
    char *buf = malloc(cap);
    bool ok = buf != NULL;
    char chunk[4096];
    for (;;) {
        ssize_t n = read(out_pipe[0], chunk, sizeof chunk);
        if (n == 0) break;
        if (n < 0) {
            if (errno == EINTR) continue;
            break;
        }
        if (ok && len + (size_t)n + 1 > cap) {
            char *grown = realloc(buf, (len + (size_t)n + 1) * 2);
            if (grown) {
                buf = grown;
                cap = (len + (size_t)n + 1) * 2;
            } else {
                ok = false;
            }
        }
        if (ok) {
            memcpy(buf + len, chunk, (size_t)n);
            len += (size_t)n;
        }
    }
    close(out_pipe[0]);
    int exec_errno = 0;
    ssize_t got;
    do got = read(exec_pipe[0], &exec_errno, sizeof exec_errno);
    while (got < 0 && errno == EINTR);
    close(exec_pipe[0]);
    int ws = 0;
    while (waitpid(pid, &ws, 0) < 0 && errno == EINTR) {
    }
    if (got == (ssize_t)sizeof exec_errno) {
        sc_msg_set(err, "cannot run %s: %s", argv[0], strerror(exec_errno));
        free(buf);
        return exec_errno ? exec_errno : EINVAL;
    }
    if (!ok) {
        sc_msg_set(err, "out of memory reading the output of %s", argv[0]);
        free(buf);
        return ENOMEM;
    }
    buf[len] = '\0';
    *out = buf;
    *status = WIFEXITED(ws) ? WEXITSTATUS(ws) : -1;
    return 0;
}

/* sgapi-ref beside this program: the two are built into, and installed to, the same folder. */
static char *find_ref(const char *argv0) {
    /* This program's path, in a buffer grown until it holds it whole. */
    char *self = NULL;
    for (size_t cap = 256; cap <= ((size_t)1 << 20); cap *= 2) {
        char *grown = realloc(self, cap);
        if (!grown) break;
        self = grown;
        ssize_t n = readlink("/proc/self/exe", self, cap);
        if (n < 0) break;
        if ((size_t)n < cap) {
            self[n] = '\0';
            char *dir = dir_of(self);
            char *ref = dir ? concat3(dir, "/", "sgapi-ref") : NULL;
            free(dir);
            free(self);
            return ref;
        }
    }
    free(self);
    if (!strchr(argv0, '/'))
        return concat3("sgapi-ref", "", ""); /* found through PATH, as this program was */
    char *dir = dir_of(argv0);
    char *ref = dir ? concat3(dir, "/", "sgapi-ref") : NULL;
    free(dir);
    return ref;
}

/* lavapipe's median time per frame of one scene at `threads` raster threads, read from the line
 * "NAME  X ms/frame ..." that sgapi-ref prints; its image is left in tmpdir/NAME.png. */
static bool run_lavapipe(const options *o, const char *ref, const char *file, const char *scene,
                         int threads, const char *tmpdir, double *ms) {
    char frames_s[16], threads_s[16], samples_s[16];
    sc_msg err = {0};
    snprintf(samples_s, sizeof samples_s, "%d", o->samples);
    snprintf(frames_s, sizeof frames_s, "%d", o->frames);
    snprintf(threads_s, sizeof threads_s, "%d", threads);
    const char *fixed[] = {ref,   file,        "--frames", frames_s, "--scene",
                           scene, "--threads", threads_s,  "-o",     tmpdir};
    enum { FIXED = sizeof fixed / sizeof fixed[0] };
    char **argv = calloc(FIXED + 2 * (size_t)o->shader_lib_count + 5, sizeof *argv);
    if (!argv) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return false;
    }
    for (int i = 0; i < FIXED; i++) argv[i] = (char *)fixed[i];
    for (int i = 0; i < o->shader_lib_count; i++) {
        argv[FIXED + 2 * i] = "--shaders";
        argv[FIXED + 2 * i + 1] = (char *)o->shader_libs[i];
    }
    int extra = FIXED + 2 * o->shader_lib_count;
    if (o->samples) {
        argv[extra++] = "--samples";
        argv[extra++] = samples_s;
    }
    if (o->mipmap) {
        argv[extra++] = "--mipmap";
        argv[extra++] = (char *)o->mipmap;
    }
    char *out;
    int status;
    int run = run_child(argv, &out, &status, &err);
    free(argv);
    if (run != 0) {
        fprintf(stderr, "sgapi-bench: %s\n", err.text);
        sc_msg_free(&err);
        fprintf(stderr, "sgapi-bench: the lavapipe reference could not run; build sgapi-ref "
                        "(it needs the Vulkan loader and glslang) or name it with --ref PATH\n");
        return false;
    }
    if (status != 0) {
        fprintf(stderr,
                "sgapi-bench: %s failed (exit status %d) on scene '%s' of %s at %d thread(s)%s\n",
                ref, status, scene, file, threads,
                status == 1 ? " (its own message, if any, is above)" : "");
        free(out);
        return false;
    }
    bool found = false;
    size_t n = strlen(scene);
    for (char *line = out; line && *line && !found;) {
        char *next = strchr(line, '\n');
        if (next) *next++ = '\0';
        if (!strncmp(line, scene, n) && (line[n] == ' ' || line[n] == '\t')) {
            char *end;
            double v = strtod(line + n, &end);
            while (*end == ' ') end++;
            if (end != line + n && !strncmp(end, "ms/frame", 8) && isfinite(v) && v >= 0) {
                *ms = v;
                found = true;
            }
        }
        line = next;
    }
    if (!found)
        fprintf(stderr, "sgapi-bench: %s printed no time for scene '%s' of %s; it printed:\n%s\n",
                ref, scene, file, out);
    free(out);
    return found;
}

/* ---- sgapi ----------------------------------------------------------------------------------- */

/* The pipeline state of a draw, as sgapi-render makes it, then changed by the setting. */
static bool pipeline_of(const options *o, const sc_file *f, const sc_draw *d, const setting *st,
                        sgPipelineDesc *p) {
    if (!ss_pipeline_desc(PROG, f, d, o->shaders, p)) return false;
    if (st->adjust) st->adjust(p);
    return true;
}

/* Draws a scene o->warmup untimed frames, then o->frames timed ones; *ms is the median time of a
 * timed frame, and pixels, when not NULL, receives the image (width * height * 4 bytes). The
 * pipelines and targets are made before the first frame, so they are not timed. */
static bool measure_scene(sgDevice *dev, ss_pso_cache *cache, const sc_file *f, const sc_scene *s,
                          const ss_uploads *u, const setting *st, const options *o, double *ms,
                          unsigned char *pixels) {
    bool ok = false;
    sgImage2D color = {0}, depth = {0};
    ss_shadow shadow = {0};
    sgPipelineStateObject *psos = calloc(s->draw_count ? s->draw_count : 1, sizeof *psos);
    double *times = calloc((size_t)o->frames, sizeof *times);
    if (!psos || !times) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        goto done;
    }
    for (size_t i = 0; i < s->draw_count; i++) {
        sgPipelineDesc desc;
        if (!pipeline_of(o, f, &s->draws[i], st, &desc) ||
            !ss_get_pso(PROG, dev, cache, &desc, &psos[i]))
            goto done;
    }
    sgPassDesc pass;
    if (!ss_create_targets(PROG, dev, s, &color, &depth, &pass) ||
        !ss_create_shadow(PROG, dev, cache, f, s, &shadow))
        goto done;
    sgResult r;

    /* A frame is the shadow's pass and the scene's, as the reference's frame is. */
    for (int frame = -o->warmup; frame < o->frames; frame++) {
        double t0 = ss_now_ms();
        if (!ss_draw_frame(PROG, dev, f, s, u, psos, &pass, &shadow)) goto done;
        double t = ss_now_ms() - t0;
        if (frame >= 0) times[frame] = t;
    }
    if (pixels) {
        r = sgReadImage2D(dev, color, pixels, 0);
        if (r != SG_OK) {
            sg_fail(dev, r, "scene '%s': sgReadImage2D", s->name);
            goto done;
        }
    }
    *ms = ss_median(times, o->frames);
    ok = true;
done:
    ss_destroy_shadow(dev, &shadow);
    if (depth.id) sgDestroyImage2D(dev, depth);
    if (color.id) sgDestroyImage2D(dev, color);
    free(psos);
    free(times);
    return ok;
}

/* ---- the run --------------------------------------------------------------------------------- */

/* Everything measured of one scene. Index [0] of the pairs is 1 thread, [1] T threads. */
typedef struct result {
    const char *file; /* as given */
    const sc_scene *scene;
    double sg_ms[2], lp_ms[2];
    sc_image lp_image;                   /* lavapipe's, until every setting is compared with it */
    double setting_ms[SETTING_COUNT];    /* sgapi at T threads; [0] is sg_ms[1] */
    sc_diff setting_diff[SETTING_COUNT]; /* against lp_image; [0] is the main table's */
} result;

/* Runs lavapipe on one scene at 1 and T threads and keeps its image. */
static bool measure_lavapipe(const options *o, const char *ref, const char *tmpdir, result *x,
                             bool load_image) {
    const sc_scene *s = x->scene;
    char *png = concat3(tmpdir, "/", s->name);
    char *path = png ? concat3(png, ".png", "") : NULL;
    free(png);
    if (!path) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return false;
    }
    /* lavapipe draws the same image at any thread count: the last run's is kept. */
    bool ok = run_lavapipe(o, ref, x->file, s->name, 1, tmpdir, &x->lp_ms[0]);
    if (ok && o->threads == 1)
        x->lp_ms[1] = x->lp_ms[0];
    else if (ok)
        ok = run_lavapipe(o, ref, x->file, s->name, o->threads, tmpdir, &x->lp_ms[1]);
    sc_msg err = {0};
    if (ok && load_image && !sc_image_load(path, &x->lp_image, &err)) {
        fprintf(stderr, "sgapi-bench: lavapipe's image of '%s': %s\n", s->name, err.text);
        ok = false;
    }
    sc_msg_free(&err);
    remove(path); /* so the temporary folder is empty at the end, whatever happened */
    free(path);
    if (!ok) return false;
    if (load_image && (x->lp_image.width != s->width || x->lp_image.height != s->height)) {
        fprintf(stderr, "sgapi-bench: lavapipe's image of '%s' is %dx%d, the scene %dx%d\n",
                s->name, x->lp_image.width, x->lp_image.height, s->width, s->height);
        return false;
    }
    return true;
}

static bool create_device(int threads, sgSimd simd, const sc_file *files, int file_count,
                          sgDevice **dev) {
    size_t images = 0, geoms = 0;
    for (int i = 0; i < file_count; i++) {
        if (files[i].texture_count > images) images = files[i].texture_count;
        if (ss_geom_count(&files[i]) > geoms) geoms = ss_geom_count(&files[i]);
    }
    /* Pools for the largest file (its textures plus the two targets and a shadow map) and for
     * every pipeline the draws and shadows can need in every setting. */
    if (images > 65535 - 3 || geoms > 65535) {
        fprintf(stderr, "sgapi-bench: too many meshes or textures in one file\n");
        return false;
    }
    sgDeviceDesc dd;
    memset(&dd, 0, sizeof dd);
    dd.thread_count = threads;
    dd.simd = simd;
    if (images + 3 > 256) dd.image_pool_size = (int)images + 3;
    if (geoms > 1024) dd.geom_pool_size = (int)geoms;
    dd.pipeline_pool_size = ss_pipeline_pool_size(files, file_count, SETTING_COUNT);
    sgResult r = sgCreateDevice(&dd, dev);
    if (r != SG_OK)
        return sg_fail(NULL, r, "sgCreateDevice with %d thread(s), --simd %s", threads,
                       simd_name(simd));
    return true;
}

/* sgapi at one thread count: its device, pipelines and the current file's uploads. */
typedef struct side {
    int threads;
    sgDevice *dev;
    ss_pso_cache cache;
    ss_uploads uploads;
} side;

static void side_close(side *sd) {
    if (sd->dev) {
        ss_destroy_uploads(sd->dev, &sd->uploads);
        sgDestroyDevice(sd->dev); /* also destroys the cached pipelines */
    }
    ss_pso_cache_free(&sd->cache);
    memset(sd, 0, sizeof *sd);
}

/* Measures one scene (of the file uploaded to sd) into slot (0: 1 thread, 1: T threads). With
 * `compare`, also every setting in use, each compared with lavapipe's image. */
static bool measure_sgapi(const options *o, side *sd, const sc_file *f, result *x, int slot,
                          bool compare) {
    const sc_scene *s = x->scene;
    int nsettings = compare && o->pareto ? SETTING_COUNT : 1;
    unsigned char *pixels = compare ? malloc((size_t)s->width * (size_t)s->height * 4) : NULL;
    if (compare && !pixels) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return false;
    }
    unsigned char bg[4];
    for (int c = 0; c < 4; c++) bg[c] = (unsigned char)lroundf(s->clear_color[c] * 255.0f);
    bool ok = true;
    for (int k = 0; ok && k < nsettings; k++) {
        double ms;
        ok = measure_scene(sd->dev, &sd->cache, f, s, &sd->uploads, &settings[k], o, &ms, pixels);
        if (!ok) {
            fprintf(stderr, "sgapi-bench: in %s, scene '%s', setting '%s', %d thread(s)\n", f->path,
                    s->name, settings[k].name, sd->threads);
            break;
        }
        if (k == 0) x->sg_ms[slot] = ms;
        if (compare) {
            x->setting_ms[k] = ms;
            x->setting_diff[k] =
                sc_image_diff(pixels, x->lp_image.pixels, s->width, s->height, bg, NULL);
        }
    }
    free(pixels);
    return ok;
}

/* Every scene, one at a time: lavapipe at 1 and T threads, then sgapi at 1 and T threads, so
 * the four times of a scene are taken close together (a shared machine's speed drifts over a
 * run, and a ratio should not take that drift). Then the floor at both thread counts. */
static bool measure_all(const options *o, const char *ref, const char *tmpdir, const sc_file *files,
                        result *res, double floor_ms[2]) {
    side sides[2] = {{.threads = 1}, {.threads = o->threads}};
    int nsides = o->threads == 1 ? 1 : 2;
    bool ok = true;
    for (int k = 0; ok && k < nsides; k++)
        ok = create_device(sides[k].threads, o->simd, files, o->file_count, &sides[k].dev);
    size_t first = 0; /* the first result of the current file */
    for (int fi = 0; ok && fi < o->file_count; fi++) {
        const sc_file *f = &files[fi];
        fprintf(stderr, "sgapi-bench: %s: lavapipe and sgapi, scene by scene...\n", f->path);
        for (int k = 0; ok && k < nsides; k++)
            ok = ss_upload(PROG, sides[k].dev, f, &sides[k].uploads);
        for (size_t si = 0; ok && si < f->scene_count; si++) {
            result *x = &res[first + si];
            double lp[2][MAX_ROUNDS], sg[2][MAX_ROUNDS];
            for (int r = 0; ok && r < o->rounds; r++) {
                /* the images are compared in the first round */
                ok = measure_lavapipe(o, ref, tmpdir, x, r == 0);
                /* The main table's error is that of the T-thread image (the same at 1 thread). */
                for (int k = 0; ok && k < nsides; k++)
                    ok = measure_sgapi(o, &sides[k], f, x, k, r == 0 && k == nsides - 1);
                if (ok && nsides == 1) x->sg_ms[1] = x->sg_ms[0];
                for (int k = 0; k < 2; k++) {
                    lp[k][r] = x->lp_ms[k];
                    sg[k][r] = x->sg_ms[k];
                }
            }
            for (int k = 0; ok && k < 2; k++) {
                x->lp_ms[k] = ss_median(lp[k], o->rounds);
                x->sg_ms[k] = ss_median(sg[k], o->rounds);
            }
        }
        for (int k = 0; k < nsides; k++)
            if (sides[k].dev) ss_destroy_uploads(sides[k].dev, &sides[k].uploads);
        first += f->scene_count;
    }
    /* No draws: neither a file nor the uploads are looked at. */
    sc_scene empty = {.name = "floor", .width = FLOOR_SIZE, .height = FLOOR_SIZE};
    for (int k = 0; ok && k < nsides; k++)
        ok = measure_scene(sides[k].dev, &sides[k].cache, NULL, &empty, &sides[k].uploads,
                           &settings[0], o, &floor_ms[k], NULL);
    if (ok && nsides == 1) floor_ms[1] = floor_ms[0];
    for (int k = 0; k < nsides; k++) side_close(&sides[k]);
    return ok;
}

/* ---- output ---------------------------------------------------------------------------------- */

static double ratio(const result *x, int slot) {
    return x->sg_ms[slot] / x->lp_ms[slot];
}

static void print_table(const options *o, const result *res, size_t count,
                        const double floor_ms[2]) {
    int t = o->threads;
    printf("| scene | sgapi 1t ms | sgapi %dt ms | lavapipe 1t ms | lavapipe %dt ms | ratio 1t | "
           "ratio %dt | PSNR dB | %% > 2/255 |\n",
           t, t, t);
    printf("| --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    double log_sum[2] = {0, 0};
    int used[2] = {0, 0};
    for (size_t i = 0; i < count; i++) {
        const result *x = &res[i];
        printf("| %s | %.3f | %.3f | %.3f | %.3f | %.2f | %.2f | %.2f | %.4f |\n", x->scene->name,
               x->sg_ms[0], x->sg_ms[1], x->lp_ms[0], x->lp_ms[1], ratio(x, 0), ratio(x, 1),
               x->setting_diff[0].psnr_db, x->setting_diff[0].pct_over[0]);
        for (int s = 0; s < 2; s++) {
            double r = ratio(x, s);
            /* A time that rounds to 0 gives no ratio worth averaging. */
            if (isfinite(r) && r > 0) {
                log_sum[s] += log(r);
                used[s]++;
            }
        }
    }
    double mean[2];
    for (int s = 0; s < 2; s++) mean[s] = used[s] ? exp(log_sum[s] / used[s]) : NAN;
    /* At --threads 1 both columns are one measurement: said once. */
    printf("\ngeometric mean of sgapi/lavapipe over %d scene%s: 1t %.2f", used[0],
           used[0] == 1 ? "" : "s", mean[0]);
    if (t > 1) printf(", %dt %.2f", t, mean[1]);
    printf("\nfloor (sgapi, one %dx%d colour + depth frame cleared and written, no draws): 1t "
           "%.3f ms",
           FLOOR_SIZE, FLOOR_SIZE, floor_ms[0]);
    if (t > 1) printf(", %dt %.3f ms", t, floor_ms[1]);
    printf("\nsgapi's instruction set: %s\n", simd_name(o->simd));
    if (o->rounds > 1)
        printf("each time: the median of %d rounds, lavapipe and sgapi in turn, each the median of "
               "%d frames\n",
               o->rounds, o->frames);
}

static void write_csv(FILE *f, const result *res, size_t count) {
    fprintf(f, "scene,sgapi_ms_1t,sgapi_ms_nt,lavapipe_ms_1t,lavapipe_ms_nt,ratio_1t,ratio_nt,"
               "psnr_db,pct_over_2\n");
    for (size_t i = 0; i < count; i++) {
        const result *x = &res[i];
        fprintf(f, "%s,%.3f,%.3f,%.3f,%.3f,%.4f,%.4f,%.2f,%.4f\n", x->scene->name, x->sg_ms[0],
                x->sg_ms[1], x->lp_ms[0], x->lp_ms[1], ratio(x, 0), ratio(x, 1),
                x->setting_diff[0].psnr_db, x->setting_diff[0].pct_over[0]);
    }
}

static void print_pareto(const options *o, const result *res, size_t count) {
    printf("\n| scene | setting | sgapi %dt ms | PSNR dB | %% > 2/255 |\n", o->threads);
    printf("| --- | --- | ---: | ---: | ---: |\n");
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < SETTING_COUNT; k++)
            printf("| %s | %s | %.3f | %.2f | %.4f |\n", res[i].scene->name, settings[k].name,
                   res[i].setting_ms[k], res[i].setting_diff[k].psnr_db,
                   res[i].setting_diff[k].pct_over[0]);
}

static void write_pareto_csv(FILE *f, const result *res, size_t count) {
    fprintf(f, "scene,setting,sgapi_ms_nt,psnr_db,pct_over_2\n");
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < SETTING_COUNT; k++)
            fprintf(f, "%s,%s,%.3f,%.2f,%.4f\n", res[i].scene->name, settings[k].name,
                    res[i].setting_ms[k], res[i].setting_diff[k].psnr_db,
                    res[i].setting_diff[k].pct_over[0]);
}

/* Writes a gnuplot string literal: single quotes, in which only '' needs escaping. */
static void gp_string(FILE *f, const char *s) {
    fputc('\'', f);
    for (; *s; s++) {
        if (*s == '\'') fputc('\'', f);
        fputc(*s, f);
    }
    fputc('\'', f);
}

/* Where a PSNR is drawn: an infinite one (identical images) on the line at inf_y. */
static double psnr_y(double psnr, double inf_y) {
    return isfinite(psnr) ? psnr : inf_y;
}

/* Plots time against PSNR, one point per scene and setting, with gnuplot; a missing gnuplot is
 * reported and skipped, as the figures are in pareto.csv anyway. */
static bool plot_pareto(const options *o, const result *res, size_t count, const char *tmpdir) {
    const char *out = o->plot ? o->plot : "pareto.png";
    /* Identical images have an infinite PSNR: they are drawn on a line above every finite one. */
    double top = 0;
    bool any_inf = false;
    for (size_t i = 0; i < count; i++)
        for (int k = 0; k < SETTING_COUNT; k++) {
            double p = res[i].setting_diff[k].psnr_db;
            if (isfinite(p) && p > top) top = p;
            any_inf |= !isfinite(p);
        }
    double inf_y = ceil(top / 10) * 10 + 10;
    char *script = concat3(tmpdir, "/pareto.gp", "");
    FILE *f = script ? fopen(script, "w") : NULL;
    if (!f) {
        fprintf(stderr, "sgapi-bench: cannot write the gnuplot script: %s\n",
                script ? strerror(errno) : "out of memory");
        free(script);
        return false;
    }
    fprintf(f, "set terminal png size 1400,1000 noenhanced\nset output ");
    gp_string(f, out);
    fprintf(f,
            "\nset title 'sgapi at %d thread%s: time per frame against error vs lavapipe'\n"
            "set xlabel 'sgapi ms per frame (median, log scale)'\n"
            "set ylabel 'PSNR against lavapipe, dB (higher is closer)'\n"
            "set logscale x\nset grid\nset key bottom right box opaque\n"
            "set offsets graph 0.02, graph 0.15, graph 0.05, graph 0.05\n",
            o->threads, o->threads == 1 ? "" : "s");
    if (any_inf)
        fprintf(f,
                "set arrow from graph 0, first %g to graph 1, first %g nohead dt 2 lc rgb 'gray'\n"
                "set label 'identical to lavapipe (infinite PSNR)' at graph 0.01, first %g "
                "offset 0, 0.8\n",
                inf_y, inf_y, inf_y);
    for (int k = 0; k < SETTING_COUNT; k++) {
        fprintf(f, "$s%d << EOD\n", k);
        for (size_t i = 0; i < count; i++) {
            const result *x = &res[i];
            /* A setting that leaves a scene's image as an earlier one made it changed nothing
             * in that scene: its point sits on the earlier one, whose label is enough. */
            bool repeat = false;
            for (int j = 0; j < k && !repeat; j++)
                repeat = psnr_y(x->setting_diff[j].psnr_db, inf_y) ==
                             psnr_y(x->setting_diff[k].psnr_db, inf_y) &&
                         x->setting_diff[j].pct_over[0] == x->setting_diff[k].pct_over[0];
            /* Scene names are [A-Za-z0-9_.-]+, so a double-quoted field needs no escape. */
            fprintf(f, "\"%s\" %.6g %.6g\n", repeat ? "" : x->scene->name, x->setting_ms[k],
                    psnr_y(x->setting_diff[k].psnr_db, inf_y));
        }
        fprintf(f, "EOD\n");
    }
    /* Each scene's settings joined by a line: the scene's own speed/error curve. */
    fprintf(f, "$curves << EOD\n");
    for (size_t i = 0; i < count; i++) {
        for (int k = 0; k < SETTING_COUNT; k++)
            fprintf(f, "%.6g %.6g\n", res[i].setting_ms[k],
                    psnr_y(res[i].setting_diff[k].psnr_db, inf_y));
        fprintf(f, "\n");
    }
    fprintf(f, "EOD\nplot $curves using 1:2 with lines lc rgb 'gray' notitle");
    for (int k = 0; k < SETTING_COUNT; k++)
        fprintf(f,
                ", \\\n  $s%d using 2:3 with points pt 7 ps 1.5 lt %d title '%s', \\\n"
                "  $s%d using 2:3:1 with labels left offset char 0.8, 0.5 font ',8' tc lt %d "
                "notitle",
                k, k + 1, settings[k].name, k, k + 1);
    fprintf(f, "\n");
    bool ok = fclose(f) == 0;
    if (!ok) {
        fprintf(stderr, "sgapi-bench: cannot write the gnuplot script: %s\n", strerror(errno));
        remove(script);
        free(script);
        return false;
    }
    char *argv[] = {"gnuplot", script, NULL};
    char *gp_out = NULL;
    sc_msg err = {0};
    int status = 0;
    int e = run_child(argv, &gp_out, &status, &err);
    if (e == ENOENT) {
        fprintf(stderr, "sgapi-bench: gnuplot is not installed: no plot (the figures are in "
                        "pareto.csv)\n");
    } else if (e != 0) {
        fprintf(stderr, "sgapi-bench: %s\n", err.text);
        ok = false;
    } else if (status != 0) {
        fprintf(stderr, "sgapi-bench: gnuplot failed (exit status %d) drawing %s\n", status, out);
        ok = false;
    } else {
        fprintf(stderr, "sgapi-bench: wrote %s\n", out);
    }
    sc_msg_free(&err);
    free(gp_out);
    remove(script);
    free(script);
    return ok;
}

/* ---- main ------------------------------------------------------------------------------------ */

/* Opens an output file at the start, so a bad path stops the run before minutes of measuring. */
static FILE *open_output(const char *path) {
    FILE *f = fopen(path, "w");
    if (!f) fprintf(stderr, "sgapi-bench: cannot write %s: %s\n", path, strerror(errno));
    return f;
}

/* Closes an output file; a failed run removes it rather than leave it empty. */
static bool close_output(FILE *f, const char *path, bool keep) {
    if (!f) return true;
    bool ok = fclose(f) == 0;
    if (keep && !ok) fprintf(stderr, "sgapi-bench: cannot write %s: %s\n", path, strerror(errno));
    if (!keep || !ok) remove(path);
    return ok;
}

int main(int argc, char **argv) {
    options o = {0};
    int status = parse_args(argc, argv, &o);
    if (status) {
        free(o.files);
        free(o.shader_libs);
        return status == 1 ? 0 : 2;
    }
    status = 1;
    sc_file *files = NULL;
    result *res = NULL;
    size_t count = 0;
    int loaded = 0;
    sc_shaders *shaders = NULL;
    char *ref = NULL, *pareto_path = NULL, *tmpdir = NULL;
    FILE *csv = NULL, *pareto_csv = NULL;
    double floor_ms[2] = {0, 0};

    ref = o.ref ? concat3(o.ref, "", "") : find_ref(argv[0]);
    if (!ref) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        goto done;
    }
    if (strchr(ref, '/') && access(ref, X_OK) != 0) {
        fprintf(stderr,
                "sgapi-bench: cannot run the lavapipe reference %s: %s\n"
                "sgapi-bench: build sgapi-ref (it needs the Vulkan loader and glslang) or name it "
                "with --ref PATH\n",
                ref, strerror(errno));
        goto done;
    }
    if (o.pareto) {
        char *dir = o.csv ? dir_of(o.csv) : NULL;
        pareto_path =
            o.csv ? (dir ? concat3(dir, "/", "pareto.csv") : NULL) : concat3("pareto.csv", "", "");
        free(dir);
        if (!pareto_path) {
            fprintf(stderr, "sgapi-bench: out of memory\n");
            goto done;
        }
        const char *base = o.csv ? strrchr(o.csv, '/') : NULL;
        if (o.csv && !strcmp(base ? base + 1 : o.csv, "pareto.csv")) {
            fprintf(stderr,
                    "sgapi-bench: --csv %s would be overwritten by --pareto's "
                    "pareto.csv: choose another name\n",
                    o.csv);
            goto done;
        }
    }
    if (o.csv && !(csv = open_output(o.csv))) goto done;
    if (pareto_path && !(pareto_csv = open_output(pareto_path))) goto done;

    /* Everything is loaded first, so a bad file stops the run before any measuring. */
    files = calloc((size_t)o.file_count, sizeof *files);
    if (!files) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        goto done;
    }
    for (; loaded < o.file_count; loaded++) {
        sc_msg err = {0};
        if (!sc_load(o.files[loaded], &files[loaded], &err)) {
            fprintf(stderr, "sgapi-bench: %s\n", err.text);
            sc_msg_free(&err);
            goto done;
        }
        count += files[loaded].scene_count;
        if (o.samples) sc_set_samples(&files[loaded], o.samples);
    }
    sc_mipmap forced;
    if (o.mipmap && sc_mipmap_from_name(o.mipmap, &forced))
        for (int i = 0; i < loaded; i++) sc_override_mipmap(&files[i], forced);
    bool clean = true;
    for (int i = 0; i < loaded; i++)
        clean &= sc_report_warnings(&files[i], "sgapi-bench", o.strict);
    if (!clean) goto done;
    /* The shaders the files name: a problem there is a bad argument (exit 2), before any
     * measuring. */
    sc_msg shader_err = {0};
    if (!sc_shaders_prepare(&shaders, (const char *const *)o.shader_libs, o.shader_lib_count, files,
                            loaded, &shader_err)) {
        fprintf(stderr, "sgapi-bench: %s\n", shader_err.text);
        sc_msg_free(&shader_err);
        status = 2;
        goto done;
    }
    o.shaders = shaders;
    res = calloc(count ? count : 1, sizeof *res);
    if (!res) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        goto done;
    }
    for (int i = 0, n = 0; i < o.file_count; i++)
        for (size_t j = 0; j < files[i].scene_count; j++, n++) {
            res[n].file = o.files[i];
            res[n].scene = &files[i].scenes[j];
        }

    /* sgapi-ref writes its images here; they are read back and removed scene by scene. */
    const char *tmp = getenv("TMPDIR");
    tmpdir = concat3(tmp && *tmp ? tmp : "/tmp", "/sgapi-bench-", "XXXXXX");
    if (!tmpdir || !mkdtemp(tmpdir)) {
        fprintf(stderr, "sgapi-bench: cannot make a temporary folder: %s\n",
                tmpdir ? strerror(errno) : "out of memory");
        free(tmpdir);
        tmpdir = NULL;
        goto done;
    }
    if (o.quick)
        fprintf(stderr, "sgapi-bench: --quick: %d frames, no warm-up: the times mean nothing\n",
                o.frames);

    if (!measure_all(&o, ref, tmpdir, files, res, floor_ms)) goto done;

    print_table(&o, res, count, floor_ms);
    if (csv) write_csv(csv, res, count);
    if (o.pareto) {
        print_pareto(&o, res, count);
        write_pareto_csv(pareto_csv, res, count);
    }
    fflush(stdout);
    status = 0;
    if (!close_output(csv, o.csv, true)) status = 1;
    csv = NULL;
    if (pareto_csv) {
        if (close_output(pareto_csv, pareto_path, true))
            fprintf(stderr, "sgapi-bench: wrote %s\n", pareto_path);
        else
            status = 1;
        pareto_csv = NULL;
    }
    if (o.pareto && !plot_pareto(&o, res, count, tmpdir)) status = 1;
done:
    close_output(csv, o.csv, false);
    close_output(pareto_csv, pareto_path, false);
    if (tmpdir) rmdir(tmpdir);
    for (size_t i = 0; res && i < count; i++) sc_image_free(&res[i].lp_image);
    for (int i = 0; i < loaded; i++) sc_free(&files[i]);
    free(files);
    free(res);
    free(tmpdir);
    free(pareto_path);
    free(ref);
    sc_shaders_close(shaders);
    free(o.files);
    free(o.shader_libs);
    return status;
}
