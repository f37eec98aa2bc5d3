/* runs.h - runs of partly covered tiles waiting to be shaded, grouped by triangle, so that a
 * draw with a runs function (sg_shade_runs_fn) packs each triangle's pixels from several tiles
 * into full vectors: small triangles cover most of their tiles partly. A group per triangle id,
 * found by a hash of the id (open addressing); the runs are put in group order when shaded. The
 * one-sample bins (rast_bin.c) shade them into the bin's colour; the multisampled ones
 * (rast_msaa.c) into a plane of their own, each run's colour then put into the samples that see
 * its triangle. */
#ifndef SG_RASTER_RUNS_H
#define SG_RASTER_RUNS_H

#include <stdbool.h>
#include <stdint.h>
#include <string.h>

#include "raster/rast_bin.h"

enum { SG_RUN_CAP = 1024, SG_RUN_SLOTS = 2 * SG_RUN_CAP };
typedef struct sg_run_set {
    int n, groups;
    bool fresh;                      /* slot not emptied yet */
    uint16_t slot[SG_RUN_SLOTS];     /* group + 1, 0 empty */
    uint32_t group_id[SG_RUN_CAP];   /* the triangle id of each group */
    uint16_t group_slot[SG_RUN_CAP]; /* its slot, emptied after the shading */
    uint16_t group_n[SG_RUN_CAP];    /* its runs */
    uint16_t run_group[SG_RUN_CAP];
    sg_run run[SG_RUN_CAP];
    /* Multisampled bins: each run's pixels per sample, sample k's in bits 16 k .. 16 k + 15. */
    uint64_t samples[SG_RUN_CAP];
} sg_run_set;

/* Where a flush puts the shaded runs: `color`, a bin's tiles; with `planes` (multisampled bins),
 * color is a scratch plane and each run's pixels go from it to planes[k] where sample k sees the
 * run's triangle (sg_run_set.samples). */
typedef struct sg_run_target {
    uint32_t *color;
    uint32_t *const *planes;
    int x0, y0; /* the bin's top-left pixel */
} sg_run_target;

/** s ready to collect runs, or NULL when no draw of the pass packs them (its slots are emptied
 *  at the first run: bins without one skip that). */
static inline sg_run_set *sg_runs_start(const sg_bin_pass *p, sg_run_set *s) {
    if (!p->any_runs) return NULL;
    s->n = s->groups = 0;
    s->fresh = true;
    return s;
}

/** Shades the runs collected so far, group by group, into the target, and empties the set. */
void sg_runs_flush(const sg_bin_pass *p, sg_run_set *s, const sg_run_target *to);

/** Adds a run of triangle `id` (in a multisampled bin, with its pixels per sample) to its group,
 *  shading what the set holds first when it is full. */
static inline void sg_runs_add(const sg_bin_pass *p, sg_run_set *s, uint32_t id, int tile,
                               uint32_t mask, uint64_t samples, const sg_run_target *to) {
    if (s->n == SG_RUN_CAP) sg_runs_flush(p, s, to);
    if (s->fresh) {
        memset(s->slot, 0, sizeof s->slot);
        s->fresh = false;
    }
    unsigned h = (id * 2654435761u) >> (32 - 11); /* SG_RUN_SLOTS = 2^11 */
    while (s->slot[h] && s->group_id[s->slot[h] - 1] != id) h = (h + 1) & (SG_RUN_SLOTS - 1);
    int g = s->slot[h] - 1;
    if (g < 0) { /* a new group: fewer groups than runs, so fewer than half the slots are used */
        g = s->groups++;
        s->slot[h] = (uint16_t)(g + 1);
        s->group_id[g] = id;
        s->group_slot[g] = (uint16_t)h;
        s->group_n[g] = 0;
    }
    s->group_n[g]++;
    s->run_group[s->n] = (uint16_t)g;
    if (to->planes) s->samples[s->n] = samples;
    s->run[s->n++] = (sg_run){(uint16_t)tile, (uint16_t)mask};
}

#endif
