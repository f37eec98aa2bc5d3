/* workers.h - the device's thread pool: runs numbered jobs on all threads, the caller included. */
#ifndef SG_WORKERS_H
#define SG_WORKERS_H

#include <pthread.h>
#include <stdatomic.h>
#include <stdbool.h>
#include <stdint.h>

typedef void (*sg_job_fn)(void *ctx, int job);

typedef struct sg_workers {
    int count; /* threads that run jobs, the caller included (>= 1) */
    pthread_t *threads;
    pthread_mutex_t lock;
    pthread_cond_t start, done;
    /* The batch being run. */
    sg_job_fn fn;
    void *ctx;
    int jobs, next;
    /* A batch run by shares (sg_workers_run_shares): the jobs taken so far, one bit each. */
    bool shares;
    uint64_t taken;
    int started; /* workers that have taken their index (the caller is 0, they 1 .. count - 1) */
    /* Written under the lock; read without it by threads that spin briefly before sleeping. */
    atomic_int finished, generation;
    atomic_int busy;       /* workers still inside the current batch */
    atomic_int caller_cpu; /* the CPU the caller started the batch on (-1: unknown) */
    atomic_bool quit;
} sg_workers;

/** Starts count - 1 threads (none when count is 1). */
bool sg_workers_start(sg_workers *w, int count, pthread_t *threads);
/** Runs fn(ctx, 0 .. jobs - 1) across the threads and returns when all are done. */
void sg_workers_run(sg_workers *w, int jobs, sg_job_fn fn, void *ctx);
/** As sg_workers_run, but thread k of n (the caller is 0) first takes the jobs of its share,
 *  k·jobs/n .. (k+1)·jobs/n − 1, in order, and only then the last jobs left of the others'
 *  (jobs <= SG_WORKERS_SHARE_MAX). Batches of the same length so run keep the data a job makes
 *  in the cache of the thread that the matching job of the next batch runs on. */
void sg_workers_run_shares(sg_workers *w, int jobs, sg_job_fn fn, void *ctx);
enum { SG_WORKERS_SHARE_MAX = 64 };

/** Stops and joins the threads. */
void sg_workers_stop(sg_workers *w);

#endif
