/* test_alloc_fail.c - every allocation point of a frame that uses every feature, made to fail.
 *
 * A script of public calls (textures, alpha blending with back-to-front sorting, flat, Gouraud and
 * Phong lighting, a depth-only shadow pass and a shadow-receiving draw, lines and wireframes, and
 * enough draws to grow every internal array) runs through the public allocator hook:
 *
 *   1. once unfailed: its allocations are counted (T) and its final image kept;
 *   2. for every N in 1..T, only allocation N fails: the call that made it must return
 *      SG_ERROR_OUT_OF_MEMORY with a message, the same call again must succeed, and the final
 *      image must be byte-identical to the unfailed run's;
 *   3. for every N in 1..T, every allocation from N on fails: the first failing call must return
 *      SG_ERROR_OUT_OF_MEMORY with a message, and destroying what was made, then the device, must
 *      leave no allocation outstanding.
 *
 * It prints T. A failed check prints the allocation number, the call and its line. */
#include <math.h>
#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <sgapi/sgapi.h>

#define W      96
#define H      64
#define SHADOW 128

enum { MODE_NONE, MODE_ONLY, MODE_FROM };

/* Atomic, so a count made from a raster thread would still be exact (none is made there today). */
typedef struct injector {
    atomic_long count; /* allocations asked for so far */
    atomic_long live;  /* allocations not yet freed */
    atomic_int failed; /* failures injected since the flag was last cleared */
    long fail_at;
    int mode;
} injector;

static void *inj_alloc(size_t size, void *user) {
    injector *in = user;
    long n = atomic_fetch_add(&in->count, 1) + 1;
    if ((in->mode == MODE_ONLY && n == in->fail_at) ||
        (in->mode == MODE_FROM && n >= in->fail_at)) {
        atomic_fetch_add(&in->failed, 1);
        return NULL;
    }
    void *p = aligned_alloc(16, (size + 15) & ~(size_t)15);
    if (p) atomic_fetch_add(&in->live, 1);
    return p;
}

static void inj_free(void *ptr, void *user) {
    injector *in = user;
    if (ptr) atomic_fetch_sub(&in->live, 1);
    free(ptr);
}

typedef struct log_rec {
    int count;
    sgResult last;
    char message[512];
} log_rec;

static void log_cb(sgResult result, const char *message, void *user) {
    log_rec *l = user;
    l->count++;
    l->last = result;
    snprintf(l->message, sizeof l->message, "%s", message ? message : "");
}

/* ---- meshes ---- */

typedef struct mesh {
    int nv, ni;
    float *pos, *col, *uv, *nrm;
    uint32_t *idx;
} mesh;

/* A UV sphere of radius 1 made of quads, with colours, texcoords and normals. */
static mesh sphere(int rings, int segs) {
    mesh m = {.nv = (rings + 1) * (segs + 1), .ni = rings * segs * 4};
    m.pos = malloc((size_t)m.nv * 4 * sizeof(float));
    m.col = malloc((size_t)m.nv * 4 * sizeof(float));
    m.uv = malloc((size_t)m.nv * 2 * sizeof(float));
    m.nrm = malloc((size_t)m.nv * 3 * sizeof(float));
    m.idx = malloc((size_t)m.ni * sizeof(uint32_t));
    if (!m.pos || !m.col || !m.uv || !m.nrm || !m.idx) abort();
    for (int r = 0, v = 0; r <= rings; r++)
        for (int s = 0; s <= segs; s++, v++) {
            float th = 3.14159265f * (float)r / (float)rings;
            float ph = 6.28318531f * (float)s / (float)segs;
            float n[3] = {sinf(th) * cosf(ph), cosf(th), sinf(th) * sinf(ph)};
            for (int k = 0; k < 3; k++) m.pos[v * 4 + k] = m.nrm[v * 3 + k] = n[k];
            m.pos[v * 4 + 3] = 1;
            m.col[v * 4 + 0] = 0.5f + 0.5f * n[0];
            m.col[v * 4 + 1] = 0.5f + 0.5f * n[1];
            m.col[v * 4 + 2] = 0.5f + 0.5f * n[2];
            m.col[v * 4 + 3] = 0.6f;
            m.uv[v * 2 + 0] = 2.0f * (float)s / (float)segs;
            m.uv[v * 2 + 1] = (float)r / (float)rings;
        }
    for (int r = 0, i = 0; r < rings; r++)
        for (int s = 0; s < segs; s++) {
            uint32_t a = (uint32_t)(r * (segs + 1) + s), b = a + (uint32_t)segs + 1;
            /* Counter-clockwise seen from outside. */
            m.idx[i++] = a;
            m.idx[i++] = a + 1;
            m.idx[i++] = b + 1;
            m.idx[i++] = b;
        }
    return m;
}

