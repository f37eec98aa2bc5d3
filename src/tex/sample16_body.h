/* sample16_body.h - the body of tex/sample16.c, included there once for each instruction set
 * it is compiled for: SG_LANES_FN(name) names this copy's functions and SG_LANES_ATTR gives their
 * target (lanes.h). No include guard: each inclusion makes a copy. */
/* One level: every lane's four channels into out. (The coordinates come as arrays: a vector
 * argument's calling convention differs between the copies.) */
static inline __attribute__((always_inline)) SG_LANES_ATTR void
SG_LANES_FN(texels16)(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,
                      const float *sp, const float *tp, sg_vi out[4]) {
    const sg_vf zero = {0};
    sg_vf s, t;
    memcpy(&s, sp, sizeof s);
    memcpy(&t, tp, sizeof t);
    /* the texels of each lane: 1 (nearest) or 4, and the 8-bit weights of the 4 */
    uint32_t texel[4][SG_SHADER_LANES];
    sg_vi wt[4];
    const uint32_t *const base = (const uint32_t *)(const void *)texels;
    if (!bilinear) {
        sg_vf x, y;
        VCOORD(x, s, (float)w, repeat);
        VCOORD(y, t, (float)h, repeat);
        VFLOOR(x, x);
        VFLOOR(y, y);
        _Alignas(64) int32_t i[SG_SHADER_LANES], j[SG_SHADER_LANES];
        const sg_vi iv = __builtin_convertvector(x, sg_vi), jv = __builtin_convertvector(y, sg_vi);
        memcpy(i, &iv, sizeof i);
        memcpy(j, &jv, sizeof j);
        SG_WRAP16(i, w, repeat);
        SG_WRAP16(j, h, repeat);
        for (int l = 0; l < SG_SHADER_LANES; l++)
            memcpy(&texel[0][l], base + (size_t)(h - 1 - j[l]) * (size_t)w + (size_t)i[l], 4);
        for (int k = 0; k < 4; k++) {
            sg_vi c;
            memcpy(&c, texel[0], sizeof c);
            out[k] = (c >> CHANNEL_SHIFT(k)) & 255;
        }
        return;
    }
    sg_vf x, y;
    VCOORD(x, s, 256.0f * (float)w, repeat);
    VCOORD(y, t, 256.0f * (float)h, repeat);
    if (!repeat) { /* beyond one texel outside, clamp-to-edge reads the edge texel anyway */
        const float xmax = 256.0f * (float)(w + 1), ymax = 256.0f * (float)(h + 1);
        x = SEL(x < -256.0f, zero - 256.0f, SEL(x > xmax, zero + xmax, x));
        y = SEL(y < -256.0f, zero - 256.0f, SEL(y > ymax, zero + ymax, y));
    }
    VFLOOR(x, x);
    VFLOOR(y, y);
    /* sg_bilinear_split */
    const sg_vi xv = __builtin_convertvector(x, sg_vi) - 128 + 512,
                yv = __builtin_convertvector(y, sg_vi) - 128 + 512;
    const sg_vi fx = xv & 255, fy = yv & 255;
    _Alignas(64) int32_t i0[SG_SHADER_LANES], j0[SG_SHADER_LANES], i1[SG_SHADER_LANES],
        j1[SG_SHADER_LANES];
    const sg_vi i0v = (xv >> 8) - 2, j0v = (yv >> 8) - 2, i1v = i0v + 1, j1v = j0v + 1;
    memcpy(i0, &i0v, sizeof i0);
    memcpy(j0, &j0v, sizeof j0);
    memcpy(i1, &i1v, sizeof i1);
    memcpy(j1, &j1v, sizeof j1);
    SG_WRAP16(i1, w, repeat);
    SG_WRAP16(j1, h, repeat);
    SG_WRAP16(i0, w, repeat);
    SG_WRAP16(j0, h, repeat);
    for (int l = 0; l < SG_SHADER_LANES; l++) {
        const uint32_t *r0 = base + (size_t)(h - 1 - j0[l]) * (size_t)w,
                       *r1 = base + (size_t)(h - 1 - j1[l]) * (size_t)w;
        memcpy(&texel[0][l], r0 + i0[l], 4);
        memcpy(&texel[1][l], r0 + i1[l], 4);
        memcpy(&texel[2][l], r1 + i0[l], 4);
        memcpy(&texel[3][l], r1 + i1[l], 4);
    }
    wt[0] = (256 - fx) * (256 - fy);
    wt[1] = fx * (256 - fy);
    wt[2] = (256 - fx) * fy;
    wt[3] = fx * fy;
    sg_vi p[4];
    for (int q = 0; q < 4; q++) memcpy(&p[q], texel[q], sizeof p[q]);
    for (int k = 0; k < 4; k++) {
        out[k] = (((p[0] >> CHANNEL_SHIFT(k)) & 255) * wt[0] +
                  ((p[1] >> CHANNEL_SHIFT(k)) & 255) * wt[1] +
                  ((p[2] >> CHANNEL_SHIFT(k)) & 255) * wt[2] +
                  ((p[3] >> CHANNEL_SHIFT(k)) & 255) * wt[3] + 32768) >>
                 16;
    }
}

