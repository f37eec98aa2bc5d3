/* image_io.c - image files in (stb_image) and PNG files out (libdeflate). */
#define _XOPEN_SOURCE 700 /* IOV_MAX, O_CLOEXEC */
#include "image_io.h"

#include "obj.h" /* sc_read_file */
#include "png_store.h"

#include <errno.h>
#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <fcntl.h>
#include <sys/uio.h>
#include <unistd.h>

#include <libdeflate.h>
#include <stb_image.h>

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

/* Whether every chunk of a PNG, up to IEND, lies inside the data. The decoder trusts an IDAT
 * chunk's length and grows its buffer to hold it before reading a byte of it: a 3.8 KB file whose
 * chunk declared a gigabyte made it allocate 2 GB (found by fuzzing). A chunk that runs past the
 * end of the file can only be a corrupt or truncated file, which the decoder would refuse once
 * its read came up short; it is refused before. Not a PNG: true. */
static bool png_chunks_ok(const unsigned char *d, size_t len) {
    static const unsigned char sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (len < 8 || memcmp(d, sig, 8) != 0) return true;
    size_t p = 8;
    while (p + 8 <= len) {
        size_t n = (size_t)d[p] << 24 | (size_t)d[p + 1] << 16 | (size_t)d[p + 2] << 8 | d[p + 3];
        if (!memcmp(d + p + 4, "IEND", 4)) return true;           /* the decoder reads no further */
        if (n > len - p - 8 || len - p - 8 - n < 4) return false; /* data and CRC */
        p += 12 + n;
    }
    return p == len; /* no IEND: the decoder refuses the file itself */
}

/* The decoder's reason for a failure; false. For an unknown PNG chunk the reason starts with the
 * chunk type, raw bytes of the file: empty when the first is 0 (as in a truncated file, read on as
 * zeros), control characters otherwise. Such a reason is replaced rather than printed. */
static bool decoder_error(sc_msg *err) {
    const char *why = stbi_failure_reason();
    bool printable = why && why[0];
    for (const char *q = why; printable && *q; q++) printable = *q >= 0x20 && *q < 0x7f;
    sc_msg_set(err, "%s",
               !printable                 ? "corrupt or unsupported image"
               : !strcmp(why, "outofmem") ? "out of memory"
                                          : why);
    return false;
}

bool sc_image_load_memory(const unsigned char *data, size_t len, sc_image *out, sc_msg *err) {
    memset(out, 0, sizeof *out);
    /* The decoder takes the length as an int. */
    if (!data || len == 0 || len > INT_MAX) {
        sc_msg_set(err, "%s", len > INT_MAX ? "image data too large" : "no image data");
        return false;
    }
    if (is_jpeg(data, len) && !jpeg_huffman_tables_ok(data, len)) {
        sc_msg_set(err, "corrupt JPEG: bad Huffman table");
        return false;
    }
    if (!png_chunks_ok(data, len)) {
        sc_msg_set(err, "corrupt PNG: a chunk runs past the end of the file");
        return false;
    }
    /* The header is read first: the checks below depend on it. Reading it allocates, so its
     * failure may be the allocator's: then the decoding must not go ahead unchecked (an
     * allocation-failure test found it going ahead without the size check). */
    int w, h, channels;
    if (!stbi_info_from_memory(data, (int)len, &w, &h, &channels)) return decoder_error(err);
    /* For a PNM of 16 bits per sample (maximum value over 255), the stb_image of Debian 12 converts
     * the samples to RGBA as if they were 8-bit, then reads twice the bytes of that buffer as
     * 16-bit ones: a heap over-read of the image's size (found by fuzzing). Such files are refused.
     * "P5" and "P6" start no other format the decoder reads. */
    if (len >= 2 && data[0] == 'P' && (data[1] == '5' || data[1] == '6') &&
        stbi_is_16_bit_from_memory(data, (int)len)) {
        sc_msg_set(err, "16-bit PNM images are not supported");
        return false;
    }
    /* A file of a few bytes can declare a size whose decoding takes gigabytes (a 44-byte GIF of
     * 16163x17746 took 2.6 GB) only to be refused by the caller: the size is checked first. */
    if (w > SC_IMAGE_MAX_SIDE || h > SC_IMAGE_MAX_SIDE) {
        sc_msg_set(err, "image is %dx%d, larger than %d on a side", w, h, SC_IMAGE_MAX_SIDE);
        return false;
    }
    /* No vertical flip: the decoder's natural order is already top row first. */
    unsigned char *px = stbi_load_from_memory(data, (int)len, &w, &h, &channels, 4);
    if (!px) return decoder_error(err);
    /* The PNM decoder takes a header without a size, as short as "P5", or with a size of 0 for
     * an image of no pixels: an image has at least one. */
    if (w <= 0 || h <= 0) {
        stbi_image_free(px);
        sc_msg_set(err, "image has no pixels (%dx%d)", w, h);
        return false;
    }
    out->width = w;
    out->height = h;
    out->pixels = px;
    return true;
}

