/* stage_times.h - wall time per pipeline stage, for profiling builds only.
 *
 * Configured with -DSGAPI_STAGE_TIMES=ON, the library adds up the wall time each stage takes
 * (front end in sgDraw; bin start, visibility, shading and bin write in sgEndRenderPass, summed
 * over the threads) and sgDestroyDevice prints the totals per pass to stderr. Other builds compile
 * every call here to nothing, so they pay nothing for it.
 */
#ifndef SG_STAGE_TIMES_H
#define SG_STAGE_TIMES_H

#include <stdint.h>

#if defined(SG_STAGE_TIMES)
#include <stdatomic.h>
#include <stdio.h>
#include <time.h>

typedef struct sg_stage_times {
    _Atomic uint64_t ns[8];
    uint64_t passes;
} sg_stage_times;

static inline uint64_t sg_stage_clock(void) {
    struct timespec ts; /* C11's clock: no POSIX feature macro needed in every includer */
    timespec_get(&ts, TIME_UTC);
    return (uint64_t)ts.tv_sec * 1000000000u + (uint64_t)ts.tv_nsec;
}

/* Adds the time since *since to `stage` and restarts the clock. */
static inline void sg_stage_add(void *times, int stage, uint64_t *since) {
    uint64_t now = sg_stage_clock();
    atomic_fetch_add_explicit(&((sg_stage_times *)times)->ns[stage], now - *since,
                              memory_order_relaxed);
    *since = now;
}

static inline void sg_stage_print(const sg_stage_times *t, const char *const names[], int count) {
    if (!t->passes) return;
    fprintf(stderr, "sgapi stage times, ms per pass (%llu passes):", (unsigned long long)t->passes);
    for (int i = 0; i < count; i++)
        fprintf(stderr, " %s %.3f", names[i], (double)atomic_load(&t->ns[i]) / 1e6 / t->passes);
    fprintf(stderr, "\n");
}
#define SG_STAGE_START(var)             uint64_t var = sg_stage_clock()
#define SG_STAGE_ADD(times, stage, var) sg_stage_add(times, stage, &var)
#else
#define SG_STAGE_START(var)             ((void)0)
#define SG_STAGE_ADD(times, stage, var) ((void)0)
#endif

#endif
