/* sgapi-bench - speed against error: sgapi next to the lavapipe reference, scene by scene.
 *
 *   sgapi-bench SCENE.json... [--frames N] [--rounds R] [--threads T] [--simd SET]
 *               [--csv FILE] [--pareto [--plot OUT.png]] [--quick] [--ref PATH]
 *   sgapi-bench SCENE.json... --quality [--ground-truth N] [--scene NAME]... [--csv FILE]
 *               [--plot OUT.png] [--frames N | --quick] [--threads T]
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
 * the machine: one 1024x1024 colour + depth frame by sgapi with no draws, after frames like it
 * (so its colour target holds the clear already: what a pass costs before anything is drawn).
 *
 * --pareto also measures, at T threads, each setting of the `settings` table below and prints
 * its time and error per scene, writes pareto.csv, and plots time against PSNR with gnuplot when
 * it is installed.
 *
 * --quality measures instead, at T threads, every quality setting (1 and 4 samples x mipmap none,
 * nearest, linear) for sgapi and for lavapipe, each against the scene's ground truth (rendered
 * once per scene by sgapi-render --ground-truth N, found beside this program): time per frame,
 * PSNR and % of pixels over 8/255. It prints a markdown table, writes quality.csv (or --csv FILE)
 * and plots each scene's time against PSNR with its frontier (quality.png, or --plot OUT.png).
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

#define WARMUP_FRAMES    3
#define MIN_FRAMES       20     /* fewer gives no steady-state median */
#define FRAMES           100    /* the default: a median that a busy moment moves little */
#define MAX_FRAMES       100000 /* sgapi-ref's limit */
#define QUICK_FRAMES     2
#define MAX_ROUNDS       25
#define MAX_THREADS      1024 /* sgapi-ref's limit */
#define FLOOR_SIZE       1024
#define GROUND_TRUTH     8  /* --ground-truth's default: 64 samples a pixel */
#define MAX_GROUND_TRUTH 64 /* sgapi-render's limit */

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

/* ---- settings of --quality ------------------------------------------------------------------- */

/* A quality setting: samples a pixel and every draw's mipmap mode, for sgapi and lavapipe alike. */
typedef struct quality_setting {
    int samples;
    sc_mipmap mipmap;
    const char *mipmap_name; /* as --mipmap takes it */
} quality_setting;

