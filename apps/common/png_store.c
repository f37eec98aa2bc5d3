/* png_store.c - the PNG file of an RGBA8 image as a list of pieces, most of them the image's own
 * rows, for writev: the fastest PNG writing (compression level 0).
 *
 * The zlib stream inside is deflate without any search: pixels go out as they are (stored
 * blocks: no copy, a row or a part of it is a piece of the file), except where a row repeats the
 * row above it or holds a run of at least RUN_MIN pixels of one colour. Those cost a few bytes as
 * matches in a fixed-Huffman block: a repeated row is its filter byte, then matches of its
 * pixels at distance row + 1; a run is its first pixel's four bytes, then matches at distance 4.
 * Rendered frames have both (a cleared background, a sky), and on a memory file system the bytes
 * not written are most of what a frame costs: the kernel's copy, not the encoding.
 *
 * Every row has filter 0 (None) and starts in a fixed-Huffman block (its filter byte, a
 * literal); no block is final, and an empty final block ends the stream. The checksums run over
 * the same bytes as a reader's: Adler-32 over the rows with their filter bytes (whatever their
 * coding), CRC-32 over the IDAT chunk's pieces. A side of at most 16384 keeps the chunk under
 * 2^31 bytes (about 1 GiB when nothing repeats).
 */
#include "png_store.h"

#include <string.h>

#include <libdeflate.h>

enum {
    BLOCK = 65535,  /* the most data bytes of a stored block */
    WINDOW = 32768, /* the farthest distance a match reaches back */
    MATCH_MAX = 258,
    MATCH_MIN = 3,
    RUN_MIN = 32, /* the fewest equal pixels coded as a run inside a row */
};

static void put_u32(unsigned char *p, uint32_t v) {
    p[0] = (unsigned char)(v >> 24);
    p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8);
    p[3] = (unsigned char)v;
}

/* The bytes of the pieces that are not pixels are appended to `heads` (sized by the caller to
 * sc_png_store_heads, so it never moves while pieces point into it); bits of the Huffman blocks
 * gather in `bits` (LSB first, as deflate packs them). */
typedef struct store {
    struct iovec *iov;
    size_t n;
    unsigned char *heads, *h;     /* start, and the next free byte */
    const unsigned char *pending; /* heads bytes not yet in a piece (from here to h) */
    uint64_t bits;
    int nbits;
    bool in_fixed; /* a fixed-Huffman block is open */
    uint32_t crc;
} store;

static void piece(store *s, const void *p, size_t len) {
    s->crc = libdeflate_crc32(s->crc, p, len);
    s->iov[s->n++] = (struct iovec){(void *)(uintptr_t)p, len};
}

/* The heads bytes written since the last piece, as one piece. */
static void close_heads(store *s) {
    if (s->h > s->pending) piece(s, s->pending, (size_t)(s->h - s->pending));
    s->pending = s->h;
}

static void put_bits(store *s, uint32_t v, int n) {
    s->bits |= (uint64_t)v << s->nbits;
    s->nbits += n;
    while (s->nbits >= 8) {
        *s->h++ = (unsigned char)s->bits;
        s->bits >>= 8;
        s->nbits -= 8;
    }
}

/* Huffman codes go most significant bit first: reversed into the LSB-first stream. */
static uint32_t reversed(uint32_t code, int n) {
    uint32_t r = 0;
    for (int i = 0; i < n; i++) r |= ((code >> i) & 1u) << (n - 1 - i);
    return r;
}

static void put_code(store *s, uint32_t code, int n) {
    put_bits(s, reversed(code, n), n);
}

/* Symbol v of the fixed literal/length code (RFC 1951, 3.2.6). */
static void put_symbol(store *s, unsigned v) {
    if (v < 144)
        put_code(s, 0x30 + v, 8);
    else if (v < 256)
        put_code(s, 0x190 + (v - 144), 9);
    else if (v < 280)
        put_code(s, v - 256, 7);
    else
        put_code(s, 0xC0 + (v - 280), 8);
}

/* The bits of a match of len (3 to 258) bytes at distance dist (1 to 32768), at most 31, as they
 * go into the stream; their count in *n. */