SG_LANES_ATTR void SG_LANES_FN(sg_sample16)(const sg_texview *tv, bool bilinear, bool repeat,
                                            bool window, const float s[SG_SHADER_LANES],
                                            const float t[SG_SHADER_LANES],
                                            int32_t texel[4][SG_SHADER_LANES]) {
    (void)window; /* no window here: the lanes read texels one by one */
    sg_vi c[4];
    SG_LANES_FN(texels16)(tv->texels, tv->width, tv->height, bilinear, repeat, s, t, c);
    for (int k = 0; k < 4; k++) memcpy(texel[k], &c[k], sizeof c[k]);
}

/* Each level the quads read is looked up once for all 16 lanes, and each lane keeps its own
 * quad's: a tile's quads mostly share one or two levels. */
SG_LANES_ATTR void SG_LANES_FN(sg_sample16_mip)(const sg_mip_chain *m, const sg_mip_pick pick[4],
                                                bool bilinear, bool repeat, bool window,
                                                const float s[SG_SHADER_LANES],
                                                const float t[SG_SHADER_LANES],
                                                int32_t texel[4][SG_SHADER_LANES]) {
    (void)window;
    _Alignas(64) int32_t l0[SG_SHADER_LANES], l1[SG_SHADER_LANES], f[SG_SHADER_LANES];
    uint32_t want0 = 0, want1 = 0; /* the levels read, as bits */
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        const sg_mip_pick *p = &pick[(i >> 1 & 1) | (i >> 3) << 1];
        l0[i] = p->level0;
        l1[i] = p->level1;
        f[i] = p->f;
        want0 |= 1u << p->level0;
        if (p->f) want1 |= 1u << p->level1; /* weight 0: sg_sample_mip reads level0 alone */
    }
    sg_vi lv0, lv1, fv, a[4] = {{0}}, b[4] = {{0}};
    memcpy(&lv0, l0, sizeof lv0);
    memcpy(&lv1, l1, sizeof lv1);
    memcpy(&fv, f, sizeof fv);
    for (uint32_t want = want0 | want1; want; want &= want - 1) {
        const int level = __builtin_ctz(want);
        const sg_texview *v = &m->level[level];
        sg_vi c[4];
        SG_LANES_FN(texels16)(v->texels, v->width, v->height, bilinear, repeat, s, t, c);
        const sg_vi in0 = lv0 == level, in1 = lv1 == level;
        for (int k = 0; k < 4; k++) {
            a[k] = SELI(in0, c[k], a[k]);
            b[k] = SELI(in1, c[k], b[k]);
        }
    }
    for (int k = 0; k < 4; k++) {
        const sg_vi r = a[k] + (((b[k] - a[k]) * fv) >> 8);
        memcpy(texel[k], &r, sizeof r);
    }
}

/* Channels 0 .. 255 to floats over 255, as a division gives them. */
SG_LANES_ATTR void SG_LANES_FN(sg_texels_to_unit)(const int32_t texel[4][SG_SHADER_LANES],
                                                  float out[4][SG_SHADER_LANES]) {
    for (int k = 0; k < 4; k++) {
        sg_vi c;
        memcpy(&c, texel[k], sizeof c);
        const sg_vf f = __builtin_convertvector(c, sg_vf) / 255.0f;
        memcpy(out[k], &f, sizeof f);
    }
}

/* sg_sample16, then sg_texels_to_unit. */
SG_LANES_ATTR void SG_LANES_FN(sg_sample16_unit)(const sg_texview *tv, bool bilinear, bool repeat,
                                                 bool window, const float s[SG_SHADER_LANES],
                                                 const float t[SG_SHADER_LANES],
                                                 float out[4][SG_SHADER_LANES]) {
    int32_t texel[4][SG_SHADER_LANES];
    SG_LANES_FN(sg_sample16)(tv, bilinear, repeat, window, s, t, texel);
    SG_LANES_FN(sg_texels_to_unit)(texel, out);
}
