/* bin.c - sorting set-up triangles into screen bins (see bin.h). Storage grows and is kept, so a
 * steady stream of similar frames allocates nothing. */
#include "raster/bin.h"

#include <stdbool.h>

#include <string.h>

enum { LAZY_BYTES = 1 << 20 };

/* Grows an array to hold `need` elements of `size` bytes, doubling, keeping its first `used`;
 * false when out of memory. */
static bool grow(sg_binner *b, void **ptr, size_t *capacity, size_t need, size_t used,
                 size_t size) {
    if (need <= *capacity) return true;
    size_t cap = *capacity ? *capacity : 64;
    while (cap < need) cap *= 2;
    /* The triangles' storage stays within the pass's memory budget (bin.h, memory_limit). */
    if (ptr == (void **)&b->tris && b->memory_limit) {
        size_t most = b->memory_limit / sg_binner_tri_bytes(b);
        /* Past LAZY_BYTES, storage the C library gives (resize) grows once to the whole budget:
         * so large a block is mapped, not taken from the heap, and its pages are touched only as
         * triangles are stored, so a big pass neither copies nor touches its storage twice. */
        if (b->resize && cap * size > LAZY_BYTES) cap = most;
        /* Never below need: triangles a round's run could not hold are appended past the
         * budget's size (the front end's rest), and must have room. Past the budget it grows
         * an eighth beyond need, not to need alone: that rest, set up a triangle at a time,
         * would resize (copy) the whole array once a triangle. */
        if (cap > most) cap = most;
        if (cap < need) cap = need + need / 8;
    }
    if (b->resize && *ptr) {
        void *p = b->resize(*ptr, cap * size, b->user);
        if (!p) return false;
        *ptr = p;
        *capacity = cap;
        return true;
    }
    void *p = b->alloc(cap * size, b->user);
    if (!p) return false;
    if (*ptr) {
        if (used) memcpy(p, *ptr, used * size);
        b->free(*ptr, b->user);
    }
    *ptr = p;
    *capacity = cap;
    return true;
}

bool sg_binner_reset(sg_binner *b, int width, int height) {
    int bx = (width + SG_BIN_SIZE - 1) >> SG_BIN_SHIFT,
        by = (height + SG_BIN_SIZE - 1) >> SG_BIN_SHIFT;
    if (bx * by > b->bin_capacity) {
        sg_bin *bins = b->alloc((size_t)(bx * by) * sizeof *bins, b->user);
        if (!bins) return false;
        memset(bins, 0, (size_t)(bx * by) * sizeof *bins);
        if (b->bins) {
            memcpy(bins, b->bins, (size_t)b->bin_capacity * sizeof *bins);
            b->free(b->bins, b->user);
        }
        b->bins = bins;
        b->bin_capacity = bx * by;
    }
    b->bins_x = bx;
    b->bins_y = by;
    b->use_ext = false;
    sg_binner_clear(b);
    return true;
}

void sg_binner_clear(sg_binner *b) {
    for (int i = 0; i < b->bins_x * b->bins_y; i++) b->bins[i].count = 0;
    b->tri_count = 0;
    b->listed = 0;
    b->out_of_memory = false;
}

size_t sg_binner_tri_bytes(const sg_binner *b) {
    return sizeof(sg_tri) + (b->use_ext ? sizeof(sg_tri_ext) : 0);
}

size_t sg_binner_bytes(const sg_binner *b) {
    return b->tri_count * sg_binner_tri_bytes(b) + b->listed * sizeof(uint32_t);
}

bool sg_binner_use_ext(sg_binner *b) {
    size_t cap = b->ext_capacity;
    if (!grow(b, (void **)&b->ext, &cap, b->tri_capacity ? b->tri_capacity : 64, 0, sizeof *b->ext))
        return false;
    b->ext_capacity = cap;
    b->use_ext = true;
    return true;
}

void sg_binner_commit(sg_binner *b) {
    b->tris[b->tri_count].draw = b->draw;
    sg_binner_list(b, (uint32_t)b->tri_count++);
}

