/* draw.c - sgDraw: validates a draw, then runs the front end:
 * vertex (vertex.c) -> assembly, clipping, setup (assemble.c, clip.c, setup.c) -> screen bins
 * (bin.c). The bins are rendered at sgEndRenderPass (rast_bin.c). */
#include "core/device.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "pipeline/assemble.h"
#include "pipeline/mat4.h"
#include "pipeline/sort.h"
#include "pipeline/vertex.h"
#include "pipeline/vertex_shader.h"
#include "raster/shade.h"
#include "raster/shade_shader.h"
#include "tex/sample16.h"

/* Above this, the pass's triangles are not copied to grow their storage: what is binned is
 * rendered first (a flush), and the storage then grows empty. Only the first frames of a large
 * scene grow, once each size. Storage that can be resized in place (bin.h, resize) just grows. */
enum { GROW_COPY_BYTES = 4 << 20 };

/* Makes way for n more triangles: when they would take the pass's binned work past the device's
 * budget, or their storage would grow by copying much, what is binned is rendered first
 * (sg_pass_flush). Empty storage grows at once to the largest pass seen (most_tris, within the
 * budget): a scene's second frame then needs no flush to grow. False: out of memory
 * (out_of_memory is set). */
static bool room_for(sgDevice *dev, size_t n) {
    sg_binner *b = &dev->binner;
    if (!b->tri_count) {
        size_t want = dev->most_tris, most = dev->bin_flush_at / sg_binner_tri_bytes(b);
        if (want > most) want = most;
        return b->tri_capacity >= want || sg_binner_grow(b, want);
    }
    size_t tb = sg_binner_tri_bytes(b);
    bool over = sg_binner_bytes(b) + n * (tb + sizeof(uint32_t)) > dev->bin_flush_at;
    bool copy =
        !b->resize && b->tri_count + n > b->tri_capacity && b->tri_count * tb > GROW_COPY_BYTES;
    if (!over && !copy) return true;
    if (!sg_pass_flush(dev)) {
        b->out_of_memory = true;
        return false;
    }
    dev->draw_first = 0; /* the draw's triangles before are in the targets now */
    dev->draw_flushed = true;
    /* Flushed to grow: the storage doubles now that it holds nothing to copy. */
    return !copy || sg_binner_grow(b, 2 * b->tri_capacity);
}

/* Setup builds each triangle in the binner's array; the bins are rendered when the pass ends, or
 * at a flush (room_for). */
static sg_tri *bin_slot(void *user, sg_tri_ext **ext) {
    sgDevice *dev = user;
    sg_binner *b = &dev->binner;
    /* The budget is looked at only when the triangles or the list entries pass half of what was
     * left at the last look, or the storage is full (room_tris, room_listed): two compares a
     * triangle. Below room_tris the storage (and the extensions') holds the triangle, so the
     * common case needs no call. */
    if (b->tri_count < dev->room_tris && b->listed < dev->room_listed && !b->out_of_memory) {
        if (b->use_ext) *ext = b->ext + b->tri_count;
        return b->tris + b->tri_count;
    }
    if (b->out_of_memory || !room_for(dev, 1) || !sg_binner_reserve(b, 1)) return NULL;
    size_t used = sg_binner_bytes(b);
    size_t left = dev->bin_flush_at > used ? dev->bin_flush_at - used : 0;
    size_t tris = left / 2 / (sg_binner_tri_bytes(b) + sizeof(uint32_t));
    if (tris > b->tri_capacity - b->tri_count) tris = b->tri_capacity - b->tri_count;
    dev->room_tris = b->tri_count + tris; /* tris 0: look again at the next triangle */
    dev->room_listed = b->listed + left / 2 / sizeof(uint32_t);
    sg_tri *t = sg_binner_reserve(b, 1);
    if (t && b->use_ext) *ext = b->ext + b->tri_count;
    return t;
}

static void bin_emit(void *user) {
    sg_binner_commit(&((sgDevice *)user)->binner);
}

/* bin_slot without flushes, where triangles set up but not listed yet are in the array. */
static sg_tri *bin_slot_kept(void *user, sg_tri_ext **ext) {
    sg_binner *b = &((sgDevice *)user)->binner;
    sg_tri *t = sg_binner_reserve(b, 1);
    if (t && b->use_ext) *ext = b->ext + b->tri_count;
    return t;
}

/* The front end of a large draw runs on all threads, in rounds: each chunk of a round's
 * primitives is assembled into its own reserved run of the pass's triangle array, and the runs
 * are then listed in the bins in chunk order, so the bins hold exactly the sequence a single
 * thread would give. A run holds its primitives' triangles unclipped and one block more; a chunk
 * works in blocks of FE_BLOCK primitives and stops before a block its run may not hold (clipping
 * makes more triangles), and the calling thread assembles the rest of it at its place in the
 * order. The array ends after the last run's triangles, so what the next round reserves follows
 * the triangles kept. (Sizing runs by the share a draw's earlier primitives kept was tried: a
 * sphere's first rounds, its poles, keep almost none, and the chunks of the next stopped at once,
 * their rest on one thread.) */
enum { FE_MIN_TRIANGLES = 4096, FE_MAX_CHUNKS = 64, FE_BLOCK = 256 };

typedef struct fe_chunk {
    sg_assembly a;
    sg_tri *out;
    sg_tri_ext *out_ext; /* beside out, when the draw uses extensions */
    size_t base, count, capacity;
    const sg_binner *binner;
    uint32_t *counts;  /* the chunk's triangles per bin (NULL: listed one by one afterwards) */
    uint32_t *ranges;  /* each triangle's bins (sg_binner_count_tri), beside out */
    int per, tris_per; /* indices a primitive, raster primitives it makes at most unclipped */
    int done;          /* primitives assembled; the rest are the calling thread's */
    uint32_t draw;
    bool overflow;
} fe_chunk;

static sg_tri *fe_slot(void *user, sg_tri_ext **ext) {
    fe_chunk *c = user;
    if (c->count < c->capacity) {
        if (c->out_ext) *ext = &c->out_ext[c->count];
        return &c->out[c->count];
    }
    c->overflow = true;
    return NULL;
}

static void fe_emit(void *user) {
    fe_chunk *c = user;
    sg_tri *t = &c->out[c->count];
    t->draw = c->draw;
    if (c->counts) c->ranges[c->count] = sg_binner_count_tri(c->binner, t, c->counts);
    c->count++;
}

/* Assembles the primitives of c->a from the first into the chunk's run, in blocks; false when it
 * stopped before a block the run may not hold (c->done primitives are in it). */
static bool fe_blocks(fe_chunk *c) {
    sg_assembly a = c->a;
    a.slot = fe_slot;
    a.emit = fe_emit;
    a.user = c;
    const int prims = c->a.index_count / c->per;
    for (c->done = 0; c->done < prims;) {
        int n = prims - c->done < FE_BLOCK ? prims - c->done : FE_BLOCK;
        /* Room for the block unclipped; clipping can make more, then the block is undone. */
        if (c->capacity - c->count < (size_t)n * (size_t)c->tris_per) return false;
        size_t before = c->count;
        a.indices = c->a.indices + (size_t)c->done * (size_t)c->per;
        a.prim_base = c->a.prim_base + c->done;
        a.index_count = n * c->per;
        sg_assemble(&a);
        if (c->overflow) {
            c->count = before;
            return false;
        }
        c->done += n;
    }
    return true;
}