static uint32_t match_bits(unsigned len, unsigned dist, int *n) {
    static const uint16_t len_base[29] = {3,  4,  5,  6,   7,   8,   9,   10,  11, 13,
                                          15, 17, 19, 23,  27,  31,  35,  43,  51, 59,
                                          67, 83, 99, 115, 131, 163, 195, 227, 258};
    static const uint8_t len_extra[29] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2,
                                          2, 3, 3, 3, 3, 4, 4, 4, 4, 5, 5, 5, 5, 0};
    static const uint16_t dist_base[30] = {
        1,   2,   3,   4,   5,   7,    9,    13,   17,   25,   33,   49,   65,    97,    129,
        193, 257, 385, 513, 769, 1025, 1537, 2049, 3073, 4097, 6145, 8193, 12289, 16385, 24577};
    static const uint8_t dist_extra[30] = {0, 0, 0, 0, 1, 1, 2, 2,  3,  3,  4,  4,  5,  5,  6,
                                           6, 7, 7, 8, 8, 9, 9, 10, 10, 11, 11, 12, 12, 13, 13};
    int l = 28, d = 29;
    while (len_base[l] > len) l--;
    while (dist_base[d] > dist) d--;
    /* length symbols 257 to 279 have 7-bit codes 0 to 22, 280 to 285 8-bit ones from 0xC0 */
    uint32_t v = l < 23 ? reversed((uint32_t)l + 1, 7) : reversed(0xC0u + (uint32_t)(l - 23), 8);
    int at = l < 23 ? 7 : 8;
    v |= (len - len_base[l]) << at;
    at += len_extra[l];
    v |= reversed((uint32_t)d, 5) << at;
    at += 5;
    v |= (dist - dist_base[d]) << at;
    *n = at + dist_extra[d];
    return v;
}

/* Matches covering len bytes at distance dist, each 3 to 258 long: most of them 258, whose bits
 * are worked out once. */
static void put_run(store *s, size_t len, unsigned dist) {
    int full_n = 0;
    uint32_t full = len >= MATCH_MAX ? match_bits(MATCH_MAX, dist, &full_n) : 0;
    while (len) {
        size_t k = len < MATCH_MAX ? len : MATCH_MAX;
        if (len - k != 0 && len - k < MATCH_MIN) k = len - MATCH_MIN; /* leave the last one 3 */
        int n = full_n;
        uint32_t bits = k == MATCH_MAX ? full : match_bits((unsigned)k, dist, &n);
        put_bits(s, bits, n);
        len -= k;
    }
}

/* A fixed-Huffman block open (left open when it is), or closed. */
static void begin_fixed(store *s) {
    if (s->in_fixed) return;
    put_bits(s, 2u, 3); /* not final, type 01 */
    s->in_fixed = true;
}

static void end_fixed(store *s) {
    if (!s->in_fixed) return;
    put_code(s, 0, 7); /* end of block (256) */
    s->in_fixed = false;
}

/* Data bytes p[0..len) as stored blocks of at most 65535 bytes. */
static void put_stored(store *s, const unsigned char *p, size_t len) {
    while (len) {
        size_t b = len < BLOCK ? len : BLOCK;
        put_bits(s, 0u, 3);                          /* not final, type 00 */
        if (s->nbits) put_bits(s, 0u, 8 - s->nbits); /* to a byte boundary */
        s->h[0] = (unsigned char)b, s->h[1] = (unsigned char)(b >> 8);
        s->h[2] = (unsigned char)~b, s->h[3] = (unsigned char)(~b >> 8);
        s->h += 4;
        close_heads(s);
        piece(s, p, b);
        p += b, len -= b;
    }
}

/* Pixel i of a row (any alignment: the caller's buffer need not be 4-byte aligned). */
static inline uint32_t pixel(const unsigned char *row, int i) {
    uint32_t v;
    memcpy(&v, row + (size_t)i * 4, 4);
    return v;
}

/* The first run of at least RUN_MIN equal pixels of row[x..width): [*start, *end), or both width.
 * A run that long holds two pixels RUN_MIN / 2 apart at the positions looked at, equal, with
 * every pixel between them: rows without runs cost one compare per RUN_MIN / 2 pixels. */
static void find_run(const unsigned char *row, int x, int width, int *start, int *end) {
    const int step = RUN_MIN / 2;
    for (int i = x; i + step < width; i += step) {
        const uint32_t c = pixel(row, i);
        if (pixel(row, i + step) != c) continue;
        bool all = true;
        for (int k = i + 1; k < i + step && all; k++) all = pixel(row, k) == c;
        if (!all) continue;
        int a = i, b = i + step + 1;
        while (a > x && pixel(row, a - 1) == c) a--;
        for (; b + 16 <= width; b += 16) { /* sixteen at a time, then one by one */
            uint32_t diff = 0;
            for (int k = 0; k < 16; k++) diff |= pixel(row, b + k) ^ c;
            if (diff) break;
        }
        while (b < width && pixel(row, b) == c) b++;
        if (b - a >= RUN_MIN) {
            *start = a;
            *end = b;
            return;
        }
    }
    *start = *end = width;
}

