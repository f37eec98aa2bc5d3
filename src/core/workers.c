#if defined(__linux__)
#define _GNU_SOURCE /* sched_getcpu, sched_setaffinity */
#endif
#define _POSIX_C_SOURCE 200809L /* clock_gettime */
/* workers.c - a small fork-join pool: a batch of jobs is handed out one index at a time under a
 * lock (jobs are whole screen bins or front-end chunks, so the lock is taken a few hundred times a
 * frame at most).
 *
 * A draw runs two short batches (vertex stage, assembly) and a pass one more, often well under a
 * millisecond apart; a thread woken from a condition variable takes tens of microseconds to start,
 * which would leave the caller to do most of a short batch alone. So a worker that finishes a batch
 * watches for the next one for a while (SPIN_NS) before it sleeps, and the caller watches for the
 * end of its batch the same way.
 *
 * On Linux a woken worker may be put on its waker's CPU while another CPU is idle, and then the
 * two share one CPU, each running while the other waits, for tens of milliseconds (the balancer
 * does not move a thread that ran a moment ago): the pool then runs no faster than one thread. A
 * worker woken on the caller's CPU moves off it (leave_cpu; docs/performance.md, "Two threads on
 * one CPU"). */
#include "core/workers.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SG_SPIN_PAUSE() _mm_pause()
#else
#define SG_SPIN_PAUSE() ((void)0)
#endif

#include <stdint.h>
#include <time.h>

#if defined(__linux__)
#include <sched.h>
#endif

/* How long a worker watches for the next batch, and the caller for the end of its own, before
 * sleeping: 1 ms, by the clock (a pause instruction takes from a few to about 150 cycles,
 * depending on the CPU). 4000 pauses (about 90 microseconds on the development machine) let the
 * workers fall asleep between the frames of a small scene: the scenes of under a millisecond ran
 * 5 % faster at two threads with this (docs/performance.md, "Four shading chains"). The cost: after
 * the last batch of a frame each worker spins for up to a millisecond before it sleeps. */
enum { SPIN_NS = 1000000 };

