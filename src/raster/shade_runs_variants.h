/* shade_runs_variants.h - the packed-runs functions (sg_shade_runs_fn) of one instruction set,
 * made from its runs body.
 *
 * Included by shade_avx2.c and shade_avx512.c after each defines
 *   shade_runs(ctx, tri, ext, bx0, by0, runs, n, color, textured, bilinear, repeat, flat, sec)
 * (always inlined, its last five arguments constants) and SG_RUNS_TABLE, the name of its
 * sg_shade_runs_fn (int index) lookup. Textured variants only: vertex colours cost less to shade
 * tile by tile than to pack (packed, line_fan took 13 % longer with AVX-512). The per-triangle
 * `flat` is split off once per triangle.
 */
#ifndef SG_RUNS_TABLE
#error "define SG_RUNS_TABLE and shade_runs before including shade_runs_variants.h"
#endif

/* runs_<tex><bil><rep><sec>: the sg_shade_runs_fn of a runs body (body(ctx, tri, ext, bx0, by0,
 * runs, n, color, textured, bilinear, repeat, flat, sec), always inlined), for the file to use
 * with other bodies too. */
#ifndef SG_RUNS_VARIANT
#define SG_RUNS_VARIANT(body, tex, bil, rep, sec)                                                  \
    static void runs_##tex##bil##rep##sec(const sg_shade_ctx *c, const sg_tri *t, int bx0,         \
                                          int by0, const sg_run *r, int n, uint32_t *color) {      \
        const sg_tri_ext *ext = sec ? sg_shade_ext(c, t) : NULL;                                   \
        if (t->flat == SG_FLAT_WHITE && !sec)                                                      \
            body(c, t, ext, bx0, by0, r, n, color, tex, bil, rep, SG_FLAT_WHITE, sec);             \
        else if (t->flat != SG_FLAT_NONE)                                                          \
            body(c, t, ext, bx0, by0, r, n, color, tex, bil, rep, SG_FLAT_COLOR, sec);             \
        else                                                                                       \
            body(c, t, ext, bx0, by0, r, n, color, tex, bil, rep, SG_FLAT_NONE, sec);              \
    }
#endif
#define SG_RUNS(tex, bil, rep, sec) SG_RUNS_VARIANT(shade_runs, tex, bil, rep, sec)
SG_RUNS(1, 0, 1, 0) /* texture, nearest, repeat */
SG_RUNS(1, 0, 0, 0) /* texture, nearest, clamp */
SG_RUNS(1, 1, 1, 0) /* texture, bilinear, repeat */
SG_RUNS(1, 1, 0, 0) /* texture, bilinear, clamp */
SG_RUNS(1, 0, 1, 1) /* the same four, plus the secondary colour */
SG_RUNS(1, 0, 0, 1)
SG_RUNS(1, 1, 1, 1)
SG_RUNS(1, 1, 0, 1)
#undef SG_RUNS

sg_shade_runs_fn SG_RUNS_TABLE(int index) {
    static const sg_shade_runs_fn table[10] = {NULL, runs_1010, runs_1000, runs_1110, runs_1100,
                                               NULL, runs_1011, runs_1001, runs_1111, runs_1101};
    return table[index];
}