static void fe_clear_counts(fe_chunk *c) {
    if (c->counts)
        memset(c->counts, 0, (size_t)(c->binner->bins_x * c->binner->bins_y) * sizeof *c->counts);
}

static void fe_run(void *chunks, int index) {
    fe_chunk *c = (fe_chunk *)chunks + index;
    fe_clear_counts(c);
    fe_blocks(c);
}

/* Lists the chunks' triangles in the bins on every thread (sg_binner_make_room, _fill), from
 * the counts the chunks made: the same lists, in the same order, as listing them one by one. */
typedef struct fe_list {
    const sg_binner *b;
    const fe_chunk *chunks;
    size_t first;
} fe_list;

static void fe_fill(void *vjob, int i) {
    const fe_list *j = vjob;
    const fe_chunk *c = &j->chunks[i];
    sg_binner_fill(j->b, j->first + c->base, c->count, c->ranges, c->counts);
}

/* Room for the counts and bin ranges of n chunks of `total` triangles in all; false: none (the
 * chunks' triangles are then listed one by one). */
static bool count_room(sgDevice *dev, int n, size_t total) {
    size_t need = (size_t)n * (size_t)(dev->binner.bins_x * dev->binner.bins_y);
    if (need > dev->fe_counts_capacity) {
        uint32_t *c = sg_alloc(dev, need * sizeof *c);
        if (!c) return false;
        sg_free(dev, dev->fe_counts);
        dev->fe_counts = c;
        dev->fe_counts_capacity = need;
    }
    if (total > dev->fe_ranges_capacity) {
        uint32_t *r = sg_alloc(dev, total * sizeof *r);
        if (!r) return false;
        sg_free(dev, dev->fe_ranges);
        dev->fe_ranges = r;
        dev->fe_ranges_capacity = total;
    }
    return true;
}

/* A chunk of assembly a whose run starts `base` triangles into the round's and holds `prims`
 * primitives unclipped and a block more. */
static void fe_chunk_start(const sgDevice *dev, fe_chunk *c, const sg_assembly *a, size_t base,
                           size_t prims, int per, int tris_per) {
    c->a = *a;
    c->base = base;
    c->count = 0;
    c->capacity = (prims + FE_BLOCK) * (size_t)tris_per;
    c->per = per;
    c->tris_per = tris_per;
    c->done = 0;
    c->draw = dev->binner.draw;
    c->overflow = false;
}

/* Reserves the runs of n chunks (their bases and capacities set, `total` triangles in all) in
 * the pass's triangle array and points the chunks at them; false: no room (out_of_memory set, or
 * a flush failed). *counted: the chunks count their triangles per bin as they go. */
static bool fe_reserve(sgDevice *dev, fe_chunk *chunks, int n, size_t total, bool *counted) {
    sg_binner *b = &dev->binner;
    if (!room_for(dev, total)) return false;
    sg_tri *room = sg_binner_reserve(b, total);
    if (!room) return false; /* out_of_memory is set: the draw fails */
    *counted = count_room(dev, n, total);
    const size_t nbins = (size_t)(b->bins_x * b->bins_y);
    for (int i = 0; i < n; i++) {
        chunks[i].out = room + chunks[i].base;
        chunks[i].out_ext = b->use_ext ? b->ext + (room - b->tris) + chunks[i].base : NULL;
        chunks[i].binner = b;
        chunks[i].counts = *counted ? dev->fe_counts + (size_t)i * nbins : NULL;
        chunks[i].ranges = *counted ? dev->fe_ranges + chunks[i].base : NULL;
    }
    return true;
}

/* After the chunks ran (their runs from triangle `first` on): the array ends after the last
 * run's triangles, and when every chunk did all its work and counted, the runs are listed in the
 * bins on every thread; false: the caller lists them one by one, with what each left undone. */
static bool fe_list_runs(sgDevice *dev, const fe_chunk *chunks, int n, size_t first, bool all,
                         bool counted) {
    sg_binner *b = &dev->binner;
    /* The room reserved past the last run's triangles is free. */
    b->tri_count += chunks[n - 1].base + chunks[n - 1].count;
    if (!all || !counted) return false;
    fe_list job = {b, chunks, first};
    if (sg_binner_make_room(b, dev->fe_counts, n))
        sg_workers_run_shares(&dev->workers, n, fe_fill, &job);
    return true;
}

/* One round of a large draw: primitives [p0, p0 + prims) on every thread. */
static void assemble_round(sgDevice *dev, const sg_assembly *a, int p0, int prims, int per,
                           int tris_per, int n) {
    fe_chunk chunks[FE_MAX_CHUNKS];
    size_t total = 0;
    for (int i = 0; i < n; i++) {
        int q0 = p0 + (int)((int64_t)prims * i / n), q1 = p0 + (int)((int64_t)prims * (i + 1) / n);
        fe_chunk_start(dev, &chunks[i], a, total, (size_t)(q1 - q0), per, tris_per);
        chunks[i].a.indices = a->indices + (size_t)q0 * (size_t)per;
        chunks[i].a.prim_base = a->prim_base + q0;
        chunks[i].a.index_count = (q1 - q0) * per;
        total += chunks[i].capacity;
    }
    sg_binner *b = &dev->binner;
    bool counted;
    if (!fe_reserve(dev, chunks, n, total, &counted)) return;
    size_t first = b->tri_count;
    sg_workers_run_shares(&dev->workers, n, fe_run, chunks);
    bool all = true;
    for (int i = 0; i < n; i++) all &= chunks[i].done == chunks[i].a.index_count / per;
    if (fe_list_runs(dev, chunks, n, first, all, counted)) return;
    for (int i = 0; i < n && !b->out_of_memory; i++) {
        for (size_t k = 0; k < chunks[i].count; k++)
            sg_binner_list(b, (uint32_t)(first + chunks[i].base + k));
        int prims_i = chunks[i].a.index_count / per;
        if (chunks[i].done < prims_i) { /* the rest, on this thread, appended to the array */
            sg_assembly rest = chunks[i].a;
            rest.indices += (size_t)chunks[i].done * (size_t)per;
            rest.prim_base += chunks[i].done;
            rest.index_count = (prims_i - chunks[i].done) * per;
            rest.slot = bin_slot_kept; /* the chunks after it are not listed yet */
            rest.emit = bin_emit;
            rest.user = dev;
            sg_assemble(&rest);
        }
    }
}

/* Assembles a draw on every thread, in rounds whose reserved triangles take at most a quarter of
 * the device's budget (a flush may come between two); false when it is too small to be worth
 * it. */
