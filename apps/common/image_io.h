/* image_io.h - reading images of any common format as RGBA8 and writing RGBA8 PNG files.
 *
 * API-neutral: pixels are plain bytes, R, G, B, A, top row first (as the image is displayed).
 */
#ifndef SC_IMAGE_IO_H
#define SC_IMAGE_IO_H

#include <stdbool.h>
#include <stddef.h>

#include "msg.h"

/* An RGBA8 image, top row first, rows tightly packed (width * 4 bytes). */
typedef struct sc_image {
    int width, height;
    unsigned char *pixels;
} sc_image;

/** Loads a PNG, BMP, JPEG, TGA, ... file as RGBA8; on failure *out is zeroed and err says why. */
bool sc_image_load(const char *path, sc_image *out, sc_msg *err);
/** Decodes the bytes of such a file, held in memory, as sc_image_load does (it reads the file and
 * calls this); on failure *out is zeroed and err says why. */
bool sc_image_load_memory(const unsigned char *data, size_t len, sc_image *out, sc_msg *err);
/** Frees an image loaded by sc_image_load(_memory) and zeroes it; a zeroed image is fine. */
void sc_image_free(sc_image *image);
/* Compression levels of written PNG files: 0, no search (pixels stored as they are, repeated rows
 * and runs of one colour as matches: png_store.c; the fastest), and libdeflate's 1 to 12 (12 the
 * smallest files). */
#define SC_PNG_LEVEL_MAX     12
#define SC_PNG_LEVEL_DEFAULT 6 /* smaller than stb_image_write, in a quarter of its time */

/* Writes PNG files, keeping its compressor and buffers from one image to the next (the frames of
 * an animation). One writer per thread. */
typedef struct sc_png_writer sc_png_writer;
/** A writer at a compression level, 0 .. SC_PNG_LEVEL_MAX; NULL when out of memory or the level is
 *  out of range. */
sc_png_writer *sc_png_writer_create(int level);
/** Frees a writer; NULL is fine. */
void sc_png_writer_destroy(sc_png_writer *writer);
/** Writes RGBA8 pixels (top row first, tightly packed) as an RGBA PNG file; the same pixels and
 *  level give the same bytes. The file is written as PATH.part and renamed to PATH, so PATH is
 *  never a partial image. On failure no file is left and err says why. */
bool sc_png_writer_write(sc_png_writer *writer, const char *path, int width, int height,
                         const unsigned char *rgba, sc_msg *err);
/** Writes RGBA8 pixels as a PNG file at SC_PNG_LEVEL_DEFAULT. */
bool sc_image_write_png(const char *path, int width, int height, const unsigned char *rgba,
                        sc_msg *err);

#endif
