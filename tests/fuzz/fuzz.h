/* fuzz.h - the fuzz targets' entry points, shared by the libFuzzer builds and the replay test. */
#ifndef SG_FUZZ_H
#define SG_FUZZ_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>

/* Each runs one input through its loader and checks what a successful load promises; a broken
 * promise aborts, so libFuzzer and the replay test both see it as a crash. They return 0. */
int fuzz_obj(const uint8_t *data, size_t size);
int fuzz_scene(const uint8_t *data, size_t size);
int fuzz_image(const uint8_t *data, size_t size);
int fuzz_off(const uint8_t *data, size_t size);
int fuzz_mtl(const uint8_t *data, size_t size);
int fuzz_api(const uint8_t *data, size_t size); /* sequences of public calls (fuzz_api.c) */

/* libFuzzer's entry point, defined by each target unless built for the replay test. */
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static inline void fuzz_fail(const char *file, int line, const char *what) {
    fprintf(stderr, "%s:%d: loader contract broken: %s\n", file, line, what);
    abort();
}

#define FUZZ_CHECK(cond)                                                                           \
    do {                                                                                           \
        if (!(cond)) fuzz_fail(__FILE__, __LINE__, #cond);                                         \
    } while (0)

/* Reads the last of bytes bytes at p: an array shorter than its promised size shows up under
 * ASan here instead of in whatever renderer would read it later. */
static inline void fuzz_touch(const void *p, size_t bytes) {
    FUZZ_CHECK(p != NULL && bytes > 0);
    volatile unsigned char last = ((const unsigned char *)p)[bytes - 1];
    (void)last;
}

#endif