static const quality_setting quality_settings[] = {
    {1, SC_MIPMAP_NONE, "none"}, /* must stay first: the gains are measured from it */
    {1, SC_MIPMAP_NEAREST, "nearest"}, {1, SC_MIPMAP_LINEAR, "linear"}, {4, SC_MIPMAP_NONE, "none"},
    {4, SC_MIPMAP_NEAREST, "nearest"}, {4, SC_MIPMAP_LINEAR, "linear"},
};
#define QUALITY_COUNT ((int)(sizeof quality_settings / sizeof quality_settings[0]))
static const char *const renderer_names[2] = {"sgapi", "lavapipe"};

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
    bool quality;       /* --quality: every quality setting against the ground truth */
    int ground_truth;   /* --ground-truth N: the ground truth's samples a side (0: not given) */
    const char **scene_names; /* --scene: only these scenes (none given: every scene) */
    int scene_name_count;
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
            "  --simd SET      sgapi's instruction set (raster, built-in shaders): scalar, sse2,\n"
            "                  avx2, avx512 or neon\n"
            "                  (default: the best this CPU runs)\n"
            "  --csv FILE      also write the table as CSV\n"
            "  --mipmap MODE   every draw's \"mipmap\" (none, nearest, linear), for sgapi and\n"
            "                  sgapi-ref alike, whatever the scenes say\n"
            "  --shaders LIB.so\n"
            "                  load the shaders of a shader library (repeatable; sgapi-ref\n"
            "                  gets the same)\n"
            "  --pareto        also measure every setting (default, nearest filter) at T threads:\n"
            "                  print a second table, write pareto.csv (beside --csv FILE, or in\n"
            "                  the current folder) and plot it when gnuplot is installed\n"
            "  --plot OUT.png  with --pareto or --quality: the plot's file (default pareto.png,\n"
            "                  quality.png)\n"
            "  --quality       instead of the table above, measure at T threads every quality\n"
            "                  setting (samples 1 and 4 x mipmap none, nearest, linear) for sgapi\n"
            "                  and lavapipe: time per frame and error against each scene's ground\n"
            "                  truth (sgapi-render --ground-truth N, found beside sgapi-bench);\n"
            "                  print a table, write quality.csv (or --csv FILE) and plot it\n"
            "  --ground-truth N\n"
            "                  with --quality: N x N samples a pixel for the ground truth, 2\n"
            "                  to %d (default %d)\n"
            "  --scene NAME    measure only this scene (repeatable; default: every scene)\n"
            "  --quick         %d frames, no warm-up: checks that everything runs; the times mean\n"
            "                  nothing\n"
            "  --ref PATH      the sgapi-ref program (default: the one beside sgapi-bench)\n"
            "  --strict        an unknown key in a scene file is an error (exit 1, nothing\n"
            "                  measured), not a warning\n"
            "  -h, --help      show this help\n",
            FLOOR_SIZE, FLOOR_SIZE, MIN_FRAMES, FRAMES, WARMUP_FRAMES, MAX_ROUNDS, MAX_GROUND_TRUTH,
            GROUND_TRUTH, QUICK_FRAMES);
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
    o->scene_names = calloc((size_t)argc, sizeof *o->scene_names);
    if (!o->files || !o->shader_libs || !o->scene_names) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return 2;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool takes_value = !strcmp(a, "--frames") || !strcmp(a, "--rounds") ||
                           !strcmp(a, "--threads") || !strcmp(a, "--simd") || !strcmp(a, "--csv") ||
                           !strcmp(a, "--plot") || !strcmp(a, "--ref") || !strcmp(a, "--shaders") ||
                           !strcmp(a, "--samples") || !strcmp(a, "--mipmap") ||
                           !strcmp(a, "--ground-truth") || !strcmp(a, "--scene");
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
        } else if (!strcmp(a, "--ground-truth")) {
            if (!sc_parse_int(value, 2, MAX_GROUND_TRUTH, &o->ground_truth)) {
                fprintf(stderr,
                        "sgapi-bench: --ground-truth needs a whole number from 2 to %d (samples "
                        "a side of each pixel), not '%s'\n",
                        MAX_GROUND_TRUTH, value);
                return 2;
            }
        } else if (!strcmp(a, "--scene")) {
            o->scene_names[o->scene_name_count++] = value;
        } else if (!strcmp(a, "--quality")) {
            o->quality = true;
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
    if (o->plot && !o->pareto && !o->quality) {
        fprintf(stderr, "sgapi-bench: --plot only works with --pareto or --quality\n");
        return 2;
    }
    const char *problem = NULL;
    if (o->ground_truth && !o->quality)
        problem = "--ground-truth only works with --quality";
    else if (o->quality && o->pareto)
        problem = "--quality and --pareto exclude each other: run them one after the other";
    else if (o->quality && o->samples)
        problem = "--quality measures 1 and 4 samples itself: drop --samples";
    else if (o->quality && o->mipmap)
        problem = "--quality measures every mipmap mode itself: drop --mipmap";
    if (problem) {
        fprintf(stderr, "sgapi-bench: %s\n", problem);
        return 2;
    }
    if (o->quality && !o->ground_truth) o->ground_truth = GROUND_TRUTH;
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

/* A program beside this one (sgapi-ref, sgapi-render): they are built into, and installed to, the
 * same folder. */
static char *find_sibling(const char *argv0, const char *name) {
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
            char *path = dir ? concat3(dir, "/", name) : NULL;
            free(dir);
            free(self);
            return path;
        }
    }
    free(self);
    if (!strchr(argv0, '/')) return concat3(name, "", ""); /* through PATH, as this program was */
    char *dir = dir_of(argv0);
    char *path = dir ? concat3(dir, "/", name) : NULL;
    free(dir);
    return path;
}

/* A child's argument vector: the n arguments of fixed, then --shaders and each library, then room
 * for `spare` more (and the closing NULL); NULL (reported) when out of memory. Freed with free. */
static char **child_argv(const options *o, const char *const *fixed, size_t n, size_t spare) {
    char **argv = calloc(n + 2 * (size_t)o->shader_lib_count + spare + 1, sizeof *argv);
    if (!argv) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return NULL;
    }
    for (size_t i = 0; i < n; i++) argv[i] = (char *)fixed[i];
    for (int i = 0; i < o->shader_lib_count; i++) {
        argv[n + 2 * (size_t)i] = "--shaders";
        argv[n + 2 * (size_t)i + 1] = (char *)o->shader_libs[i];
    }
    return argv;
}

