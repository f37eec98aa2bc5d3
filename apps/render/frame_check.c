/* frame_check.c - whole PNG files on disk (frame_check.h). */
#define _POSIX_C_SOURCE 200809L
#include "frame_check.h"

#include <errno.h>
#include <fcntl.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include <libdeflate.h>

static uint32_t get_u32(const unsigned char *p) {
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* Reads the whole file into buf; false with why set when it cannot. */
static bool read_file(int fd, size_t size, fc_buffer *buf, sc_msg *why) {
    if (size > buf->cap) {
        unsigned char *p = realloc(buf->data, size);
        if (!p) {
            sc_msg_set(why, "cannot be read: out of memory for %zu bytes", size);
            return false;
        }
        buf->data = p;
        buf->cap = size;
    }
    size_t got = 0;
    while (got < size) {
        ssize_t n = read(fd, buf->data + got, size - got);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            sc_msg_set(why, "cannot be read: %s", n < 0 ? strerror(errno) : "it shrank");
            return false;
        }
        got += (size_t)n;
    }
    return true;
}

/* The chunks from p (after the signature) to the end: every one whole with its CRC right, IHDR
 * first and of the size wanted, IDAT present, IEND last and at the very end. */
static fc_status check_chunks(const unsigned char *p, size_t len, int width, int height,
                              sc_msg *why) {
    size_t at = 0;
    bool idat = false;
    for (int n = 0;; n++) {
        if (len - at < 12) {
            sc_msg_set(why, "ends before its IEND chunk (%zu bytes)", len + 8);
            return FC_BAD;
        }
        uint32_t size = get_u32(p + at);
        const unsigned char *type = p + at + 4;
        if (size > 0x7FFFFFFFu || size > len - at - 12) {
            sc_msg_set(why, "ends inside its chunk '%.4s' (%zu bytes)", (const char *)type,
                       len + 8);
            return FC_BAD;
        }
        uint32_t crc = (uint32_t)libdeflate_crc32(0, type, (size_t)size + 4);
        if (crc != get_u32(type + 4 + size)) {
            sc_msg_set(why, "has a damaged chunk '%.4s' (its CRC does not match)",
                       (const char *)type);
            return FC_BAD;
        }
        if (n == 0) {
            if (memcmp(type, "IHDR", 4) != 0 || size != 13) {
                sc_msg_set(why, "is not a PNG file (no IHDR first)");
                return FC_BAD;
            }
            uint32_t w = get_u32(type + 4), h = get_u32(type + 8);
            if (w != (uint32_t)width || h != (uint32_t)height) {
                sc_msg_set(why, "is %ux%u, not %dx%d", (unsigned)w, (unsigned)h, width, height);
                return FC_BAD;
            }
            if (type[12] != 8 || type[13] != 6) {
                sc_msg_set(why, "is not 8-bit RGBA");
                return FC_BAD;
            }
        }
        idat |= memcmp(type, "IDAT", 4) == 0;
        at += (size_t)size + 12;
        if (memcmp(type, "IEND", 4) == 0) {
            if (!idat) {
                sc_msg_set(why, "has no image data (no IDAT chunk)");
                return FC_BAD;
            }
            if (at != len) {
                sc_msg_set(why, "has %zu bytes after its IEND chunk", len - at);
                return FC_BAD;
            }
            return FC_WHOLE;
        }
    }
}

fc_status fc_check(const char *path, int width, int height, fc_buffer *buf, sc_msg *why) {
    int fd = open(path, O_RDONLY | O_CLOEXEC);
    if (fd < 0) {
        if (errno == ENOENT) return FC_MISSING;
        sc_msg_set(why, "cannot be opened: %s", strerror(errno));
        return FC_BAD;
    }
    struct stat st;
    fc_status s = FC_BAD;
    static const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (fstat(fd, &st) != 0 || !S_ISREG(st.st_mode))
        sc_msg_set(why, "is not a file");
    else if (st.st_size < 8 + 25 + 12)
        sc_msg_set(why, "is too short for a PNG file (%lld bytes)", (long long)st.st_size);
    else if ((unsigned long long)st.st_size > SIZE_MAX)
        sc_msg_set(why, "is too large");
    else if (read_file(fd, (size_t)st.st_size, buf, why)) {
        if (memcmp(buf->data, signature, 8) != 0)
            sc_msg_set(why, "is not a PNG file");
        else
            s = check_chunks(buf->data + 8, (size_t)st.st_size - 8, width, height, why);
    }
    close(fd);
    return s;
}

void fc_buffer_free(fc_buffer *buf) {
    free(buf->data);
    buf->data = NULL;
    buf->cap = 0;
}
