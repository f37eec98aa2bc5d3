/* regression.h - the outcome of comparing each rendered scene with its golden image: figures
 * against targets, why a scene failed, the order a reader wants (failures first, worst first),
 * and accepting new golden images. The JUnit file (junit.h) and the HTML report (report.h) are
 * written from these records. */
#ifndef RG_REGRESSION_H
#define RG_REGRESSION_H

#include <stdbool.h>
#include <stddef.h>

#include "image_diff.h"
#include "image_io.h"
#include "thresholds.h"

/* One scene of a run. Paths are NULL when there is no such image (no golden, or no heat map when
 * the golden could not be compared). */
typedef struct rg_scene {
    char *suite; /* the scene file's stem */
    char *name;
    int width, height;
    double time_s; /* render time: the median time of one frame */
    rg_limits limits;
    bool compared; /* diff holds figures (the golden was read and of the scene's size) */
    sc_diff diff;
    bool passed;
    sc_msg reason;  /* why it failed: every figure past its target, or the golden's problem */
    char *expected; /* the golden image, when it is readable */
    char *actual;   /* the rendered image */
    char *heat;     /* the heat map */
    bool golden_updated;
} rg_scene;

/** Compares the rendered pixels of a scene (its suite, name, size and limits already in s) with
 *  golden_dir/<name>.png: sets the figures, the verdict and the reason, keeps the paths of the
 *  actual image (`actual`, already written) and of the golden, and writes the heat map to
 *  out_dir/<name>-heat.png with `png`. A golden that is missing, unreadable or of another size is
 *  a failure of the scene. False only when the comparison itself could not be done (out of
 *  memory, the heat map not written), with err. */
bool rg_compare(rg_scene *s, const unsigned char *pixels, const unsigned char background[4],
                const char *golden_dir, const char *actual, const char *out_dir, sc_png_writer *png,
                sc_msg *err);
/** Checks figures against the scene's limits: sets passed and, on failure, reason. */
void rg_judge(rg_scene *s);
/** Marks a scene failed because its golden could not be compared, with the reason (printf). */
void rg_fail_golden(rg_scene *s, const char *fmt, ...) SC_PRINTF_LIKE(2, 3);
/** Formats a limit's figure for reading: "40 dB" and the like into buf. */
const char *rg_format_psnr(double db, char *buf, size_t len);
/** The order a reader wants: failing scenes first, those without figures first of them, then
 *  lowest PSNR first; then passing scenes in run order. Fills order[0..n). */
void rg_sort(const rg_scene *scenes, size_t n, size_t *order);
/** Copies a file byte for byte (through DST.part, renamed). */
bool rg_copy_file(const char *src, const char *dst, sc_msg *err);
/** Writes the actual image of every failing scene into golden_dir/<name>.png and prints what it
 *  replaced or added; passing scenes are not touched. False when a write failed (reported). */
bool rg_update_golden(rg_scene *scenes, size_t n, const char *golden_dir);
/** Frees the names, paths and reasons of the records. */
void rg_scenes_free(rg_scene *scenes, size_t n);

#endif
