/* pool.c - slot pools with kinds and generation counters (see pool.h). */
#include "core/pool.h"

static uint16_t next_generation(uint32_t g) {
    return (uint16_t)(g % SG_POOL_GENERATIONS + 1); /* 1 .. 16383, never 0 */
}

void sg_pool_init(sg_pool *pool, int capacity, uint32_t kind, uint32_t seed, uint16_t *generation,
                  bool *live, int *free_slots) {
    pool->capacity = capacity;
    pool->kind = kind & 3u;
    pool->generation = generation;
    pool->live = live;
    pool->free_slots = free_slots;
    pool->free_count = capacity;
    for (int i = 0; i < capacity; i++) {
        generation[i] = next_generation(seed);
        live[i] = false;
        free_slots[i] = capacity - 1 - i; /* hand out low slots first */
    }
}

uint32_t sg_pool_acquire(sg_pool *pool) {
    if (pool->free_count == 0) return 0;
    int slot = pool->free_slots[--pool->free_count];
    pool->live[slot] = true;
    return ((uint32_t)pool->generation[slot] << 18) | (pool->kind << 16) | (uint32_t)slot;
}

int sg_pool_lookup(const sg_pool *pool, uint32_t id) {
    int slot = (int)(id & 0xffffu);
    uint32_t kind = (id >> 16) & 3u, gen = id >> 18;
    if (id == 0 || kind != pool->kind || slot >= pool->capacity || !pool->live[slot] ||
        pool->generation[slot] != gen)
        return -1;
    return slot;
}

void sg_pool_release(sg_pool *pool, uint32_t id) {
    int slot = (int)(id & 0xffffu);
    pool->live[slot] = false;
    pool->generation[slot] = next_generation(pool->generation[slot]);
    pool->free_slots[pool->free_count++] = slot;
}
