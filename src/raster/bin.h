/* bin.h - screen bins: the set-up triangles of a whole render pass sorted into 64 x 64-pixel
 * bins, in submission order, so that bins can be rendered on any thread in any order with the
 * same result. */
#ifndef SG_BIN_H
#define SG_BIN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "pipeline/setup.h"

#define SG_BIN_SHIFT 6
#define SG_BIN_SIZE  (1 << SG_BIN_SHIFT)

typedef struct sg_bin {
    uint32_t *tris; /* indices into sg_binner.tris, in submission order */
    uint32_t count, capacity;
} sg_bin;

typedef struct sg_binner {
    void *(*alloc)(size_t size, void *user);
    void (*free)(void *ptr, void *user);
    /* Optional (NULL: alloc, copy, free): grows a block keeping its contents. The C library's
     * realloc moves a large block's pages instead of copying them, so the storage of a big pass
     * grows without copying what is binned or touching its pages twice. */
    void *(*resize)(void *ptr, size_t size, void *user);
    void *user;
    sg_tri *tris;
    size_t tri_count, tri_capacity;
    size_t listed;       /* entries in all bins' lists */
    size_t memory_limit; /* the triangles' storage never grows past it (0: no limit) */
    /* Beside tris, same index: the attributes beyond SG_TRI_ATTRS of lit draws. Kept as large as
     * tris once a pass has used it (use_ext), so a triangle's extension is always at hand. */
    sg_tri_ext *ext;
    size_t ext_capacity;
    bool use_ext;
    sg_bin *bins;
    int bins_x, bins_y, bin_capacity;
    uint32_t draw;      /* stamped on each added triangle */
    bool out_of_memory; /* set when a list could not grow; the draw is then abandoned */
} sg_binner;

/** Empties every bin and sizes the grid for a width x height target. */
bool sg_binner_reset(sg_binner *b, int width, int height);
/** Empties every bin and forgets every triangle, keeping the grid and the storage (a flush). */
void sg_binner_clear(sg_binner *b);
/** Bytes a stored triangle takes: its record, and its extension while the pass uses them. */
size_t sg_binner_tri_bytes(const sg_binner *b);
/** Bytes of binned work: the stored triangles' records and the bins' list entries. */
size_t sg_binner_bytes(const sg_binner *b);
/** From now on in this pass, every triangle has room for an sg_tri_ext; false: out of memory
 *  (nothing changed). */
bool sg_binner_use_ext(sg_binner *b);
/** Room for n more triangles at tris + tri_count (NULL, and out_of_memory, when there is none);
 *  the caller fills them, then moves tri_count and lists each filled one with sg_binner_list.
 *  Growing copies the tri_count triangles stored (none right after sg_binner_clear). */
sg_tri *sg_binner_reserve(sg_binner *b, size_t n);
/** Room for `capacity` triangles in all (doubling; copies the tri_count stored, none right after
 *  sg_binner_clear); false, and out_of_memory, when there is none. */
bool sg_binner_grow(sg_binner *b, size_t capacity);
/** The triangle just built at tris + tri_count (sg_binner_reserve) is kept: stamped with
 *  b->draw and listed. */
void sg_binner_commit(sg_binner *b);
/** Lists a stored triangle in every bin its bounds touch (after those listed before it). */
void sg_binner_list(sg_binner *b, uint32_t index);
/* Listing many stored triangles on several threads, in the order one thread would give: each
 * thread counts its run's triangles per bin as it stores them (sg_binner_count_tri, while the
 * triangle is still in its cache), sg_binner_make_room turns the counts of all runs into each
 * run's first free place in every bin (growing the lists), and each thread then writes its run
 * there from the bin ranges the counting kept (4 bytes a triangle, not its 224). counts is runs x
 * bins_x * bins_y entries, run-major. */

/** Adds triangle t's bins to counts[]; returns its bin range, packed for sg_binner_fill. */
uint32_t sg_binner_count_tri(const sg_binner *b, const sg_tri *t, uint32_t *counts);
/** Counts of `runs` runs -> their write positions; grows every list; false when out of memory
 *  (out_of_memory is set and nothing was listed). */
bool sg_binner_make_room(sg_binner *b, uint32_t *counts, int runs);
/** Writes the indices of tris[first .. first + n) at the positions `at` (advancing them);
 *  ranges[i] is what sg_binner_count_tri returned for tris[first + i]. */
void sg_binner_fill(const sg_binner *b, size_t first, size_t n, const uint32_t *ranges,
                    uint32_t *at);
/** Forgets every triangle from index `count` on: undoes a draw that ran out of memory. */
void sg_binner_truncate(sg_binner *b, size_t count);
/** Frees everything the binner holds. */
void sg_binner_release(sg_binner *b);

#endif
