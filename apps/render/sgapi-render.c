/* sgapi-render - renders every scene of scene files with sgapi and writes one PNG per scene, or a
 * turntable of each scene (a PNG per frame, and a GIF and an MP4 through ffmpeg).
 *
 *   sgapi-render [--frames N] [--scene NAME]... [--threads T] [--simd SET] SCENE.json... -o DIR
 *   sgapi-render SCENE.json... -o DIR --turntable N [--up I] [--spin I] [--video gif,mp4]
 *                [--shard I/N] [--resume] [--progress-file F] [--assemble]
 *
 * Writes DIR/<scene name>.png and prints, per scene, the wall-clock time of one frame: the time
 * from sgBeginRenderPass to the return of sgEndRenderPass, of the shadow's depth-only pass and the
 * scene's pass together when the scene has a shadow (loading and uploads are not counted), the
 * median over N frames. A turntable writes DIR/<scene name>/0000.png ... and prints, per scene,
 * its frames per second from its first frame to its last written file; each frame, once on
 * disk, gets a line "frame <scene>/<frame>.png <ms> ms", and the run a summary line last.
 *
 * Exit status: 0 done, every item on disk; 1 not all done: a failure while loading, rendering or
 * writing (named on stderr; what was written is whole, --resume renders the rest); 2 bad arguments
 * or a setup that cannot work (an unwritable DIR, no ffmpeg for --video, a --shaders library that
 * cannot be used, a shader draw its shader refuses), found before any rendering.
 */
#define _POSIX_C_SOURCE 200809L

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

#include <sgapi/sgapi.h>

#include "cli.h"
#include "batch_log.h"
#include "frame_check.h"
#include "frame_writer.h"
#include "image_diff.h"
#include "image_io.h"
#include "junit.h"
#include "model.h"
#include "progress.h"
#include "regression.h"
#include "report.h"
#include "scene_sgapi.h"
#include "scene.h"
#include "scene_keys.h"
#include "thresholds.h"
#include "turntable.h"
#include "video.h"

typedef struct options {
    const char *out_dir;
    int frames;
    bool frame_times; /* --frame-times: each frame's time to stderr (the first frame's own cost) */
    int threads;
    int samples;       /* --samples: every scene's samples a pixel (0: as the scenes say) */
    size_t bin_memory; /* --bin-memory: sgDeviceDesc.bin_memory_limit (0: the default) */
    sgSimd simd;
    const char **files;
    int file_count;
    const char **scenes; /* --scene filters; none: every scene */
    int scene_count;
    const char *compare_dir; /* --compare: reference images, one DIR/<scene>.png per scene */
    double min_psnr, max_over2, max_coverage; /* thresholds of --compare; < 0: none */
    const char *thresholds_path;              /* --thresholds: per-scene targets (CSV) */
    const char *junit_path;                   /* --junit: JUnit XML of the comparison */
    const char *report_dir;                   /* --report: HTML report folder */
    bool update_golden;                       /* --update-golden: bless failing scenes */
    bool depth_only; /* --depth-only: the scene's pass without its colour target */
    bool frames_given;
    int turntable;                /* --turntable N: frames of a turn; 0: still images */
    int spin;                     /* --spin I: the draw that spins; -1: the camera orbits */
    int up;                       /* --up I: the axis is draw I's +y; -1: view-space +y */
    int shard_index, shard_count; /* --shard I/N: every item k with k mod N = I; 0/1: all */
    bool shard_given;
    bool resume;               /* --resume: items whole on disk are not rendered again */
    const char *progress_path; /* --progress-file: events as JSON lines */
    unsigned video;            /* --video: VIDEO_GIF | VIDEO_MP4 */
    int fps;                   /* --fps: of the videos */
    int video_width;           /* --video-width: of the videos; 0: the frames' */
    bool assemble;             /* --assemble: only make the videos of frames on disk */
    bool quiet;                /* --quiet: no progress bar */
    bool strict;               /* --strict: an unknown key in a scene file is an error */
    bool no_write;             /* --no-write: render and read back, write nothing */
    int ground_truth;          /* --ground-truth N: N x N samples a pixel, box-filtered; 0: off */
    int writers;   /* --writers: threads writing turntable frames; 0: the rendering thread; -1:
                      default */
    int png_level; /* --png-level; -1: the run's default */
    int model_width, model_height; /* --size: of the images of model files */
    const char **shader_libs;      /* --shaders: shader libraries to load, in order */
    int shader_lib_count;
    int mipmap; /* --mipmap: an sc_mipmap every draw takes; -1: as the scenes say */
} options;