size_t sc_png_store_pieces(int width, int height) {
    /* one before the data; per row, per stored part, at most two blocks (of 65535 bytes; a part
     * is at most 65536), each a piece of heads and one of pixels; the heads after the last row;
     * one after */
    const size_t parts = (size_t)width / RUN_MIN + 1;
    return 3 + (size_t)height * parts * 4;
}

size_t sc_png_store_heads(int width, int height) {
    const size_t row = (size_t)width * 4, parts = (size_t)width / RUN_MIN + 1;
    /* per row: its filter byte's block (3 + 9 + 7 bits), a repeat (at most 31 bits per 258
     * bytes, and one more match) or runs (each a block of 3 + 7 bits, four literals of 9 bits and
     * its matches: together at most 31 bits per 258 bytes of the row, and one more each); per
     * stored part, two block headers of at most 6 bytes */
    const size_t bits = 19 + 2 * (row / MATCH_MAX + 2) * 31 + parts * (46 + 31);
    return 43 + (size_t)height * (bits / 8 + 2 + parts * 12) + 24;
}

size_t sc_png_store_build(struct iovec *iov, unsigned char *heads, int width, int height,
                          const unsigned char *rgba) {
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    static const unsigned char filter_none = 0;
    const size_t row = (size_t)width * 4;
    unsigned char *h = heads;
    memcpy(h, signature, 8);
    memcpy(h + 8 + 4, "IHDR", 4);
    put_u32(h + 8, 13);
    put_u32(h + 8 + 8, (uint32_t)width);
    put_u32(h + 8 + 12, (uint32_t)height);
    const unsigned char ihdr_rest[5] = {8, 6, 0, 0, 0}; /* RGBA8, deflate, filters, no interlace */
    memcpy(h + 8 + 16, ihdr_rest, 5);
    put_u32(h + 8 + 21, libdeflate_crc32(0, h + 8 + 4, 17));
    /* IDAT: length (set at the end), type, zlib header (deflate, 32 KiB window, fastest) */
    unsigned char *idat = h + 33;
    memcpy(idat + 4, "IDAT", 4);
    idat[8] = 0x78;
    idat[9] = 0x01;
    store s = {iov, 0, heads, idat + 10, idat + 10, 0, 0, false, 0};
    s.iov[s.n++] = (struct iovec){h, 33 + 10};
    s.crc = libdeflate_crc32(0, idat + 4, 6);
    uint32_t adler = 1;
    for (int y = 0; y < height; y++) {
        const unsigned char *px = rgba + (size_t)y * row;
        adler = libdeflate_adler32(adler, &filter_none, 1);
        adler = libdeflate_adler32(adler, px, row);
        begin_fixed(&s);
        put_symbol(&s, 0); /* the filter byte */
        if (y && row + 1 <= WINDOW && !memcmp(px, px - row, row)) {
            put_run(&s, row, (unsigned)(row + 1)); /* the row above again */
            continue;
        }
        for (int x = 0; x < width;) {
            int start, end;
            find_run(px, x, width, &start, &end);
            if (start > x) { /* pixels x to start as they are */
                end_fixed(&s);
                put_stored(&s, px + (size_t)x * 4, (size_t)(start - x) * 4);
            }
            if (end > start) { /* the run's first pixel, then matches of it */
                begin_fixed(&s);
                for (int c = 0; c < 4; c++) put_symbol(&s, px[(size_t)start * 4 + (size_t)c]);
                put_run(&s, (size_t)(end - start - 1) * 4, 4);
            }
            x = end;
        }
    }
    end_fixed(&s);
    put_bits(&s, 3u, 3); /* final, type 01: an empty block */
    put_code(&s, 0, 7);
    if (s.nbits) put_bits(&s, 0u, 8 - s.nbits);
    put_u32(s.h, adler);
    s.h += 4;
    close_heads(&s);
    /* The chunk's length, now known, and its CRC; then IEND. */
    size_t idat_len = 0;
    for (size_t i = 1; i < s.n; i++) idat_len += s.iov[i].iov_len;
    idat_len += 2; /* the zlib header, in the first piece */
    put_u32(idat, (uint32_t)idat_len);
    put_u32(s.h, s.crc);
    memset(s.h + 4, 0, 4); /* IEND: length 0, type, CRC */
    memcpy(s.h + 8, "IEND", 4);
    put_u32(s.h + 12, libdeflate_crc32(0, s.h + 8, 4));
    s.iov[s.n++] = (struct iovec){s.h, 16};
    return s.n;
}
