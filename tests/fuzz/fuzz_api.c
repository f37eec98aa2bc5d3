/* fuzz_api.c - libFuzzer target: the input decodes into a sequence of public calls on two devices
 * (creating and destroying images, geoms and pipelines from valid and invalid descs, passes,
 * draws with random state, stale handles, handles of the other device or of another kind, double
 * destroys, destroying a pass's targets, draws outside a pass, shadow maps that alias the pass's
 * targets, NaN, infinite and huge floats everywhere).
 *
 * Invariants, beyond not crashing:
 *   - every failing call returns a code docs/api.md lists for that call, and (given a device)
 *     leaves a non-empty message and logs it exactly once; a failed create leaves its handle 0;
 *   - a failing call changes nothing: the sequence is run a second time without the calls that
 *     failed, where every call must succeed and every pass must leave the same pixels and depths;
 *   - the thread count never shows: the first run's device 0 renders on 1 thread, the second
 *     run's on 3 (device 1: 2, then 1).
 * The pixels compared: each target of each pass, read back at its end, and every image at the end
 * of the sequence. */
#include "fuzz.h"

#include <math.h>
#include <stdbool.h>
#include <stddef.h>
#include <string.h>

#include <sgapi/sgapi.h>

enum {
    SLOTS = 8,       /* handles kept per kind and device */
    MAX_OPS = 192,   /* calls per input */
    MAX_SIDE = 64,   /* largest valid image side the decoder makes */
    MAX_VERTS = 40,  /* vertices per geom */
    MAX_INDEX = 120, /* indices per geom */
    PITCH_MAX = MAX_SIDE * 4 + 8,
    MAX_DIGESTS = 2 * MAX_OPS + 2 * 3 * SLOTS,
};

typedef struct reader {
    const uint8_t *p;
    size_t n, at;
} reader;

static unsigned u8(reader *r) {
    return r->at < r->n ? r->p[r->at++] : 0;
}

/* Mostly ordinary values, and the ones that break arithmetic: NaN, infinities, huge, tiny. */
static float f32(reader *r) {
    static const float table[16] = {0,     1,      -1,    0.5f,   2,   0.25f,    -0.5f,     3,
                                    100.f, 1e-30f, 1e30f, -1e30f, NAN, INFINITY, -INFINITY, 0.75f};
    unsigned b = u8(r);
    if (b < 0xF8) return table[b & 15];
    uint32_t bits = u8(r) | (uint32_t)u8(r) << 8 | (uint32_t)u8(r) << 16 | (uint32_t)u8(r) << 24;
    float f;
    memcpy(&f, &bits, sizeof f);
    return f;
}

/* Arrays of a geom. Each create decodes into fresh ones, kept unchanged until the end: a geom
 * with SG_STORAGE_REFERENCE uses them in place for as long as it lives. */
typedef struct geom_data {
    float pos[MAX_VERTS * 4], col[MAX_VERTS * 4], uv[MAX_VERTS * 2], nrm[MAX_VERTS * 3];
    uint32_t idx[MAX_INDEX];
} geom_data;

/* Each device's own allocator. A device seeds its handles' generations from its address, so an id
 * of the other device is accepted when the generations happen to coincide (1 in 16383, as
 * documented): for the two runs to agree on that, each device must have the same address in
 * both. Its first allocation, the device itself, therefore comes from a fixed block. */
typedef struct dev_alloc {
    _Alignas(64) unsigned char block[1 << 16];
    bool used;
} dev_alloc;

static void *fa_alloc(size_t size, void *user) {
    dev_alloc *a = user;
    if (!a->used && size <= sizeof a->block) {
        a->used = true;
        return a->block;
    }
    return aligned_alloc(16, (size + 15) & ~(size_t)15);
}

static void fa_free(void *p, void *user) {
    dev_alloc *a = user;
    if (p == a->block)
        a->used = false;
    else
        free(p);
}

typedef struct dev_state {
    dev_alloc alloc;
    sgDevice *dev;
    uint32_t img[SLOTS], geom[SLOTS], pso[SLOTS];
    geom_data geoms[MAX_OPS];
    int geom_next;
    int logs;        /* log callback calls since the last check */
    sgPassDesc pass; /* the last pass begun (targets of the open pass, when one is) */
} dev_state;

