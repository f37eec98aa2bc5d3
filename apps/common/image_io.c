/* image_io.c - image files in and out, on top of the stb image libraries. */
#include "image_io.h"

#include "obj.h" /* sc_read_file */

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

/* The largest side of an image accepted: that of scene files and of the API (SC_MAX_IMAGE_SIZE,
 * SG_MAX_IMAGE_SIZE). The fuzz build lowers it, to keep each input within libFuzzer's memory. */
#ifndef SC_IMAGE_MAX_SIDE
#define SC_IMAGE_MAX_SIDE 16384
#endif

/* Byte k of the data, or 0 past its end, as the decoder reads it. */
static unsigned at(const unsigned char *d, size_t len, size_t k) {
    return k < len ? d[k] : 0;
}

/* Whether the decoder takes the data for a JPEG: marker FF D8 (start of image) after any number of
 * FF fill bytes. No other format it reads starts with FF. */
static bool is_jpeg(const unsigned char *d, size_t len) {
    size_t i = 0;
    while (i < len && d[i] == 0xFF) i++;
    return i > 0 && i < len && d[i] == 0xD8;
}

/* The stb_image of Debian 12 (2.27) trusts the 16 code counts of a JPEG Huffman table (a DHT
 * segment) to add up to at most 256; more makes it write past the table, up to 4 KB of bytes from
 * the file over the decoder's state (found by fuzzing; later stb_image checks this itself). Each
 * FF C4 pair in the file is where the decoder may read a DHT segment, so each is walked as it
 * would be, and a table of more than 256 codes refuses the file. So that crafted overlapping
 * segments cannot make this quadratic, the walk has a budget far above what real files need. */
static bool jpeg_huffman_tables_ok(const unsigned char *d, size_t len) {
    size_t budget = 16 * (len < SIZE_MAX / 32 ? len : SIZE_MAX / 32) + 65536;
    for (size_t i = 0; i + 1 < len; i++) {
        if (d[i] != 0xFF || d[i + 1] != 0xC4) continue;
        size_t p = i + 2;
        long left = (long)(at(d, len, p) << 8 | at(d, len, p + 1)) - 2;
        p += 2;
        /* Past the end the decoder reads zeros: tables of no codes. */
        while (left > 0 && p < len) {
            unsigned q = at(d, len, p);
            if (q >> 4 > 1 || (q & 15) > 3) break; /* the decoder refuses this segment itself */
            size_t n = 0;
            for (size_t k = 1; k <= 16; k++) n += at(d, len, p + k);
            if (n > 256 || 17 + n > budget) return false;
            budget -= 17 + n;
            p += 17 + n;
            left -= (long)(17 + n);
        }
    }
    return true;
}

bool sc_image_load_memory(const unsigned char *data, size_t len, sc_image *out, char *err,
                          size_t errlen) {
    memset(out, 0, sizeof *out);
    /* The decoder takes the length as an int. */
    if (!data || len == 0 || len > INT_MAX) {
        snprintf(err, errlen, "%s", len > INT_MAX ? "image data too large" : "no image data");
        return false;
    }
    if (is_jpeg(data, len) && !jpeg_huffman_tables_ok(data, len)) {
        snprintf(err, errlen, "corrupt JPEG: bad Huffman table");
        return false;
    }
    /* For a PNM of 16 bits per sample (maximum value over 255), the stb_image of Debian 12 converts
     * the samples to RGBA as if they were 8-bit, then reads twice the bytes of that buffer as
     * 16-bit ones: a heap over-read of the image's size (found by fuzzing). Such files are refused.
     * "P5" and "P6" start no other format the decoder reads. */
    if (len >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '6') &&
        stbi_is_16_bit_from_memory(data, (int)len)) {
        snprintf(err, errlen, "16-bit PNM images are not supported");
        return false;
    }
    int w, h, channels;
    /* A file of a few bytes can declare a size whose decoding takes gigabytes (a 44-byte GIF of
     * 16163x17746 took 2.6 GB) only to be refused by the caller: the size is checked first. */
    if (stbi_info_from_memory(data, (int)len, &w, &h, &channels) &&
        (w > SC_IMAGE_MAX_SIDE || h > SC_IMAGE_MAX_SIDE)) {
        snprintf(err, errlen, "image is %dx%d, larger than %d on a side", w, h, SC_IMAGE_MAX_SIDE);
        return false;
    }
    /* No vertical flip: the decoder's natural order is already top row first. */
    unsigned char *px = stbi_load_from_memory(data, (int)len, &w, &h, &channels, 4);
    if (!px) {
        /* For an unknown PNG chunk the decoder's reason starts with the chunk type, raw bytes of
         * the file: empty when the first is 0 (as in a truncated file, read on as zeros), control
         * characters otherwise. Such a reason is replaced rather than printed. */
        const char *why = stbi_failure_reason();
        bool printable = why && why[0];
        for (const char *q = why; printable && *q; q++) printable = *q >= 0x20 && *q < 0x7f;
        snprintf(err, errlen, "%s", printable ? why : "corrupt or unsupported image");
        return false;
    }
    /* The PNM decoder takes a header without a size, as short as "P5", or with a size of 0 for
     * an image of no pixels: an image has at least one. */
    if (w <= 0 || h <= 0) {
        stbi_image_free(px);
        snprintf(err, errlen, "image has no pixels (%dx%d)", w, h);
        return false;
    }
    out->width = w;
    out->height = h;
    out->pixels = px;
    return true;
}

/* Reads the whole file and decodes it from memory, so files and the fuzz target share one path. */
bool sc_image_load(const char *path, sc_image *out, char *err, size_t errlen) {
    char *data;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &data, &len, err, errlen)) return false;
    char why[256];
    bool ok = sc_image_load_memory((const unsigned char *)data, len, out, why, sizeof why);
    free(data);
    if (!ok) snprintf(err, errlen, "cannot load image '%s': %s", path, why);
    return ok;
}

void sc_image_free(sc_image *image) {
    if (!image) return;
    stbi_image_free(image->pixels);
    memset(image, 0, sizeof *image);
}

/* The encoder hands the whole file to this callback; write errors are kept for the caller. */
typedef struct png_sink {
    FILE *f;
    bool failed;
} png_sink;

static void write_to_file(void *context, void *data, int size) {
    png_sink *sink = context;
    if (size > 0 && fwrite(data, 1, (size_t)size, sink->f) != (size_t)size) sink->failed = true;
}

bool sc_image_write_png(const char *path, int width, int height, const unsigned char *rgba,
                        char *err, size_t errlen) {
    if (width <= 0 || height <= 0 || width > INT_MAX / 4 || !rgba) {
        snprintf(err, errlen, "cannot write '%s': invalid image (%dx%d)", path, width, height);
        return false;
    }
    png_sink sink = {fopen(path, "wb"), false};
    if (!sink.f) {
        snprintf(err, errlen, "cannot write '%s': %s", path, strerror(errno));
        return false;
    }
    /* Returns 0 only when encoding fails (out of memory); then nothing was written. */
    bool encoded = stbi_write_png_to_func(write_to_file, &sink, width, height, 4, rgba, width * 4);
    int saved = errno;
    bool closed = fclose(sink.f) == 0;
    if (!encoded || sink.failed || !closed) {
        snprintf(err, errlen, "cannot write '%s': %s", path,
                 !encoded ? "PNG encoding failed" : strerror(sink.failed ? saved : errno));
        remove(path);
        return false;
    }
    return true;
}
