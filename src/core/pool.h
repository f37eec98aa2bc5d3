/* pool.h - fixed-size slot pools behind the public handles.
 *
 * An id is generation (14 bits) << 18 | kind (2 bits) << 16 | slot (16 bits).
 * - The kind tells an image id from a geom or pipeline id, whatever their slots hold.
 * - Generations never take the value 0, so 0 is never a valid id; a slot's generation moves on
 *   when its object is destroyed, so an id kept after that no longer matches.
 * - Each device starts its generations at its own seed, so an id from another device is refused
 *   unless its generation happens to coincide with the slot's (1 chance in 16383 for a fresh id).
 */
#ifndef SG_POOL_H
#define SG_POOL_H

#include <stdbool.h>
#include <stdint.h>

#define SG_POOL_MAX_SLOTS   65535
#define SG_POOL_GENERATIONS 16383u /* 14 bits, without 0 */

typedef struct sg_pool {
    int capacity;
    int free_count;
    uint32_t kind;        /* 0 .. 3 */
    uint16_t *generation; /* per slot, 1 .. SG_POOL_GENERATIONS */
    bool *live;
    int *free_slots; /* stack of free slot indices */
} sg_pool;

/** Fills an empty pool's arrays (allocated by the caller) for `capacity` slots. */
void sg_pool_init(sg_pool *pool, int capacity, uint32_t kind, uint32_t seed, uint16_t *generation,
                  bool *live, int *free_slots);
/** Takes a free slot and returns its id, or 0 when the pool is full. */
uint32_t sg_pool_acquire(sg_pool *pool);
/** Returns the slot of a live id of this pool, or -1 when the id is 0, stale, foreign or of another
 *  kind. */
int sg_pool_lookup(const sg_pool *pool, uint32_t id);
/** Frees the slot of a live id (the caller looked it up first). */
void sg_pool_release(sg_pool *pool, uint32_t id);

#endif
