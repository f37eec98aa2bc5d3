/* shade_shader_tile.h - the 16-lane parts of the fragment stage of shader pipelines (the batch's
 * set-up and conversion, the in-place writes, the portable walks' depth test), written once over
 * vectors of SG_LANES_W lanes and compiled by shade_shader.c once per copy (tex/lanes_copies.h: 4,
 * 8 or 16 lanes). A copy's vectors are its registers' width: GCC 12 turns a comparison of vectors
 * wider than the target's registers into one compare a lane, so the AVX2 copy works on two halves
 * of a tile, the portable one on four rows. Every lane does the scalar operations of its pixel in
 * the same order, so every copy gives the same bits. No include guard. */

typedef float SG_LANES_FN(vf) __attribute__((vector_size(4 * SG_LANES_W)));
typedef int32_t SG_LANES_FN(vi) __attribute__((vector_size(4 * SG_LANES_W)));
#define VF            SG_LANES_FN(vf)
#define VI            SG_LANES_FN(vi)
#define TSEL(m, a, b) ((VF)(((m) & (VI)(a)) | (~(m) & (VI)(b))))
/* a > b ? a : b and a < b ? a : b, lane by lane (b where either is NaN or both are zeros): one
 * instruction each on x86, two there with the selects. */
#if defined(__x86_64__) && SG_LANES_W == 16
#define VMAX(a, b) ((VF)_mm512_max_ps((__m512)(a), (__m512)(b)))
#define VMIN(a, b) ((VF)_mm512_min_ps((__m512)(a), (__m512)(b)))
#elif defined(__x86_64__) && SG_LANES_W == 8
#define VMAX(a, b) ((VF)_mm256_max_ps((__m256)(a), (__m256)(b)))
#define VMIN(a, b) ((VF)_mm256_min_ps((__m256)(a), (__m256)(b)))
#elif defined(__x86_64__) && SG_LANES_W == 4
#define VMAX(a, b) ((VF)_mm_max_ps((__m128)(a), (__m128)(b)))
#define VMIN(a, b) ((VF)_mm_min_ps((__m128)(a), (__m128)(b)))
#else
#define VMAX(a, b) TSEL((a) > (b), a, b)
#define VMIN(a, b) TSEL((a) < (b), a, b)
#endif

/* The tile's lanes h .. h + SG_LANES_W - 1: their columns and rows (sg_tile_lane_x, _y). */
SG_LANES_ATTR static inline void SG_LANES_FN(lanes)(int h, VF *x, VF *y) {
    memcpy(x, sg_tile_lane_x + h, sizeof *x);
    memcpy(y, sg_tile_lane_y + h, sizeof *y);
}