static void mesh_free(mesh *m) {
    free(m->pos);
    free(m->col);
    free(m->uv);
    free(m->nrm);
    free(m->idx);
}

/* ---- a shader pipeline: eight varyings (the triangles' extension), a texture, uniforms,
 * instances, and discarded fragments (bins redone in place) ---- */

static void shader_vs(sgVertexBatch *b, const void *uniforms) {
    const float *u = uniforms;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        float p[4], v[4];
        for (int r = 0; r < 4; r++)
            v[r] = b->world_view[r * 4] * b->position[0][i] +
                   b->world_view[r * 4 + 1] * b->position[1][i] +
                   b->world_view[r * 4 + 2] * b->position[2][i] + b->world_view[r * 4 + 3];
        v[0] += u[0] * (float)b->instance;
        for (int r = 0; r < 4; r++)
            p[r] = b->proj[r * 4] * v[0] + b->proj[r * 4 + 1] * v[1] + b->proj[r * 4 + 2] * v[2] +
                   b->proj[r * 4 + 3] * v[3];
        for (int r = 0; r < 4; r++) b->clip[r][i] = p[r];
        for (int k = 0; k < 8; k++)
            b->varying[k][i] = k < 3 ? b->normal[k][i] : b->texcoord[k & 1][i];
    }
}

static void shader_fs(sgFragmentBatch *b, const void *uniforms) {
    (void)uniforms;
    float rgba[4][SG_SHADER_LANES];
    sgSample(b, 0, b->varying[6], b->varying[7], rgba);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        for (int k = 0; k < 3; k++) b->color[k][i] = rgba[k][i] * (0.5f + 0.5f * b->varying[k][i]);
        b->color[3][i] = 1.0f;
        if ((b->x + b->y + i) % 3 == 0) b->discard |= 1u << i;
    }
}

/* ---- the script ---- */

typedef struct script {
    injector in;
    log_rec log;
    const mesh *ball, *big; /* big: enough triangles for the front end to run on all threads */
    int threads;
    sgDevice *dev;
    sgImage2D color, depth, tex, shadow_map, mip_tex;
    sgGeom ball_g, ref_g, floor_g, lines_g, tri_g, big_g;
    sgPipelineStateObject opaque, textured, blend, flat, gouraud, phong, wire, caster, line, shader,
        mipped;
    uint8_t image[W * H * 4];
    int failures;    /* checks that failed */
    int oom_seen;    /* calls that returned SG_ERROR_OUT_OF_MEMORY */
    int absorbed;    /* calls that succeeded although an allocation failed under them */
    int stopped;     /* the script stopped at a failed call */
    sgPassDesc open; /* the pass the script has open, if any (targets 0: none) */
    size_t limit;    /* sgDeviceDesc.bin_memory_limit: small, the passes flush (0: default) */
    int pass_failed; /* a draw failed after a flush rendered part of it: the frame is redone */
} script;

static void check(script *s, int ok, int line, const char *call, const char *what) {
    if (ok) return;
    s->failures++;
    fprintf(stderr, "mode %d, allocation %ld: line %d: %s: %s (last message: \"%s\")\n", s->in.mode,
            s->in.fail_at, line, call, what, s->log.message);
}

/* Runs a call. On SG_ERROR_OUT_OF_MEMORY with exactly one allocation failed since it began (the
 * only allowed failure), checks the message; under MODE_ONLY runs it again, which must succeed,
 * else stops the script. Any other failure is a broken check. */
