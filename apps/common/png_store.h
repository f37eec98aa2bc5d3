/* png_store.h - the PNG file of an RGBA8 image as pieces for writev, most of them its own rows
 * (compression level 0; see png_store.c). */
#ifndef SC_PNG_STORE_H
#define SC_PNG_STORE_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>
#include <sys/uio.h>

/** The most pieces sc_png_store_build makes for an image of that size (sides up to 16384). */
size_t sc_png_store_pieces(int width, int height);
/** The most bytes of `heads` sc_png_store_build uses for an image of that size. */
size_t sc_png_store_heads(int width, int height);
/** Fills iov with the file's pieces in order: pointers into rgba (the rows) and into heads (the
 * rest); returns how many. The pieces stay valid as long as rgba and heads do. */
size_t sc_png_store_build(struct iovec *iov, unsigned char *heads, int width, int height,
                          const unsigned char *rgba);

#endif