static bool assemble_parallel(sgDevice *dev, const sg_assembly *a) {
    /* Per primitive: its indices and the raster primitives it makes at most (a wireframe
     * triangle three lines, a quad four). */
    int per = a->lines ? 2 : a->quads ? 4 : 3;
    int tris_per = a->wire ? (a->quads ? 4 : 3) : a->quads ? 2 : 1;
    int prims = a->index_count / per;
    if (dev->thread_count < 2 || prims * tris_per < FE_MIN_TRIANGLES) return false;
    int n = 4 * dev->thread_count < FE_MAX_CHUNKS ? 4 * dev->thread_count : FE_MAX_CHUNKS;
    const sg_binner *b = &dev->binner;
    size_t slots = dev->bin_flush_at / 4 / (sg_binner_tri_bytes(b) + sizeof(uint32_t));
    size_t margin = (size_t)n * FE_BLOCK * (size_t)tris_per;
    for (int p = 0; p < prims && !b->out_of_memory;) {
        size_t fit = slots > margin ? (slots - margin) / (size_t)tris_per : 0;
        int r = (size_t)(prims - p) > fit ? (int)fit : prims - p;
        if ((size_t)r * (size_t)tris_per < FE_MIN_TRIANGLES) { /* the rest on this thread */
            sg_assembly rest = *a;
            rest.indices = a->indices + (size_t)p * (size_t)per;
            rest.prim_base = a->prim_base + p;
            rest.index_count = (prims - p) * per;
            sg_assemble(&rest);
            break;
        }
        assemble_round(dev, a, p, r, per, tris_per, n);
        p += r;
    }
    return true;
}

/* The vertex stage of a large geom, in chunks of vertices on all threads. */
typedef struct vs_job {
    const float *mvp, *positions, *colors, *texcoords;
    const sgDevice *dev;
    const sg_guard *guard;
    const sg_setup_params *setup;
    const sg_vertex_lit *lit; /* lit draws: their vertex attributes, into dev->lit */
    int count, chunks;
} vs_job;

static void vs_run(void *vjob, int index) {
    const vs_job *j = vjob;
    int v0 = (int)((int64_t)j->count * index / j->chunks);
    int v1 = (int)((int64_t)j->count * (index + 1) / j->chunks);
    const sgDevice *dev = j->dev;
    sg_vertex_transform_project(j->mvp, j->positions + (size_t)v0 * 4, v1 - v0, dev->outcodes + v0,
                                j->guard, j->setup, dev->screen + v0, dev->screen_ok + v0);
    if (j->lit)
        sg_vertex_lit_attributes(j->lit, v0, v1 - v0, dev->lit, dev->screen_ok);
    else
        sg_vertex_check_attributes(j->colors ? j->colors + (size_t)v0 * 4 : NULL,
                                   j->texcoords ? j->texcoords + (size_t)v0 * 2 : NULL,
                                   j->setup->nattr, v1 - v0, dev->screen_ok + v0);
}

static void transform_vertices(sgDevice *dev, const float *mvp, const sg_geom *geom,
                               const sg_guard *guard, const sg_setup_params *setup,
                               const sg_vertex_lit *lit, const float *colors) {
    vs_job job = {mvp,   geom->positions, colors, geom->texcoords,    dev,
                  guard, setup,           lit,    geom->vertex_count, 1};
    if (dev->thread_count > 1 && geom->vertex_count >= FE_MIN_TRIANGLES)
        job.chunks = 2 * dev->thread_count;
    sg_workers_run_shares(&dev->workers, job.chunks, vs_run, &job);
}

/* Room for one more draw record in the open pass. */
static bool grow_draws(sgDevice *dev) {
    if (dev->draw_count < dev->draw_capacity) return true;
    size_t cap = dev->draw_capacity ? 2 * dev->draw_capacity : 64;
    sg_draw_state *d = sg_alloc(dev, cap * sizeof *d);
    if (!d) return false;
    if (dev->draw_count) memcpy(d, dev->draws, dev->draw_count * sizeof *d);
    sg_free(dev, dev->draws);
    dev->draws = d;
    dev->draw_capacity = cap;
    dev->pass.draws = d;
    return true;
}

static bool grow_vertex_arenas(sgDevice *dev, size_t n) {
    if (dev->vertex_capacity >= n) return true;
    size_t cap = dev->vertex_capacity ? dev->vertex_capacity : 1024;
    while (cap < n) cap *= 2;
    sg_free(dev, dev->clip);
    sg_free(dev, dev->outcodes);
    sg_free(dev, dev->screen);
    sg_free(dev, dev->screen_ok);
    dev->clip = sg_alloc(dev, cap * sizeof *dev->clip);
    dev->outcodes = sg_alloc(dev, cap * sizeof *dev->outcodes);
    dev->screen = sg_alloc(dev, cap * sizeof *dev->screen);
    dev->screen_ok = sg_alloc(dev, cap * sizeof *dev->screen_ok);
    if (!dev->clip || !dev->outcodes || !dev->screen || !dev->screen_ok) {
        sg_free(dev, dev->clip);
        sg_free(dev, dev->outcodes);
        sg_free(dev, dev->screen);
        sg_free(dev, dev->screen_ok);
        dev->clip = NULL;
        dev->outcodes = NULL;
        dev->screen = NULL;
        dev->screen_ok = NULL;
        dev->vertex_capacity = 0;
        return false;
    }
    dev->vertex_capacity = cap;
    return true;
}

/* Room for a lit draw's vertex attributes. */
static bool grow_lit(sgDevice *dev, size_t floats) {
    if (dev->lit_capacity >= floats) return true;
    float *p = sg_alloc(dev, floats * sizeof *p);
    if (!p) return false;
    sg_free(dev, dev->lit);
    dev->lit = p;
    dev->lit_capacity = floats;
    return true;
}

/* A back-to-front draw's primitives, sorted into the device's scratch (sort.h): a.indices then
 * lists them as plain triangles (or lines). False: out of memory. */
static bool sort_primitives(sgDevice *dev, const sg_geom *geom, const float world_view[16],
                            sg_assembly *a) {
    const int per = a->lines ? 2 : a->quads ? 4 : 3, out_per = a->lines ? 2 : 3;
    size_t prims = (size_t)(geom->index_count / per) * (a->quads ? 2u : 1u);
    size_t scratch = sg_sort_scratch_size(geom->vertex_count, prims);
    size_t need = scratch + (size_t)out_per * prims * sizeof(uint32_t);
    if (need > dev->sort_scratch_capacity) {
        void *p = sg_alloc(dev, need);
        if (!p) return false;
        sg_free(dev, dev->sort_scratch);
        dev->sort_scratch = p;
        dev->sort_scratch_capacity = need;
    }
    uint32_t *out = (uint32_t *)(void *)((char *)dev->sort_scratch + scratch);
    sg_sort_back_to_front(world_view, geom->positions, geom->vertex_count, geom->indices,
                          geom->index_count, per, dev->sort_scratch, out);
    a->indices = out;
    a->index_count = (int)((size_t)out_per * prims);
    a->quads = 0;
    return true;
}

/* The shader vertex stage of one instance, in chunks of vertices on all threads. */
typedef struct vsh_job {
    sg_vertex_shader_run run;
    int count, chunks;
} vsh_job;