typedef struct run {
    dev_state d[2];
    int replay;              /* 0: first run, recording; 1: without the failed calls */
    int trace;               /* FUZZ_API_TRACE set: each call result on stderr */
    uint8_t failed[MAX_OPS]; /* first run: which calls failed */
    uint64_t digests[MAX_DIGESTS];
    int ndigests;
    uint8_t buf[MAX_SIDE * PITCH_MAX];
    const uint8_t *pattern; /* what buf holds at the start of each run */
} run;

/* The pixels uploads send, made once: filling them byte by byte for every run cost a quarter of
 * the target's time under coverage instrumentation. */
static const uint8_t *upload_pattern(void) {
    static uint8_t p[MAX_SIDE * PITCH_MAX];
    static int made;
    static const uint8_t rgba[4] = {200, 100, 50, 255};
    if (!made) {
        for (size_t i = 0; i < sizeof p; i++) p[i] = rgba[i & 3] ^ (uint8_t)(i >> 6);
        made = 1;
    }
    return p;
}

static void log_cb(sgResult r, const char *msg, void *user) {
    (void)r;
    FUZZ_CHECK(msg != NULL && msg[0] != '\0');
    ((dev_state *)user)->logs++;
}

#define BIT(c) (1u << (c))
enum {
    ALLOW_CREATE_IMAGE = BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_INVALID_ENUM) |
                         BIT(SG_ERROR_INVALID_SIZE) | BIT(SG_ERROR_OUT_OF_MEMORY) |
                         BIT(SG_ERROR_POOL_EXHAUSTED),
    ALLOW_DESTROY_IMAGE = BIT(SG_ERROR_INVALID_HANDLE) | BIT(SG_ERROR_IN_USE),
    ALLOW_TRANSFER = BIT(SG_ERROR_INVALID_HANDLE) | BIT(SG_ERROR_NULL_POINTER) |
                     BIT(SG_ERROR_INVALID_SIZE) | BIT(SG_ERROR_IN_USE),
    ALLOW_INFO = BIT(SG_ERROR_INVALID_HANDLE),
    ALLOW_CREATE_GEOM = BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_INVALID_ENUM) |
                        BIT(SG_ERROR_INVALID_COUNT) | BIT(SG_ERROR_INDEX_OUT_OF_RANGE) |
                        BIT(SG_ERROR_OUT_OF_MEMORY) | BIT(SG_ERROR_POOL_EXHAUSTED),
    ALLOW_DESTROY = BIT(SG_ERROR_INVALID_HANDLE),
    ALLOW_CREATE_PSO = BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_INVALID_ENUM) |
                       BIT(SG_ERROR_INVALID_VALUE) | BIT(SG_ERROR_INVALID_COUNT) |
                       BIT(SG_ERROR_POOL_EXHAUSTED),
    ALLOW_BEGIN = BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_ALREADY_IN_PASS) |
                  BIT(SG_ERROR_INVALID_HANDLE) | BIT(SG_ERROR_FORMAT_MISMATCH) |
                  BIT(SG_ERROR_INVALID_SIZE) | BIT(SG_ERROR_INVALID_ENUM) |
                  BIT(SG_ERROR_INVALID_VALUE) | BIT(SG_ERROR_OUT_OF_MEMORY),
    ALLOW_DRAW =
        BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_NOT_IN_PASS) | BIT(SG_ERROR_INVALID_HANDLE) |
        BIT(SG_ERROR_INVALID_ENUM) | BIT(SG_ERROR_INVALID_VALUE) | BIT(SG_ERROR_MISSING_DEPTH) |
        BIT(SG_ERROR_INVALID_COUNT) | BIT(SG_ERROR_UNSUPPORTED) | BIT(SG_ERROR_MISSING_ATTRIBUTE) |
        BIT(SG_ERROR_MISSING_TEXTURE) | BIT(SG_ERROR_NOT_SAMPLEABLE) | BIT(SG_ERROR_IN_USE) |
        BIT(SG_ERROR_FORMAT_MISMATCH) | BIT(SG_ERROR_INVALID_SIZE) | BIT(SG_ERROR_OUT_OF_MEMORY),
    ALLOW_END =
        BIT(SG_ERROR_NULL_POINTER) | BIT(SG_ERROR_NOT_IN_PASS) | BIT(SG_ERROR_PASS_MISMATCH),
};

/* Shader stages (sgShaderDesc): a vertex stage from the matrices and every input, a fragment stage
 * that samples two slots, discards by a varying and writes colours out of range. Lane by lane,
 * so the pixels do not depend on how lanes are batched. */