/* Reads the whole file and decodes it from memory, so files and the fuzz target share one path. */
bool sc_image_load(const char *path, sc_image *out, sc_msg *err) {
    char *data;
    size_t len;
    memset(out, 0, sizeof *out);
    if (!sc_read_file(path, &data, &len, err)) return false;
    bool ok = sc_image_load_memory((const unsigned char *)data, len, out, err);
    free(data);
    if (!ok) sc_msg_set(err, "cannot load image '%s': %s", path, sc_msg_text(err));
    return ok;
}

void sc_image_free(sc_image *image) {
    if (!image) return;
    stbi_image_free(image->pixels);
    memset(image, 0, sizeof *image);
}

/* ---- PNG writing ------------------------------------------------------------------------------
 * RGBA8, 8 bits a channel, one IDAT chunk compressed by libdeflate: several times faster than
 * stb_image_write and smaller (docs/performance.md, "Writing frames"); at level 0 a stream without
 * search that costs little more than a copy (png_store.c). */

struct sc_png_writer {
    struct libdeflate_compressor *compressor;
    int level;
    unsigned char *raw; /* the filtered rows: one filter byte, then the row */
    size_t raw_cap;
    unsigned char *file; /* the whole file: signature, IHDR, IDAT, IEND */
    size_t file_cap;
    /* Level 0: the file as pieces, most of them the pixels themselves (write_stored). */
    struct iovec *iov;
    size_t iov_cap;
    unsigned char *heads; /* the pieces that are not pixels: headers, block and row starts */
    size_t heads_cap;
};

sc_png_writer *sc_png_writer_create(int level) {
    if (level < 0 || level > SC_PNG_LEVEL_MAX) return NULL;
    sc_png_writer *w = calloc(1, sizeof *w);
    if (!w) return NULL;
    w->level = level;
    w->compressor = libdeflate_alloc_compressor(level);
    if (!w->compressor) {
        free(w);
        return NULL;
    }
    return w;
}

void sc_png_writer_destroy(sc_png_writer *w) {
    if (!w) return;
    libdeflate_free_compressor(w->compressor);
    free(w->raw);
    free(w->file);
    free(w->iov);
    free(w->heads);
    free(w);
}