/* Triangle t interpolated at lanes h .. h + SG_LANES_W - 1 of n tiles (1 or 2, a constant) at
 * (xs[j], ys[j]), into b[j]'s depth and varyings: every lane its pixel centre (helper lanes too),
 * as the fixed shading does (attribute / w and 1 / w planes, then one division). Each plane's
 * coefficients are read and spread once for the n tiles, whose chains (the division, then the
 * varyings) run side by side; every lane does the same operations whatever n, so the same bits.
 * `all`: every lane written, else those of `sel` only (a lane's value is the same either way).
 * depth false: b[j]'s depth is 0, for a stage that does not read it (sgShaderDesc.varyings_only)
 * of a tile whose depth is settled already. */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(interp_n)(const sg_shade_ctx *c, const sg_tri *t, const int n, const int *xs,
                      const int *ys, int h, VI sel, const bool all, const bool depth,
                      sgFragmentBatch *b) {
    const sg_shader_state *s = &c->shader;
    const sg_tri_ext *ext = s->varying_count > SG_TRI_ATTRS ? sg_shade_ext(c, t) : NULL;
    const VF zero = {0}, one = zero + 1.0f;
#define PUT(dst, v)                                                                                \
    do {                                                                                           \
        VF o_ = (v);                                                                               \
        if (!all) {                                                                                \
            VF d_;                                                                                 \
            memcpy(&d_, (dst), sizeof d_);                                                         \
            o_ = TSEL(sel, o_, d_);                                                                \
        }                                                                                          \
        memcpy((dst), &o_, sizeof o_);                                                             \
    } while (0)
    VF lx, ly, dx[2], dy[2], w[2];
    SG_LANES_FN(lanes)(h, &lx, &ly);
    for (int j = 0; j < n; j++) {
        dx[j] = (float)(xs[j] - t->minx) + lx;
        dy[j] = (float)(ys[j] - t->miny) + ly;
    }
    for (int j = 0; j < n; j++) {
        if (depth) {
            const VF z = t->z + t->z_dx * dx[j] + t->z_dy * dy[j];
            PUT(b[j].z + h, VMIN(one, VMAX(zero, z))); /* sg_tri_depth */
        } else
            PUT(b[j].z + h, zero);
        w[j] = 1.0f / (t->q + t->q_dx * dx[j] + t->q_dy * dy[j]);
    }
    for (int k = 0; k < s->varying_count; k++) {
        const bool own = k < SG_TRI_ATTRS;
        const VF va = zero + (own ? t->a[k] : ext->a[k - SG_TRI_ATTRS]);
        if (t->same >> k & 1) { /* flat, or the same at every vertex: as it is */
            for (int j = 0; j < n; j++) PUT(b[j].varying[k] + h, va);
            continue;
        }
        const VF vx = zero + (own ? t->a_dx[k] : ext->a_dx[k - SG_TRI_ATTRS]);
        const VF vy = zero + (own ? t->a_dy[k] : ext->a_dy[k - SG_TRI_ATTRS]);
        for (int j = 0; j < n; j++) PUT(b[j].varying[k] + h, (va + vx * dx[j] + vy * dy[j]) * w[j]);
    }
#undef PUT
}

/* interp_n of one tile, at (x0, y0), into b. */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(interp)(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, int h, VI sel,
                    const bool all, sgFragmentBatch *b) {
    SG_LANES_FN(interp_n)(c, t, 1, &x0, &y0, h, sel, all, true, b);
}

/* A float of each lane's triangle: ts[0]'s, then for each j from 1 ts[j]'s in the lanes of
 * sel[j]; the float at byte `at` of what ps[j] points to. The bits are picked; with plus0, 0 is
 * then added, as interp_n spreads a varying's coefficients (-0 becomes 0; its depth and 1 / w
 * planes it takes as they are). */
SG_LANES_ATTR static inline __attribute__((always_inline)) VF
SG_LANES_FN(pick)(const void *const *ps, const VI *sel, int n, size_t at, const bool plus0) {
    const VI none = {0};
    int32_t f;
    memcpy(&f, (const char *)ps[0] + at, sizeof f);
    VI v = none + f;
    for (int j = 1; j < n; j++) {
        memcpy(&f, (const char *)ps[j] + at, sizeof f);
        v = (sel[j] & f) | (~sel[j] & v);
    }
    return plus0 ? (VF){0} + (VF)v : (VF)v;
}