static void vsh_run(void *vjob, int index) {
    const vsh_job *j = vjob;
    int v0 = (int)((int64_t)j->count * index / j->chunks);
    int v1 = (int)((int64_t)j->count * (index + 1) / j->chunks);
    sg_vertex_shade(&j->run, v0, v1 - v0);
}

/* A shader draw of a small geom drawn many times runs its front end on every thread too, in rounds
 * of instances: each chunk of a round takes a run of instances, shades each one's vertices into
 * that instance's own slots of the arenas (slot s: vertices s v .. s v + v - 1 of a v-vertex
 * geom), then assembles them in order into its run of the triangle array, as a chunk of a large
 * draw does its primitives (the same blocks, the same listing in chunk order, the calling thread
 * doing what a run could not hold). The bins get the sequence the instances one by one give. */
typedef struct fe_inst {
    int first, count; /* the chunk's slots */
    int finished;     /* instances all of whose primitives are in the run */
} fe_inst;

typedef struct fe_inst_round {
    fe_chunk *chunks;
    fe_inst *inst;
    const vsh_job *vs;
    const sg_assembly *a; /* the draw's, its arenas from slot 0 */
    int instance0;        /* the instance in slot 0 */
} fe_inst_round;

/* The draw's assembly for the instance in slot s. */
static sg_assembly slot_assembly(const fe_inst_round *r, int s) {
    const size_t at = (size_t)s * (size_t)r->vs->count;
    sg_assembly a = *r->a;
    a.clip += at;
    a.outcodes += at;
    a.screen += at;
    a.screen_ok += at;
    a.vattr += at * (size_t)a.vstride;
    a.instance = r->instance0 + s;
    return a;
}

static void fe_inst_run(void *vround, int index) {
    const fe_inst_round *r = vround;
    fe_chunk *c = &r->chunks[index];
    fe_inst *in = &r->inst[index];
    for (int s = in->first; s < in->first + in->count; s++) {
        const size_t at = (size_t)s * (size_t)r->vs->count;
        sg_vertex_shader_run run = r->vs->run;
        run.instance = r->instance0 + s;
        run.clip += at;
        run.varyings += at * (size_t)run.varying_count;
        run.outcodes += at;
        run.screen += at;
        run.screen_ok += at;
        sg_vertex_shade(&run, 0, r->vs->count);
    }
    fe_clear_counts(c);
    for (in->finished = 0; in->finished < in->count; in->finished++) {
        c->a = slot_assembly(r, in->first + in->finished);
        if (!fe_blocks(c)) return;
    }
}

/* One round: the instances in slots [0, slots) on every thread (n chunks). */
static void instance_round(sgDevice *dev, const sg_assembly *a, const vsh_job *vs, int instance0,
                           int slots, int per, int tris_per, int n) {
    fe_chunk chunks[FE_MAX_CHUNKS];
    fe_inst inst[FE_MAX_CHUNKS];
    const size_t prims = (size_t)(a->index_count / per);
    size_t total = 0;
    for (int i = 0; i < n; i++) {
        inst[i].first = (int)((int64_t)slots * i / n);
        inst[i].count = (int)((int64_t)slots * (i + 1) / n) - inst[i].first;
        inst[i].finished = 0;
        fe_chunk_start(dev, &chunks[i], a, total, (size_t)inst[i].count * prims, per, tris_per);
        total += chunks[i].capacity;
    }
    sg_binner *b = &dev->binner;
    bool counted;
    if (!fe_reserve(dev, chunks, n, total, &counted)) return;
    size_t first = b->tri_count;
    fe_inst_round round = {chunks, inst, vs, a, instance0};
    sg_workers_run_shares(&dev->workers, n, fe_inst_run, &round);
    bool all = true;
    for (int i = 0; i < n; i++) all &= inst[i].finished == inst[i].count;
    if (fe_list_runs(dev, chunks, n, first, all, counted)) return;
    for (int i = 0; i < n && !b->out_of_memory; i++) {
        for (size_t k = 0; k < chunks[i].count; k++)
            sg_binner_list(b, (uint32_t)(first + chunks[i].base + k));
        /* the rest, on this thread, appended to the array: the unfinished instance from where
         * its run stopped, then the chunk's later ones */
        for (int f = inst[i].finished; f < inst[i].count && !b->out_of_memory; f++) {
            sg_assembly rest = slot_assembly(&round, inst[i].first + f);
            if (f == inst[i].finished) {
                rest.indices += (size_t)chunks[i].done * (size_t)per;
                rest.prim_base += chunks[i].done;
                rest.index_count -= chunks[i].done * per;
            }
            rest.slot = bin_slot_kept; /* the chunks after it are not listed yet */
            rest.emit = bin_emit;
            rest.user = dev;
            sg_assemble(&rest);
        }
    }
}

/* Instances a round of a shader draw may take (the arenas' slots), or 1: instances one by one,
 * each on every thread where its geom is large enough. */
enum { FE_INSTANCE_VERTICES = 65536 };
static int instance_slots(const sgDevice *dev, const sg_geom *geom, int instances) {
    const int vertices = geom->vertex_count;
    if (dev->thread_count < 2 || instances < 2 || vertices < 1 || vertices >= FE_MIN_TRIANGLES ||
        geom->index_count >= FE_MIN_TRIANGLES)
        return 1;
    const int most = FE_INSTANCE_VERTICES / vertices;
    return instances < most ? instances : most;
}

/* Every instance of a shader draw in rounds of at most `slots` (the arenas hold that many
 * instances' vertices), each round's reserved triangles at most a quarter of the device's budget,
 * as assemble_parallel's; a round too small to be worth it runs its instances one by one. */
static void assemble_instances(sgDevice *dev, sg_assembly *a, vsh_job *vs, int instances,
                               int slots) {
    const int per = a->lines ? 2 : a->quads ? 4 : 3;
    const int tris_per = a->wire ? (a->quads ? 4 : 3) : a->quads ? 2 : 1;
    const size_t inst_tris = (size_t)(a->index_count / per) * (size_t)tris_per;
    const int n = 4 * dev->thread_count < FE_MAX_CHUNKS ? 4 * dev->thread_count : FE_MAX_CHUNKS;
    const sg_binner *b = &dev->binner;
    const size_t room = dev->bin_flush_at / 4 / (sg_binner_tri_bytes(b) + sizeof(uint32_t));
    const size_t margin = (size_t)n * FE_BLOCK * (size_t)tris_per;
    for (int i = 0; i < instances && !b->out_of_memory;) {
        size_t fit = room > margin && inst_tris ? (room - margin) / inst_tris : 0;
        int k = instances - i < slots ? instances - i : slots;
        if ((size_t)k > fit) k = (int)fit;
        if (k < 2 || (size_t)k * inst_tris < FE_MIN_TRIANGLES) { /* one by one, in slot 0 */
            vs->run.instance = i;
            a->instance = i;
            sg_vertex_shade(&vs->run, 0, vs->count);
            sg_assemble(a);
            i++;
            continue;
        }
        instance_round(dev, a, vs, i, k, per, tris_per, k < n ? k : n);
        i += k;
    }
}