#define DO(call)                                                                                   \
    do {                                                                                           \
        atomic_store(&s->in.failed, 0);                                                            \
        s->log.count = 0;                                                                          \
        sgResult r_ = (call);                                                                      \
        if (r_ == SG_OK) {                                                                         \
            /* Only an optional allocation may fail under a call that succeeds (a faster path      \
             * falls back to a slower one); the final image then proves nothing changed. */        \
            s->absorbed += atomic_load(&s->in.failed) != 0;                                        \
            break;                                                                                 \
        }                                                                                          \
        s->oom_seen++;                                                                             \
        check(s, r_ == SG_ERROR_OUT_OF_MEMORY, __LINE__, #call, sgResultName(r_));                 \
        check(s, atomic_load(&s->in.failed) >= 1, __LINE__, #call,                                 \
              "out of memory with no failed allocation");                                          \
        check(s, s->dev == NULL || sgGetLastError(s->dev)[0] != '\0', __LINE__, #call,             \
              "no message");                                                                       \
        check(s, s->log.count == 1 && s->log.message[0] != '\0', __LINE__, #call,                  \
              "not logged once with a message");                                                   \
        if (s->in.mode != MODE_ONLY || s->failures) {                                              \
            s->stopped = 1;                                                                        \
            return;                                                                                \
        }                                                                                          \
        if (s->dev && strstr(sgGetLastError(s->dev), "the pass can only end")) {                   \
            s->pass_failed = 1; /* part of the draw is in the targets: no retry, a new frame */    \
            return;                                                                                \
        }                                                                                          \
        r_ = (call);                                                                               \
        check(s, r_ == SG_OK, __LINE__, #call, "the retry failed");                                \
        if (r_ != SG_OK) {                                                                         \
            s->stopped = 1;                                                                        \
            return;                                                                                \
        }                                                                                          \
    } while (0)

static void translate(float *m, float sx, float x, float y, float z) {
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = sx;
    m[15] = 1;
    m[3] = x;
    m[7] = y;
    m[11] = z;
}

/* A perspective projection (OpenGL's glFrustum, near 1, far 20). */
static void perspective(float *m) {
    const float n = 1, f = 20, t = 0.5f, r = t * (float)W / (float)H;
    memset(m, 0, 16 * sizeof(float));
    m[0] = n / r;
    m[5] = n / t;
    m[10] = -(f + n) / (f - n);
    m[11] = -2 * f * n / (f - n);
    m[14] = -1;
}

/* The light looks along view-space -z from far in front: an orthographic box of the scene. */
static void light_ortho(float *m) {
    memset(m, 0, 16 * sizeof(float));
    m[0] = 1 / 4.0f;
    m[5] = 1 / 3.0f;
    m[10] = -2 / 20.0f; /* view z 0 .. -20 to -1 .. 1 */
    m[11] = -1;
    m[15] = 1;
}

static void frame(script *s, int frame_no) {
    sgLighting lights = {.ambient = {0.1f, 0.1f, 0.12f}, .light_count = 2};
    lights.lights[0] = (sgLight){
        .type = SG_LIGHT_DIRECTIONAL, .direction = {0.2f, -0.3f, -1}, .color = {0.8f, 0.8f, 0.7f}};
    lights.lights[1] = (sgLight){.type = SG_LIGHT_POINT,
                                 .position = {1, 2, -4},
                                 .color = {0.5f, 0.4f, 0.9f},
                                 .attenuation = {1, 0.1f, 0.02f}};
    sgShadow shadow = {.map = s->shadow_map, .light = 0, .pcf = frame_no == 0};
    light_ortho(shadow.matrix);

    /* The shadow pass: depth only, the casters seen from the light. */
    sgPassDesc sp = {.depth = s->shadow_map};
    DO(sgBeginRenderPass(s->dev, &sp));
    s->open = sp;
    for (int i = 0; i < 6; i++) {
        sgDrawParams dp = {0};
        translate(dp.world_view, 0.5f, -2.5f + (float)i, 0.5f, -6);
        light_ortho(dp.proj);
        DO(sgDraw(s->dev, s->caster, s->ball_g, &dp));
    }
    DO(sgEndRenderPass(s->dev, &sp));
    s->open = (sgPassDesc){0};

    /* With a small bin_memory_limit the depth is not stored: its flushes keep it in a scratch
     * image, one more allocation point. */
    sgPassDesc mp = {.color = s->color,
                     .depth = s->depth,
                     .clear_color = {0.1f, 0.2f, 0.3f, 1},
                     .depth_store = s->limit ? SG_STORE_DONT_CARE : SG_STORE_DEFAULT,
                     /* The third frame multisampled: its flushes keep the samples in buffers of
                      * the device, more allocation points. */
                     .samples = frame_no == 2 ? 4 : 1};
    DO(sgBeginRenderPass(s->dev, &mp));
    s->open = mp;
    sgDrawParams dp = {.texture = s->tex, .shadow = &shadow};
    perspective(dp.proj);
    translate(dp.world_view, 1, 0, 0, -7);
    DO(sgDraw(s->dev, s->textured, s->floor_g, &dp));
    dp.shadow = NULL;
    /* The floor again, mipmapped (trilinear) and blended over itself. */
    dp.texture = s->mip_tex;
    DO(sgDraw(s->dev, s->mipped, s->floor_g, &dp));
    dp.texture = s->tex;
    /* Lit balls in each mode, the Phong ones receiving the shadow; many draws grow the arrays. */
    const sgPipelineStateObject lit[3] = {s->flat, s->gouraud, s->phong};
    for (int i = 0; i < 24; i++) {
        sgDrawParams lp = {.lighting = &lights, .specular = {0.6f, 0.6f, 0.6f}, .shininess = 24};
        perspective(lp.proj);
        translate(lp.world_view, 0.35f, -2.6f + 0.45f * (float)(i % 12), i < 12 ? 1.3f : 0.9f,
                  -6 - 0.1f * (float)i);
        lp.shadow = i % 3 == 2 ? &shadow : NULL;
        DO(sgDraw(s->dev, lit[i % 3], i % 2 ? s->ref_g : s->ball_g, &lp));
    }
    const float su[2] = {0.8f, 0};
    sgDrawParams shp = {.uniforms = su, .uniform_size = sizeof su, .instance_count = 2};
    shp.textures[0] = s->tex;
    perspective(shp.proj);
    translate(shp.world_view, 0.4f, -2.4f, -1.6f, -5.5f);
    DO(sgDraw(s->dev, s->shader, s->ball_g, &shp));
    sgDrawParams op = {0};
    perspective(op.proj);
    translate(op.world_view, 0.6f, 2.2f, -1.2f, -5);
    DO(sgDraw(s->dev, s->opaque, s->tri_g, &op));
    translate(op.world_view, 0.5f, 2.3f, 0.9f, -6);
    DO(sgDraw(s->dev, s->opaque, s->big_g, &op));
    /* Wireframe and lines. */
    translate(op.world_view, 0.7f, -2.0f, -1.3f, -5);
    DO(sgDraw(s->dev, s->wire, s->ball_g, &op));
    translate(op.world_view, 1, 0, 0, -5);
    DO(sgDraw(s->dev, s->line, s->lines_g, &op));
    /* Transparent balls last, sorted back to front, one with a draw colour. */
    const sgColor tint = {1, 0.8f, 0.6f, 0.7f};
    for (int i = 0; i < 3; i++) {
        sgDrawParams bp = {.sort = SG_SORT_BACK_TO_FRONT, .color = i == 1 ? &tint : NULL};
        perspective(bp.proj);
        translate(bp.world_view, 0.6f, -1.5f + 1.5f * (float)i, -0.5f, -5.5f);
        DO(sgDraw(s->dev, s->blend, s->ball_g, &bp));
    }
    DO(sgEndRenderPass(s->dev, &mp));
    s->open = (sgPassDesc){0};
}

/* A frame, again after a pass failed: the pass must end with SG_ERROR_OUT_OF_MEMORY, and the
 * device then render the frame whole. */
static void frame_checked(script *s, int frame_no) {
    frame(s, frame_no);
    if (!s->pass_failed) return;
    s->pass_failed = 0;
    sgResult r = sgEndRenderPass(s->dev, &s->open);
    check(s, r == SG_ERROR_OUT_OF_MEMORY, __LINE__, "sgEndRenderPass",
          "a failed pass did not fail");
    s->open = (sgPassDesc){0};
    if (!s->failures) frame(s, frame_no);
    check(s, !s->pass_failed, __LINE__, "frame", "failed again");
}

static void run(script *s) {
    sgDeviceDesc dd = {.thread_count = s->threads,
                       .bin_memory_limit = s->limit,
                       .allocator = {inj_alloc, inj_free, &s->in},
                       .log = log_cb,
                       .log_user_data = &s->log};
    DO(sgCreateDevice(&dd, &s->dev));
    const sgImage2DDesc cd = {.width = W, .height = H, .format = SG_FORMAT_RGBA8_UNORM};
    const sgImage2DDesc zd = {.width = W, .height = H, .format = SG_FORMAT_D32_FLOAT};
    const sgImage2DDesc md = {.width = SHADOW, .height = SHADOW, .format = SG_FORMAT_D32_FLOAT};
    uint8_t texels[8 * 8 * 4];
    for (int i = 0; i < 64; i++) {
        int on = ((i & 7) + (i >> 3)) & 1;
        texels[i * 4 + 0] = on ? 230 : 40;
        texels[i * 4 + 1] = on ? 200 : 90;
        texels[i * 4 + 2] = (uint8_t)(i * 4);
        texels[i * 4 + 3] = on ? 255 : 128;
    }
    const sgImage2DDesc td = {
        .width = 8, .height = 8, .format = SG_FORMAT_RGBA8_UNORM, .data = texels};
    DO(sgCreateImage2D(s->dev, &cd, &s->color));
    DO(sgCreateImage2D(s->dev, &zd, &s->depth));
    DO(sgCreateImage2D(s->dev, &td, &s->tex));
    DO(sgCreateImage2D(s->dev, &md, &s->shadow_map));
    /* A mipmapped texture: its levels in the allocation of level 0, made again by an upload. */
    sgImage2DDesc mtd = td;
    mtd.mip_levels = SG_MIP_LEVELS_ALL;
    DO(sgCreateImage2D(s->dev, &mtd, &s->mip_tex));
    DO(sgUploadImage2D(s->dev, s->mip_tex, texels, 0));

    const mesh *b = s->ball;
    const sgGeomDesc bd = {.vertex_count = b->nv,
                           .positions = b->pos,
                           .colors = b->col,
                           .texcoords = b->uv,
                           .normals = b->nrm,
                           .index_count = b->ni,
                           .indices = b->idx,
                           .primitive = SG_PRIMITIVE_QUADS};
    DO(sgCreateGeom(s->dev, &bd, &s->ball_g));
    sgGeomDesc gd = bd;
    gd.vertex_count = s->big->nv;
    gd.positions = s->big->pos;
    gd.colors = s->big->col;
    gd.texcoords = s->big->uv;
    gd.normals = s->big->nrm;
    gd.index_count = s->big->ni;
    gd.indices = s->big->idx;
    DO(sgCreateGeom(s->dev, &gd, &s->big_g));
    sgGeomDesc rd = bd;
    rd.storage = SG_STORAGE_REFERENCE;
    DO(sgCreateGeom(s->dev, &rd, &s->ref_g));
    static const float fpos[] = {-4, -2, 1, 1, 4, -2, 1, 1, 4, -2, -6, 1, -4, -2, -6, 1};
    static const float fuv[] = {0, 0, 3, 0, 3, 3, 0, 3};
    static const uint32_t fidx[] = {0, 1, 2, 0, 2, 3};
    const sgGeomDesc fd = {
        .vertex_count = 4, .positions = fpos, .texcoords = fuv, .index_count = 6, .indices = fidx};
    DO(sgCreateGeom(s->dev, &fd, &s->floor_g));
    /* A star of lines: 16 segments from the centre, two of them reaching past the near plane. */
    float lpos[17 * 4], lcol[17 * 4];
    uint32_t lidx[32];
    for (int i = 0; i <= 16; i++) {
        float a = 0.3927f * (float)i, r = i ? 2.5f : 0;
        lpos[i * 4 + 0] = r * cosf(a);
        lpos[i * 4 + 1] = r * sinf(a);
        lpos[i * 4 + 2] = i == 3 || i == 9 ? 8.0f : 0.0f;
        lpos[i * 4 + 3] = 1;
        for (int k = 0; k < 4; k++) lcol[i * 4 + k] = k == 3 ? 1 : (float)((i + k) % 3) * 0.5f;
        if (i) {
            lidx[(i - 1) * 2] = 0;
            lidx[(i - 1) * 2 + 1] = (uint32_t)i;
        }
    }
    const sgGeomDesc ld = {.vertex_count = 17,
                           .positions = lpos,
                           .colors = lcol,
                           .index_count = 32,
                           .indices = lidx,
                           .primitive = SG_PRIMITIVE_LINES};
    DO(sgCreateGeom(s->dev, &ld, &s->lines_g));
    static const float tpos[] = {-1, -1, 0, 1, 1, -1, 0, 1, 0, 1, 0, 1};
    static const uint32_t tidx[] = {0, 1, 2};
    const sgGeomDesc trd = {
        .vertex_count = 3, .positions = tpos, .index_count = 3, .indices = tidx};
    DO(sgCreateGeom(s->dev, &trd, &s->tri_g));

    const sgPipelineDesc depth_on = {.depth = {.compare = SG_COMPARE_LESS, .write = true},
                                     .cull = SG_CULL_BACK};
    sgPipelineDesc pd = depth_on;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->opaque));
    pd = depth_on;
    pd.shade = SG_SHADE_TEXTURE_MODULATE;
    pd.filter = SG_FILTER_BILINEAR;
    pd.cull = SG_CULL_NONE;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->textured));
    pd.mipmap = SG_MIPMAP_LINEAR;
    pd.filter = SG_FILTER_BILINEAR;
    pd.blend = SG_BLEND_ALPHA;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->mipped));
    pd = (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS_EQUAL}, .blend = SG_BLEND_ALPHA};
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->blend));
    pd = depth_on;
    pd.lighting = SG_LIGHTING_FLAT;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->flat));
    pd.lighting = SG_LIGHTING_GOURAUD;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->gouraud));
    pd.lighting = SG_LIGHTING_PHONG;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->phong));
    pd = depth_on;
    pd.polygon_mode = SG_POLYGON_MODE_LINE;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->wire));
    pd = depth_on;
    pd.depth.bias_constant = 0.002f;
    pd.depth.bias_slope = 1.5f;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->caster));
    pd = (sgPipelineDesc){.depth = {.compare = SG_COMPARE_LESS_EQUAL}};
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->line));
    pd = depth_on;
    pd.shader = (sgShaderDesc){shader_vs, shader_fs, 8, 0, 1, false, false};
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->shader));

    /* Three frames (the third with 4 samples a pixel): the second draws into the arrays the first
     * grew. In between, a geom and a pipeline are destroyed and made again (a slot reused). */
    frame_checked(s, 0);
    if (s->stopped) return;
    DO(sgDestroyGeom(s->dev, s->tri_g));
    s->tri_g.id = 0;
    DO(sgDestroyPipelineStateObject(s->dev, s->opaque));
    s->opaque.id = 0;
    DO(sgCreateGeom(s->dev, &trd, &s->tri_g));
    pd = depth_on;
    DO(sgCreatePipelineStateObject(s->dev, &pd, &s->opaque));
    frame_checked(s, 1);
    if (s->stopped) return;
    frame_checked(s, 2);
    if (s->stopped) return;
    DO(sgReadImage2D(s->dev, s->color, s->image, 0));
}