sg_tri *sg_binner_reserve(sg_binner *b, size_t n) {
    /* Ids are index + 1 in 32 bits (depth.h). */
    if (b->out_of_memory || n > UINT32_MAX - 1 - b->tri_count) {
        b->out_of_memory = true;
        return NULL;
    }
    /* The extensions are checked too: when the triangles grew and the extensions then could not,
     * the call failed, and a retry must grow the extensions rather than write past them. */
    if (b->tri_count + n <= b->tri_capacity && (!b->use_ext || b->ext_capacity >= b->tri_capacity))
        return b->tris + b->tri_count;
    /* Growing: the extensions grow with the triangles while the pass uses them. */
    if (!grow(b, (void **)&b->tris, &b->tri_capacity, b->tri_count + n, b->tri_count,
              sizeof *b->tris) ||
        (b->use_ext && !grow(b, (void **)&b->ext, &b->ext_capacity, b->tri_capacity, b->tri_count,
                             sizeof *b->ext))) {
        b->out_of_memory = true;
        return NULL;
    }
    return b->tris + b->tri_count;
}

bool sg_binner_grow(sg_binner *b, size_t capacity) {
    if (b->out_of_memory) return false;
    if (!grow(b, (void **)&b->tris, &b->tri_capacity, capacity, b->tri_count, sizeof *b->tris) ||
        (b->use_ext && !grow(b, (void **)&b->ext, &b->ext_capacity, b->tri_capacity, b->tri_count,
                             sizeof *b->ext))) {
        b->out_of_memory = true;
        return false;
    }
    return true;
}

static int64_t floor_div(int64_t a, int64_t b) { /* b > 0 */
    int64_t q = a / b;
    return q - (a % b < 0);
}

/* The bins a line's band crosses (line.h): along its major axis, the one or two bins across that
 * its band reaches in each (its minor coordinate moves at most a pixel a pixel). A long diagonal
 * line is listed in about twice as many bins as it is long in bins, not in every bin of its
 * bounds. */
enum { LINE_BINS_MAX = 2 * (SG_MAX_IMAGE_SIZE / SG_BIN_SIZE + 1) };

static int line_bins(const sg_binner *b, const sg_tri *t, int out[LINE_BINS_MAX]) {
    const bool xm = t->line == 1;
    const int64_t major_step = xm ? t->edge_dx[0] : t->edge_dy[0];
    const int64_t minor_step = -(xm ? t->edge_dy[0] : t->edge_dx[0]); /* > 0 */
    const int maj_lo = xm ? t->minx : t->miny, maj_hi = xm ? t->maxx : t->maxy;
    const int min_lo = xm ? t->miny : t->minx, min_hi = xm ? t->maxy : t->maxx;
    int n = 0;
    for (int m = maj_lo >> SG_BIN_SHIFT; m <= maj_hi >> SG_BIN_SHIFT; m++) {
        int u0 = m << SG_BIN_SHIFT, u1 = u0 + SG_BIN_SIZE - 1;
        if (u0 < maj_lo) u0 = maj_lo;
        if (u1 > maj_hi) u1 = maj_hi;
        int64_t v0 = floor_div(t->edge[0] + (int64_t)(u0 - maj_lo) * major_step, minor_step);
        int64_t v1 = floor_div(t->edge[0] + (int64_t)(u1 - maj_lo) * major_step, minor_step);
        int64_t lo = (v0 < v1 ? v0 : v1) + min_lo, hi = (v0 < v1 ? v1 : v0) + min_lo;
        if (lo < min_lo) lo = min_lo;
        if (hi > min_hi) hi = min_hi;
        for (int64_t k = lo >> SG_BIN_SHIFT; k <= hi >> SG_BIN_SHIFT; k++)
            out[n++] = xm ? (int)k * b->bins_x + m : m * b->bins_x + (int)k;
    }
    return n;
}

/* Appends triangle `index` to bin k; false: out of memory. */
static bool list_in(sg_binner *b, int k, uint32_t index) {
    sg_bin *bin = &b->bins[k];
    if (bin->count == bin->capacity) {
        size_t cap = bin->capacity;
        if (!grow(b, (void **)&bin->tris, &cap, bin->count + 1u, bin->count, sizeof *bin->tris)) {
            b->out_of_memory = true;
            return false;
        }
        bin->capacity = (uint32_t)cap;
    }
    bin->tris[bin->count++] = index;
    b->listed++;
    return true;
}

void sg_binner_list(sg_binner *b, uint32_t index) {
    const sg_tri *tri = &b->tris[index];
    if (tri->line) {
        int bins[LINE_BINS_MAX], n = line_bins(b, tri, bins);
        for (int i = 0; i < n && list_in(b, bins[i], index); i++) continue;
        return;
    }
    for (int y = tri->miny >> SG_BIN_SHIFT; y <= tri->maxy >> SG_BIN_SHIFT; y++)
        for (int x = tri->minx >> SG_BIN_SHIFT; x <= tri->maxx >> SG_BIN_SHIFT; x++)
            if (!list_in(b, y * b->bins_x + x, index)) return;
}