/* Assembles the open draw (its state is dev->draws' last) into the bins: once, or each of
 * `instances` after its vertex stage (vs: a shader draw). On running out of memory the draw's
 * triangles are taken back, unless a flush rendered some of them (then the pass fails). */
static sgResult run_front_end(sgDevice *dev, sg_assembly *a, vsh_job *vs, int instances,
                              int slots) {
    dev->draw_first = dev->binner.tri_count;
    dev->draw_flushed = false;
    dev->binner.draw = (uint32_t)(dev->draw_count - 1);
    if (vs && slots > 1) assemble_instances(dev, a, vs, instances, slots);
    for (int i = 0; slots <= 1 && i < instances && !dev->binner.out_of_memory; i++) {
        if (vs) {
            vs->run.instance = i;
            a->instance = i;
            sg_workers_run(&dev->workers, vs->chunks, vsh_run, vs);
        }
        if (!assemble_parallel(dev, a)) sg_assemble(a);
    }
    if (dev->binner.out_of_memory) { /* the pass goes on without this draw */
        size_t total = dev->binner.tri_count;
        sg_binner_truncate(&dev->binner, dev->draw_first);
        dev->draw_count--;
        if (dev->draw_flushed) {
            dev->pass_failed = true;
            return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                            "sgDraw: out of memory for %zu triangles in the pass, after a flush "
                            "(bin_memory_limit) rendered part of the draw; the pass can only end",
                            total);
        }
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: out of memory for %zu triangles in the pass", total);
    }
    return SG_OK;
}

static bool unit_range(float v) {
    return v >= 0.0f && v <= 1.0f; /* false for NaN */
}

/* sg_light_prepare's refusal of a draw's lighting, recorded as the draw's error. */
typedef struct light_refusal {
    sgDevice *dev;
    sgResult result;
} light_refusal;

static void refuse_lighting(void *user, int code, const char *fmt, va_list ap) {
    light_refusal *r = user;
    r->result = sg_verror(r->dev, (sgResult)code, "sgDraw: ", fmt, ap);
}

/* What the assembly of every draw starts from: the geom's primitives, the vertex stage's arenas
 * and the binner as the triangles' destination. */
static sg_assembly assembly_of(sgDevice *dev, const sg_pso *pso, const sg_geom *geom) {
    sg_assembly a = {0};
    a.guard = sg_guard_for_viewport(dev->pass.width, dev->pass.height);
    a.indices = geom->indices;
    a.index_count = geom->index_count;
    a.quads = geom->primitive == SG_PRIMITIVE_QUADS;
    a.lines = geom->primitive == SG_PRIMITIVE_LINES;
    a.wire = !a.lines && pso->desc.polygon_mode == SG_POLYGON_MODE_LINE;
    a.clip = (const float(*)[4])dev->clip;
    a.outcodes = dev->outcodes;
    a.screen = dev->screen;
    a.screen_ok = dev->screen_ok;
    a.slot = bin_slot;
    a.emit = bin_emit;
    a.user = dev;
    return a;
}

/* The uniforms of a shader draw copied into the pass's arena (16-byte aligned); their offset, or
 * SIZE_MAX when out of memory. The arena is reused by the next pass. */
static size_t copy_uniforms(sgDevice *dev, const void *src, size_t size) {
    size_t at = (dev->uniforms_used + 15) & ~(size_t)15;
    if (at + size > dev->uniforms_capacity) {
        size_t cap = dev->uniforms_capacity ? dev->uniforms_capacity : 4096;
        while (cap < at + size) cap *= 2;
        unsigned char *p = sg_alloc(dev, cap);
        if (!p) return SIZE_MAX;
        if (dev->uniforms_used) memcpy(p, dev->uniforms, dev->uniforms_used);
        sg_free(dev, dev->uniforms);
        dev->uniforms = p;
        dev->uniforms_capacity = cap;
    }
    if (size) memcpy(dev->uniforms + at, src, size);
    dev->uniforms_used = at + size;
    return at;
}

/* sgDraw of a shader pipeline (sgShaderDesc): checked, then the vertex stage per instance and the
 * front end as for fixed pipelines; the fragment stage runs when the bins are rendered. */
/* A multisampled pass's visibility functions of the draw's depth state: as the pipeline writes
 * depth, and without depth write, for the draws shaded in place (rast_msaa.c). */
static void sample_fns(const sgDevice *dev, const sg_pso *pso, sg_draw_state *ds) {
    if (dev->pass.samples <= 1) return;
    ds->vis_fn = sg_depth_samples_select(pso->desc.depth.compare, pso->desc.depth.write, dev->isa);
    ds->test_fn = sg_depth_samples_select(pso->desc.depth.compare, false, dev->isa);
    ds->vis_record_fn =
        sg_depth_record_select(pso->desc.depth.compare, pso->desc.depth.write, dev->isa);
    ds->test_record_fn = sg_depth_record_select(pso->desc.depth.compare, false, dev->isa);
    ds->record_pass_fn =
        pso->raster_pass ? sg_depth_record_select(SG_COMPARE_ALWAYS, false, dev->isa) : NULL;
}

