/* test_rng.h - the tests' random cases: splitmix64, deterministic, the same cases on every run and
 * platform. */
#ifndef SG_TEST_RNG_H
#define SG_TEST_RNG_H

#include <stdint.h>

typedef struct rng {
    uint64_t s;
} rng;

static inline uint64_t next(rng *g) {
    uint64_t z = (g->s += 0x9e3779b97f4a7c15u);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9u;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebu;
    return z ^ (z >> 31);
}

static inline int irange(rng *g, int lo, int hi) { /* lo .. hi inclusive */
    return lo + (int)(next(g) % (uint64_t)(hi - lo + 1));
}

static inline float frange(rng *g, float lo, float hi) {
    return lo + (hi - lo) * (float)(next(g) >> 40) * (1.0f / 16777216.0f);
}

static inline int chance(rng *g, int percent) {
    return irange(g, 0, 99) < percent;
}

#endif