/* The n triangles ts[j] that share the tile at (x0, y0) interpolated at its lanes h .. h +
 * SG_LANES_W - 1 into b: each lane takes its own triangle's plane coefficients (those of the last
 * j whose sel[j] holds it, else ts[0]'s), then one interpolation does interp's operations on
 * them, so each lane has the bits interp gives it. */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(interp_shared)(const sg_shade_ctx *c, const sg_tri *const *ts, const VI *sel, int n,
                           int x0, int y0, int h, sgFragmentBatch *b) {
    const sg_shader_state *s = &c->shader;
    const void *const *tp = (const void *const *)ts;
    const void *ep[SG_TILE_PIXELS];
    if (s->varying_count > SG_TRI_ATTRS)
        for (int j = 0; j < n; j++) ep[j] = sg_shade_ext(c, ts[j]);
    const VF zero = {0}, one = zero + 1.0f;
    VI mx = (VI){0} + ts[0]->minx, my = (VI){0} + ts[0]->miny;
    for (int j = 1; j < n; j++) {
        mx = (sel[j] & ts[j]->minx) | (~sel[j] & mx);
        my = (sel[j] & ts[j]->miny) | (~sel[j] & my);
    }
    VF lx, ly;
    SG_LANES_FN(lanes)(h, &lx, &ly);
    const VF dx = __builtin_convertvector(x0 - mx, VF) + lx;
    const VF dy = __builtin_convertvector(y0 - my, VF) + ly;
#define PICK(field) SG_LANES_FN(pick)(tp, sel, n, offsetof(sg_tri, field), false)
    const VF z = PICK(z) + PICK(z_dx) * dx + PICK(z_dy) * dy;
    const VF zc = VMIN(one, VMAX(zero, z)); /* sg_tri_depth */
    memcpy(b->z + h, &zc, sizeof zc);
    const VF w = 1.0f / (PICK(q) + PICK(q_dx) * dx + PICK(q_dy) * dy);
    /* The varyings every lane's triangle takes as they are (sg_tri.same), and those some do:
     * for those, each lane's own bits (the high half of the word at shader_const). */
    uint32_t all = 0xffffu, any = 0;
    for (int j = 0; j < n; j++) {
        all &= ts[j]->same;
        any |= ts[j]->same;
    }
#if defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_BIG_ENDIAN__
#error "sg_tri.same is read as the high half of a little-endian word"
#endif
    const VI same =
        any & ~all ? (VI)SG_LANES_FN(pick)(tp, sel, n, offsetof(sg_tri, shader_const), false) >> 16
                   : (VI){0};
    for (int k = 0; k < s->varying_count; k++) {
        const bool own = k < SG_TRI_ATTRS;
        const void *const *p = own ? tp : ep;
        const int e = own ? k : k - SG_TRI_ATTRS;
        const size_t a = own ? offsetof(sg_tri, a) : offsetof(sg_tri_ext, a);
        const size_t ax = own ? offsetof(sg_tri, a_dx) : offsetof(sg_tri_ext, a_dx);
        const size_t ay = own ? offsetof(sg_tri, a_dy) : offsetof(sg_tri_ext, a_dy);
        const size_t f = (size_t)e * sizeof(float);
        const VF va = SG_LANES_FN(pick)(p, sel, n, a + f, true);
        VF v = va;
        if (!(all >> k & 1)) {
            v = (va + SG_LANES_FN(pick)(p, sel, n, ax + f, true) * dx +
                 SG_LANES_FN(pick)(p, sel, n, ay + f, true) * dy) *
                w;
            if (any >> k & 1) v = TSEL(((same >> k) & 1) != 0, va, v);
        }
        memcpy(b->varying[k] + h, &v, sizeof v);
    }
#undef PICK
}

/* The batch's fixed fields from t, its mask and tile. */
SG_LANES_ATTR static inline void SG_LANES_FN(batch)(const sg_shade_ctx *c, const sg_tri *t, int x0,
                                                    int y0, uint32_t mask, sgFragmentBatch *b) {
    b->mask = mask;
    b->x = x0;
    b->y = y0;
    b->front_facing = t->sh.front_facing != 0;
    b->primitive = t->sh.primitive;
    b->instance = t->sh.instance;
    b->discard = 0;
    b->internal = c;
}

/* The batch's outputs and the varyings past the count set to 0, before the call. */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(prepare)(const sg_shader_state *s, sgFragmentBatch *b) {
    const VF zero = {0};
    /* Vector stores, not a call of memset: a tile is a few hundred cycles in all (a loop from
     * the count on became one). */
    for (int k = 0; k < SG_MAX_VARYINGS; k++)
        if (k >= s->varying_count)
            for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W)
                memcpy(b->varying[k] + h, &zero, sizeof zero);
    for (int ch = 0; ch < 4; ch++)
        for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W)
            memcpy(b->color[ch] + h, &zero, sizeof zero);
}