static sgResult draw_shader(sgDevice *dev, sg_pso *pso, sgPipelineStateObject pso_h, sg_geom *geom,
                            const sgDrawParams *params) {
    const sgShaderDesc *sh = &pso->desc.shader;
    if (params->texture.id)
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgDraw: params->texture is set on a shader pipeline: bind its textures "
                        "in params->textures (sgSample's slots)");
    if (params->shadow)
        return sg_error(dev, SG_ERROR_UNSUPPORTED,
                        "sgDraw: params->shadow on a shader pipeline: bind the shadow map as a "
                        "texture (sgSample gives a depth image as (d, d, d, 1))");
    if (params->color)
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgDraw: params->color on a shader pipeline: give the colour to the "
                        "shader as a uniform");
    if (params->uniform_size > SG_MAX_UNIFORM_SIZE)
        return sg_error(dev, SG_ERROR_INVALID_SIZE,
                        "sgDraw: params->uniform_size = %zu is over SG_MAX_UNIFORM_SIZE (%d)",
                        params->uniform_size, SG_MAX_UNIFORM_SIZE);
    if (params->uniform_size && !params->uniforms)
        return sg_error(dev, SG_ERROR_NULL_POINTER,
                        "sgDraw: params->uniforms is NULL but uniform_size = %zu",
                        params->uniform_size);
    sg_shade_ctx ctx = {.texel_window = dev->texel_window};
    sg_shader_state *st = &ctx.shader;
    for (int k = 0; k < SG_MAX_DRAW_TEXTURES; k++) {
        const sgImage2D h = params->textures[k];
        if (!h.id) {
            if (k < sh->texture_count)
                return sg_error(dev, SG_ERROR_MISSING_TEXTURE,
                                "sgDraw: the shader samples %d texture%s but params->textures[%d] "
                                "is 0",
                                sh->texture_count, sh->texture_count == 1 ? "" : "s", k);
            continue;
        }
        sg_image *img = sg_lookup_image(dev, h);
        if (!img)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgDraw: params->textures[%d] id 0x%08x is not a live image", k, h.id);
        if (h.id == dev->pass_color.id || h.id == dev->pass_depth.id)
            return sg_error(dev, SG_ERROR_IN_USE,
                            "sgDraw: params->textures[%d] 0x%08x is a target of the open pass", k,
                            h.id);
        st->textures[k] =
            (sg_shader_tex){img->data,  img->width, img->height, img->format == SG_FORMAT_D32_FLOAT,
                            &img->mips, NULL};
    }
    const int instances = params->instance_count ? params->instance_count : 1;
    const int slots = instance_slots(dev, geom, instances);
    const size_t vertices = (size_t)slots * (size_t)geom->vertex_count;
    if (!grow_vertex_arenas(dev, vertices))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for %zu vertices",
                        vertices);
    const int nv = sh->varying_count;
    if (!grow_lit(dev, vertices * (size_t)(nv ? nv : 1)))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: out of memory for the varyings of %d vertices",
                        geom->vertex_count);
    if (nv > SG_TRI_ATTRS && !dev->binner.use_ext && !sg_binner_use_ext(&dev->binner))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: out of memory for the varyings of the pass");
    if (!grow_draws(dev))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for the draw list");
    size_t uoff = copy_uniforms(dev, params->uniforms, params->uniform_size);
    if (uoff == SIZE_MAX)
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for %zu uniform bytes",
                        params->uniform_size);
    st->fragment = sh->fragment;
    st->uniform_offset = params->uniform_size ? uoff : SIZE_MAX;
    st->varying_count = nv;
    st->konst = sh->varyings_only;
    st->bilinear = pso->desc.filter == SG_FILTER_BILINEAR;
    st->sample16 = dev->isa == SG_ISA_AVX512 ? SG_SAMPLE16_AVX512
                   : dev->isa == SG_ISA_AVX2 ? SG_SAMPLE16_AVX2
                                             : SG_SAMPLE16_PORTABLE;
    st->repeat = pso->desc.wrap == SG_WRAP_REPEAT;
    st->mipmap = pso->desc.mipmap;
    st->pso = pso_h.id;
    for (int k = 0; k < SG_MAX_DRAW_TEXTURES; k++) {
        sg_shader_tex *tx = &st->textures[k];
        if (tx->data && !tx->depth && st->mipmap == SG_MIPMAP_NONE)
            tx->unit =
                sg_sample16_unit_fn_of(st->sample16, st->bilinear, st->repeat, ctx.texel_window);
    }

    const int width = dev->pass.width, height = dev->pass.height;
    const bool depth_only = dev->pass.color == NULL;
    sg_assembly a = assembly_of(dev, pso, geom);
    a.vattr = dev->lit;
    a.vstride = nv;
    a.setup = (sg_setup_params){width,
                                height,
                                0,
                                0,
                                width,
                                height,
                                pso->desc.cull,
                                pso->desc.front_face,
                                depth_only ? 0 : nv,
                                0,
                                0,
                                pso->desc.depth.bias_constant,
                                pso->desc.depth.bias_slope,
                                1,
                                depth_only ? 0 : sh->flat_varyings,
                                dev->pass.samples};
    if (params->sort == SG_SORT_BACK_TO_FRONT &&
        !sort_primitives(dev, geom, params->world_view, &a))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: out of memory to sort %d indices back to front",
                        geom->index_count);

    vsh_job vs = {
        {sh->vertex,
         NULL,
         geom->positions,
         geom->colors,
         geom->normals,
         geom->texcoords,
         {geom->attributes[0], geom->attributes[1], geom->attributes[2], geom->attributes[3]},
         params->world_view,
         params->proj,
         0,
         nv,
         dev->clip,
         dev->lit,
         dev->outcodes,
         dev->screen,
         dev->screen_ok,
         &a.guard,
         &a.setup},
        geom->vertex_count,
        1};
    /* The arena does not move before the draw ends; no bytes: no pointer. */
    vs.run.uniforms = params->uniform_size ? dev->uniforms + uoff : NULL;
    if (dev->thread_count > 1 && geom->vertex_count >= FE_MIN_TRIANGLES)
        vs.chunks = 2 * dev->thread_count;

    sg_draw_state *ds = &dev->draws[dev->draw_count++];
    memset(ds, 0, sizeof *ds);
    ds->in_place = !depth_only && (pso->desc.blend == SG_BLEND_ALPHA || pso->discards);
    ds->raster_fn = depth_only     ? pso->depth_fn
                    : ds->in_place ? pso->shader_in_place
                                   : pso->raster_fn;
    ds->shader_in_place = pso->shader_in_place;
    ds->writes_depth = pso->desc.depth.write;
    ds->shade_fn = pso->shade_fn;
    ds->shade2_fn = pso->shade2_fn;
    ds->mixed_fn = pso->mixed_fn;
    ds->ctx = ctx;
    ds->compare = pso->desc.depth.compare;
    sample_fns(dev, pso, ds);
    ds->blend = pso->desc.blend == SG_BLEND_ALPHA;
    dev->pass.any_in_place |= ds->in_place;
    dev->pass.any_mixed |= ds->mixed_fn != NULL;
    dev->pass.any_pair |= ds->shade2_fn != NULL;
    dev->pass.any_shader = true;
    dev->pass.any_konst |= sh->varyings_only && !depth_only;
    /* The stage reads its varyings alone: a triangle whose varyings agree is shaded once. */
    const sg_shader_konst konst = {&ds->ctx, vs.run.uniforms};
    if (sh->varyings_only && !depth_only) {
        a.konst = sg_shader_constant;
        a.konst_user = &konst;
    }
    sgResult r = run_front_end(dev, &a, &vs, instances, slots);
    if (r != SG_OK) return r;
    for (int k = 0; k < SG_MAX_DRAW_TEXTURES; k++)
        if (params->textures[k].id)
            sg_lookup_image(dev, params->textures[k])->pass_use = dev->pass_serial;
    return SG_OK;
}

