/* sample16.c - 16 texture lookups at once (see sample16.h): the steps of tex/sample.h on GCC
 * vectors, float coordinates, then integer indices, weights and sums, each the scalar operation
 * in every lane, so each lane gets the scalar bits; only the texel reads go lane by lane. The
 * body (sample16_body.h) is compiled twice: portable, and for AVX-512, where the 16 lanes are
 * one register (lanes.h says why the copies are whole functions of their own). */
#include "tex/sample16.h"

#include <string.h>

#include "tex/lanes.h"

#define SG_LANES_BODY "tex/sample16_body.h"
#include "tex/lanes_copies.h"