/* The batch's colours after the call into RGBA8 pixels px: each channel to unorm8 as
 * sg_to_unorm8 rounds it (NaN and below 0 give 0). */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(convert)(const sgFragmentBatch *b, uint32_t px[SG_SHADER_LANES]) {
#if defined(__x86_64__) && (SG_LANES_W == 16 || SG_LANES_W == 8)
    /* Saturating packs instead of the clamp: min(2, v) keeps NaN (the second operand) and takes
     * infinities and large values to 2; then v 255 + 0.5 truncated is at most 510, and negative
     * (below 0, NaN, -inf) where sg_to_unorm8 gives 0; the two unsigned packs saturate to 0 ..
     * 255, as the clamp did. Each 128-bit lane packs pixels 4l .. 4l + 3 as R0-3 G0-3 B0-3 A0-3,
     * which one byte shuffle puts in pixel order. */
#if SG_LANES_W == 16
#define CV_PS(v)       ((__m512)(v))
#define CV_MIN         _mm512_min_ps
#define CV_SET         _mm512_set1_ps
#define CV_CVT         _mm512_cvttps_epi32
#define CV_PACK32      _mm512_packus_epi32
#define CV_PACK16      _mm512_packus_epi16
#define CV_SHUF(v)     _mm512_shuffle_epi8(v, _mm512_broadcast_i32x4(order))
#define CV_STORE(p, v) _mm512_storeu_si512((void *)(p), v)
    typedef __m512i cv_i;
#else
#define CV_PS(v)       ((__m256)(v))
#define CV_MIN         _mm256_min_ps
#define CV_SET         _mm256_set1_ps
#define CV_CVT         _mm256_cvttps_epi32
#define CV_PACK32      _mm256_packus_epi32
#define CV_PACK16      _mm256_packus_epi16
#define CV_SHUF(v)     _mm256_shuffle_epi8(v, _mm256_broadcastsi128_si256(order))
#define CV_STORE(p, v) _mm256_storeu_si256((void *)(p), v)
    typedef __m256i cv_i;
#endif
    const __m128i order = _mm_setr_epi8(0, 4, 8, 12, 1, 5, 9, 13, 2, 6, 10, 14, 3, 7, 11, 15);
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) {
        cv_i q[4];
        for (int ch = 0; ch < 4; ch++) {
            VF v;
            memcpy(&v, b->color[ch] + h, sizeof v);
            v = (VF)CV_MIN(CV_SET(2.0f), CV_PS(v));
            q[ch] = CV_CVT(CV_PS(v * 255.0f + 0.5f));
        }
        CV_STORE(px + h, CV_SHUF(CV_PACK16(CV_PACK32(q[0], q[1]), CV_PACK32(q[2], q[3]))));
    }
#undef CV_PS
#undef CV_MIN
#undef CV_SET
#undef CV_CVT
#undef CV_PACK32
#undef CV_PACK16
#undef CV_SHUF
#undef CV_STORE
#else
    const VF zero = {0}, one = zero + 1.0f;
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) {
        VI p = {0};
        for (int ch = 0; ch < 4; ch++) {
            VF v;
            memcpy(&v, b->color[ch] + h, sizeof v);
            v = VMIN(VMAX(v, zero), one);
            p |= __builtin_convertvector(v * 255.0f + 0.5f, VI) << (8 * ch);
        }
        memcpy(px + h, &p, sizeof p);
    }
#endif
}

/* The interpolated batch of the tile's pixels `mask` through the fragment stage, into RGBA8
 * pixels px, or, when direct is not NULL, mask the whole tile and no lane discarded, straight
 * into direct (sg_shade_direct); returns the lanes discarded. */
SG_LANES_ATTR static inline __attribute__((always_inline)) uint32_t
SG_LANES_FN(run)(const sg_shade_ctx *c, sgFragmentBatch *b, uint32_t mask,
                 uint32_t px[SG_SHADER_LANES], uint32_t *direct) {
    const sg_shader_state *s = &c->shader;
    SG_LANES_FN(prepare)(s, b);
    s->fragment(b, s->uniforms);
    SG_LANES_FN(convert)(b, sg_shade_direct(direct, mask, b->discard) ? direct : px);
    return b->discard;
}