sgResult sgDraw(sgDevice *dev, sgPipelineStateObject pso_h, sgGeom geom_h,
                const sgDrawParams *params) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    SG_STAGE_START(clock);
    if (!params) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgDraw: params is NULL");
    if (!dev->in_pass)
        return sg_error(dev, SG_ERROR_NOT_IN_PASS,
                        "sgDraw: no render pass is open (call sgBeginRenderPass first)");
    if (dev->pass_failed)
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: an earlier draw of this pass ran out of memory after part of it "
                        "was rendered; end the pass");
    sg_pso *pso = sg_lookup_pso(dev, pso_h);
    if (!pso)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgDraw: pipeline id 0x%08x is not a live pipeline", pso_h.id);
    sg_geom *geom = sg_lookup_geom(dev, geom_h);
    if (!geom)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE, "sgDraw: geom id 0x%08x is not a live geom",
                        geom_h.id);
    if ((int)params->sort < SG_SORT_DEFAULT || params->sort > SG_SORT_BACK_TO_FRONT)
        return sg_error(dev, SG_ERROR_INVALID_ENUM, "sgDraw: params->sort = %d is not an sgSort",
                        (int)params->sort);
    if (params->instance_count < 0)
        return sg_error(dev, SG_ERROR_INVALID_COUNT,
                        "sgDraw: params->instance_count = %d is below 0", params->instance_count);
    if (pso->uses_depth && !dev->pass_depth.id)
        return sg_error(
            dev, SG_ERROR_MISSING_DEPTH,
            "sgDraw: the pipeline tests or writes depth but the pass has no depth target");
    if (pso->shader) {
        sgResult r = draw_shader(dev, pso, pso_h, geom, params);
        SG_STAGE_ADD(dev->pass.stage_times, SG_STAGE_FRONT, clock);
        return r;
    }
    bool any_texture = false;
    for (int k = 0; k < SG_MAX_DRAW_TEXTURES; k++) any_texture |= params->textures[k].id != 0;
    if (params->uniforms || params->uniform_size || params->instance_count > 1 || any_texture)
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgDraw: params->%s is for shader pipelines, and this pipeline has none",
                        params->uniforms || params->uniform_size ? "uniforms"
                        : params->instance_count > 1             ? "instance_count"
                                                                 : "textures");
    float tint[4] = {1.0f, 1.0f, 1.0f, 1.0f};
    if (params->color) {
        const sgColor *c = params->color;
        const float v[4] = {c->r, c->g, c->b, c->a};
        for (int k = 0; k < 4; k++) {
            if (!unit_range(v[k]))
                return sg_error(dev, SG_ERROR_INVALID_VALUE,
                                "sgDraw: params->color.%c = %g is outside [0, 1]", "rgba"[k],
                                (double)v[k]);
            tint[k] = v[k];
        }
    }
    bool tinted = tint[0] != 1.0f || tint[1] != 1.0f || tint[2] != 1.0f || tint[3] != 1.0f;
    sg_shade_ctx ctx = {.texel_window = dev->texel_window};
    const sgLightingMode lighting = pso->desc.lighting;
    if (lighting != SG_LIGHTING_NONE) {
        light_refusal refusal = {dev, SG_OK};
        if (!sg_light_prepare(params->lighting, params->specular, params->shininess, &ctx.lights,
                              refuse_lighting, &refusal))
            return refusal.result;
        if (lighting == SG_LIGHTING_FLAT && geom->primitive == SG_PRIMITIVE_LINES)
            return sg_error(dev, SG_ERROR_UNSUPPORTED,
                            "sgDraw: flat lighting needs a face normal, and the geom holds lines: "
                            "light lines per vertex or per pixel, with normals");
        if (lighting != SG_LIGHTING_FLAT && !geom->normals)
            return sg_error(dev, SG_ERROR_MISSING_ATTRIBUTE,
                            "sgDraw: the pipeline lights per %s but the geom has no normals",
                            lighting == SG_LIGHTING_GOURAUD ? "vertex" : "pixel");
    }
    sg_image *tex = NULL;
    if (pso->desc.shade == SG_SHADE_TEXTURE_MODULATE) {
        if (!params->texture.id)
            return sg_error(dev, SG_ERROR_MISSING_TEXTURE,
                            "sgDraw: the pipeline samples a texture but params->texture is 0");
        tex = sg_lookup_image(dev, params->texture);
        if (!tex)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgDraw: texture id 0x%08x is not a live image", params->texture.id);
        if (tex->format != SG_FORMAT_RGBA8_UNORM)
            return sg_error(dev, SG_ERROR_NOT_SAMPLEABLE,
                            "sgDraw: texture 0x%08x is D32_FLOAT, which cannot be sampled",
                            params->texture.id);
        if (params->texture.id == dev->pass_color.id)
            return sg_error(dev, SG_ERROR_IN_USE,
                            "sgDraw: texture 0x%08x is the color target of the open pass",
                            params->texture.id);
        if (!geom->texcoords)
            return sg_error(dev, SG_ERROR_MISSING_ATTRIBUTE,
                            "sgDraw: the pipeline samples a texture but the geom has no texcoords");
        ctx.tex = tex->mips.level[0];
        ctx.mips = &tex->mips;
    }
    sg_image *smap = NULL;
    if (params->shadow && pso->desc.mipmap != SG_MIPMAP_NONE && tex)
        return sg_error(dev, SG_ERROR_UNSUPPORTED,
                        "sgDraw: a mipmapped pipeline's draw receives a shadow map; this version "
                        "shades shadow receivers without mipmaps (use SG_MIPMAP_NONE)");
    if (params->shadow) {
        const sgShadow *sh = params->shadow;
        smap = sg_lookup_image(dev, sh->map);
        if (!smap)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgDraw: params->shadow->map id 0x%08x is not a live image",
                            sh->map.id);
        if (smap->format != SG_FORMAT_D32_FLOAT)
            return sg_error(dev, SG_ERROR_FORMAT_MISMATCH,
                            "sgDraw: params->shadow->map 0x%08x is RGBA8_UNORM; a shadow map is a "
                            "D32_FLOAT image",
                            sh->map.id);
        if (sh->map.id == dev->pass_depth.id)
            return sg_error(dev, SG_ERROR_IN_USE,
                            "sgDraw: params->shadow->map 0x%08x is the depth target of the open "
                            "pass; render the map in a pass of its own first",
                            sh->map.id);
        for (int k = 0; k < 16; k++)
            if (!(fabsf(sh->matrix[k]) <= FLT_MAX))
                return sg_error(dev, SG_ERROR_INVALID_VALUE,
                                "sgDraw: params->shadow->matrix[%d] = %g is not finite", k,
                                (double)sh->matrix[k]);
        if (lighting != SG_LIGHTING_NONE && (sh->light < 0 || sh->light >= ctx.lights.count))
            return sg_error(dev, SG_ERROR_INVALID_VALUE,
                            "sgDraw: params->shadow->light = %d, but the draw has %d light%s",
                            sh->light, ctx.lights.count, ctx.lights.count == 1 ? "" : "s");
        ctx.shadow.map = (const float *)(const void *)smap->data;
        ctx.shadow.width = smap->width;
        ctx.shadow.height = smap->height;
        memcpy(ctx.shadow.m, sh->matrix, sizeof ctx.shadow.m);
        ctx.shadow.light = lighting != SG_LIGHTING_NONE ? sh->light : -1;
        ctx.shadow.pcf = sh->pcf;
    }
    if (!grow_vertex_arenas(dev, (size_t)geom->vertex_count))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for %d vertices",
                        geom->vertex_count);

    if (!grow_draws(dev))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for the draw list");
    int width = dev->pass.width, height = dev->pass.height;

    /* A lit draw's vertices carry the attributes of light.h (SG_LIT_*): flat, base colour,
     * texcoords and view position, lit per triangle at assembly; Gouraud, the lit colours
     * (primary, texcoords, secondary when the material has a specular colour); Phong, base colour,
     * texcoords, position and normal, lit per pixel. An unlit draw that receives a shadow map
     * carries base colour, texcoords and position; a flat or Gouraud one the split colours of
     * light.h (SG_LIT_SPLIT_*: the hidden light's part apart) and position, Gouraud's made per
     * vertex, flat's per triangle from base colour, texcoords and position. A depth-only pass
     * reads no attribute. */
    const bool depth_only = dev->pass.color == NULL;
    const bool shadowed = smap && !depth_only;
    const bool textured = pso->desc.shade == SG_SHADE_TEXTURE_MODULATE;
    const bool spec = lighting != SG_LIGHTING_NONE && ctx.lights.has_specular;
    const bool split =
        shadowed && (lighting == SG_LIGHTING_FLAT || lighting == SG_LIGHTING_GOURAUD);
    int nattr = depth_only ? 0 : pso->nattr, sec = 0, vstride = 0;
    float normal_matrix[9];
    sg_vertex_lit lit = {0};
    const bool vattr = !depth_only && (lighting != SG_LIGHTING_NONE || shadowed);
    if (vattr) {
        vstride = lighting == SG_LIGHTING_PHONG ? SG_LIT_NRM + 3
                  : lighting == SG_LIGHTING_FLAT || lighting == SG_LIGHTING_NONE || spec
                      ? SG_LIT_SEC + 3
                  /* Gouraud: the colour, and the texcoords when it samples (16 bytes a vertex
                   * less to write and read on an untextured mesh) */
                  : textured ? SG_LIT_SEC
                             : SG_LIT_ST;
        nattr = lighting == SG_LIGHTING_PHONG  ? SG_LIT_NRM + 3
                : lighting == SG_LIGHTING_NONE ? SG_LIT_POS + 3
                : spec                         ? SG_LIT_SEC + 3
                                               : (textured ? 6 : 4);
        sec = spec && lighting != SG_LIGHTING_PHONG ? SG_LIT_SEC : 0;
        if (split) {
            nattr = spec ? SG_LIT_SPLIT_END : SG_LIT_SPLIT_SEC;
            vstride = lighting == SG_LIGHTING_GOURAUD ? nattr : vstride;
            sec = SG_LIT_SPLIT_D;
        }
        if (!grow_lit(dev, (size_t)geom->vertex_count * (size_t)vstride))
            return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                            "sgDraw: out of memory for the %s attributes of %d vertices",
                            lighting != SG_LIGHTING_NONE ? "lit" : "shadowed", geom->vertex_count);
        if (nattr > SG_TRI_ATTRS && !dev->binner.use_ext && !sg_binner_use_ext(&dev->binner))
            return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                            "sgDraw: out of memory for the %s attributes of the pass",
                            lighting != SG_LIGHTING_NONE ? "lit" : "shadowed");
        sg_normal_matrix(params->world_view, normal_matrix);
        lit.mode = lighting;
        lit.world_view = params->world_view;
        lit.normal_matrix = normal_matrix;
        lit.positions = geom->positions;
        lit.normals = geom->normals;
        lit.colors = geom->colors;
        lit.texcoords = textured ? geom->texcoords : NULL;
        lit.tint = tinted ? tint : NULL;
        lit.lights = &ctx.lights;
        lit.stride = vstride;
        lit.split = split ? params->shadow->light + 1 : 0;
        lit.gouraud = dev->vertex_gouraud;
    }

    sg_assembly a = assembly_of(dev, pso, geom);
    sg_mat4_mul(a.mvp, params->proj, params->world_view);
    a.positions = geom->positions; /* the vertex stage keeps no clip positions */
    a.colors = depth_only ? NULL : geom->colors;
    a.texcoords = depth_only ? NULL : geom->texcoords;
    a.tint = tinted && !depth_only ? tint : NULL; /* white multiplies nothing */
    a.rebase_texcoords = !depth_only && pso->desc.shade == SG_SHADE_TEXTURE_MODULATE &&
                         pso->desc.wrap == SG_WRAP_REPEAT;
    a.setup.width = width;
    a.setup.height = height;
    a.setup.rect_x0 = 0;
    a.setup.rect_y0 = 0;
    a.setup.rect_x1 = width;
    a.setup.rect_y1 = height;
    a.setup.cull = pso->desc.cull;
    a.setup.front_face = pso->desc.front_face;
    a.setup.nattr = nattr;
    a.setup.sec = sec;
    a.setup.sec_end = split ? nattr : 0;
    a.setup.bias_constant = pso->desc.depth.bias_constant;
    a.setup.bias_slope = pso->desc.depth.bias_slope;
    a.setup.samples = dev->pass.samples;
    if (vattr) {
        a.vattr = dev->lit;
        a.vstride = vstride;
        if (lighting == SG_LIGHTING_FLAT) a.flat = &ctx.lights;
        if (lighting == SG_LIGHTING_FLAT && split) a.flat_split = params->shadow->light + 1;
    }
    if (params->sort == SG_SORT_BACK_TO_FRONT &&
        !sort_primitives(dev, geom, params->world_view, &a))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY,
                        "sgDraw: out of memory to sort %d indices back to front",
                        geom->index_count);
    transform_vertices(dev, a.mvp, geom, &a.guard, &a.setup, vattr ? &lit : NULL, a.colors);
    /* The draw's state is in place before its triangles: a flush may render some of them. */
    sg_draw_state *ds = &dev->draws[dev->draw_count++];
    const bool put_lines = a.lines && pso->raster_line && !depth_only && !shadowed && !sec;
    ds->raster_fn = depth_only  ? pso->depth_fn
                    : shadowed  ? pso->raster_shadow
                    : put_lines ? pso->raster_line
                                : pso->raster_fn;
    ds->raster_pass_fn = depth_only || put_lines ? NULL
                         : shadowed              ? pso->raster_shadow_pass
                                                 : pso->raster_pass;
    ds->writes_depth = pso->desc.depth.write;
    ds->shade_fn = shadowed ? pso->shade_shadow : sec ? pso->shade_sec : pso->shade_fn;
    ds->shade2_fn = shadowed ? NULL : sec ? pso->shade2_sec : pso->shade2_fn;
    ds->runs_fn = shadowed ? NULL : sec ? pso->runs_sec : pso->runs_fn;
    ds->mixed_fn = shadowed || sec ? NULL : pso->mixed_fn;
    ds->ctx = ctx;
    ds->shader_in_place = NULL;
    ds->compare = pso->desc.depth.compare;
    sample_fns(dev, pso, ds);
    ds->blend = pso->desc.blend == SG_BLEND_ALPHA;
    ds->in_place = put_lines || (!depth_only && pso->desc.blend == SG_BLEND_ALPHA);
    dev->pass.any_in_place |= ds->in_place;
    dev->pass.any_pair |= ds->shade2_fn != NULL;
    dev->pass.any_runs |= ds->runs_fn != NULL;
    dev->pass.any_mixed |= ds->mixed_fn != NULL;
    sgResult r = run_front_end(dev, &a, NULL, 1, 1);
    if (r != SG_OK) return r;
    if (tex) tex->pass_use = dev->pass_serial;
    if (smap) smap->pass_use = dev->pass_serial;
    SG_STAGE_ADD(dev->pass.stage_times, SG_STAGE_FRONT, clock);
    return SG_OK;
}