/* A triangle's bins as four bytes: first and last column, first and last row (a target is at
 * most 256 bins wide and high). A line, whose bins are not its bounds', is marked by a first
 * column past its last. */
enum { RANGE_LINE = 0xffu };
_Static_assert(SG_MAX_IMAGE_SIZE / SG_BIN_SIZE <= 256, "a bin index fits a byte");

uint32_t sg_binner_count_tri(const sg_binner *b, const sg_tri *t, uint32_t *counts) {
    if (t->line) {
        int bins[LINE_BINS_MAX], nb = line_bins(b, t, bins);
        for (int k = 0; k < nb; k++) counts[bins[k]]++;
        return RANGE_LINE;
    }
    const int x0 = t->minx >> SG_BIN_SHIFT, x1 = t->maxx >> SG_BIN_SHIFT;
    const int y0 = t->miny >> SG_BIN_SHIFT, y1 = t->maxy >> SG_BIN_SHIFT;
    for (int y = y0; y <= y1; y++)
        for (int x = x0; x <= x1; x++) counts[y * b->bins_x + x]++;
    return (uint32_t)x0 | (uint32_t)x1 << 8 | (uint32_t)y0 << 16 | (uint32_t)y1 << 24;
}

bool sg_binner_make_room(sg_binner *b, uint32_t *counts, int runs) {
    int nbins = b->bins_x * b->bins_y;
    for (int i = 0; i < nbins; i++) {
        sg_bin *bin = &b->bins[i];
        uint64_t need = bin->count;
        for (int r = 0; r < runs; r++) need += counts[(size_t)r * (size_t)nbins + (size_t)i];
        size_t cap = bin->capacity;
        if (need > UINT32_MAX ||
            !grow(b, (void **)&bin->tris, &cap, (size_t)need, bin->count, sizeof *bin->tris)) {
            b->out_of_memory = true;
            return false;
        }
        bin->capacity = (uint32_t)cap;
    }
    for (int i = 0; i < nbins; i++) { /* then no list changes unless all could grow */
        sg_bin *bin = &b->bins[i];
        for (int r = 0; r < runs; r++) {
            uint32_t *c = &counts[(size_t)r * (size_t)nbins + (size_t)i], k = *c;
            *c = bin->count;
            bin->count += k;
            b->listed += k;
        }
    }
    return true;
}

void sg_binner_fill(const sg_binner *b, size_t first, size_t n, const uint32_t *ranges,
                    uint32_t *at) {
    for (size_t i = 0; i < n; i++) {
        const uint32_t r = ranges[i], index = (uint32_t)(first + i);
        if (r == RANGE_LINE) {
            int bins[LINE_BINS_MAX], nb = line_bins(b, &b->tris[first + i], bins);
            for (int k = 0; k < nb; k++) b->bins[bins[k]].tris[at[bins[k]]++] = index;
            continue;
        }
        const int x0 = (int)(r & 0xffu), x1 = (int)(r >> 8 & 0xffu);
        const int y0 = (int)(r >> 16 & 0xffu), y1 = (int)(r >> 24);
        for (int y = y0; y <= y1; y++)
            for (int x = x0; x <= x1; x++) {
                int bin = y * b->bins_x + x;
                b->bins[bin].tris[at[bin]++] = index;
            }
    }
}

void sg_binner_truncate(sg_binner *b, size_t count) {
    for (int i = 0; i < b->bins_x * b->bins_y; i++) {
        sg_bin *bin = &b->bins[i];
        while (bin->count && bin->tris[bin->count - 1] >= count) {
            bin->count--;
            b->listed--;
        }
    }
    b->tri_count = count;
    b->out_of_memory = false;
}

void sg_binner_release(sg_binner *b) {
    for (int i = 0; i < b->bin_capacity; i++)
        if (b->bins[i].tris) b->free(b->bins[i].tris, b->user);
    if (b->bins) b->free(b->bins, b->user);
    if (b->tris) b->free(b->tris, b->user);
    if (b->ext) b->free(b->ext, b->user);
    memset(b, 0, sizeof *b);
}