static uint64_t now_ns(void) {
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Whether the spin that started at `start` (now_ns) may go on, asked after each pause: the clock
 * is read every 64th time. */
static inline bool spin_on(uint64_t start, unsigned *polls) {
    SG_SPIN_PAUSE();
    return (++*polls & 63u) != 0 || now_ns() - start < SPIN_NS;
}

/* The CPU the calling thread runs on, or -1. */
static int current_cpu(void) {
#if defined(__linux__)
    return sched_getcpu();
#else
    return -1;
#endif
}

/* Moves the calling thread off CPU `cpu`, the one it is on, when it may run on another: its
 * affinity without that CPU moves it at once, and the affinity it had is then given back (the
 * thread stays where it went). */
static void leave_cpu(int cpu) {
#if defined(__linux__)
    cpu_set_t mine, other;
    if (sched_getaffinity(0, sizeof mine, &mine) != 0) return;
    other = mine;
    CPU_CLR(cpu, &other);
    if (CPU_COUNT(&other) > 0 && sched_setaffinity(0, sizeof other, &other) == 0)
        sched_setaffinity(0, sizeof mine, &mine);
#else
    (void)cpu;
#endif
}

/* The next job of a batch run by shares for thread `id`: the first its share has left, else the
 * last any other share has left (its owner takes from the front); -1 when all are taken. Called
 * with the lock held. */
static int next_shared(sg_workers *w, int id) {
    const int n = w->count, jobs = w->jobs;
    const int lo = (int)((int64_t)jobs * id / n), hi = (int)((int64_t)jobs * (id + 1) / n);
    for (int j = lo; j < hi; j++)
        if (!(w->taken >> j & 1u)) return j;
    for (int j = jobs - 1; j >= 0; j--)
        if (!(w->taken >> j & 1u)) return j;
    return -1;
}

/* Takes job indices until the batch is exhausted; returns with the lock held. */
static void drain(sg_workers *w, int id) {
    while (w->next < w->jobs) {
        int job = w->next++;
        if (w->shares) {
            job = next_shared(w, id);
            w->taken |= (uint64_t)1 << job;
        }
        sg_job_fn fn = w->fn; /* read under the lock: the next batch may replace them */
        void *ctx = w->ctx;
        pthread_mutex_unlock(&w->lock);
        fn(ctx, job);
        pthread_mutex_lock(&w->lock);
        w->finished++;
    }
}

static void *worker_main(void *arg) {
    sg_workers *w = arg;
    int seen = 0;
    pthread_mutex_lock(&w->lock);
    const int id = ++w->started;
    for (;;) {
        pthread_mutex_unlock(&w->lock);
        const uint64_t start = now_ns();
        unsigned polls = 0;
        while (atomic_load(&w->generation) == seen && !atomic_load(&w->quit) &&
               spin_on(start, &polls)) {
        }
        pthread_mutex_lock(&w->lock);
        bool slept = false;
        while (!w->quit && w->generation == seen) {
            pthread_cond_wait(&w->start, &w->lock);
            slept = true;
        }
        if (w->quit) break;
        seen = w->generation;
        /* A wake-up places a thread; a spinning one stays where it is. */
        const int caller = atomic_load_explicit(&w->caller_cpu, memory_order_relaxed);
        if (slept && caller >= 0 && current_cpu() == caller) {
            pthread_mutex_unlock(&w->lock);
            leave_cpu(caller);
            pthread_mutex_lock(&w->lock);
        }
        w->busy++;
        drain(w, id);
        w->busy--;
        if (w->finished == w->jobs && w->busy == 0) pthread_cond_signal(&w->done);
    }
    pthread_mutex_unlock(&w->lock);
    return NULL;
}

bool sg_workers_start(sg_workers *w, int count, pthread_t *threads) {
    w->count = count < 1 ? 1 : count;
    w->threads = threads;
    w->jobs = w->next = 0;
    w->shares = false;
    w->taken = 0;
    w->started = 0;
    atomic_init(&w->finished, 0);
    atomic_init(&w->generation, 0);
    atomic_init(&w->busy, 0);
    atomic_init(&w->caller_cpu, -1);
    atomic_init(&w->quit, false);
    if (pthread_mutex_init(&w->lock, NULL) != 0) return false;
    pthread_cond_init(&w->start, NULL);
    pthread_cond_init(&w->done, NULL);
    for (int i = 0; i + 1 < w->count; i++)
        if (pthread_create(&threads[i], NULL, worker_main, w) != 0) {
            w->count = i + 1; /* run with the threads that did start */
            break;
        }
    return true;
}

static void run(sg_workers *w, int jobs, sg_job_fn fn, void *ctx, bool shares) {
    if (w->count == 1 || jobs <= 1) { /* nothing to share: no locking at all */
        for (int i = 0; i < jobs; i++) fn(ctx, i);
        return;
    }
    /* Written only when it changes: the line is the one the spinning workers read. */
    const int cpu = current_cpu();
    if (cpu != atomic_load_explicit(&w->caller_cpu, memory_order_relaxed))
        atomic_store_explicit(&w->caller_cpu, cpu, memory_order_relaxed);
    pthread_mutex_lock(&w->lock);
    w->fn = fn;
    w->ctx = ctx;
    w->jobs = jobs;
    w->next = 0;
    w->shares = shares;
    w->taken = 0;
    atomic_store(&w->finished, 0);
    atomic_fetch_add(&w->generation, 1);
    pthread_cond_broadcast(&w->start);
    drain(w, 0);
    if (w->finished < w->jobs || w->busy > 0) { /* others are still on the last jobs */
        pthread_mutex_unlock(&w->lock);
        const uint64_t start = now_ns();
        unsigned polls = 0;
        while ((atomic_load(&w->finished) < jobs || atomic_load(&w->busy) > 0) &&
               spin_on(start, &polls)) {
        }
        pthread_mutex_lock(&w->lock);
    }
    while (w->finished < w->jobs || w->busy > 0) pthread_cond_wait(&w->done, &w->lock);
    pthread_mutex_unlock(&w->lock);
}

void sg_workers_run(sg_workers *w, int jobs, sg_job_fn fn, void *ctx) {
    run(w, jobs, fn, ctx, false);
}

void sg_workers_run_shares(sg_workers *w, int jobs, sg_job_fn fn, void *ctx) {
    run(w, jobs, fn, ctx, jobs <= SG_WORKERS_SHARE_MAX);
}

void sg_workers_stop(sg_workers *w) {
    pthread_mutex_lock(&w->lock);
    w->quit = true;
    pthread_cond_broadcast(&w->start);
    pthread_mutex_unlock(&w->lock);
    for (int i = 0; i + 1 < w->count; i++) pthread_join(w->threads[i], NULL);
    pthread_cond_destroy(&w->start);
    pthread_cond_destroy(&w->done);
    pthread_mutex_destroy(&w->lock);
}