/* The colour of a triangle shaded once (sg_tri.shader_const) in every lane of out. */
SG_LANES_ATTR static inline void SG_LANES_FN(fill)(uint32_t color, uint32_t *out) {
    const VI v = (VI){0} + (int32_t)color;
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) memcpy(out + h, &v, sizeof v);
}

/* sg_shader_constant in this copy: a batch whose lanes all hold the varyings, through the stage,
 * lane 0 converted. */
SG_LANES_ATTR static uint32_t SG_LANES_FN(shade_constant)(const sg_shade_ctx *c,
                                                          const void *uniforms,
                                                          const float *varyings, int *discarded) {
    const sg_shader_state *s = &c->shader;
    sgFragmentBatch b;
    b.mask = 0xffffu;
    b.x = b.y = 0;
    b.front_facing = true;
    b.primitive = b.instance = 0;
    b.discard = 0;
    b.internal = c;
    const VF zero = {0};
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) memcpy(b.z + h, &zero, sizeof zero);
    for (int k = 0; k < s->varying_count; k++) /* the bits as they are (-0 stays -0) */
        for (int i = 0; i < SG_SHADER_LANES; i++) b.varying[k][i] = varyings[k];
    SG_LANES_FN(prepare)(s, &b);
    s->fragment(&b, uniforms);
    uint32_t px[SG_SHADER_LANES];
    SG_LANES_FN(convert)(&b, px);
    *discarded = b.discard & 1u;
    return px[0];
}

/* Batch b of the tile at (x0, y0) of one triangle: its fixed fields and every lane
 * interpolated. */
SG_LANES_ATTR static inline __attribute__((always_inline)) void
SG_LANES_FN(one_triangle)(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                          sgFragmentBatch *b) {
    SG_LANES_FN(batch)(c, t, x0, y0, mask, b);
    const VI none = {0};
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W)
        SG_LANES_FN(interp)(c, t, x0, y0, h, none, true, b);
}

/* A tile of one triangle through the fragment stage, into RGBA8 pixels px or direct (run);
 * returns the lanes discarded. */
SG_LANES_ATTR static uint32_t SG_LANES_FN(shade_tile)(const sg_shade_ctx *c, const sg_tri *t,
                                                      int x0, int y0, uint32_t mask,
                                                      uint32_t px[SG_SHADER_LANES],
                                                      uint32_t *direct) {
    if (c->shader.konst && t->shader_const) {
        SG_LANES_FN(fill)(t->sh.color, sg_shade_direct(direct, mask, 0) ? direct : px);
        return 0;
    }
    sgFragmentBatch b;
    SG_LANES_FN(one_triangle)(c, t, x0, y0, mask, &b);
    return SG_LANES_FN(run)(c, &b, mask, px, direct);
}

/* Two whole tiles of one triangle, at (x0, y0) and (x1, y1), into dst[0] and dst[1]: set up
 * both, then the two calls, then both conversions, so that the second tile's work overlaps the
 * end of the first's (each tile the bytes shade_tile gives it); a tile that discards nothing is
 * converted straight into its pixels, else its lanes not discarded are put. Returns the lanes
 * discarded, the second tile's in bits 16 to 31. */