/* Destroys every object made, each call checked, then the device. */
static void teardown(script *s) {
    if (!s->dev) return;
    /* Targets of an open pass cannot be destroyed: the pass is ended first, which allocates
     * nothing. */
    /* A pass a draw failed after a flush ends with SG_ERROR_OUT_OF_MEMORY, closed all the same. */
    if (s->open.color.id || s->open.depth.id) {
        sgResult r = sgEndRenderPass(s->dev, &s->open);
        if (r != SG_OK &&
            !(r == SG_ERROR_OUT_OF_MEMORY && strstr(sgGetLastError(s->dev), "The pass is closed")))
            check(s, 0, __LINE__, "sgEndRenderPass", sgGetLastError(s->dev));
    }
    const sgImage2D im[] = {s->color, s->depth, s->tex, s->shadow_map, s->mip_tex};
    for (size_t i = 0; i < sizeof im / sizeof *im; i++)
        if (im[i].id && sgDestroyImage2D(s->dev, im[i]) != SG_OK)
            check(s, 0, __LINE__, "sgDestroyImage2D", sgGetLastError(s->dev));
    const sgGeom g[] = {s->ball_g, s->ref_g, s->floor_g, s->lines_g, s->tri_g, s->big_g};
    for (size_t i = 0; i < sizeof g / sizeof *g; i++)
        if (g[i].id && sgDestroyGeom(s->dev, g[i]) != SG_OK)
            check(s, 0, __LINE__, "sgDestroyGeom", sgGetLastError(s->dev));
    const sgPipelineStateObject p[] = {s->opaque,  s->textured, s->blend, s->flat,
                                       s->gouraud, s->phong,    s->wire,  s->caster,
                                       s->line,    s->shader,   s->mipped};
    for (size_t i = 0; i < sizeof p / sizeof *p; i++)
        if (p[i].id && sgDestroyPipelineStateObject(s->dev, p[i]) != SG_OK)
            check(s, 0, __LINE__, "sgDestroyPipelineStateObject", sgGetLastError(s->dev));
    sgDestroyDevice(s->dev);
    s->dev = NULL;
}