static void usage(FILE *f) {
    fprintf(f, "usage: sgapi-render [options] SCENE.json|MODEL.obj|MODEL.off... -o DIR\n"
               "Renders every scene of the files to DIR/<scene name>.png and prints each scene's\n"
               "time per frame (render passes only). A model file (.obj with its materials, .off)\n"
               "is a scene of its own named after the file (DIR/<stem>.png): the camera framed\n"
               "on the model's bounding sphere, a default light, its colours and textures.\n"
               "  --size WxH      image size of model files (default 1024x768)\n"
               "  --mipmap MODE   every draw's \"mipmap\" (none, nearest, linear), whatever the\n"
               "                  scenes say\n"
               "  --shaders LIB.so\n"
               "                  load the shaders of a shader library (repeatable): scene\n"
               "                  files name them with \"shader\" (docs/scene-format.md)\n"
               "  -o DIR          output folder, created if missing (required)\n"
               "  --frames N      render each scene N times and print the median (default 1)\n"
               "  --frame-times   print each frame's time to stderr, first frame first (the first\n"
               "                  grows the device's storage to the scene's size)\n"
               "  --scene NAME    render only scenes of that name (repeatable)\n"
               "  --threads T     worker threads for the device (default 0: all cores)\n"
               "  --samples N     samples a pixel, 1 or 4, for every scene (default: each\n"
               "                  scene's \"samples\")\n"
               "  --bin-memory B  bytes of binned work a pass holds before it renders them and\n"
               "                  goes on (sgDeviceDesc.bin_memory_limit; default 0: 256 MiB;\n"
               "                  same images)\n"
               "  --simd SET      instruction set of the raster and the built-in shaders: scalar,\n"
               "                  sse2, avx2, avx512 or neon (default: the best this CPU runs;\n"
               "                  all give the same images)\n"
               "  --compare DIR   compare each image with DIR/<scene name>.png: print PSNR,\n"
               "                  %% of pixels over 2/255 and coverage mismatch next to the time,\n"
               "                  and write DIR_OUT/<scene name>-heat.png\n"
               "                  exit 1 when a scene is past its thresholds (default PSNR\n"
               "                  >= 40 dB, <= 0.5 %% of pixels over 2/255, coverage <= 0.05 %%)\n"
               "                  or its golden image is missing, unreadable or of another size\n"
               "  --min-psnr DB, --max-over2 PCT, --max-coverage PCT\n"
               "                  with --compare: these thresholds for every scene\n"
               "  --thresholds F  per-scene thresholds, rows of the CSV file F:\n"
               "                  suite,scene,min_psnr_db,max_pct_over_2,max_coverage_pct\n"
               "                  (suite: the scene file's stem, its folder's name, or *)\n"
               "  --junit F.xml   write the comparison as JUnit XML (one testcase per scene)\n"
               "  --report DIR    write DIR/index.html, a self-contained report (expected,\n"
               "                  actual and heat map of every scene), and DIR/results.json\n"
               "  --update-golden write the images of failing and missing scenes into the\n"
               "                  --compare folder (listing them); passing ones are untouched\n"
               "  --depth-only    render each scene's pass with its depth target alone (a\n"
               "                  depth-only pass, no shadow pass) and write the depth as a grey\n"
               "                  image, white near, black at the far plane: the time of\n"
               "                  visibility alone\n"
               "  --png-level L   PNG compression, 0 (fastest, largest: pixels stored as they\n"
               "                  are, but repeated rows and runs of one colour) to 12\n"
               "                  (smallest); default 6 for still images, 0 for turntable\n"
               "                  frames\n"
               "  --ground-truth N\n"
               "                  the ground truth: render each scene at N times its width and\n"
               "                  height (8 is the usual N; one sample, bilinear textures, no\n"
               "                  mipmaps) and box-filter it down, N x N samples a pixel, into\n"
               "                  DIR/<scene name>.png like a plain render\n"
               "  --no-write      render and read each image back, but write no file (to time\n"
               "                  the rendering alone against a run that writes)\n"
               "  --strict        an unknown key in a scene file is an error (exit 1, nothing\n"
               "                  rendered), not a warning\n"
               "  --quiet         no progress bar (it is drawn on stderr only when stderr is a\n"
               "                  terminal: frames done of all, frames per second, time left)\n"
               "  --shard I/N     render only the items k (scenes in order; with --turntable\n"
               "                  every frame of every scene, counted on across scenes) with\n"
               "                  k mod N = I, 0 <= I < N: N such runs together write exactly\n"
               "                  the files of one run without --shard, byte for byte\n"
               "  --resume        skip the images and frames already whole on disk (a PNG of\n"
               "                  the scene's size, every chunk whole), render the rest: a\n"
               "                  run stopped half-way (a task killed or requeued) ends with\n"
               "                  the files of an uninterrupted run; a file of another size or\n"
               "                  cut short is rendered again and named on stderr\n"
               "  --progress-file F\n"
               "                  append the run's events to F as JSON lines (start, each\n"
               "                  item done, skipped or redone, end with the exit status), each\n"
               "                  flushed at once, for job monitors\n"
               "Turntables:\n"
               "  --turntable N   render N frames of each scene to DIR/<scene name>/0000.png ...\n"
               "                  (more digits past 10000 frames): the camera orbits the centre\n"
               "                  of the scene's view-space box about the view's vertical axis,\n"
               "                  frame k at 360 k / N degrees, moving to its right (the scene\n"
               "                  turns clockwise seen from above); frame 0 is the scene as\n"
               "                  written; the lights turn with the scene; prints frames/s\n"
               "  --spin I        instead, only draw I (0: the scene's first) turns, the same\n"
               "                  way, about the centre of its own box; camera and lights stay\n"
               "  --up I          turn about draw I's own +y as it is in view space instead of\n"
               "                  the view's vertical: the up of a floor the camera looks down\n"
               "                  on (about the view's vertical, half a turn would look at the\n"
               "                  floor from below)\n"
               "  --video LIST    also write DIR/<scene name>.gif and/or .mp4 (LIST: gif, mp4 or\n"
               "                  gif,mp4) with ffmpeg: a palette-optimised GIF, H.264 in yuv420p\n"
               "  --fps F         frames per second of the videos (default 25)\n"
               "  --video-width W scale the videos to W pixels wide (default: the frames' size)\n"
               "  --assemble      render nothing: make the videos from the frames already in\n"
               "                  DIR (the final step after a run split with --shard)\n"
               "  --writers W     threads that encode and write frames while the next ones\n"
               "                  render (default: one per core, at least 2; 0: the rendering\n"
               "                  thread writes each frame before it renders the next)\n"
               "  -h, --help      show this help\n"
               "Output: a line per still image (its time per frame) or per frame written\n"
               "(\"frame <scene>/0007.png 12.34 ms\", its rendering time) as each is on disk;\n"
               "with --turntable, --shard, --resume or --progress-file a summary line last\n"
               "(\"done: ...\" or \"failed: ...\", with what was rendered and skipped).\n"
               "Exit status: 0 all done (every item of the run, or of its shard, on disk); 1 some\n"
               "failed: an item could not be loaded, rendered or written (named on stderr; the\n"
               "files written are whole, run again with --resume for the rest); 2 bad arguments\n"
               "or setup (found before anything is rendered).\n");
}

/* "I/N" with 0 <= I < N. */
static bool parse_shard(const char *value, options *o) {
    const char *slash = strchr(value, '/');
    char first[32];
    if (!slash || slash - value >= (long)sizeof first) return false;
    memcpy(first, value, (size_t)(slash - value));
    first[slash - value] = '\0';
    int i, n;
    if (!sc_parse_int(first, 0, INT_MAX, &i) || !sc_parse_int(slash + 1, 1, INT_MAX, &n) || i >= n)
        return false;
    o->shard_index = i;
    o->shard_count = n;
    return true;
}

/* Options that do not go together, and what --video needs; 0 or 2 (reported). */
static int check_combination(const options *o) {
    const char *problem = NULL;
    if (!o->turntable && (o->spin >= 0 || o->up >= 0 || o->video || o->assemble))
        problem = o->spin >= 0 ? "--spin needs --turntable"
                  : o->up >= 0 ? "--up needs --turntable"
                  : o->video   ? "--video needs --turntable: a video of which frames?"
                               : "--assemble needs --turntable N and --video";
    else if (o->ground_truth && (o->turntable || o->depth_only || o->samples || o->mipmap >= 0))
        problem = o->turntable    ? "--ground-truth renders still images, not turntables"
                  : o->depth_only ? "--ground-truth renders colour: drop --depth-only"
                  : o->samples    ? "--ground-truth takes one sample a pixel: drop --samples"
                               : "--ground-truth samples textures without mipmaps: drop --mipmap";
    else if (o->turntable && (o->frames_given || o->compare_dir || o->depth_only))
        problem = o->frames_given
                      ? "--frames times still images; a turntable renders each frame once"
                  : o->compare_dir ? "--compare checks still images, not turntables"
                                   : "--depth-only renders still images, not turntables";
    else if (o->assemble && !o->video)
        problem = "--assemble needs --video: the formats to make";
    else if (o->video && o->shard_count > 1)
        problem = "--video needs every frame, and a shard has some: render the shards without "
                  "--video, then run the same command once with --video LIST --assemble "
                  "(docs/scale-out.md)";
    else if (o->resume && (o->assemble || o->no_write || o->compare_dir))
        problem = o->assemble   ? "--assemble renders nothing: --resume has nothing to skip"
                  : o->no_write ? "--resume skips what is on disk; --no-write writes nothing"
                                : "--compare needs every image rendered: drop --resume";
    else if (o->assemble && o->no_write)
        problem = "--assemble writes videos only; --no-write has nothing to add";
    else if (o->no_write && (o->video || o->compare_dir))
        problem = o->video ? "--video needs the frames written: drop --no-write"
                           : "--compare writes heat maps: drop --no-write";
    else if (!o->compare_dir &&
             (o->thresholds_path || o->junit_path || o->report_dir || o->update_golden))
        problem = "--thresholds, --junit, --report and --update-golden need --compare GOLDEN";
    if (problem) {
        fprintf(stderr, "sgapi-render: %s\n", problem);
        return 2;
    }
    if (o->video && !vd_have_ffmpeg()) {
        fprintf(stderr, "sgapi-render: --video needs the ffmpeg program, and there is none on PATH "
                        "(Debian: apt-get install ffmpeg; tools/install-deps.sh installs it)\n");
        return 2;
    }
    return 0;
}