SG_LANES_ATTR static uint32_t SG_LANES_FN(shade_tile2)(const sg_shade_ctx *c, const sg_tri *t,
                                                       int x0, int y0, int x1, int y1,
                                                       uint32_t *const dst[2]) {
    if (c->shader.konst && t->shader_const) { /* whole tiles: their pixels */
        for (int j = 0; j < 2; j++) SG_LANES_FN(fill)(t->sh.color, dst[j]);
        return 0;
    }
    const sg_shader_state *s = &c->shader;
    sgFragmentBatch b[2];
    const int xs[2] = {x0, x1}, ys[2] = {y0, y1};
    for (int j = 0; j < 2; j++) SG_LANES_FN(batch)(c, t, xs[j], ys[j], 0xffffu, &b[j]);
    const VI none = {0};
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W)
        SG_LANES_FN(interp_n)(c, t, 2, xs, ys, h, none, true, !c->shader.konst, b);
    for (int j = 0; j < 2; j++) SG_LANES_FN(prepare)(s, &b[j]);
    s->fragment(&b[0], s->uniforms);
    s->fragment(&b[1], s->uniforms);
    for (int j = 0; j < 2; j++) {
        if (sg_shade_direct(dst[j], 0xffffu, b[j].discard)) {
            SG_LANES_FN(convert)(&b[j], dst[j]);
            continue;
        }
        uint32_t px[SG_SHADER_LANES];
        SG_LANES_FN(convert)(&b[j], px);
        sg_fb_put_lanes(dst[j], px, 0xffffu & ~b[j].discard);
    }
    return b[0].discard | b[1].discard << 16;
}

/* The colours of the triangles ts[j] shaded once into their lanes masks[j] of out. */
SG_LANES_ATTR static inline void
SG_LANES_FN(put_const)(const sg_tri *const *ts, const uint32_t *masks, int n, uint32_t *out) {
    for (int j = 0; j < n; j++) {
        if (!ts[j]->shader_const) continue;
        const VI color = (VI){0} + (int32_t)ts[j]->sh.color;
        for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) {
            VI bit, o;
            memcpy(&bit, sg_tile_lane_bit + h, sizeof bit);
            memcpy(&o, out + h, sizeof o);
            const VI m = (bit & (int32_t)masks[j]) != 0;
            o = SELI(m, color, o);
            memcpy(out + h, &o, sizeof o);
        }
    }
}

/* The same for a tile that n triangles of a draw with independent lanes share, in one batch:
 * ts[j] covers the lanes of masks[j] and each lane takes its own triangle's values (the lanes
 * of none take ts[0]'s); facing, primitive and instance are ts[0]'s (the facing is
 * every triangle's). z, when not NULL, receives each lane's window depth; direct as run's. */
SG_LANES_ATTR static uint32_t
SG_LANES_FN(shade_shared)(const sg_shade_ctx *c, const sg_tri *const *ts, const uint32_t *masks,
                          int n, int x0, int y0, uint32_t mask, uint32_t px[SG_SHADER_LANES],
                          float *z, uint32_t *direct) {
    /* The lanes of triangles shaded once take their colours; with every lane so, and no depth
     * wanted, there is nothing to interpolate or call. */
    uint32_t konst = 0;
    for (int j = 0; j < n && c->shader.konst; j++)
        if (ts[j]->shader_const) konst |= masks[j];
    konst &= mask;
    if (konst && konst == mask && !z) {
        uint32_t *out = sg_shade_direct(direct, mask, 0) ? direct : px;
        SG_LANES_FN(put_const)(ts, masks, n, out);
        return 0;
    }
    sgFragmentBatch b;
    SG_LANES_FN(batch)(c, ts[0], x0, y0, mask, &b);
    const VI none = {0};
    for (int h = 0; h < SG_SHADER_LANES; h += SG_LANES_W) {
        VI bit, sel[SG_TILE_PIXELS];
        memcpy(&bit, sg_tile_lane_bit + h, sizeof bit);
        /* Two triangles of few varyings: the second interpolation costs less than the picks. */
        if (n == 1 || (n == 2 && c->shader.varying_count <= 4)) {
            SG_LANES_FN(interp)(c, ts[0], x0, y0, h, none, true, &b);
            if (n == 2 && masks[1] >> h & ((1u << SG_LANES_W) - 1u))
                SG_LANES_FN(interp)(c, ts[1], x0, y0, h, (bit & (int32_t)masks[1]) != 0, false, &b);
            continue;
        }
        for (int j = 1; j < n; j++) sel[j] = (bit & (int32_t)masks[j]) != 0;
        SG_LANES_FN(interp_shared)(c, ts, sel, n, x0, y0, h, &b);
    }
    if (z) memcpy(z, b.z, sizeof b.z);
    if (!konst) return SG_LANES_FN(run)(c, &b, mask, px, direct);
    const uint32_t discard = SG_LANES_FN(run)(c, &b, mask, px, NULL) & ~konst;
    SG_LANES_FN(put_const)(ts, masks, n, px);
    if (sg_shade_direct(direct, mask, discard))
        memcpy(direct, px, sizeof(uint32_t) * SG_SHADER_LANES);
    return discard;
}