static void put_u32(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* Grows a kept buffer; the buffers live as long as the writer, so an animation's frames reuse
 * them instead of faulting in fresh pages for every image. */
static bool reserve(unsigned char **buf, size_t *cap, size_t need) {
    if (need <= *cap) return true;
    unsigned char *p = realloc(*buf, need);
    if (!p) return false;
    *buf = p;
    *cap = need;
    return true;
}

/* Ends a chunk whose length field is at p[0..3], type at p[4..7] and len data bytes after: writes
 * the length and the CRC of type and data; returns the position after the chunk. */
static unsigned char *end_chunk(unsigned char *p, size_t len) {
    put_u32(p, (uint32_t)len);
    put_u32(p + 8 + len, libdeflate_crc32(0, p + 4, len + 4));
    return p + 12 + len;
}

/* The PNG file of an image in w->file; its size, or 0 when out of memory. */
static size_t encode_png(sc_png_writer *w, int width, int height, const unsigned char *rgba) {
    const size_t row = (size_t)width * 4, raw_len = (size_t)height * (row + 1);
    if (!reserve(&w->raw, &w->raw_cap, raw_len)) return 0;
    /* Filter Sub (each byte minus the same channel of the pixel to its left) turns smooth
     * shading and flat colour into small numbers and runs, at the cost of one subtraction a
     * byte. (Level 0 does not come here: write_stored.) */
    for (int y = 0; y < height; y++) {
        const unsigned char *src = rgba + (size_t)y * row;
        unsigned char *dst = w->raw + (size_t)y * (row + 1);
        dst[0] = 1;
        memcpy(dst + 1, src, 4);
        for (size_t i = 4; i < row; i++) dst[1 + i] = (unsigned char)(src[i] - src[i - 4]);
    }
    const size_t bound = libdeflate_zlib_compress_bound(w->compressor, raw_len);
    if (bound > SIZE_MAX - 64 || !reserve(&w->file, &w->file_cap, 8 + 25 + 12 + bound + 12))
        return 0;
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    unsigned char *p = w->file;
    memcpy(p, signature, 8);
    p += 8;
    memcpy(p + 4, "IHDR", 4);
    put_u32(p + 8, (uint32_t)width);
    put_u32(p + 12, (uint32_t)height);
    /* 8 bits a sample, colour type 6 (RGBA), deflate, adaptive filtering, no interlace. */
    const unsigned char ihdr_rest[5] = {8, 6, 0, 0, 0};
    memcpy(p + 16, ihdr_rest, 5);
    p = end_chunk(p, 13);
    memcpy(p + 4, "IDAT", 4);
    size_t z = libdeflate_zlib_compress(w->compressor, w->raw, raw_len, p + 8, bound);
    /* A chunk holds less than 2^31 bytes: a 16384^2 image that does not compress is 1 GiB. */
    if (z == 0 || z > 0x7FFFFFFF) return 0;
    p = end_chunk(p, z);
    memcpy(p + 4, "IEND", 4);
    p = end_chunk(p, 0);
    return (size_t)(p - w->file);
}

/* Writes len bytes; false: a write failed (errno set). */
static bool write_all(int fd, const unsigned char *p, size_t len) {
    while (len) {
        ssize_t wrote = write(fd, p, len);
        if (wrote < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        p += wrote;
        len -= (size_t)wrote;
    }
    return true;
}

/* Level 0, without copying the pixels: the file as pieces, most of them the image's rows as they
 * are (png_store.c), written by writev. The pieces are (re)built in kept arrays, so an
 * animation's frames allocate nothing. False: out of memory (errno ENOMEM) or a write failed
 * (errno set). */
static bool write_stored(sc_png_writer *w, int fd, int width, int height,
                         const unsigned char *rgba) {
    const size_t pieces = sc_png_store_pieces(width, height);
    if (pieces > w->iov_cap) {
        struct iovec *v = realloc(w->iov, pieces * sizeof *v);
        if (!v) return errno = ENOMEM, false;
        w->iov = v;
        w->iov_cap = pieces;
    }
    if (!reserve(&w->heads, &w->heads_cap, sc_png_store_heads(width, height)))
        return errno = ENOMEM, false;
    size_t n = sc_png_store_build(w->iov, w->heads, width, height, rgba);
    /* writev takes at most IOV_MAX pieces and may write less than asked: go on from there. */
    struct iovec *v = w->iov;
    while (n) {
        int count = n < IOV_MAX ? (int)n : IOV_MAX;
        ssize_t wrote = writev(fd, v, count);
        if (wrote < 0) {
            if (errno == EINTR) continue;
            return false;
        }
        size_t r = (size_t)wrote;
        while (n && r >= v->iov_len) r -= v->iov_len, v++, n--;
        if (n && r) {
            v->iov_base = (unsigned char *)v->iov_base + r;
            v->iov_len -= r;
        }
    }
    return true;
}

bool sc_png_writer_write(sc_png_writer *w, const char *path, int width, int height,
                         const unsigned char *rgba, sc_msg *err) {
    if (width <= 0 || height <= 0 || width > SC_IMAGE_MAX_SIDE || height > SC_IMAGE_MAX_SIDE ||
        !rgba) {
        sc_msg_set(err, "cannot write '%s': invalid image (%dx%d)", path, width, height);
        return false;
    }
    size_t len = w->level == 0 ? 0 : encode_png(w, width, height, rgba);
    if (w->level != 0 && len == 0) {
        sc_msg_set(err, "cannot write '%s': PNG encoding failed (out of memory)", path);
        return false;
    }
    /* Written beside, then renamed over the name: a file of that name is always a whole image,
     * even when the writer is stopped half-way (a job array's shard killed by its scheduler). */
    char *part = sc_format("%s.part", path);
    if (!part) {
        sc_msg_set(err, "cannot write '%s': out of memory", path);
        return false;
    }
    int fd = open(part, O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) {
        sc_msg_set(err, "cannot write '%s': %s", part, strerror(errno));
        free(part);
        return false;
    }
    bool written =
        w->level == 0 ? write_stored(w, fd, width, height, rgba) : write_all(fd, w->file, len);
    int saved = errno;
    bool closed = close(fd) == 0;
    if (!closed && written) saved = errno;
    bool renamed = written && closed && rename(part, path) == 0;
    if (written && closed && !renamed) saved = errno;
    if (!renamed) {
        sc_msg_set(err, "cannot write '%s': %s", path, strerror(saved));
        remove(part);
    }
    free(part);
    return renamed;
}

bool sc_image_write_png(const char *path, int width, int height, const unsigned char *rgba,
                        sc_msg *err) {
    sc_png_writer *w = sc_png_writer_create(SC_PNG_LEVEL_DEFAULT);
    if (!w) {
        sc_msg_set(err, "cannot write '%s': out of memory", path);
        return false;
    }
    bool ok = sc_png_writer_write(w, path, width, height, rgba, err);
    sc_png_writer_destroy(w);
    return ok;
}
