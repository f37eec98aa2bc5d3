/* warn.h - warnings of the model loaders: what a file holds that is ignored or replaced, said once
 * per kind so that a large file with many such lines gives one line of output, not thousands.
 */
#ifndef SC_WARN_H
#define SC_WARN_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"

#define SC_MAX_WARNINGS 16

/* Kinds of warning, one bit each. */
enum {
    SC_WARN_OFF_COLORMAP = 1u << 0,    /* an OFF face colour given as a colour-map index */
    SC_WARN_OFF_SMALL_FACE = 1u << 1,  /* an OFF face of fewer than 3 vertices */
    SC_WARN_OBJ_POINTS = 1u << 2,      /* OBJ points (p) */
    SC_WARN_OBJ_UNKNOWN = 1u << 3,     /* OBJ statements not drawn (curves, surfaces ...) */
    SC_WARN_MTL_UNKNOWN = 1u << 4,     /* MTL statements not used */
    SC_WARN_MTL_MISSING = 1u << 5,     /* a material library that cannot be read */
    SC_WARN_MTL_NO_MATERIAL = 1u << 6, /* usemtl of a material no library defines */
    SC_WARN_TEXTURE_MISSING = 1u << 7, /* a texture a material names that cannot be read */
    SC_WARN_MTL_BAD_VALUE = 1u << 8,   /* a malformed value in a material library */
};

/* Warnings so far: the kinds seen and the first message of each, whole (text[i].text). Zero-
 * initialise it; free it with sc_warnings_free. */
typedef struct sc_warnings {
    unsigned kinds;
    int count;
    sc_msg text[SC_MAX_WARNINGS];
} sc_warnings;

/** Records a warning of one kind unless that kind was recorded before; w may be NULL. */
void sc_warn(sc_warnings *w, unsigned kind, const char *fmt, ...) SC_PRINTF_LIKE(3, 4);
/** Frees the warnings' texts and zeroes them; NULL and a zeroed value are fine. */
void sc_warnings_free(sc_warnings *w);

#endif
