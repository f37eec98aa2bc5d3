/* sgapi-diff - compares two images of the same size and says how far apart they are.
 *
 *   sgapi-diff A.png B.png [--heat OUT.png] [--background R,G,B,A]
 *              [--min-psnr DB] [--max-over2 PCT] [--max-coverage PCT]
 *
 * Prints PSNR over R, G, B (dB), mean absolute and maximum error (in 1/255 steps, all four
 * channels), the share of pixels whose largest channel difference exceeds 2, 8 and 32, and the
 * coverage mismatch: pixels that are background (exactly the background colour) in one image and
 * not in the other. With thresholds given, the exit status is 0 when all hold and 1 when any fails;
 * 2 means the images could not be compared.
 */
#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_image.h>
#include <stb_image_write.h>

#include "cli.h"
#include "image_diff.h"

static int usage(FILE *f) {
    fprintf(f, "usage: sgapi-diff A.png B.png [--heat OUT.png] [--background R,G,B,A]\n"
               "                  [--min-psnr DB] [--max-over2 PCT] [--max-coverage PCT]\n"
               "Compares two images; with thresholds, exits 1 when any is exceeded.\n");
    return f == stderr ? 2 : 0;
}

int main(int argc, char **argv) {
    const char *paths[2] = {NULL, NULL}, *heat_path = NULL;
    double min_psnr = -1, max_over2 = -1, max_cov = -1;
    int bg[4] = {0, 0, 0, 0}, npaths = 0;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (!strcmp(a, "-h") || !strcmp(a, "--help")) return usage(stdout);
        int has_value = i + 1 < argc;
        if (!strcmp(a, "--heat") && has_value) {
            heat_path = argv[++i];
        } else if (!strcmp(a, "--background") && has_value) {
            if (sscanf(argv[++i], "%d,%d,%d,%d", &bg[0], &bg[1], &bg[2], &bg[3]) != 4 ||
                bg[0] < 0 || bg[0] > 255 || bg[1] < 0 || bg[1] > 255 || bg[2] < 0 || bg[2] > 255 ||
                bg[3] < 0 || bg[3] > 255) {
                fprintf(stderr, "sgapi-diff: --background wants R,G,B,A in 0..255\n");
                return 2;
            }
        } else if ((!strcmp(a, "--min-psnr") || !strcmp(a, "--max-over2") ||
                    !strcmp(a, "--max-coverage")) &&
                   has_value) {
            double v;
            if (!sc_parse_double(argv[++i], 0.0, &v)) {
                fprintf(stderr, "sgapi-diff: %s wants a number, got '%s'\n", a, argv[i]);
                return 2;
            }
            *(!strcmp(a, "--min-psnr")    ? &min_psnr
              : !strcmp(a, "--max-over2") ? &max_over2
                                          : &max_cov) = v;
        } else if (a[0] == '-' && a[1] != '\0') {
            fprintf(stderr, "sgapi-diff: unknown option or missing value: %s\n", a);
            return usage(stderr);
        } else if (npaths < 2) {
            paths[npaths++] = a;
        } else {
            return usage(stderr);
        }
    }
    if (npaths != 2) return usage(stderr);

    int w[2], h[2], n;
    unsigned char *img[2];
    for (int k = 0; k < 2; k++) {
        img[k] = stbi_load(paths[k], &w[k], &h[k], &n, 4);
        if (!img[k]) {
            fprintf(stderr, "sgapi-diff: cannot read %s: %s\n", paths[k], stbi_failure_reason());
            return 2;
        }
    }
    if (w[0] != w[1] || h[0] != h[1]) {
        fprintf(stderr, "sgapi-diff: sizes differ: %dx%d vs %dx%d\n", w[0], h[0], w[1], h[1]);
        return 2;
    }
    unsigned char background[4];
    for (int c = 0; c < 4; c++) background[c] = (unsigned char)bg[c];
    unsigned char *hm = heat_path ? malloc((size_t)w[0] * (size_t)h[0] * 4) : NULL;
    sc_diff d = sc_image_diff(img[0], img[1], w[0], h[0], background, hm);
    double psnr = d.psnr_db, pct2 = d.pct_over[0], pctcov = d.pct_coverage;
    printf("psnr_db %.2f\n", psnr);
    printf("mean_abs_error %.4f\n", d.mean_abs_error);
    printf("max_error %d\n", d.max_error);
    printf("pct_over_2 %.4f\n", pct2);
    printf("pct_over_8 %.4f\n", d.pct_over[1]);
    printf("pct_over_32 %.4f\n", d.pct_over[2]);
    printf("coverage_mismatch_pct %.4f (%zu pixels)\n", pctcov, d.coverage_mismatch);
    int status = 0;
    if (hm) {
        if (!stbi_write_png(heat_path, w[0], h[0], 4, hm, w[0] * 4)) {
            fprintf(stderr, "sgapi-diff: cannot write %s\n", heat_path);
            status = 2;
        }
        free(hm);
    }
    if (min_psnr >= 0 && psnr < min_psnr) {
        printf("FAIL psnr %.2f dB < %.2f dB\n", psnr, min_psnr);
        status = status ? status : 1;
    }
    if (max_over2 >= 0 && pct2 > max_over2) {
        printf("FAIL %.4f %% of pixels over 2/255 > %.4f %%\n", pct2, max_over2);
        status = status ? status : 1;
    }
    if (max_cov >= 0 && pctcov > max_cov) {
        printf("FAIL coverage mismatch %.4f %% > %.4f %%\n", pctcov, max_cov);
        status = status ? status : 1;
    }
    stbi_image_free(img[0]);
    stbi_image_free(img[1]);
    return status;
}
