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

static int usage(FILE *f) {
    fprintf(f, "usage: sgapi-diff A.png B.png [--heat OUT.png] [--background R,G,B,A]\n"
               "                  [--min-psnr DB] [--max-over2 PCT] [--max-coverage PCT]\n"
               "Compares two images; with thresholds, exits 1 when any is exceeded.\n");
    return f == stderr ? 2 : 0;
}

static int parse_double(const char *s, double *out) {
    char *end;
    errno = 0;
    *out = strtod(s, &end);
    return errno == 0 && end != s && *end == '\0' && isfinite(*out);
}

/* Heat map colour for a difference of d/255: black, then blue, red, yellow, white. */
static void heat(int d, unsigned char *p) {
    static const int stops[5][3] = {
        {0, 0, 0}, {0, 0, 255}, {255, 0, 0}, {255, 255, 0}, {255, 255, 255}};
    static const int at[5] = {0, 1, 8, 32, 128};
    if (d <= 0) {
        p[0] = p[1] = p[2] = 0;
    } else {
        int k = 0;
        while (k < 3 && d > at[k + 1]) k++;
        double t = d >= at[4] ? 1.0 : (double)(d - at[k]) / (at[k + 1] - at[k]);
        if (d >= at[4]) k = 3;
        for (int c = 0; c < 3; c++)
            p[c] = (unsigned char)lround(stops[k][c] + t * (stops[k + 1][c] - stops[k][c]));
    }
    p[3] = 255;
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
            if (sscanf(argv[++i], "%d,%d,%d,%d", &bg[0], &bg[1], &bg[2], &bg[3]) != 4) {
                fprintf(stderr, "sgapi-diff: --background wants R,G,B,A in 0..255\n");
                return 2;
            }
        } else if ((!strcmp(a, "--min-psnr") || !strcmp(a, "--max-over2") ||
                    !strcmp(a, "--max-coverage")) &&
                   has_value) {
            double v;
            if (!parse_double(argv[++i], &v)) {
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
    size_t pixels = (size_t)w[0] * (size_t)h[0];
    unsigned char *hm = heat_path ? malloc(pixels * 4) : NULL;
    double sq = 0, abs_sum = 0;
    int max_err = 0;
    size_t over2 = 0, over8 = 0, over32 = 0, cov = 0;
    for (size_t i = 0; i < pixels; i++) {
        const unsigned char *a = img[0] + i * 4, *b = img[1] + i * 4;
        int m = 0, bga = 1, bgb = 1;
        for (int c = 0; c < 4; c++) {
            int d = abs((int)a[c] - (int)b[c]);
            if (c < 3) sq += (double)d * d;
            abs_sum += d;
            if (d > m) m = d;
            bga &= a[c] == bg[c];
            bgb &= b[c] == bg[c];
        }
        if (m > max_err) max_err = m;
        over2 += m > 2;
        over8 += m > 8;
        over32 += m > 32;
        cov += bga != bgb;
        if (hm) heat(m, hm + i * 4);
    }
    double mse = sq / ((double)pixels * 3);
    double psnr = mse > 0 ? 10.0 * log10(255.0 * 255.0 / mse) : INFINITY;
    double pct2 = 100.0 * over2 / pixels, pctcov = 100.0 * cov / pixels;
    printf("psnr_db %.2f\n", psnr);
    printf("mean_abs_error %.4f\n", abs_sum / ((double)pixels * 4));
    printf("max_error %d\n", max_err);
    printf("pct_over_2 %.4f\n", pct2);
    printf("pct_over_8 %.4f\n", 100.0 * over8 / pixels);
    printf("pct_over_32 %.4f\n", 100.0 * over32 / pixels);
    printf("coverage_mismatch_pct %.4f (%zu pixels)\n", pctcov, cov);
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
