/* workers.c - a small fork-join pool: a batch of jobs is handed out one index at a time under a
 * lock (jobs are whole screen bins or front-end chunks, so the lock is taken a few hundred times a
 * frame at most).
 *
 * A draw runs two short batches (vertex stage, assembly) and a pass one more, often well under a
 * millisecond apart; a thread woken from a condition variable takes tens of microseconds to start,
 * which would leave the caller to do most of a short batch alone. So a worker that finishes a batch
 * watches for the next one for a short while before it sleeps, and the caller watches for the end
 * of its batch the same way. */
#include "core/workers.h"

#if defined(__x86_64__) || defined(__i386__)
#include <immintrin.h>
#define SG_SPIN_PAUSE() _mm_pause()
#else
#define SG_SPIN_PAUSE() ((void)0)
#endif

/* Polls (about 100 microseconds on current x86) before falling back to sleeping. */
enum { SPIN_POLLS = 4000 };

/* Takes job indices until the batch is exhausted; returns with the lock held. */
static void drain(sg_workers *w) {
    while (w->next < w->jobs) {
        int job = w->next++;
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
    for (;;) {
        pthread_mutex_unlock(&w->lock);
        for (int i = 0;
             i < SPIN_POLLS && atomic_load(&w->generation) == seen && !atomic_load(&w->quit); i++)
            SG_SPIN_PAUSE();
        pthread_mutex_lock(&w->lock);
        while (!w->quit && w->generation == seen) pthread_cond_wait(&w->start, &w->lock);
        if (w->quit) break;
        seen = w->generation;
        w->busy++;
        drain(w);
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
    atomic_init(&w->finished, 0);
    atomic_init(&w->generation, 0);
    atomic_init(&w->busy, 0);
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

void sg_workers_run(sg_workers *w, int jobs, sg_job_fn fn, void *ctx) {
    if (w->count == 1 || jobs <= 1) { /* nothing to share: no locking at all */
        for (int i = 0; i < jobs; i++) fn(ctx, i);
        return;
    }
    pthread_mutex_lock(&w->lock);
    w->fn = fn;
    w->ctx = ctx;
    w->jobs = jobs;
    w->next = 0;
    atomic_store(&w->finished, 0);
    atomic_fetch_add(&w->generation, 1);
    pthread_cond_broadcast(&w->start);
    drain(w);
    if (w->finished < w->jobs || w->busy > 0) { /* others are still on the last jobs */
        pthread_mutex_unlock(&w->lock);
        for (int i = 0;
             i < SPIN_POLLS && (atomic_load(&w->finished) < jobs || atomic_load(&w->busy) > 0); i++)
            SG_SPIN_PAUSE();
        pthread_mutex_lock(&w->lock);
    }
    while (w->finished < w->jobs || w->busy > 0) pthread_cond_wait(&w->done, &w->lock);
    pthread_mutex_unlock(&w->lock);
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
