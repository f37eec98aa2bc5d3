/* sample16.c - 16 texture lookups at once (see sample16.h), the portable copy: the steps of
 * tex/sample.h on GCC vectors, float coordinates, then integer indices, weights and sums, each the
 * scalar operation in every lane, so each lane gets the scalar bits; only the texel reads go lane
 * by lane. The AVX-512 copy (sample16_avx512.c) is the fixed shading's fetch and filter. */
#include "tex/sample16.h"

#include <string.h>

#include "tex/lanes.h"

#define SG_LANES_FN(name) name##_portable
#define SG_LANES_ATTR
#include "tex/sample16_body.h"