/* 0: parsed; 1: help was printed; 2: bad arguments (already reported). */
static int parse_args(int argc, char **argv, options *o) {
    o->frames = 1;
    o->min_psnr = o->max_over2 = o->max_coverage = -1;
    o->spin = -1;
    o->up = -1;
    o->writers = -1;
    o->shard_count = 1;
    o->fps = 25;
    o->png_level = -1;
    o->mipmap = -1;
    o->files = calloc((size_t)argc, sizeof *o->files);
    o->scenes = calloc((size_t)argc, sizeof *o->scenes);
    o->shader_libs = calloc((size_t)argc, sizeof *o->shader_libs);
    if (!o->files || !o->scenes || !o->shader_libs) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        return 2;
    }
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        const char *value = i + 1 < argc ? argv[i + 1] : NULL;
        bool threshold =
            !strcmp(a, "--min-psnr") || !strcmp(a, "--max-over2") || !strcmp(a, "--max-coverage");
        bool takes_value =
            !strcmp(a, "-o") || !strcmp(a, "--frames") || !strcmp(a, "--scene") ||
            !strcmp(a, "--threads") || !strcmp(a, "--simd") || !strcmp(a, "--bin-memory") ||
            !strcmp(a, "--compare") || threshold || !strcmp(a, "--turntable") ||
            !strcmp(a, "--spin") || !strcmp(a, "--up") || !strcmp(a, "--shard") ||
            !strcmp(a, "--video") || !strcmp(a, "--fps") || !strcmp(a, "--video-width") ||
            !strcmp(a, "--png-level") || !strcmp(a, "--writers") || !strcmp(a, "--thresholds") ||
            !strcmp(a, "--junit") || !strcmp(a, "--report") || !strcmp(a, "--size") ||
            !strcmp(a, "--shaders") || !strcmp(a, "--progress-file") ||
            !strcmp(a, "--ground-truth") || !strcmp(a, "--samples") || !strcmp(a, "--mipmap");
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
        } else if (!strcmp(a, "--shaders")) {
            o->shader_libs[o->shader_lib_count++] = value;
        } else if (!strcmp(a, "--mipmap")) {
            sc_mipmap m;
            if (!sc_mipmap_from_name(value, &m)) {
                fprintf(stderr, "sgapi-render: --mipmap needs none, nearest or linear, not '%s'\n",
                        value);
                return 2;
            }
            o->mipmap = (int)m;
        } else if (!strcmp(a, "--size")) {
            char w[16], h[16];
            const char *x = strchr(value, 'x');
            if (!x || x - value >= (long)sizeof w || strlen(x + 1) >= sizeof h ||
                (memcpy(w, value, (size_t)(x - value)), w[x - value] = '\0', strcpy(h, x + 1),
                 !sc_parse_int(w, 1, SC_MAX_IMAGE_SIZE, &o->model_width)) ||
                !sc_parse_int(h, 1, SC_MAX_IMAGE_SIZE, &o->model_height)) {
                fprintf(stderr, "sgapi-render: --size needs WxH, each 1..%d, not '%s'\n",
                        SC_MAX_IMAGE_SIZE, value);
                return 2;
            }
        } else if (!strcmp(a, "--frames")) {
            if (!sc_parse_int(value, 1, 1000000, &o->frames)) {
                fprintf(stderr, "sgapi-render: --frames needs a whole number >= 1, not '%s'\n",
                        value);
                return 2;
            }
            o->frames_given = true;
        } else if (!strcmp(a, "--turntable")) {
            if (!sc_parse_int(value, 1, 1000000, &o->turntable)) {
                fprintf(stderr,
                        "sgapi-render: --turntable needs a frame count from 1 to 1000000, not "
                        "'%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--spin")) {
            if (!sc_parse_int(value, 0, INT_MAX, &o->spin)) {
                fprintf(stderr, "sgapi-render: --spin needs a draw index >= 0, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--up")) {
            if (!sc_parse_int(value, 0, INT_MAX, &o->up)) {
                fprintf(stderr, "sgapi-render: --up needs a draw index >= 0, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--shard")) {
            o->shard_given = true;
            if (!parse_shard(value, o)) {
                fprintf(stderr,
                        "sgapi-render: --shard needs I/N, whole numbers with 0 <= I < N, not "
                        "'%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--video")) {
            const char *bad;
            int bad_len;
            if (!vd_parse_formats(value, &o->video, &bad, &bad_len)) {
                fprintf(stderr,
                        "sgapi-render: --video takes gif, mp4 or both (gif,mp4), not '%.*s' in "
                        "'%s'\n",
                        bad_len, bad, value);
                return 2;
            }
        } else if (!strcmp(a, "--fps")) {
            if (!sc_parse_int(value, 1, 1000, &o->fps)) {
                fprintf(stderr,
                        "sgapi-render: --fps needs a whole number from 1 to 1000, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--video-width")) {
            if (!sc_parse_int(value, 2, SC_MAX_IMAGE_SIZE, &o->video_width)) {
                fprintf(stderr,
                        "sgapi-render: --video-width needs a whole number from 2 to %d, not '%s'\n",
                        SC_MAX_IMAGE_SIZE, value);
                return 2;
            }
        } else if (!strcmp(a, "--png-level")) {
            if (!sc_parse_int(value, 0, SC_PNG_LEVEL_MAX, &o->png_level)) {
                fprintf(stderr,
                        "sgapi-render: --png-level needs a whole number from 0 to %d, not '%s'\n",
                        SC_PNG_LEVEL_MAX, value);
                return 2;
            }
        } else if (!strcmp(a, "--writers")) {
            if (!sc_parse_int(value, 0, 64, &o->writers)) {
                fprintf(stderr,
                        "sgapi-render: --writers needs a whole number from 0 to 64, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--thresholds")) {
            o->thresholds_path = value;
        } else if (!strcmp(a, "--junit")) {
            o->junit_path = value;
        } else if (!strcmp(a, "--report")) {
            o->report_dir = value;
        } else if (!strcmp(a, "--update-golden")) {
            o->update_golden = true;
        } else if (!strcmp(a, "--resume")) {
            o->resume = true;
        } else if (!strcmp(a, "--progress-file")) {
            o->progress_path = value;
        } else if (!strcmp(a, "--assemble")) {
            o->assemble = true;
        } else if (!strcmp(a, "--quiet")) {
            o->quiet = true;
        } else if (!strcmp(a, "--strict")) {
            o->strict = true;
        } else if (!strcmp(a, "--no-write")) {
            o->no_write = true;
        } else if (!strcmp(a, "--frame-times")) {
            o->frame_times = true;
        } else if (!strcmp(a, "--samples")) {
            if (!sc_parse_samples(value, &o->samples)) {
                fprintf(stderr, "sgapi-render: --samples needs 1 or 4, not '%s'\n", value);
                return 2;
            }
        } else if (!strcmp(a, "--threads")) {
            if (!sc_parse_int(value, 0, 4096, &o->threads)) {
                fprintf(stderr, "sgapi-render: --threads needs a whole number >= 0, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--bin-memory")) {
            char *end = NULL;
            unsigned long long v =
                value && *value >= '0' && *value <= '9' ? strtoull(value, &end, 10) : 0;
            if (!end || *end || v > SIZE_MAX) {
                fprintf(stderr,
                        "sgapi-render: --bin-memory needs a whole number of bytes >= 0, not '%s'\n",
                        value);
                return 2;
            }
            o->bin_memory = (size_t)v;
        } else if (!strcmp(a, "--simd")) {
            if (!strcmp(value, "scalar")) {
                o->simd = SG_SIMD_SCALAR;
            } else if (!strcmp(value, "sse2")) {
                o->simd = SG_SIMD_SSE2;
            } else if (!strcmp(value, "avx2")) {
                o->simd = SG_SIMD_AVX2;
            } else if (!strcmp(value, "avx512")) {
                o->simd = SG_SIMD_AVX512;
            } else if (!strcmp(value, "neon")) {
                o->simd = SG_SIMD_NEON;
            } else {
                fprintf(stderr,
                        "sgapi-render: --simd is scalar, sse2, avx2, avx512 or neon, not '%s'\n",
                        value);
                return 2;
            }
        } else if (!strcmp(a, "--depth-only")) {
            o->depth_only = true;
        } else if (!strcmp(a, "--ground-truth")) {
            if (!sc_parse_int(value, 1, 64, &o->ground_truth)) {
                fprintf(stderr,
                        "sgapi-render: --ground-truth needs a whole number from 1 to 64 (samples "
                        "a side of each pixel), not '%s'\n",
                        value);
                return 2;
            }
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
    return check_combination(o);
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

/* What every scene of a run shares. */
typedef struct run {
    sgDevice *dev;
    ss_pso_cache cache;
    sc_png_writer *png;   /* still images */
    frame_writer *frames; /* turntable frames */
    progress bar;
    int digits;                /* of a turntable's frame names */
    const sc_shaders *shaders; /* the shaders scene files may name */
    rg_thresholds thresholds;  /* --compare: the targets of every scene */
    rg_scene *results;         /* --compare: one record per compared scene */
    size_t result_count;
    batch_log log; /* item lines, summary, --progress-file */
    bool log_open;
    size_t out_dir_len; /* items are named relative to the output folder */
    fc_buffer check;    /* --resume, --assemble: files read back */
} run;

/* Compares a rendered scene (written to `png`, rendered in `ms` per frame) with its golden image:
 * appends the figures to the scene's line (without its newline), writes the heat map, and records
 * the outcome, naming a failing scene on stderr with what failed. A failing scene does not stop
 * the run; false only when the comparison itself could not be done (out of memory, a heat map
 * that cannot be written). */
static bool compare_scene(run *rn, const options *o, const sc_file *f, const sc_scene *s,
                          const unsigned char *pixels, const char *png, double ms) {
    rg_scene *rec = &rn->results[rn->result_count++];
    rec->suite = rg_file_stem(f->path);
    rec->name = sc_format("%s", s->name);
    if (!rec->suite || !rec->name) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        return false;
    }
    rec->width = s->width;
    rec->height = s->height;
    rec->time_s = ms / 1e3;
    rec->limits = rg_thresholds_for(&rn->thresholds, f->path, s->name);
    /* Background, for the coverage figure, is the scene's clear colour as stored. */
    unsigned char bg[4];
    for (int c = 0; c < 4; c++) bg[c] = (unsigned char)lroundf(s->clear_color[c] * 255.0f);
    sc_msg err = {0};
    bool ok = rg_compare(rec, pixels, bg, o->compare_dir, png, o->out_dir, rn->png, &err);
    if (ok && rec->compared) {
        const sc_diff *d = &rec->diff;
        printf("  psnr %6.2f dB  >2/255 %7.4f %%  >8/255 %7.4f %%  max %3d  coverage %7.4f %%",
               d->psnr_db, d->pct_over[0], d->pct_over[1], d->max_error, d->pct_coverage);
    }
    printf("%s\n", ok && !rec->passed ? "  FAIL" : "");
    fflush(stdout);
    if (!ok)
        fprintf(stderr, "sgapi-render: %s\n", err.text);
    else if (!rec->passed)
        fprintf(stderr, "sgapi-render: FAIL %s/%s: %s\n", rec->suite, rec->name,
                sc_msg_text(&rec->reason));
    sc_msg_free(&err);
    return ok;
}

/* The scenes as the ground truth renders them: n times as wide and high, textures bilinear
 * (sampled exactly where a pixel's samples fall, nothing averaged beforehand). False (reported):
 * a scene would pass the largest image side. */
static bool ground_truth_scenes(sc_file *files, int count, int n) {
    for (int i = 0; i < count; i++)
        for (size_t k = 0; k < files[i].scene_count; k++) {
            sc_scene *s = &files[i].scenes[k];
            if ((int64_t)s->width * n > SC_MAX_IMAGE_SIZE ||
                (int64_t)s->height * n > SC_MAX_IMAGE_SIZE) {
                fprintf(stderr,
                        "sgapi-render: %s: scene '%s' is %d x %d: --ground-truth %d would render "
                        "it at %lld x %lld, over the largest image side %d\n",
                        files[i].path, s->name, s->width, s->height, n, (long long)s->width * n,
                        (long long)s->height * n, SC_MAX_IMAGE_SIZE);
                return false;
            }
            s->width *= n;
            s->height *= n;
            s->samples = 1;
            for (size_t d = 0; d < s->draw_count; d++) {
                s->draws[d].filter = SC_FILTER_BILINEAR;
                s->draws[d].mipmap = SC_MIPMAP_NONE;
            }
        }
    return true;
}

/* Averages each n x n block of the RGBA8 image of `width` pixels a row into one pixel of a w x h
 * image written over its start, each channel rounded to nearest: the ground truth's filter. */
static void box_filter(unsigned char *pixels, int width, int n, int w, int h) {
    const uint32_t count = (uint32_t)n * (uint32_t)n;
    for (int y = 0; y < h; y++)
        for (int x = 0; x < w; x++) {
            uint32_t sum[4] = {0, 0, 0, 0};
            for (int j = 0; j < n; j++) {
                const unsigned char *row =
                    pixels + ((size_t)(y * n + j) * (size_t)width + (size_t)x * (size_t)n) * 4;
                for (int i = 0; i < n * 4; i++) sum[i & 3] += row[i];
            }
            /* Written behind every block still to be read: row y of the output ends before
             * input row y n + 1 starts. */
            unsigned char *out = pixels + ((size_t)y * (size_t)w + (size_t)x) * 4;
            for (int k = 0; k < 4; k++) out[k] = (unsigned char)((sum[k] + count / 2) / count);
        }
}

/* Renders one scene frames times, writes its PNG and prints its median time per frame. */
static bool render_scene(run *rn, const options *o, const sc_file *f, const sc_scene *s,
                         const ss_uploads *u) {
    sgDevice *dev = rn->dev;
    ss_pso_cache *cache = &rn->cache;
    bool ok = false;
    sgImage2D color = {0}, depth = {0};
    ss_shadow shadow = {0};
    sgPipelineStateObject *psos = calloc(s->draw_count ? s->draw_count : 1, sizeof *psos);
    double *times = calloc((size_t)o->frames, sizeof *times);
    unsigned char *pixels = malloc((size_t)s->width * (size_t)s->height * 4);
    char *png = sc_format("%s/%s.png", o->out_dir, s->name);
    if (!psos || !times || !pixels || !png) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        goto done;
    }
    for (size_t i = 0; i < s->draw_count; i++) {
        sgPipelineDesc desc;
        if (!ss_pipeline_desc(PROG, f, &s->draws[i], rn->shaders, &desc) ||
            !ss_get_pso(PROG, dev, cache, &desc, &psos[i])) {
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
        if (o->frame_times)
            fprintf(stderr, "%s frame %d: %.3f ms\n", s->name, frame + 1, times[frame]);
        pg_step(&rn->bar, 1);
    }

    r = o->depth_only ? read_depth(dev, depth, s, pixels) : sgReadImage2D(dev, color, pixels, 0);
    if (r != SG_OK) {
        sg_fail(dev, r, "scene '%s': sgReadImage2D", s->name);
        goto done;
    }
    /* The ground truth: the N x N samples of each pixel averaged, the image N times smaller. */
    sc_scene small = *s;
    if (o->ground_truth > 1) {
        small.width = s->width / o->ground_truth;
        small.height = s->height / o->ground_truth;
        box_filter(pixels, s->width, o->ground_truth, small.width, small.height);
        s = &small;
    }
    sc_msg err = {0};
    if (!o->no_write && !sc_png_writer_write(rn->png, png, s->width, s->height, pixels, &err)) {
        pg_hide(&rn->bar);
        fprintf(stderr, "sgapi-render: %s\n", err.text);
        sc_msg_free(&err);
        goto done;
    }
    double median = ss_median(times, o->frames);
    pg_hide(&rn->bar);
    if (o->frames > 1)
        printf("%-32s %10.3f ms/frame (median of %d)", s->name, median, o->frames);
    else
        printf("%-32s %10.3f ms/frame", s->name, median);
    ok = o->compare_dir ? compare_scene(rn, o, f, s, pixels, png, median) : (printf("\n"), true);
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

/* Whether item k (a scene, or a turntable's frame, counted across the run) is this shard's. */
static bool in_shard(const options *o, long long k) {
    return k % o->shard_count == o->shard_index;
}

/* How many of a turntable's frames, the first of which is item first, are this shard's. */
static int shard_frames(const options *o, long long first) {
    int n = 0;
    for (int k = 0; k < o->turntable; k++) n += in_shard(o, first + k);
    return n;
}

/* DIR/<scene>/<frame>.png, or DIR/<scene> when frame < 0; NULL when out of memory. */
static char *frame_path(const options *o, const run *rn, const sc_scene *s, int frame) {
    size_t len = strlen(o->out_dir) + strlen(s->name) + 32;
    char *p = malloc(len);
    if (!p) return NULL;
    if (frame < 0)
        snprintf(p, len, "%s/%s", o->out_dir, s->name);
    else
        snprintf(p, len, "%s/%s/%0*d.png", o->out_dir, s->name, rn->digits, frame);
    return p;
}

/* A frame on disk: its line and progress event (fw_collect's callback). */
static void frame_done(void *ctx, const char *path, double ms) {
    run *rn = ctx;
    pg_hide(&rn->bar);
    bl_done(&rn->log, path + rn->out_dir_len + 1, ms, true);
}

/* --resume: whether the image at path is already whole (then it is counted as skipped); one that
 * is there but not whole is named and rendered again. */
static bool already_done(run *rn, const options *o, const char *path, int width, int height) {
    if (!o->resume) return false;
    sc_msg why = {0};
    fc_status st = fc_check(path, width, height, &rn->check, &why);
    if (st == FC_WHOLE)
        bl_skipped(&rn->log, path + rn->out_dir_len + 1);
    else if (st == FC_BAD)
        bl_redo(&rn->log, PROG, o->out_dir, path + rn->out_dir_len + 1, sc_msg_text(&why));
    sc_msg_free(&why);
    return st == FC_WHOLE;
}

/* Renders this shard's frames of a scene's turntable (the first frame is item `first` of the
 * run) but those already whole on disk with --resume, hands each to the frame writer, and prints
 * the scene's frames per second: from the start of its first frame until its last file is
 * written. */
static bool render_turntable(run *rn, const options *o, const sc_file *f, const sc_scene *s,
                             const ss_uploads *u, long long first) {
    if (shard_frames(o, first) == 0) return true;
    /* Which frames to render: checked first, so a scene whose frames are all there costs no
     * pipelines or targets. */
    bool *todo = calloc((size_t)o->turntable, sizeof *todo);
    char *check_path = frame_path(o, rn, s, o->turntable - 1);
    if (!todo || !check_path) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        free(todo);
        free(check_path);
        return false;
    }
    int count = 0;
    for (int k = 0; k < o->turntable; k++) {
        if (!in_shard(o, first + k)) continue;
        snprintf(check_path + strlen(check_path) - (size_t)rn->digits - 4, (size_t)rn->digits + 5,
                 "%0*d.png", rn->digits, k);
        todo[k] = !already_done(rn, o, check_path, s->width, s->height);
        count += todo[k];
    }
    free(check_path);
    pg_step(&rn->bar, shard_frames(o, first) - count);
    if (count == 0) {
        pg_hide(&rn->bar);
        printf("%-32s %d frames already on disk, none to render\n", s->name,
               shard_frames(o, first));
        fflush(stdout);
        free(todo);
        return true;
    }
    sgDevice *dev = rn->dev;
    bool ok = false;
    sgImage2D color = {0}, depth = {0};
    ss_shadow shadow = {0};
    sgPipelineStateObject *psos = calloc(s->draw_count ? s->draw_count : 1, sizeof *psos);
    sc_draw *draws = calloc(s->draw_count ? s->draw_count : 1, sizeof *draws);
    /* Frames go to the writer threads' buffers, or, written here or not at all, to one of ours. */
    unsigned char *scratch = rn->frames ? NULL : malloc((size_t)s->width * (size_t)s->height * 4);
    char *path = frame_path(o, rn, s, o->turntable - 1);
    if (!psos || !draws || !path || (!rn->frames && !scratch)) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        goto done;
    }
    for (size_t i = 0; i < s->draw_count; i++) {
        sgPipelineDesc desc;
        if (!ss_pipeline_desc(PROG, f, &s->draws[i], rn->shaders, &desc) ||
            !ss_get_pso(PROG, dev, &rn->cache, &desc, &psos[i])) {
            fprintf(stderr, "sgapi-render: in %s, scene '%s', draw %zu\n", f->path, s->name, i);
            goto done;
        }
    }
    sgPassDesc pass;
    if (!ss_create_targets(PROG, dev, s, &color, &depth, &pass) ||
        !ss_create_shadow(PROG, dev, &rn->cache, f, s, &shadow))
        goto done;
    sc_turntable table;
    sc_turntable_init(f, s, o->spin, o->up, &table); /* checked before the run */
    const size_t bytes = (size_t)s->width * (size_t)s->height * 4;
    double t0 = ss_now_ms();
    for (int k = 0; k < o->turntable; k++) {
        if (!todo[k]) continue;
        double frame_t0 = ss_now_ms();
        sc_scene turned;
        sc_turntable_at(&table, s, 360.0 * k / o->turntable, draws, &turned);
        /* The casters moved against the light's fit (a spinning draw), or the fit's box is no
         * longer what it was (an orbit): the map is fitted again. */
        if (k > 0 && !ss_fit_shadow(PROG, f, &turned, &shadow)) goto done;
        if (!ss_draw_frame(PROG, dev, f, &turned, u, psos, &pass, &shadow)) goto done;
        unsigned char *pixels = rn->frames ? fw_acquire(rn->frames, bytes) : scratch;
        if (!pixels) {
            pg_hide(&rn->bar);
            fprintf(stderr, "sgapi-render: %s\n", fw_error(rn->frames));
            goto done;
        }
        sgResult r = sgReadImage2D(dev, color, pixels, 0);
        if (r != SG_OK) {
            sg_fail(dev, r, "scene '%s', frame %d: sgReadImage2D", s->name, k);
            goto done;
        }
        double ms = ss_now_ms() - frame_t0;
        snprintf(path + strlen(path) - (size_t)rn->digits - 4, (size_t)rn->digits + 5, "%0*d.png",
                 rn->digits, k);
        sc_msg err = {0};
        bool written = rn->frames ? fw_submit(rn->frames, pixels, s->width, s->height, path, ms)
                       : rn->png
                           ? sc_png_writer_write(rn->png, path, s->width, s->height, pixels, &err)
                           : true;
        if (!written) {
            pg_hide(&rn->bar);
            fprintf(stderr, "sgapi-render: %s\n", rn->frames ? fw_error(rn->frames) : err.text);
            sc_msg_free(&err);
            goto done;
        }
        if (rn->frames)
            fw_collect(rn->frames, frame_done, rn);
        else if (rn->png)
            frame_done(rn, path, ms);
        else
            bl_done(&rn->log, path + rn->out_dir_len + 1, ms, false); /* --no-write */
        pg_step(&rn->bar, 1);
    }
    if (rn->frames && !fw_drain(rn->frames)) {
        pg_hide(&rn->bar);
        fprintf(stderr, "sgapi-render: %s\n", fw_error(rn->frames));
        goto done;
    }
    if (rn->frames) fw_collect(rn->frames, frame_done, rn);
    double seconds = (ss_now_ms() - t0) / 1e3;
    pg_hide(&rn->bar);
    if (count == o->turntable)
        printf("%-32s %10.2f frames/s (%d frames in %.3f s)\n", s->name, count / seconds, count,
               seconds);
    else
        printf("%-32s %10.2f frames/s (%d of %d frames in %.3f s)\n", s->name, count / seconds,
               count, o->turntable, seconds);
    fflush(stdout);
    ok = true;
done:
    ss_destroy_shadow(dev, &shadow);
    if (depth.id) sgDestroyImage2D(dev, depth);
    if (color.id) sgDestroyImage2D(dev, color);
    free(psos);
    free(draws);
    free(scratch);
    free(path);
    free(todo);
    return ok;
}

/* --assemble: how many of a scene's frames are missing or not whole, naming the first ten of them
 * on stderr; -1 when out of memory. */
static int missing_frames(const options *o, run *rn, const sc_scene *s) {
    char *frame = frame_path(o, rn, s, o->turntable - 1);
    if (!frame) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        return -1;
    }
    int bad = 0;
    for (int k = 0; k < o->turntable; k++) {
        snprintf(frame + strlen(frame) - (size_t)rn->digits - 4, (size_t)rn->digits + 5, "%0*d.png",
                 rn->digits, k);
        sc_msg why = {0};
        fc_status st = fc_check(frame, s->width, s->height, &rn->check, &why);
        if (st != FC_WHOLE && ++bad <= 10)
            fprintf(stderr, "sgapi-render: --assemble: %s %s\n", frame,
                    st == FC_MISSING ? "is missing" : sc_msg_text(&why));
        sc_msg_free(&why);
    }
    if (bad > 10) fprintf(stderr, "sgapi-render: --assemble: ... and %d more\n", bad - 10);
    if (bad)
        fprintf(stderr,
                "sgapi-render: --assemble: %d of the %d frames of '%s' missing or not whole: "
                "every shard must have finished (run the shards that did not again, with "
                "--resume)\n",
                bad, o->turntable, s->name);
    free(frame);
    return bad;
}

/* Makes a scene's videos from its frames on disk. */
static bool make_videos(const options *o, const run *rn, const sc_scene *s) {
    char *dir = frame_path(o, rn, s, -1);
    char *out = NULL;
    bool ok = dir != NULL;
    if (!ok) fprintf(stderr, "sgapi-render: out of memory\n");
    for (unsigned fmt = VIDEO_GIF; ok && fmt <= VIDEO_MP4; fmt <<= 1) {
        if (!(o->video & fmt)) continue;
        free(out);
        out = sc_format("%s/%s.%s", o->out_dir, s->name, vd_extension(fmt));
        if (!out) {
            fprintf(stderr, "sgapi-render: out of memory\n");
            ok = false;
            break;
        }
        ok = vd_make(PROG, dir, rn->digits, o->turntable, o->fps, o->video_width, fmt, out);
        if (ok) printf("%-32s %s\n", s->name, out);
    }
    fflush(stdout);
    free(dir);
    free(out);
    return ok;
}

/* Whether a file can be created in a folder: tried, since permissions alone do not tell (root
 * writes anywhere but on a read-only file system). */
static bool writable_dir(const char *dir) {
    char *probe = sc_format("%s/.sgapi-render-XXXXXX", dir);
    if (!probe) return false;
    int fd = mkstemp(probe);
    int saved = errno;
    if (fd >= 0) {
        close(fd);
        remove(probe);
    } else {
        fprintf(stderr, "sgapi-render: cannot write in '%s': %s\n", dir, strerror(saved));
    }
    free(probe);
    return fd >= 0;
}

/* ---- regression: checks before the run, outputs after it ------------------------------------- */

/* The thresholds file, the golden folder, the report folder and the JUnit file's folder, checked
 * before anything renders; false when one cannot work (reported). */
static bool regression_setup(const options *o, run *rn) {
    rg_thresholds_init(&rn->thresholds);
    rg_limits *ov = &rn->thresholds.overrides;
    if (o->min_psnr >= 0) ov->min_psnr = o->min_psnr;
    if (o->max_over2 >= 0) ov->max_over2 = o->max_over2;
    if (o->max_coverage >= 0) ov->max_coverage = o->max_coverage;
    sc_msg err = {0};
    if (o->thresholds_path && !rg_thresholds_load(&rn->thresholds, o->thresholds_path, &err)) {
        fprintf(stderr, "sgapi-render: --thresholds: %s\n", err.text);
        sc_msg_free(&err);
        return false;
    }
    struct stat st;
    if (stat(o->compare_dir, &st) != 0) {
        /* A golden folder that is not there yet is made by --update-golden; otherwise it is a
         * wrong path, not a run of missing images. */
        if (!o->update_golden) {
            fprintf(stderr, "sgapi-render: --compare: no folder '%s'\n", o->compare_dir);
            return false;
        }
        if (!make_dirs(o->compare_dir)) return false;
    } else if (!S_ISDIR(st.st_mode)) {
        fprintf(stderr, "sgapi-render: --compare: '%s' is not a folder\n", o->compare_dir);
        return false;
    }
    if (o->update_golden && !writable_dir(o->compare_dir)) return false;
    if (o->report_dir && (!make_dirs(o->report_dir) || !writable_dir(o->report_dir))) return false;
    if (o->junit_path) {
        size_t n = strlen(o->junit_path);
        char *dir = malloc(n + 2);
        if (!dir) return false;
        memcpy(dir, o->junit_path, n + 1);
        char *slash = strrchr(dir, '/');
        if (slash)
            slash[slash == dir ? 1 : 0] = '\0';
        else
            strcpy(dir, ".");
        bool ok = (stat(o->junit_path, &st) != 0 || S_ISREG(st.st_mode)) && make_dirs(dir) &&
                  writable_dir(dir);
        if (stat(o->junit_path, &st) == 0 && !S_ISREG(st.st_mode))
            fprintf(stderr, "sgapi-render: --junit: '%s' is not a file\n", o->junit_path);
        free(dir);
        if (!ok) return false;
    }
    return true;
}

/* After the run: the report, the JUnit file, the golden updates and the summary line. Returns the
 * exit status: 0 when every scene passed (or every failing one was blessed), else 1. */
static int regression_finish(const options *o, run *rn, int argc, char **argv) {
    sc_msg err = {0};
    size_t failed = 0;
    for (size_t i = 0; i < rn->result_count; i++) failed += !rn->results[i].passed;
    bool ok = true;
    /* Goldens are updated after the report is written, so that it shows the golden images that
     * were compared; it says which ones this run replaces. */
    for (size_t i = 0; i < rn->result_count; i++)
        rn->results[i].golden_updated =
            o->update_golden && !rn->results[i].passed && rn->results[i].actual;
    if (o->report_dir) {
        char *cmd = rg_command_line(argc, argv);
        ok = cmd && rg_write_report(o->report_dir, rn->results, rn->result_count, cmd,
                                    o->compare_dir, &err);
        if (!ok) fprintf(stderr, "sgapi-render: --report: %s\n", cmd ? err.text : "out of memory");
        free(cmd);
    }
    if (ok && o->update_golden && failed)
        ok = rg_update_golden(rn->results, rn->result_count, o->compare_dir);
    if (ok && o->junit_path) {
        ok = rg_write_junit(o->junit_path, rn->results, rn->result_count, o->report_dir, &err);
        if (!ok) fprintf(stderr, "sgapi-render: --junit: %s\n", err.text);
    }
    sc_msg_free(&err);
    printf("%zu of %zu scenes passed, %zu failed%s\n", rn->result_count - failed, rn->result_count,
           failed, failed && o->update_golden ? " (golden images updated)" : "");
    if (o->report_dir) printf("report: %s/index.html\n", o->report_dir);
    if (o->junit_path) printf("junit: %s\n", o->junit_path);
    fflush(stdout);
    if (!ok) return 1;
    return failed && !o->update_golden ? 1 : 0;
}

/* ---- main ------------------------------------------------------------------------------------ */

static size_t max_size(size_t a, size_t b) {
    return a > b ? a : b;
}

/* The digits of a turntable's frame names: 4, more when the last frame needs them. */
static int frame_digits(int frames) {
    int d = 1;
    for (int n = frames - 1; n >= 10; n /= 10) d++;
    return d < 4 ? 4 : d;
}

/* A model file's scene name: its file name without folder and extension, any character a scene
 * name cannot hold made '_'. */
static void model_name(const char *path, char *out, size_t len) {
    const char *b = strrchr(path, '/');
    b = b ? b + 1 : path;
    const char *dot = strrchr(b, '.');
    size_t n = dot && dot > b ? (size_t)(dot - b) : strlen(b);
    if (n >= len) n = len - 1;
    for (size_t i = 0; i < n; i++) {
        char c = b[i];
        bool ok = (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                  c == '_' || c == '-' || c == '.';
        out[i] = ok ? c : '_';
    }
    if (n == 0) out[n++] = '_';
    out[n] = '\0';
}

int main(int argc, char **argv) {
    options o = {0};
    int status = parse_args(argc, argv, &o);
    if (status) {
        free(o.files);
        free(o.scenes);
        free(o.shader_libs);
        return status == 1 ? 0 : 2;
    }

    /* Everything is loaded first, so a bad file stops the run before any rendering. */
    sc_file *files = calloc((size_t)o.file_count, sizeof *files);
    run rn = {.digits = frame_digits(o.turntable)};
    int loaded = 0;
    sc_shaders *shaders = NULL;
    status = 1;
    if (!files) {
        fprintf(stderr, "sgapi-render: out of memory\n");
        goto done;
    }
    for (; loaded < o.file_count; loaded++) {
        sc_msg err = {0};
        if (sc_is_model_path(o.files[loaded])) {
            /* A model is a scene named after its file. */
            char name[SC_MAX_NAME_LENGTH + 1];
            model_name(o.files[loaded], name, sizeof name);
            sc_warnings w = {0};
            bool ok =
                sc_model_scene(&o.files[loaded], 1, name, o.model_width ? o.model_width : 1024,
                               o.model_height ? o.model_height : 768, &files[loaded], &w, &err);
            for (int k = 0; k < w.count; k++)
                fprintf(stderr, "sgapi-render: warning: %s\n", w.text[k].text);
            sc_warnings_free(&w);
            if (!ok) {
                fprintf(stderr, "sgapi-render: %s\n", err.text);
                sc_msg_free(&err);
                goto done;
            }
            continue;
        }
        if (!sc_load(o.files[loaded], &files[loaded], &err)) {
            fprintf(stderr, "sgapi-render: %s\n", err.text);
            sc_msg_free(&err);
            goto done;
        }
    }
    for (int i = 0; o.samples && i < loaded; i++) sc_set_samples(&files[i], o.samples);
    if (o.mipmap >= 0)
        for (int i = 0; i < loaded; i++) sc_override_mipmap(&files[i], (sc_mipmap)o.mipmap);
    /* Every file's warnings, then (with --strict) the verdict, before anything is rendered. */
    bool clean = true;
    for (int i = 0; i < loaded; i++)
        clean &= sc_report_warnings(&files[i], "sgapi-render", o.strict);
    if (!clean) goto done;
    /* The shaders the files name: a library that cannot be used, a shader no library has or
     * uniforms that do not fit it are bad arguments for these files (exit 2), found before
     * anything renders. */
    status = 2;
    sc_msg shader_err = {0};
    if (!sc_shaders_prepare(&shaders, o.simd, (const char *const *)o.shader_libs,
                            o.shader_lib_count, files, loaded, &shader_err)) {
        fprintf(stderr, "sgapi-render: %s\n", shader_err.text);
        sc_msg_free(&shader_err);
        goto done;
    }
    rn.shaders = shaders;
    if (o.ground_truth > 1 && !ground_truth_scenes(files, loaded, o.ground_truth)) goto done;
    status = 1;

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

    /* The items of the run, counted as --shard counts them: what this run renders, its folders
     * and the progress bar's total. Problems of the arguments with these scenes are exit 2. */
    long long items = 0, total = 0;
    status = 2;
    for (int i = 0; i < o.file_count; i++) {
        for (size_t j = 0; j < files[i].scene_count; j++) {
            const sc_scene *s = &files[i].scenes[j];
            if (!selected(&o, s->name)) continue;
            int bad = o.spin >= 0 && (size_t)o.spin >= s->draw_count ? o.spin
                      : o.up >= 0 && (size_t)o.up >= s->draw_count   ? o.up
                                                                     : -1;
            if (bad >= 0) {
                fprintf(stderr, "sgapi-render: --%s %d: scene '%s' has %zu draws\n",
                        bad == o.spin ? "spin" : "up", bad, s->name, s->draw_count);
                goto done;
            }
            sc_turntable t;
            if (o.turntable && !sc_turntable_init(&files[i], s, o.spin, o.up, &t)) {
                fprintf(stderr, "sgapi-render: --up %d: in scene '%s', the draw's +y is %s\n", o.up,
                        s->name, "zero or not finite");
                goto done;
            }
        }
    }
    /* The progress file before the output folder, so that nothing is made when it cannot be. */
    if (!o.assemble && !(rn.log_open = bl_open(&rn.log, o.progress_path))) goto done;
    if (!make_dirs(o.out_dir) || (!o.no_write && !writable_dir(o.out_dir))) goto done;
    if (o.compare_dir && !regression_setup(&o, &rn)) goto done;
    for (int i = 0; i < o.file_count; i++) {
        for (size_t j = 0; j < files[i].scene_count; j++) {
            const sc_scene *s = &files[i].scenes[j];
            if (!selected(&o, s->name)) continue;
            long long mine = o.turntable ? shard_frames(&o, items) : in_shard(&o, items);
            items += o.turntable ? o.turntable : 1;
            total += o.turntable ? mine : mine * o.frames;
            if (o.turntable && mine > 0 && !o.no_write && !o.assemble) {
                char *dir = frame_path(&o, &rn, s, -1);
                bool made = dir && make_dirs(dir);
                free(dir);
                if (!made) goto done;
            }
        }
    }
    status = 1;
    if (o.compare_dir) {
        rn.results = calloc(items ? (size_t)items : 1, sizeof *rn.results);
        if (!rn.results) {
            fprintf(stderr, "sgapi-render: out of memory\n");
            goto done;
        }
    }

    if (o.assemble) {
        /* Every scene's frames checked before any video is made: a run with frames missing
         * names them all and makes nothing. */
        long long bad = 0;
        for (int i = 0; bad >= 0 && i < o.file_count; i++)
            for (size_t j = 0; j < files[i].scene_count; j++)
                if (selected(&o, files[i].scenes[j].name)) {
                    int n = missing_frames(&o, &rn, &files[i].scenes[j]);
                    if (n < 0) {
                        bad = -1;
                        break;
                    }
                    bad += n;
                }
        bool ok = bad == 0;
        for (int i = 0; ok && i < o.file_count; i++)
            for (size_t j = 0; ok && j < files[i].scene_count; j++)
                if (selected(&o, files[i].scenes[j].name))
                    ok = make_videos(&o, &rn, &files[i].scenes[j]);
        status = ok ? 0 : 1;
        goto done;
    }

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
    dd.bin_memory_limit = o.bin_memory;
    if (max_images + 3 > 256) dd.image_pool_size = (int)max_images + 3;
    if (max_geoms > 1024) dd.geom_pool_size = (int)max_geoms;
    dd.pipeline_pool_size = ss_pipeline_pool_size(files, o.file_count, 1);
    sgResult r = sgCreateDevice(&dd, &rn.dev);
    if (r != SG_OK) {
        sg_fail(NULL, r, "sgCreateDevice");
        goto done;
    }
    /* Still images are written one at a time here; a turntable's frames, at level 0 by default,
     * on writer threads while the next ones render (docs/performance.md, "Writing frames"). */
    int level = o.png_level >= 0 ? o.png_level : o.turntable ? 0 : SC_PNG_LEVEL_DEFAULT;
    /* A thread per core: compressed levels are bound by the CPU, and at level 0 a second thread
     * keeps writing while the first waits for the disk. Two frames more than threads let
     * rendering run ahead without holding more than a few frames. */
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    int writers = o.writers >= 0 ? o.writers : cores > 2 ? (cores < 64 ? (int)cores : 64) : 2;
    if (o.no_write) {
        /* nothing to write */
    } else if (o.turntable && writers > 0) {
        rn.frames = fw_start(PROG, writers, writers + 2, level);
        if (!rn.frames) goto done;
    } else {
        rn.png = sc_png_writer_create(level);
        if (!rn.png) {
            fprintf(stderr, "sgapi-render: out of memory\n");
            goto done;
        }
    }
    pg_init(&rn.bar, !o.quiet, (long)total);
    rn.out_dir_len = strlen(o.out_dir);
    bl_start(&rn.log, o.turntable > 0, o.turntable || o.shard_given || o.resume || o.progress_path,
             o.turntable ? total : total / o.frames, o.shard_index, o.shard_count, o.resume);

    items = 0;
    for (int i = 0; i < o.file_count; i++) {
        const sc_file *f = &files[i];
        ss_uploads u;
        bool ok = ss_upload(PROG, rn.dev, f, &u);
        for (size_t j = 0; ok && j < f->scene_count; j++) {
            const sc_scene *s = &f->scenes[j];
            if (!selected(&o, s->name)) continue;
            if (o.turntable) {
                ok = render_turntable(&rn, &o, f, s, &u, items);
                if (ok && o.video) ok = make_videos(&o, &rn, s);
                items += o.turntable;
            } else {
                if (in_shard(&o, items)) {
                    char *png = sc_format("%s/%s.png", o.out_dir, s->name);
                    ok = png != NULL;
                    if (!ok) fprintf(stderr, "sgapi-render: out of memory\n");
                    if (ok && !already_done(&rn, &o, png, s->width, s->height)) {
                        ok = render_scene(&rn, &o, f, s, &u);
                        if (ok) bl_done(&rn.log, png + rn.out_dir_len + 1, -1.0, false);
                    }
                    free(png);
                }
                items++;
            }
        }
        ss_destroy_uploads(rn.dev, &u);
        if (!ok) goto done;
    }
    status = o.compare_dir ? regression_finish(&o, &rn, argc, argv) : 0;
done:
    pg_hide(&rn.bar);
    if (rn.frames) {
        /* After a failure: what was written before it is on disk, and counted. */
        fw_drain(rn.frames);
        fw_collect(rn.frames, frame_done, &rn);
    }
    if (rn.log_open) bl_close(&rn.log, status);
    fc_buffer_free(&rn.check);
    fw_stop(rn.frames);
    sc_png_writer_destroy(rn.png);
    sgDestroyDevice(rn.dev); /* also destroys the cached pipelines */
    ss_pso_cache_free(&rn.cache);
    rg_scenes_free(rn.results, rn.result_count);
    free(rn.results);
    rg_thresholds_free(&rn.thresholds);
    for (int i = 0; i < loaded; i++) sc_free(&files[i]);
    free(files);
    sc_shaders_close(shaders); /* after the device: no pipeline runs a library's code any more */
    free(o.files);
    free(o.scenes);
    free(o.shader_libs);
    return status;
}
