/* thresholds.h - the accuracy targets of image regression: the project's standard, per-scene rows
 * of a CSV file (suite,scene,min_psnr_db,max_pct_over_2,max_coverage_pct), and command-line
 * overrides, resolved for each scene. */
#ifndef RG_THRESHOLDS_H
#define RG_THRESHOLDS_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"

/* The targets of one scene. */
typedef struct rg_limits {
    double min_psnr;     /* dB over RGB, at least */
    double max_over2;    /* % of pixels differing by more than 2/255 in a channel, at most */
    double max_coverage; /* % of pixels background in one image and not the other, at most */
} rg_limits;

/* The project's standard: PSNR >= 40 dB, <= 0.5 % over 2/255, coverage <= 0.05 %. */
#define RG_DEFAULT_MIN_PSNR     40.0
#define RG_DEFAULT_MAX_OVER2    0.5
#define RG_DEFAULT_MAX_COVERAGE 0.05

/* A row of a thresholds file; a figure it leaves out is NAN (the default holds). */
typedef struct rg_row {
    char *suite; /* a scene file's stem, or "*" for any */
    char *scene;
    rg_limits limits;
} rg_row;

typedef struct rg_thresholds {
    rg_row *rows;
    size_t count;
    rg_limits overrides; /* the command line's, for every scene; NAN: not given */
} rg_thresholds;

/** Empty thresholds: every scene gets the default, no overrides. */
void rg_thresholds_init(rg_thresholds *t);
/** Reads the rows of a CSV file into t (lines starting with '#' and blank lines are skipped; a
 *  first line "suite,scene,..." is a header). On a malformed row returns false and err names the
 *  file and the line. */
bool rg_thresholds_load(rg_thresholds *t, const char *path, sc_msg *err);
/** The targets of a scene of a file: the row of its suite (the file's stem), else of the file's
 *  folder name, else of suite "*"; figures no row gives are the defaults; the overrides win. */
rg_limits rg_thresholds_for(const rg_thresholds *t, const char *file_path, const char *scene);
/** The stem of a file path ("scenes/default.json" -> "default") as a new string; NULL when out of
 *  memory. */
char *rg_file_stem(const char *path);
/** Frees the rows. */
void rg_thresholds_free(rg_thresholds *t);

#endif
