/* frame_check.h - whether an image file already on disk is whole, for --resume and --assemble:
 * a PNG of the expected size whose chunks all end, each with its CRC right, in IEND at the end
 * of the file. What an interrupted write or a damaged copy leaves fails that; a full inflate
 * would say no more about files this program wrote (each is renamed into place whole) and costs
 * ten times as long. */
#ifndef FC_FRAME_CHECK_H
#define FC_FRAME_CHECK_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"

typedef enum fc_status {
    FC_WHOLE,   /* there, the right size, every chunk whole */
    FC_MISSING, /* no file of that name */
    FC_BAD      /* there, but not a whole PNG of that size (why says what) */
} fc_status;

/* A buffer kept from one check to the next, so checking a thousand frames allocates once. */
typedef struct fc_buffer {
    unsigned char *data;
    size_t cap;
} fc_buffer;

/** Checks the file at path against a width x height RGBA8 PNG; on FC_BAD, why says what is wrong
 *  (e.g. "is 32x32, not 64x64", "ends before its IEND chunk"). buf is grown as needed. */
fc_status fc_check(const char *path, int width, int height, fc_buffer *buf, sc_msg *why);
/** Frees the buffer's memory; a zeroed buffer is fine. */
void fc_buffer_free(fc_buffer *buf);

#endif