/* The portable walks' (shade_shader_walk.h); blend_avx2.c and blend_avx512.c have their own. */
#if SG_LANES_W == 4
/* The depth test of a tile shaded in place: each lane's window depth into z (sg_tri_depth's
 * operations, so its bits), and the lanes of mask that pass `op` against the tile's stored depths
 * dp (all of them when dp is NULL). */
SG_LANES_ATTR static uint32_t SG_LANES_FN(tile_depth)(const sg_tri *t, int x0, int y0,
                                                      uint32_t mask, const float *dp, sgCompare op,
                                                      float z[SG_TILE_PIXELS]) {
    const VF zero = {0}, one = zero + 1.0f;
    const VI none = {0}, all = none - 1;
    uint32_t bits = 0; /* lane i in bit i */
    for (int h = 0; h < SG_TILE_PIXELS; h += SG_LANES_W) {
        VF lx, ly;
        SG_LANES_FN(lanes)(h, &lx, &ly);
        const VF dx = (float)(x0 - t->minx) + lx, dy = (float)(y0 - t->miny) + ly;
        const VF zr = t->z + t->z_dx * dx + t->z_dy * dy;
        const VF zc = VMIN(one, VMAX(zero, zr));
        memcpy(z + h, &zc, sizeof zc);
        if (!dp) continue;
        VF d;
        memcpy(&d, dp + h, sizeof d);
        VI pass;
        switch (op) { /* sg_depth_passes, lane by lane */
        case SG_COMPARE_NEVER:
            pass = none;
            break;
        case SG_COMPARE_LESS:
            pass = zc < d;
            break;
        case SG_COMPARE_EQUAL:
            pass = zc == d;
            break;
        case SG_COMPARE_LESS_EQUAL:
            pass = zc <= d;
            break;
        case SG_COMPARE_GREATER:
            pass = zc > d;
            break;
        case SG_COMPARE_NOT_EQUAL:
            pass = zc != d;
            break;
        case SG_COMPARE_GREATER_EQUAL:
            pass = zc >= d;
            break;
        default:
            pass = all;
            break;
        }
        for (int i = 0; i < SG_LANES_W; i++) bits |= (uint32_t)(pass[i] & 1) << (h + i);
    }
    return dp ? mask & bits : mask;
}

#endif

/* The lanes of keep written: depth z into dp (when not NULL) and the colours src put into dst. */
SG_LANES_ATTR static void SG_LANES_FN(put_tile)(uint32_t keep, const float z[SG_TILE_PIXELS],
                                                float *dp, const uint32_t src[SG_TILE_PIXELS],
                                                uint32_t *dst) {
    for (int h = 0; h < SG_TILE_PIXELS; h += SG_LANES_W) {
        VI bit;
        memcpy(&bit, sg_tile_lane_bit + h, sizeof bit);
        const VI m = (bit & (int32_t)keep) != 0;
        VI a, b;
        if (dp) {
            memcpy(&a, z + h, sizeof a);
            memcpy(&b, dp + h, sizeof b);
            b = SELI(m, a, b);
            memcpy(dp + h, &b, sizeof b);
        }
        memcpy(&a, src + h, sizeof a);
        memcpy(&b, dst + h, sizeof b);
        b = SELI(m, a, b);
        memcpy(dst + h, &b, sizeof b);
    }
}

#undef VF
#undef VI
#undef TSEL
#undef VMAX
#undef VMIN