static void fuzz_vs(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float v[4];
        for (int r = 0; r < 4; r++)
            v[r] = b->world_view[r * 4] * b->position[0][i] +
                   b->world_view[r * 4 + 1] * b->position[1][i] +
                   b->world_view[r * 4 + 2] * b->position[2][i] +
                   b->world_view[r * 4 + 3] * b->position[3][i];
        v[0] += (u ? u[0] : 0.0f) * (float)b->instance;
        for (int r = 0; r < 4; r++)
            b->clip[r][i] = b->proj[r * 4] * v[0] + b->proj[r * 4 + 1] * v[1] +
                            b->proj[r * 4 + 2] * v[2] + b->proj[r * 4 + 3] * v[3];
        for (int k = 0; k < SG_MAX_VARYINGS; k++)
            b->varying[k][i] = k < 4   ? b->color[k][i]
                               : k < 6 ? b->texcoord[k - 4][i]
                               : k < 9 ? b->normal[k - 6][i]
                                       : b->attribute[k & 3][k & 3][i] + (float)b->index[i];
    }
}

static void fuzz_fs(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    float t0[4][SG_SHADER_LANES], t1[4][SG_SHADER_LANES];
    sgSample(b, 0, b->varying[4], b->varying[5], t0);
    sgSample(b, 1, b->varying[5], b->varying[4], t1);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 4; k++)
            b->color[k][i] = b->varying[k][i] * t0[k][i] + t1[k][i] * b->z[i] +
                             (float)(b->primitive + b->instance) * 0.01f;
        if (b->varying[6][i] > 0.5f || (b->front_facing && b->varying[7][i] < -0.5f))
            b->discard |= 1u << i;
    }
}

static uint64_t fnv(uint64_t h, const void *p, size_t n) {
    const uint8_t *b = p;
    for (size_t i = 0; i < n; i++) h = (h ^ b[i]) * 1099511628211u;
    return h;
}

static void digest(run *R, uint64_t h) {
    if (!R->replay) {
        if (R->ndigests < MAX_DIGESTS) R->digests[R->ndigests] = h;
    } else if (R->ndigests < MAX_DIGESTS) {
        /* The same pixels with the failed calls left out and another thread count. */
        FUZZ_CHECK(R->digests[R->ndigests] == h);
    }
    R->ndigests++;
}

/* Reads an image back (when it can be: the result must be the same in both runs) into the
 * digests. */
static void digest_image(run *R, dev_state *D, uint32_t id) {
    int w = 0, h = 0;
    sgFormat f;
    sgImage2D im = {id};
    sgResult info = sgGetImage2DInfo(D->dev, im, &w, &h, &f);
    uint64_t hv = 1469598103934665603u ^ (uint64_t)info;
    if (info == SG_OK) {
        FUZZ_CHECK(w >= 1 && w <= MAX_SIDE && h >= 1 && h <= MAX_SIDE);
        sgResult r = sgReadImage2D(D->dev, im, R->buf, 0);
        hv ^= (uint64_t)r << 8;
        if (r == SG_OK) hv = fnv(hv, R->buf, (size_t)w * (size_t)h * 4);
    }
    D->logs = 0; /* these calls are not part of the sequence */
    digest(R, hv);
}

/* A handle of the kind `own`: one of this device's slots (live, stale or 0), one of the other
 * device's, a live id of another kind, or an id no device makes. */
static uint32_t pick(reader *r, const uint32_t *own, const uint32_t *other, const uint32_t *kind) {
    unsigned b = u8(r);
    switch (b >> 5) {
    case 5:
        return other[b & (SLOTS - 1)];
    case 6:
        return (b & 16) ? kind[b & (SLOTS - 1)] : 0;
    case 7:
        return (b & 16) ? 0xFFFFFFFFu : own[b & (SLOTS - 1)] ^ 0x4000u;
    default:
        return own[b & (SLOTS - 1)];
    }
}

static int side(reader *r) {
    static const int t[16] = {1, 2, 3, 4, 7, 8, 16, 17, 32, 33, 64, 0, -1, SG_MAX_IMAGE_SIZE + 1,
                              8, 16};
    return t[u8(r) & 15];
}