/* One run of the script with the given failure; returns its failed checks. */
static int attempt(const mesh *ball, const mesh *big, int threads, size_t limit, int mode,
                   long fail_at, long *allocations, uint8_t *image, const uint8_t *expect,
                   int *absorbed) {
    script *s = calloc(1, sizeof *s);
    if (!s) abort();
    s->ball = ball;
    s->big = big;
    s->threads = threads;
    s->limit = limit;
    s->in.mode = mode;
    s->in.fail_at = fail_at;
    run(s);
    teardown(s);
    long live = atomic_load(&s->in.live);
    if (live) check(s, 0, __LINE__, "teardown", "allocations outstanding after sgDestroyDevice");
    if (mode == MODE_ONLY && !s->failures) {
        check(s, s->oom_seen + s->absorbed == 1, __LINE__, "script",
              "not exactly one call met the failed allocation");
        check(s, memcmp(s->image, expect, sizeof s->image) == 0, __LINE__, "script",
              "the final image differs from the unfailed run's");
    }
    if (mode == MODE_FROM && !s->failures)
        check(s, s->oom_seen == 1 || s->absorbed, __LINE__, "script",
              "no call met the failed allocations");
    if (allocations) *allocations = atomic_load(&s->in.count);
    if (image) memcpy(image, s->image, sizeof s->image);
    if (absorbed) *absorbed += s->absorbed != 0;
    int failures = s->failures;
    free(s);
    return failures;
}

