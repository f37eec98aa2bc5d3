/* replay.c - runs every committed fuzz reproducer through its target's entry point, built with the
 * normal compiler, so a loader crash once fixed stays fixed (ctest: fuzz_regressions).
 *
 * Usage: fuzz_replay DIR [TARGET...], where DIR/obj, DIR/scene, DIR/image, DIR/off and DIR/mtl
 * (or only the TARGETs named) hold one input per file; built with FUZZ_REPLAY_API (test_api_seq),
 * DIR/api: sequences of API calls (fuzz_api.c).
 */
#define _POSIX_C_SOURCE 200809L /* opendir, readdir */

#include "fuzz.h"

#include <dirent.h>
#include <stdbool.h>
#include <string.h>

static const struct {
    const char *dir;
    int (*run)(const uint8_t *, size_t);
} targets[] = {
#if defined(FUZZ_REPLAY_API)
    {"api", fuzz_api},
#else
    {"obj", fuzz_obj}, {"scene", fuzz_scene}, {"image", fuzz_image},
    {"off", fuzz_off}, {"mtl", fuzz_mtl},
#endif
};

/* Reads a whole file; NULL when it cannot (the caller reports it). */
static uint8_t *read_all(const char *path, size_t *len) {
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    uint8_t *buf = NULL;
    size_t cap = 0, n = 0, got;
    do {
        if (n == cap) {
            cap = cap ? cap * 2 : 4096;
            uint8_t *q = realloc(buf, cap);
            if (!q) {
                free(buf);
                fclose(f);
                return NULL;
            }
            buf = q;
        }
        got = fread(buf + n, 1, cap - n, f);
        n += got;
    } while (got > 0);
    bool failed = ferror(f);
    fclose(f);
    if (failed) {
        free(buf);
        return NULL;
    }
    *len = n;
    return buf;
}

int main(int argc, char **argv) {
    if (argc < 2) {
        fprintf(stderr, "usage: %s DIR [TARGET...]\n", argv[0]);
        return 2;
    }
    int inputs = 0, errors = 0;
    for (size_t t = 0; t < sizeof targets / sizeof targets[0]; t++) {
        bool named = argc == 2;
        for (int i = 2; i < argc; i++) named |= !strcmp(argv[i], targets[t].dir);
        if (!named) continue;
        char dir[4096];
        snprintf(dir, sizeof dir, "%s/%s", argv[1], targets[t].dir);
        DIR *d = opendir(dir);
        if (!d) {
            /* Every target has reproducers; a missing folder means a wrong argument. */
            fprintf(stderr, "cannot open %s\n", dir);
            errors++;
            continue;
        }
        const struct dirent *e;
        while ((e = readdir(d)) != NULL) {
            if (e->d_name[0] == '.') continue; /* ., .. and hidden files */
            char path[8192];
            snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
            size_t len = 0;
            uint8_t *data = read_all(path, &len);
            if (!data) {
                fprintf(stderr, "cannot read %s\n", path);
                errors++;
                continue;
            }
            /* A crash or a broken contract aborts inside, which fails the test. */
            printf("%s/%s (%zu bytes)\n", targets[t].dir, e->d_name, len);
            fflush(stdout);
            targets[t].run(data, len);
            free(data);
            inputs++;
        }
        closedir(d);
    }
    printf("%d inputs replayed, %d errors\n", inputs, errors);
    return errors || inputs == 0 ? 1 : 0;
}