static void matrix(reader *r, float *m) {
    static const float persp[16] = {1.5f, 0, 0, 0, 0, 2, 0, 0, 0, 0, -1.2f, -2.2f, 0, 0, -1, 0};
    static const float ident[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    unsigned b = u8(r);
    switch (b & 3) {
    case 0:
        memcpy(m, ident, sizeof ident);
        break;
    case 1:
        memcpy(m, persp, sizeof persp);
        break;
    case 2:
        for (int k = 0; k < 16; k++) m[k] = f32(r);
        break;
    default:
        memcpy(m, (b & 4) ? persp : ident, sizeof persp);
        m[(b >> 3) & 15] = f32(r);
        break;
    }
    if ((b & 3) != 2 && (b & 0x80)) m[11] -= 3; /* move it in front of the eye */
}

/* Checks a call's result against the codes its documentation lists; returns whether it
 * succeeded. */
static int result(run *R, dev_state *D, int op, sgResult res, unsigned allowed) {
    if (R->trace && !R->replay)
        fprintf(stderr, "call %d, device %d: %s %s\n", op, D == &R->d[1], sgResultName(res),
                res != SG_OK ? sgGetLastError(D->dev) : "");
    if (!R->replay) {
        R->failed[op] = res != SG_OK;
        if (res != SG_OK) {
            if (!((unsigned)res < 32 && (allowed & BIT(res)))) {
                fprintf(stderr, "call %d: %s is not documented for it\n", op, sgResultName(res));
                FUZZ_CHECK(0);
            }
            FUZZ_CHECK(sgGetLastError(D->dev)[0] != '\0');
            FUZZ_CHECK(D->logs == 1);
        } else {
            FUZZ_CHECK(D->logs == 0);
        }
    } else if (res != SG_OK) {
        fprintf(stderr, "call %d failed (%s: %s) once the failed calls before it were left out\n",
                op, sgResultName(res), sgGetLastError(D->dev));
        FUZZ_CHECK(0);
    }
    D->logs = 0;
    return res == SG_OK;
}

static void one_run(run *R, const uint8_t *data, size_t size) {
    const int threads[2][2] = {{1, 2}, {3, 1}};
    for (int i = 0; i < 2; i++) {
        dev_state *D = &R->d[i];
        sgDeviceDesc dd = {.thread_count = threads[R->replay][i],
                           .image_pool_size = i ? 4 : 0,
                           .geom_pool_size = i ? 4 : 0,
                           .pipeline_pool_size = i ? 4 : 0,
                           .allocator = {fa_alloc, fa_free, &D->alloc},
                           .log = log_cb,
                           .log_user_data = D};
        FUZZ_CHECK(sgCreateDevice(&dd, &D->dev) == SG_OK);
        FUZZ_CHECK((void *)D->dev == (void *)D->alloc.block);
    }
    reader rd = {data, size, 0}, *r = &rd;
    memcpy(R->buf, R->pattern, sizeof R->buf);

    for (int op = 0; op < MAX_OPS && rd.at < rd.n; op++) {
        unsigned b = u8(r);
        int di = b & 1;
        dev_state *D = &R->d[di], *O = &R->d[!di];
        /* In the second run the calls that failed in the first are decoded (so the input stays
         * in step) but not made. */
        const int skip = R->replay && R->failed[op];
        sgResult res = SG_OK;
        unsigned allowed = 0;
        int s = (int)(u8(r) & (SLOTS - 1));
        switch ((b >> 1) % 12) {
        case 0: { /* create an image */
            sgImage2DDesc id = {.width = side(r), .height = side(r)};
            unsigned f = u8(r);
            id.format = (sgFormat)(f & 3);
            id.data = (f & 4) ? R->buf : NULL;
            sgImage2D h = {0x1234u};
            if (skip) break;
            res = sgCreateImage2D(D->dev, (f & 0xF0) == 0xF0 ? NULL : &id, &h);
            allowed = ALLOW_CREATE_IMAGE;
            if (res != SG_OK) FUZZ_CHECK(h.id == 0);
            if (result(R, D, op, res, allowed)) D->img[s] = h.id;
            continue;
        }
        case 1: { /* destroy an image: stale, foreign, a pass's target, sampled... */
            sgImage2D h = {pick(r, D->img, O->img, D->geom)};
            if (skip) break;
            res = sgDestroyImage2D(D->dev, h);
            allowed = ALLOW_DESTROY_IMAGE;
            break;
        }
        case 2: { /* upload or read */
            sgImage2D h = {pick(r, D->img, O->img, D->pso)};
            unsigned m = u8(r);
            int w = 0;
            sgImage2D probe = h;
            size_t pitch = 0;
            if ((m & 6) && sgGetImage2DInfo(D->dev, probe, &w, NULL, NULL) == SG_OK)
                pitch = (m & 2) ? (size_t)w * 4 + (m & 4 ? 3 : 0) : 1;
            D->logs = 0;
            if (skip) break;
            void *p = (m & 0x80) ? NULL : R->buf;
            res =
                (m & 1) ? sgReadImage2D(D->dev, h, p, pitch) : sgUploadImage2D(D->dev, h, p, pitch);
            allowed = ALLOW_TRANSFER;
            break;
        }
        case 3: { /* image info */
            sgImage2D h = {pick(r, D->img, O->img, D->geom)};
            if (skip) break;
            int w = -7, hh = -7;
            res = sgGetImage2DInfo(D->dev, h, &w, &hh, NULL);
            if (res != SG_OK) FUZZ_CHECK(w == -7 && hh == -7);
            allowed = ALLOW_INFO;
            break;
        }
        case 4: { /* create a geom */
            geom_data *g = &D->geoms[D->geom_next++];
            memset(g, 0, sizeof *g); /* the run's memset leaves the geoms out */
            unsigned m = u8(r), m2 = u8(r);
            int nv = 1 + (int)(u8(r) % MAX_VERTS);
            static const int counts[8] = {3, 6, 12, 24, 4, 8, 2, 0};
            int ni = counts[m2 & 7] * (1 + (int)((m2 >> 3) & 3));
            if ((m2 & 0xE0) == 0xE0) ni = (m2 & 16) ? -3 : 5;
            for (int v = 0; v < nv; v++) {
                for (int k = 0; k < 3; k++) g->pos[v * 4 + k] = f32(r);
                g->pos[v * 4 + 3] = (m & 0x40) ? f32(r) : 1;
                for (int k = 0; k < 4; k++) g->col[v * 4 + k] = (m & 2) ? f32(r) : 1;
                for (int k = 0; k < 2; k++) g->uv[v * 2 + k] = (m & 4) ? f32(r) : 0.5f;
                for (int k = 0; k < 3; k++) g->nrm[v * 3 + k] = (m & 8) ? f32(r) : 0;
            }
            for (int i = 0; i < (ni > 0 ? ni : 0); i++) {
                unsigned x = u8(r);
                g->idx[i] = x == 0xFF ? 0xFFFFFFFFu : x % (unsigned)(nv + (m & 0x80 ? 1 : 0));
            }
            sgGeomDesc gd = {.vertex_count = (m & 0x20) && (m2 & 1) ? 0 : nv,
                             .positions = (m & 1) || !(m & 0x10) ? g->pos : NULL,
                             .colors = (m & 2) ? g->col : NULL,
                             .texcoords = (m & 4) ? g->uv : NULL,
                             .normals = (m & 8) ? g->nrm : NULL,
                             .index_count = ni,
                             .indices = (m & 0x20) && (m2 & 2) ? NULL : g->idx,
                             .primitive = (sgPrimitive)(u8(r) % 5),
                             .storage = (sgStorage)(u8(r) % 4)};
            sgGeom h = {0x1234u};
            if (skip) break;
            res = sgCreateGeom(D->dev, &gd, &h);
            if (res != SG_OK) FUZZ_CHECK(h.id == 0);
            if (result(R, D, op, res, ALLOW_CREATE_GEOM)) D->geom[s] = h.id;
            continue;
        }
        case 5: { /* destroy a geom */
            sgGeom h = {pick(r, D->geom, O->geom, D->img)};
            if (skip) break;
            res = sgDestroyGeom(D->dev, h);
            allowed = ALLOW_DESTROY;
            break;
        }
        case 6: { /* create a pipeline */
            unsigned a = u8(r), c = u8(r), e = u8(r);
            sgPipelineDesc pd = {.shade = (sgShade)(a % 4),
                                 .filter = (sgFilter)((a >> 2) % 4),
                                 .wrap = (sgWrap)((a >> 4) % 4),
                                 .depth = {.compare = (sgCompare)(c % 10), .write = (c >> 4) & 1},
                                 .cull = (sgCull)((a >> 6) % 4),
                                 .front_face = (sgFrontFace)((c >> 5) % 4),
                                 .blend = (sgBlend)(e % 4),
                                 .lighting = (sgLightingMode)((e >> 2) % 6),
                                 .polygon_mode = (sgPolygonMode)((e >> 5) % 4)};
            if (e & 0x80) {
                pd.depth.bias_constant = f32(r);
                pd.depth.bias_slope = f32(r);
            }
            if (a % 4 == 3) { /* an invalid shade becomes a shader pipeline, valid or not */
                unsigned x = u8(r);
                pd.shade = (x & 0x80) ? SG_SHADE_TEXTURE_MODULATE : SG_SHADE_DEFAULT;
                if (!(x & 0x40)) pd.lighting = SG_LIGHTING_DEFAULT;
                pd.shader = (sgShaderDesc){(x & 1) ? NULL : fuzz_vs,
                                           (x & 2) ? NULL : fuzz_fs,
                                           (int)(u8(r) % 19) - 1,
                                           u8(r) & 0x3fu,
                                           (int)((x >> 2) % 4) - ((x & 0x20) ? 2 : 0),
                                           (x & 0x10) != 0,
                                           (x & 0x40) != 0};
                if ((x & 3) == 3) pd.shader.varying_count = 0;
            }
            sgPipelineStateObject h = {0x1234u};
            if (skip) break;
            res = sgCreatePipelineStateObject(D->dev, &pd, &h);
            if (res != SG_OK) FUZZ_CHECK(h.id == 0);
            if (result(R, D, op, res, ALLOW_CREATE_PSO)) D->pso[s] = h.id;
            continue;
        }
        case 7: { /* destroy a pipeline */
            sgPipelineStateObject h = {pick(r, D->pso, O->pso, D->geom)};
            if (skip) break;
            res = sgDestroyPipelineStateObject(D->dev, h);
            allowed = ALLOW_DESTROY;
            break;
        }
        case 8: { /* begin a pass */
            unsigned m = u8(r);
            sgPassDesc pd = {.color = {(m & 1) ? pick(r, D->img, O->img, D->geom) : 0},
                             .depth = {(m & 2) ? pick(r, D->img, O->img, D->geom) : 0},
                             .color_load = (sgLoadOp)((m >> 2) & 3),
                             .depth_load = (sgLoadOp)((m >> 4) & 3),
                             .depth_store = (sgStoreOp)((m >> 6) & 3)};
            unsigned v = u8(r);
            for (int k = 0; k < 4; k++) pd.clear_color[k] = (v & 1) ? f32(r) : 0.25f * (float)k;
            pd.clear_depth = (v & 2) ? f32(r) : 1;
            if (skip) break;
            res = sgBeginRenderPass(D->dev, (v & 0xFC) == 0xFC ? NULL : &pd);
            if (result(R, D, op, res, ALLOW_BEGIN)) D->pass = pd;
            continue;
        }
        case 9: { /* draw */
            unsigned m = u8(r), m2 = u8(r);
            sgPipelineStateObject p = {pick(r, D->pso, O->pso, D->img)};
            sgGeom g = {pick(r, D->geom, O->geom, D->pso)};
            sgDrawParams dp = {.sort = (sgSort)(m % 4)};
            matrix(r, dp.world_view);
            matrix(r, dp.proj);
            if (m & 4) dp.texture.id = pick(r, D->img, O->img, D->geom);
            sgColor color = {f32(r), f32(r), f32(r), f32(r)};
            if (m & 8) dp.color = &color;
            sgLighting li = {.ambient = {f32(r), f32(r), f32(r)}};
            if (m & 16) {
                li.light_count = (int)(u8(r) % 10);
                for (int k = 0; k < li.light_count && k < SG_MAX_LIGHTS; k++) {
                    sgLight *l = &li.lights[k];
                    l->type = (sgLightType)(u8(r) % 4);
                    for (int j = 0; j < 3; j++) {
                        l->direction[j] = f32(r);
                        l->position[j] = f32(r);
                        l->color[j] = f32(r);
                        l->attenuation[j] = (m2 & 1) ? f32(r) : 0;
                    }
                }
                dp.lighting = &li;
            }
            if (m & 32) {
                for (int k = 0; k < 3; k++) dp.specular[k] = f32(r);
                dp.shininess = f32(r) * 16;
            }
            sgShadow sh = {0};
            if (m & 64) {
                /* Often the open pass's own targets: the aliasing the draw must refuse. */
                unsigned a = u8(r);
                sh.map.id = a & 1   ? D->pass.depth.id
                            : a & 2 ? D->pass.color.id
                                    : pick(r, D->img, O->img, D->geom);
                matrix(r, sh.matrix);
                sh.light = (int)(u8(r) % 4) - 1;
                sh.pcf = (a >> 2) & 1;
                dp.shadow = &sh;
            }
            float uni[4] = {0};
            if (m2 & 2) { /* shader draws' bindings (refused on fixed pipelines) */
                unsigned x = u8(r);
                uni[0] = f32(r);
                dp.uniforms = (x & 1) ? NULL : uni;
                dp.uniform_size = (x & 2) ? (size_t)SG_MAX_UNIFORM_SIZE + 1 : sizeof uni;
                if (x & 4) dp.textures[0].id = pick(r, D->img, O->img, D->geom);
                if (x & 8) dp.textures[1].id = pick(r, D->img, O->img, D->geom);
                dp.instance_count = (int)((x >> 4) % 5) - 1;
            }
            if (skip) break;
            res = sgDraw(D->dev, p, g, (m2 & 0xF0) == 0xF0 ? NULL : &dp);
            allowed = ALLOW_DRAW;
            break;
        }
        case 10: { /* end the pass, with its targets or others */
            unsigned m = u8(r);
            sgPassDesc pd = D->pass;
            if (m & 1) pd.color.id = pick(r, D->img, O->img, D->geom);
            if (m & 2) pd.depth.id = 0;
            if (skip) break;
            res = sgEndRenderPass(D->dev, (m & 0xF0) == 0xF0 ? NULL : &pd);
            if (result(R, D, op, res, ALLOW_END)) {
                if (pd.color.id) digest_image(R, D, pd.color.id);
                if (pd.depth.id) digest_image(R, D, pd.depth.id);
            }
            continue;
        }
        default: { /* calls without a device: only their code, nothing logged */
            sgImage2D h = {D->img[s]};
            FUZZ_CHECK(sgDestroyImage2D(NULL, h) == SG_ERROR_NULL_POINTER);
            FUZZ_CHECK(sgBeginRenderPass(NULL, &D->pass) == SG_ERROR_NULL_POINTER);
            FUZZ_CHECK(sgEndRenderPass(NULL, &D->pass) == SG_ERROR_NULL_POINTER);
            FUZZ_CHECK(sgGetLastError(NULL)[0] != '\0');
            if (!R->replay) R->failed[op] = 0;
            continue;
        }
        }
        if (skip) continue;
        result(R, D, op, res, allowed);
    }
    /* Every image of both devices as the sequence left it; then teardown with whatever is
     * alive, a pass perhaps still open. */
    for (int i = 0; i < 2; i++)
        for (int s = 0; s < SLOTS; s++) digest_image(R, &R->d[i], R->d[i].img[s]);
    for (int i = 0; i < 2; i++) sgDestroyDevice(R->d[i].dev);
}

/* Zeros R but for each device's geom arrays (a megabyte), which a create zeros as it takes one. */
static void run_clear(run *R) {
    for (int i = 0; i < 2; i++) {
        dev_state *D = &R->d[i];
        memset(D, 0, offsetof(dev_state, geoms));
        memset((char *)D + offsetof(dev_state, geom_next), 0,
               sizeof *D - offsetof(dev_state, geom_next));
    }
    memset((char *)R + sizeof R->d, 0, sizeof *R - sizeof R->d);
}

int fuzz_api(const uint8_t *data, size_t size) {
    static run R; /* large: kept out of the stack; each input starts from zeros */
    run_clear(&R);
    R.trace = getenv("FUZZ_API_TRACE") != NULL;
    R.pattern = upload_pattern();
    one_run(&R, data, size);
    int first = R.ndigests;
    uint8_t failed[MAX_OPS];
    memcpy(failed, R.failed, sizeof failed);
    uint64_t digests[MAX_DIGESTS];
    memcpy(digests, R.digests, sizeof digests);
    run_clear(&R);
    R.replay = 1;
    R.pattern = upload_pattern();
    memcpy(R.failed, failed, sizeof failed);
    memcpy(R.digests, digests, sizeof digests);
    one_run(&R, data, size);
    FUZZ_CHECK(R.ndigests == first);
    return 0;
}

#ifndef FUZZ_REPLAY
int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    return fuzz_api(data, size);
}
#endif
