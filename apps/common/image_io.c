/* image_io.c - image files in and out, on top of the stb image libraries. */
#include "image_io.h"

#include <errno.h>
#include <limits.h>
#include <stdio.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

bool sc_image_load(const char *path, sc_image *out, char *err, size_t errlen) {
    memset(out, 0, sizeof *out);
    int w, h, channels;
    /* No vertical flip: the decoder's natural order is already top row first. */
    unsigned char *px = stbi_load(path, &w, &h, &channels, 4);
    if (!px) {
        const char *why = stbi_failure_reason();
        snprintf(err, errlen, "cannot load image '%s': %s", path, why ? why : "unknown error");
        return false;
    }
    out->width = w;
    out->height = h;
    out->pixels = px;
    return true;
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