/* The whole check at one bin_memory_limit; returns non-zero on failure. */
static int check_all(const mesh *ball, const mesh *big, int threads, size_t limit,
                     const char *ppm) {
    static uint8_t expect[W * H * 4];
    long total = 0;
    int failures = attempt(ball, big, threads, limit, MODE_NONE, 0, &total, expect, NULL, NULL);
    if (failures) {
        fprintf(stderr, "the unfailed run failed\n");
        return 1;
    }
    /* The image must show something: not all clear colour. */
    int differ = 0;
    for (int i = 0; i < W * H; i++) differ += memcmp(&expect[i * 4], &expect[0], 4) != 0;
    if (differ < W * H / 4) {
        fprintf(stderr, "the script drew almost nothing (%d pixels)\n", differ);
        return 1;
    }
    if (ppm) { /* write the image as a binary PPM, to look at */
        FILE *f = fopen(ppm, "wb");
        if (f) {
            fprintf(f, "P6\n%d %d\n255\n", W, H);
            for (int i = 0; i < W * H; i++) fwrite(&expect[i * 4], 1, 3, f);
            fclose(f);
        }
    }
    /* Everything must be deterministic: a second unfailed run asks for the same allocations. */
    long again = 0;
    failures += attempt(ball, big, threads, limit, MODE_NONE, 0, &again, NULL, NULL, NULL);
    if (again != total) {
        fprintf(stderr, "the unfailed runs made %ld and %ld allocations\n", total, again);
        return 1;
    }
    int bad_only = 0, bad_from = 0, absorbed = 0;
    for (long n = 1; n <= total; n++) {
        bad_only +=
            attempt(ball, big, threads, limit, MODE_ONLY, n, NULL, NULL, expect, &absorbed) != 0;
        bad_from += attempt(ball, big, threads, limit, MODE_FROM, n, NULL, NULL, NULL, NULL) != 0;
    }
    printf("bin_memory_limit %zu: %ld allocation points at %d threads; only-N failing: %ld "
           "passed, %d failed (%d of them optional: the call succeeded on a slower path, same "
           "image); N-onwards failing: %ld passed, %d failed\n",
           limit, total, threads, total - bad_only, bad_only, absorbed, total - bad_from, bad_from);
    return failures || bad_only || bad_from;
}

int main(int argc, char **argv) {
    /* Default 3 threads: the device's worker array is one of the allocation points. */
    int threads = argc > 1 ? atoi(argv[1]) : 3;
    mesh ball = sphere(10, 16), big = sphere(48, 48);
    /* The default budget, then one that flushes several times a pass (and inside draws). */
    int bad = check_all(&ball, &big, threads, 0, argc > 2 ? argv[2] : NULL);
    bad |= check_all(&ball, &big, threads, 24 << 10, NULL);
    mesh_free(&ball);
    mesh_free(&big);
    return bad ? 1 : 0;
}