/* lavapipe's median time per frame of one scene at `threads` raster threads, read from the line
 * "NAME  X ms/frame ..." that sgapi-ref prints; its image is left in tmpdir/NAME.png. samples
 * (0: the scene's) and mipmap (NULL: the scene's) are handed to sgapi-ref. */
static bool run_lavapipe(const options *o, const char *ref, const char *file, const char *scene,
                         int threads, const char *tmpdir, int samples, const char *mipmap,
                         double *ms) {
    char frames_s[16], threads_s[16], samples_s[16];
    sc_msg err = {0};
    snprintf(samples_s, sizeof samples_s, "%d", samples);
    snprintf(frames_s, sizeof frames_s, "%d", o->frames);
    snprintf(threads_s, sizeof threads_s, "%d", threads);
    const char *fixed[] = {ref,   file,        "--frames", frames_s, "--scene",
                           scene, "--threads", threads_s,  "-o",     tmpdir};
    enum { FIXED = sizeof fixed / sizeof fixed[0] };
    char **argv = child_argv(o, fixed, FIXED, 4);
    if (!argv) return false;
    int extra = FIXED + 2 * o->shader_lib_count;
    if (samples) {
        argv[extra++] = "--samples";
        argv[extra++] = samples_s;
    }
    if (mipmap) {
        argv[extra++] = "--mipmap";
        argv[extra++] = (char *)mipmap;
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
    int file_index;   /* into the loaded files */
    const sc_scene *scene;
    double sg_ms[2], lp_ms[2];
    sc_image lp_image;                   /* lavapipe's, until every setting is compared with it */
    double setting_ms[SETTING_COUNT];    /* sgapi at T threads; [0] is sg_ms[1] */
    sc_diff setting_diff[SETTING_COUNT]; /* against lp_image; [0] is the main table's */
    /* --quality: [0] sgapi, [1] lavapipe, at T threads, each against the ground truth */
    sc_image truth;
    double quality_ms[2][QUALITY_COUNT];
    sc_diff quality_diff[2][QUALITY_COUNT];
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
    bool ok =
        run_lavapipe(o, ref, x->file, s->name, 1, tmpdir, o->samples, o->mipmap, &x->lp_ms[0]);
    if (ok && o->threads == 1)
        x->lp_ms[1] = x->lp_ms[0];
    else if (ok)
        ok = run_lavapipe(o, ref, x->file, s->name, o->threads, tmpdir, o->samples, o->mipmap,
                          &x->lp_ms[1]);
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

/* A device for the files, with room for `upload_sets` uploads of a file at once and pipelines for
 * `settings` settings of each draw. */
static bool create_device(int threads, sgSimd simd, const sc_file *files, int file_count,
                          int upload_sets, int settings, sgDevice **dev) {
    size_t images = 0, geoms = 0;
    for (int i = 0; i < file_count; i++) {
        if (files[i].texture_count > images) images = files[i].texture_count;
        if (ss_geom_count(&files[i]) > geoms) geoms = ss_geom_count(&files[i]);
    }
    images *= (size_t)upload_sets;
    geoms *= (size_t)upload_sets;
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
    dd.pipeline_pool_size = ss_pipeline_pool_size(files, file_count, settings);
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
                        result *res, size_t count, double floor_ms[2]) {
    side sides[2] = {{.threads = 1}, {.threads = o->threads}};
    int nsides = o->threads == 1 ? 1 : 2;
    bool ok = true;
    for (int k = 0; ok && k < nsides; k++)
        ok = create_device(sides[k].threads, o->simd, files, o->file_count, 1, SETTING_COUNT,
                           &sides[k].dev);
    for (int fi = 0; ok && fi < o->file_count; fi++) {
        const sc_file *f = &files[fi];
        fprintf(stderr, "sgapi-bench: %s: lavapipe and sgapi, scene by scene...\n", f->path);
        for (int k = 0; ok && k < nsides; k++)
            ok = ss_upload(PROG, sides[k].dev, f, &sides[k].uploads);
        for (size_t i = 0; ok && i < count; i++) {
            result *x = &res[i];
            if (x->file_index != fi) continue;
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
    printf("\nfloor (sgapi, one %dx%d colour + depth frame, no draws, its clear already in the "
           "target): 1t %.3f ms",
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

/* ---- --quality ------------------------------------------------------------------------------- */

/* Loads tmpdir/NAME.png, which a child program wrote, into *img and removes the file; `whose`
 * names the image in messages. The image must be the scene's size. */
static bool take_image(const char *tmpdir, const sc_scene *s, const char *whose, sc_image *img) {
    char *path = sc_format("%s/%s.png", tmpdir, s->name);
    if (!path) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return false;
    }
    sc_msg err = {0};
    bool ok = sc_image_load(path, img, &err);
    if (!ok) fprintf(stderr, "sgapi-bench: %s image of '%s': %s\n", whose, s->name, err.text);
    sc_msg_free(&err);
    remove(path); /* so the temporary folder is empty at the end, whatever happened */
    free(path);
    if (ok && (img->width != s->width || img->height != s->height)) {
        fprintf(stderr, "sgapi-bench: %s image of '%s' is %dx%d, the scene %dx%d\n", whose, s->name,
                img->width, img->height, s->width, s->height);
        sc_image_free(img);
        ok = false;
    }
    return ok;
}

/* The ground truth of one scene, drawn by sgapi-render --ground-truth N into x->truth. */
static bool render_truth(const options *o, const char *render, const char *tmpdir, result *x) {
    char n_s[16], threads_s[16];
    snprintf(n_s, sizeof n_s, "%d", o->ground_truth);
    snprintf(threads_s, sizeof threads_s, "%d", o->threads);
    const char *fixed[] = {render,           x->file, "--scene",   x->scene->name,
                           "--ground-truth", n_s,     "--threads", threads_s,
                           "--frames",       "1",     "-o",        tmpdir};
    enum { FIXED = sizeof fixed / sizeof fixed[0] };
    char **argv = child_argv(o, fixed, FIXED, 0);
    if (!argv) return false;
    char *out = NULL;
    int status = 0;
    sc_msg err = {0};
    int run = run_child(argv, &out, &status, &err);
    free(argv);
    free(out);
    if (run != 0) {
        fprintf(stderr,
                "sgapi-bench: %s\nsgapi-bench: --quality needs sgapi-render beside sgapi-bench for "
                "the ground truth\n",
                err.text);
        sc_msg_free(&err);
        return false;
    }
    if (status != 0) {
        fprintf(stderr,
                "sgapi-bench: %s failed (exit status %d) on the ground truth of scene '%s' of "
                "%s%s\n",
                render, status, x->scene->name, x->file,
                status == 1 || status == 2 ? " (its own message is above)" : "");
        return false;
    }
    return take_image(tmpdir, x->scene, "the ground truth's", &x->truth);
}

/* Every scene chosen, one at a time: its ground truth, then each quality setting, lavapipe and
 * sgapi back to back at T threads (--rounds R: R times in turn, the medians kept). sgapi's device
 * holds each file twice, its textures with one level and with their chains, as sgapi-render
 * uploads them for a scene without and with mipmaps. */
static bool measure_quality(const options *o, const char *ref, const char *render,
                            const char *tmpdir, sc_file *files, result *res, size_t count) {
    side sd = {.threads = o->threads};
    ss_uploads up[2]; /* [0] textures of one level, [1] with their chains */
    memset(up, 0, sizeof up);
    unsigned char *pixels = NULL;
    bool ok =
        create_device(o->threads, o->simd, files, o->file_count, 2, QUALITY_COUNT + 1, &sd.dev);
    for (int fi = 0; ok && fi < o->file_count; fi++) {
        sc_file *f = &files[fi];
        bool used = false;
        for (size_t i = 0; i < count; i++) used |= res[i].file_index == fi;
        if (!used) continue;
        fprintf(stderr,
                "sgapi-bench: %s: the ground truth, then lavapipe and sgapi, setting by "
                "setting...\n",
                f->path);
        sc_override_mipmap(f, SC_MIPMAP_NONE);
        ok = ss_upload(PROG, sd.dev, f, &up[0]);
        sc_override_mipmap(f, SC_MIPMAP_LINEAR);
        ok = ok && ss_upload(PROG, sd.dev, f, &up[1]);
        for (size_t i = 0; ok && i < count; i++) {
            result *x = &res[i];
            const sc_scene *s = x->scene;
            if (x->file_index != fi) continue;
            ok = render_truth(o, render, tmpdir, x);
            unsigned char *grown =
                ok ? realloc(pixels, (size_t)s->width * (size_t)s->height * 4) : NULL;
            if (ok && !grown) {
                fprintf(stderr, "sgapi-bench: out of memory\n");
                ok = false;
            }
            if (grown) pixels = grown;
            unsigned char bg[4];
            for (int c = 0; c < 4; c++) bg[c] = (unsigned char)lroundf(s->clear_color[c] * 255.0f);
            double t[2][QUALITY_COUNT][MAX_ROUNDS];
            for (int r = 0; ok && r < o->rounds; r++)
                for (int k = 0; ok && k < QUALITY_COUNT; k++) {
                    const quality_setting *q = &quality_settings[k];
                    ok = run_lavapipe(o, ref, x->file, s->name, o->threads, tmpdir, q->samples,
                                      q->mipmap_name, &t[1][k][r]);
                    sc_image lp = {0};
                    /* the images are compared in the first round */
                    if (ok && r == 0 && (ok = take_image(tmpdir, s, "lavapipe's", &lp)))
                        x->quality_diff[1][k] = sc_image_diff(lp.pixels, x->truth.pixels, s->width,
                                                              s->height, bg, NULL);
                    sc_image_free(&lp);
                    if (!ok) break;
                    char *left = sc_format("%s/%s.png", tmpdir, s->name);
                    if (left) remove(left); /* a later round's image, not looked at */
                    free(left);
                    sc_set_samples(f, q->samples);
                    sc_override_mipmap(f, q->mipmap);
                    ok = measure_scene(sd.dev, &sd.cache, f, s, &up[q->mipmap != SC_MIPMAP_NONE],
                                       &settings[0], o, &t[0][k][r], r == 0 ? pixels : NULL);
                    if (!ok)
                        fprintf(stderr, "sgapi-bench: in %s, scene '%s', %d sample(s), mipmap %s\n",
                                f->path, s->name, q->samples, q->mipmap_name);
                    else if (r == 0)
                        x->quality_diff[0][k] =
                            sc_image_diff(pixels, x->truth.pixels, s->width, s->height, bg, NULL);
                }
            for (int side_k = 0; ok && side_k < 2; side_k++)
                for (int k = 0; k < QUALITY_COUNT; k++)
                    x->quality_ms[side_k][k] = ss_median(t[side_k][k], o->rounds);
        }
        for (int k = 0; k < 2; k++) ss_destroy_uploads(sd.dev, &up[k]);
    }
    free(pixels);
    side_close(&sd);
    return ok;
}

/* Whether setting k of renderer r lies on its scene's frontier: no other point of the scene (either
 * renderer) is at least as fast and at least as close to the ground truth, and better in one. */
static bool on_frontier(const result *x, int r, int k) {
    double ms = x->quality_ms[r][k], db = x->quality_diff[r][k].psnr_db;
    for (int r2 = 0; r2 < 2; r2++)
        for (int k2 = 0; k2 < QUALITY_COUNT; k2++) {
            double ms2 = x->quality_ms[r2][k2], db2 = x->quality_diff[r2][k2].psnr_db;
            if ((r2 != r || k2 != k) && ms2 <= ms && db2 >= db && (ms2 < ms || db2 > db))
                return false;
        }
    return true;
}

/* PSNR gain of setting k over the scene's first setting (1 sample, no mipmaps), same renderer. */
static double quality_gain(const result *x, int r, int k) {
    return x->quality_diff[r][k].psnr_db - x->quality_diff[r][0].psnr_db;
}

static void print_quality(const options *o, const result *res, size_t count) {
    int t = o->threads;
    printf("| scene | samples | mipmap | sgapi %dt ms | lavapipe %dt ms | sgapi PSNR dB | "
           "lavapipe PSNR dB | sgapi gain dB | lavapipe gain dB | sgapi %% > 8/255 | "
           "lavapipe %% > 8/255 | frontier |\n",
           t, t);
    printf("| --- | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | --- |\n");
    for (size_t i = 0; i < count; i++) {
        const result *x = &res[i];
        for (int k = 0; k < QUALITY_COUNT; k++) {
            bool f0 = on_frontier(x, 0, k), f1 = on_frontier(x, 1, k);
            printf(
                "| %s | %d | %s | %.3f | %.3f | %.2f | %.2f | %+.2f | %+.2f | %.3f | %.3f | %s |\n",
                x->scene->name, quality_settings[k].samples, quality_settings[k].mipmap_name,
                x->quality_ms[0][k], x->quality_ms[1][k], x->quality_diff[0][k].psnr_db,
                x->quality_diff[1][k].psnr_db, quality_gain(x, 0, k), quality_gain(x, 1, k),
                x->quality_diff[0][k].pct_over[1], x->quality_diff[1][k].pct_over[1],
                f0 && f1 ? "both"
                : f0     ? "sgapi"
                : f1     ? "lavapipe"
                         : "");
        }
    }
    printf(
        "\nerror against each scene's ground truth (sgapi-render --ground-truth %d: %d samples a "
        "pixel, bilinear, no mipmaps); gain: PSNR over the same renderer's 1 sample, no "
        "mipmaps; frontier: no other point of the scene is both as fast and as close\n"
        "sgapi's instruction set: %s\n",
        o->ground_truth, o->ground_truth * o->ground_truth, simd_name(o->simd));
    if (o->rounds > 1)
        printf("each time: the median of %d rounds, lavapipe and sgapi in turn, each the median of "
               "%d frames\n",
               o->rounds, o->frames);
}

static void write_quality_csv(FILE *f, const result *res, size_t count) {
    fprintf(f, "scene,renderer,samples,mipmap,ms,psnr_db,pct_over_8,gain_db,frontier\n");
    for (size_t i = 0; i < count; i++)
        for (int r = 0; r < 2; r++)
            for (int k = 0; k < QUALITY_COUNT; k++) {
                const result *x = &res[i];
                fprintf(f, "%s,%s,%d,%s,%.3f,%.2f,%.4f,%.2f,%d\n", x->scene->name,
                        renderer_names[r], quality_settings[k].samples,
                        quality_settings[k].mipmap_name, x->quality_ms[r][k],
                        x->quality_diff[r][k].psnr_db, x->quality_diff[r][k].pct_over[1],
                        quality_gain(x, r, k), on_frontier(x, r, k) ? 1 : 0);
            }
}

/* Runs gnuplot on a script; a missing gnuplot is reported and skipped, as the figures are in the
 * CSV anyway. */
static bool run_gnuplot(const char *script, const char *out, const char *csv) {
    char *argv[] = {"gnuplot", (char *)script, NULL};
    char *gp_out = NULL;
    sc_msg err = {0};
    int status = 0;
    bool ok = true;
    int e = run_child(argv, &gp_out, &status, &err);
    if (e == ENOENT) {
        fprintf(stderr, "sgapi-bench: gnuplot is not installed: no plot (the figures are in %s)\n",
                csv);
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
    return ok;
}

/* Whether settings j and k of renderer r gave the scene the same error (as good as the same
 * image: its PSNR and share of pixels over 8/255 to the last bit). */
static bool same_image(const result *x, int r, int j, int k) {
    const sc_diff *a = &x->quality_diff[r][j], *b = &x->quality_diff[r][k];
    return a->psnr_db == b->psnr_db && a->pct_over[1] == b->pct_over[1] &&
           a->mean_abs_error == b->mean_abs_error;
}

/* The gnuplot script tmpdir/name, opened for writing (its path in *path, to free); NULL, said on
 * stderr, when it cannot be. */
static FILE *open_script(const char *tmpdir, const char *name, char **path) {
    *path = concat3(tmpdir, name, "");
    FILE *f = *path ? fopen(*path, "w") : NULL;
    if (!f) {
        fprintf(stderr, "sgapi-bench: cannot write the gnuplot script: %s\n",
                *path ? strerror(errno) : "out of memory");
        free(*path);
        *path = NULL;
    }
    return f;
}

/* One panel a scene: time against PSNR for each setting of each renderer, the frontier joined. */
static bool plot_quality(const options *o, const result *res, size_t count, const char *tmpdir,
                         const char *csv) {
    const char *out = o->plot ? o->plot : "quality.png";
    int cols = count > 1 ? 2 : 1, rows = (int)((count + (size_t)cols - 1) / (size_t)cols);
    char *script = NULL;
    FILE *f = open_script(tmpdir, "/quality.gp", &script);
    if (!f) return false;
    static const char *const colour[2] = {"#1f6fb4", "#c8322a"};
    fprintf(f, "set terminal png size %d,%d noenhanced\nset output ",
            800 * cols + (cols == 1) * 100, 560 * rows + 40);
    gp_string(f, out);
    fprintf(f,
            "\nset multiplot layout %d,%d title 'Which setting? Time per frame at %d thread%s "
            "against PSNR vs the %dx%d ground truth: up and left is better'\n"
            "set xlabel 'ms per frame (median, log scale)'\n"
            "set ylabel 'PSNR against the ground truth, dB'\n"
            "set logscale x\nset grid\nset key bottom right box opaque font ',9'\n"
            "set offsets graph 0.06, graph 0.3, graph 0.1, graph 0.1\n",
            rows, cols, o->threads, o->threads == 1 ? "" : "s", o->ground_truth, o->ground_truth);
    for (size_t i = 0; i < count; i++) {
        const result *x = &res[i];
        double top = 0;
        for (int r = 0; r < 2; r++)
            for (int k = 0; k < QUALITY_COUNT; k++)
                if (isfinite(x->quality_diff[r][k].psnr_db) && x->quality_diff[r][k].psnr_db > top)
                    top = x->quality_diff[r][k].psnr_db;
        double inf_y = ceil(top / 10) * 10 + 10;
        fprintf(f, "set title ");
        gp_string(f, x->scene->name);
        fprintf(f, "\n");
        for (int r = 0; r < 2; r++) {
            fprintf(f, "$r%d << EOD\n", r);
            for (int k = 0; k < QUALITY_COUNT; k++) {
                /* Settings that give the same image (mipmaps on an untextured scene) share one
                 * point and one label, written at the first of them. */
                bool repeat = false;
                for (int j = 0; j < k && !repeat; j++) repeat = same_image(x, r, j, k);
                fprintf(f, "\"");
                for (int j = k; j < QUALITY_COUNT && !repeat; j++)
                    if (j == k)
                        fprintf(f, "%dx %s", quality_settings[j].samples,
                                quality_settings[j].mipmap_name);
                    else if (same_image(x, r, k, j) &&
                             quality_settings[j].samples == quality_settings[k].samples)
                        fprintf(f, "/%s", quality_settings[j].mipmap_name);
                    else if (same_image(x, r, k, j))
                        fprintf(f, ", %dx %s", quality_settings[j].samples,
                                quality_settings[j].mipmap_name);
                fprintf(f, "\" %.6g %.6g\n", x->quality_ms[r][k],
                        psnr_y(x->quality_diff[r][k].psnr_db, inf_y));
            }
            fprintf(f, "EOD\n");
        }
        /* The frontier, fastest first: its points are ordered by time and by PSNR alike. */
        fprintf(f, "$frontier << EOD\n");
        bool done[2][QUALITY_COUNT] = {{false}};
        for (;;) {
            int br = -1, bk = -1;
            for (int r = 0; r < 2; r++)
                for (int k = 0; k < QUALITY_COUNT; k++)
                    if (!done[r][k] && on_frontier(x, r, k) &&
                        (br < 0 || x->quality_ms[r][k] < x->quality_ms[br][bk])) {
                        br = r;
                        bk = k;
                    }
            if (br < 0) break;
            done[br][bk] = true;
            fprintf(f, "%.6g %.6g\n", x->quality_ms[br][bk],
                    psnr_y(x->quality_diff[br][bk].psnr_db, inf_y));
        }
        fprintf(f, "EOD\nplot $frontier using 1:2 with lines lw 2 dt 2 lc rgb 'gray30' "
                   "title 'frontier'");
        for (int r = 0; r < 2; r++)
            fprintf(f,
                    ", \\\n  $r%d using 2:3 with points pt %d ps 1.6 lc rgb '%s' title '%s', \\\n"
                    "  $r%d using 2:3:1 with labels %s offset char %s font ',8' tc rgb '%s' "
                    "notitle",
                    r, r == 0 ? 7 : 5, colour[r], renderer_names[r], r, r == 0 ? "left" : "right",
                    r == 0 ? "0.9, 0.5" : "-0.9, -0.5", colour[r]);
        fprintf(f, "\n");
    }
    fprintf(f, "unset multiplot\n");
    bool ok = fclose(f) == 0;
    if (!ok)
        fprintf(stderr, "sgapi-bench: cannot write the gnuplot script: %s\n", strerror(errno));
    else
        ok = run_gnuplot(script, out, csv);
    remove(script);
    free(script);
    return ok;
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
    char *script = NULL;
    FILE *f = open_script(tmpdir, "/pareto.gp", &script);
    if (!f) return false;
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
    ok = run_gnuplot(script, out, "pareto.csv");
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

/* Whether the program at path (from find_sibling or --ref; NULL: out of memory) can be run:
 * false, reported with what and the hint, when it names a file that is not executable. */
static bool runnable(const char *path, const char *what, const char *hint) {
    if (!path) {
        fprintf(stderr, "sgapi-bench: out of memory\n");
        return false;
    }
    if (strchr(path, '/') && access(path, X_OK) != 0) {
        fprintf(stderr, "sgapi-bench: cannot run %s%s: %s\nsgapi-bench: %s\n", what, path,
                strerror(errno), hint);
        return false;
    }
    return true;
}

int main(int argc, char **argv) {
    options o = {0};
    int status = parse_args(argc, argv, &o);
    if (status) {
        free(o.files);
        free(o.shader_libs);
        free(o.scene_names);
        return status == 1 ? 0 : 2;
    }
    status = 1;
    sc_file *files = NULL;
    result *res = NULL;
    size_t count = 0;
    int loaded = 0;
    sc_shaders *shaders = NULL;
    char *ref = NULL, *render = NULL, *pareto_path = NULL, *tmpdir = NULL;
    FILE *csv = NULL, *pareto_csv = NULL;
    double floor_ms[2] = {0, 0};

    ref = o.ref ? concat3(o.ref, "", "") : find_sibling(argv[0], "sgapi-ref");
    if (!runnable(ref, "the lavapipe reference ",
                  "build sgapi-ref (it needs the Vulkan loader and glslang) or name it with "
                  "--ref PATH"))
        goto done;
    if (o.quality) {
        render = find_sibling(argv[0], "sgapi-render");
        if (!runnable(render, "",
                      "--quality needs sgapi-render beside sgapi-bench for the ground truth"))
            goto done;
        if (!o.csv) o.csv = "quality.csv";
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
    if (!sc_shaders_prepare(&shaders, o.simd, (const char *const *)o.shader_libs,
                            o.shader_lib_count, files, loaded, &shader_err)) {
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
    /* The scenes to measure: every one, or those --scene names, in file order. */
    count = 0;
    for (int i = 0; i < o.file_count; i++)
        for (size_t j = 0; j < files[i].scene_count; j++) {
            bool chosen = o.scene_name_count == 0;
            for (int k = 0; k < o.scene_name_count && !chosen; k++)
                chosen = !strcmp(o.scene_names[k], files[i].scenes[j].name);
            if (!chosen) continue;
            res[count].file = o.files[i];
            res[count].file_index = i;
            res[count].scene = &files[i].scenes[j];
            count++;
        }
    for (int k = 0; k < o.scene_name_count; k++) {
        bool found = false;
        for (size_t i = 0; i < count && !found; i++)
            found = !strcmp(o.scene_names[k], res[i].scene->name);
        if (!found) {
            fprintf(stderr, "sgapi-bench: --scene %s: no scene of that name in the files given\n",
                    o.scene_names[k]);
            status = 2;
            goto done;
        }
    }
    /* The ground truth's size is checked before minutes of measuring, as sgapi-render would. */
    for (size_t i = 0; o.quality && i < count; i++) {
        const sc_scene *s = res[i].scene;
        if ((int64_t)s->width * o.ground_truth > SC_MAX_IMAGE_SIZE ||
            (int64_t)s->height * o.ground_truth > SC_MAX_IMAGE_SIZE) {
            fprintf(stderr,
                    "sgapi-bench: %s: scene '%s' is %d x %d: its ground truth at --ground-truth "
                    "%d would be %lld x %lld, over the largest image side %d: give a smaller "
                    "--ground-truth\n",
                    res[i].file, s->name, s->width, s->height, o.ground_truth,
                    (long long)s->width * o.ground_truth, (long long)s->height * o.ground_truth,
                    SC_MAX_IMAGE_SIZE);
            status = 2;
            goto done;
        }
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

    if (o.quality) {
        if (!measure_quality(&o, ref, render, tmpdir, files, res, count)) goto done;
        print_quality(&o, res, count);
        write_quality_csv(csv, res, count);
        fflush(stdout);
        status = 0;
        if (close_output(csv, o.csv, true))
            fprintf(stderr, "sgapi-bench: wrote %s\n", o.csv);
        else
            status = 1;
        csv = NULL;
        if (!plot_quality(&o, res, count, tmpdir, o.csv)) status = 1;
        goto done;
    }
    if (!measure_all(&o, ref, tmpdir, files, res, count, floor_ms)) goto done;

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
    for (size_t i = 0; res && i < count; i++) {
        sc_image_free(&res[i].lp_image);
        sc_image_free(&res[i].truth);
    }
    for (int i = 0; i < loaded; i++) sc_free(&files[i]);
    free(files);
    free(res);
    free(tmpdir);
    free(pareto_path);
    free(ref);
    free(render);
    sc_shaders_close(shaders);
    free(o.files);
    free(o.shader_libs);
    free(o.scene_names);
    return status;
}
