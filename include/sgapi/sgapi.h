/* sgapi.h - a small, explicit graphics API whose whole pipeline runs on the CPU.
 *
 * Objects
 *   sgDevice              owns everything; create one per thread that draws.
 *   sgImage2D             RGBA8 texture / colour target, or D32 float depth target.
 *   sgGeom                vertex arrays + 32-bit indices (triangles or quads).
 *   sgPipelineStateObject immutable state, validated once at creation.
 *
 * Frame
 *   sgBeginRenderPass(dev, &pass);
 *   sgDraw(dev, pso, geom, &params); ...
 *   sgEndRenderPass(dev, &pass);
 *
 * Conventions
 *   - Descriptors are zero-initialised structs: every field left at 0 takes the documented default.
 *   - Every call returns an sgResult. On failure nothing is changed but a create call's out-handle,
 *     which is zeroed, and sgGetLastError() returns a readable message (the device's log callback,
 *     if set, receives it too). A call given a NULL device can only return its code; a failed
 *     sgCreateDevice reports its message to the desc's log callback.
 *   - Vertex data and matrices may hold NaN or infinity: a triangle that meets one is not drawn,
 *     and nothing else is affected. Texcoords under repeat wrapping keep full precision however
 *     far from 0 they are.
 *   - Matrices are 16 floats, row-major: m[0..3] is the first row. Positions are column vectors:
 *     clip = proj * worldView * position.
 *   - Clip space is OpenGL's: x, y, z in [-w, w]; NDC y = +1 is the top row of the colour target,
 *     NDC z = -1 maps to depth 0 and z = +1 to depth 1.
 *   - Pixel data is uploaded and read back top row first. A texture coordinate t = 0 addresses the
 *     bottom row (the last uploaded row), as in OpenGL.
 */
#ifndef SGAPI_H
#define SGAPI_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

#define SGAPI_VERSION_MAJOR 0
#define SGAPI_VERSION_MINOR 1

/* Public functions are the only symbols the shared library exports. */
#if defined(SGAPI_BUILDING) && defined(__GNUC__)
#define SGAPI_API __attribute__((visibility("default")))
#else
#define SGAPI_API
#endif

/* Largest supported image side; the fixed-point setup is proven not to overflow up to this size. */
#define SG_MAX_IMAGE_SIZE 16384

/* Programmable stages (sgShaderDesc): lanes of a batch, varyings a vertex passes on, vertex
 * attributes a geom may add, textures and uniform bytes a draw may bind. */
#define SG_SHADER_LANES      16
#define SG_MAX_VARYINGS      16
#define SG_MAX_ATTRIBUTES    4
#define SG_MAX_DRAW_TEXTURES 8
#define SG_MAX_UNIFORM_SIZE  65536
/* The batches' lane arrays start on 64-byte lines, so that 16 lanes are one aligned vector (a
 * vector split across two lines cannot be forwarded from the store that wrote it). */
#if defined(__cplusplus)
#define SG_LANES_ALIGNED alignas(64)
#else
#define SG_LANES_ALIGNED _Alignas(64)
#endif

typedef enum sgResult {
    SG_OK = 0,
    SG_ERROR_NULL_POINTER,       /* a required pointer argument or descriptor field is NULL */
    SG_ERROR_INVALID_ENUM,       /* an enum field holds an unknown value */
    SG_ERROR_INVALID_HANDLE,     /* zero, destroyed, of another kind, or of another device */
    SG_ERROR_INVALID_VALUE,      /* a clear value or colour is outside [0, 1] or NaN */
    SG_ERROR_INVALID_SIZE,       /* image side outside 1..SG_MAX_IMAGE_SIZE, sizes differ, or a row
                                    pitch shorter than a row */
    SG_ERROR_INVALID_COUNT,      /* a count below 1, an index count not a multiple of the
                                    primitive size, a pool size above 65535, thread_count < 0 */
    SG_ERROR_INDEX_OUT_OF_RANGE, /* an index is >= the vertex count */
    SG_ERROR_NOT_IN_PASS,        /* sgDraw / sgEndRenderPass outside a render pass */
    SG_ERROR_ALREADY_IN_PASS,    /* sgBeginRenderPass inside a render pass */
    SG_ERROR_PASS_MISMATCH,      /* sgEndRenderPass names other targets than sgBeginRenderPass */
    SG_ERROR_FORMAT_MISMATCH,    /* image has the wrong format for this use */
    SG_ERROR_NOT_SAMPLEABLE,     /* bound texture's format cannot be sampled */
    SG_ERROR_MISSING_ATTRIBUTE,  /* the pipeline reads a vertex attribute the geom does not have */
    SG_ERROR_MISSING_TEXTURE,    /* the pipeline samples a texture but none is bound */
    SG_ERROR_MISSING_DEPTH,      /* the pipeline uses depth but the pass has no depth target */
    SG_ERROR_IN_USE,             /* the image is a target of the open pass */
    SG_ERROR_UNSUPPORTED,        /* a valid state this version does not implement yet */
    SG_ERROR_POOL_EXHAUSTED,     /* no free slot of that object kind (see sgDeviceDesc) */
    SG_ERROR_OUT_OF_MEMORY,      /* the allocator returned NULL */
    SG_RESULT_COUNT
} sgResult;

/* Handles: a 32-bit id (slot, kind and generation). 0 is never valid. An id of another kind is
 * always refused; a stale id is refused until its slot has been reused 16383 times (the generation
 * then wraps); an id of another device is refused unless its generation happens to coincide
 * (1 chance in 16383). */
typedef struct sgImage2D {
    uint32_t id;
} sgImage2D;
typedef struct sgGeom {
    uint32_t id;
} sgGeom;
typedef struct sgPipelineStateObject {
    uint32_t id;
} sgPipelineStateObject;

typedef struct sgDevice sgDevice;

/* ---- device ------------------------------------------------------------------------------------
 */

typedef struct sgAllocator {
    void *(*alloc)(size_t size, void *user_data); /* must return memory aligned to 16 bytes */
    void (*free)(void *ptr, void *user_data);
    void *user_data;
} sgAllocator;

/* Instruction set of the raster. All give the same images, byte for byte. */
typedef enum sgSimd {
    SG_SIMD_DEFAULT = 0, /* the best this CPU runs */
    SG_SIMD_SCALAR,      /* portable C, the reference the others are tested against */
    SG_SIMD_SSE2,        /* x86-64 baseline */
    SG_SIMD_AVX2,        /* x86-64 with AVX2 */
    SG_SIMD_AVX512,      /* x86-64 with AVX-512 F/BW/VL/DQ */
    SG_SIMD_NEON,        /* 64-bit ARM (AArch64) Advanced SIMD, in every ARMv8-A CPU */
} sgSimd;

typedef struct sgDeviceDesc {
    int thread_count;       /* raster threads, the caller included; 0: all cores */
    sgSimd simd;            /* 0: the best this CPU runs; a set it lacks is SG_ERROR_UNSUPPORTED */
    int image_pool_size;    /* 0: 256; at most 65535 */
    int geom_pool_size;     /* 0: 1024; at most 65535 */
    int pipeline_pool_size; /* 0: 64; at most 65535 */
    sgAllocator allocator;  /* both NULL: malloc / free */
    /* Optional: called with every error as it happens. */
    void (*log)(sgResult result, const char *message, void *user_data);
    void *log_user_data;
    /* Bytes of a pass's binned work (set-up triangles and their bin lists) before what is binned
     * is rendered and the pass goes on, same image; 0: SG_DEFAULT_BIN_MEMORY_LIMIT. Less than one
     * triangle's records is SG_ERROR_INVALID_VALUE. A pass may render its binned work sooner
     * (same image): a device first bins 32 bytes a target pixel (at least 32 MiB), and up to
     * this limit once a pass had to flush. */
    size_t bin_memory_limit;
} sgDeviceDesc;

/* The default sgDeviceDesc.bin_memory_limit: 256 MiB. */
#define SG_DEFAULT_BIN_MEMORY_LIMIT ((size_t)256 << 20)

/** Creates a device; desc may be NULL for all defaults. */
SGAPI_API sgResult sgCreateDevice(const sgDeviceDesc *desc, sgDevice **out_device);
/** Destroys a device and every object it still owns. NULL is a no-op. */
SGAPI_API void sgDestroyDevice(sgDevice *device);
/** The message of the last failed call on this device ("" if none). Valid until the next call. */
SGAPI_API const char *sgGetLastError(const sgDevice *device);
/** A short fixed name for a result code, e.g. "SG_ERROR_INVALID_HANDLE". */
SGAPI_API const char *sgResultName(sgResult result);

/* ---- images ------------------------------------------------------------------------------------
 */

typedef enum sgFormat {
    SG_FORMAT_RGBA8_UNORM = 1, /* 4 bytes a pixel: R, G, B, A. Texture or colour target. */
    SG_FORMAT_D32_FLOAT,       /* one float a pixel. Depth target only. */
} sgFormat;

typedef struct sgImage2DDesc {
    int width, height; /* 1 .. SG_MAX_IMAGE_SIZE */
    sgFormat format;   /* required */
    /* Optional initial contents, top row first; row pitch = width * pixel size. NULL: zeros. */
    const void *data;
    /* Mipmap levels (docs/api.md, "Mipmaps"): 0 or 1, one level; SG_MIP_LEVELS_ALL, the chain down
     * to 1 x 1; n, the first n levels of that chain. Level k is max(1, width >> k) x
     * max(1, height >> k); creating and uploading fill level 0 and make the others from it with
     * a 2 x 2 box filter. RGBA8 only; negative or longer than the chain: SG_ERROR_INVALID_COUNT. */
    int mip_levels;
} sgImage2DDesc;

/* sgImage2DDesc.mip_levels: every level down to 1 x 1. */
#define SG_MIP_LEVELS_ALL 0x7fffffff
/* Most levels an image has (a side of SG_MAX_IMAGE_SIZE). */
#define SG_MAX_MIP_LEVELS 15

/** Creates a 2D image; its storage is owned by the device. */
SGAPI_API sgResult sgCreateImage2D(sgDevice *device, const sgImage2DDesc *desc,
                                   sgImage2D *out_image);
/** Destroys an image. Fails with SG_ERROR_IN_USE while it is a target of the open pass. */
SGAPI_API sgResult sgDestroyImage2D(sgDevice *device, sgImage2D image);
/** Replaces all pixels, top row first; row_pitch 0 means tightly packed. */
SGAPI_API sgResult sgUploadImage2D(sgDevice *device, sgImage2D image, const void *data,
                                   size_t row_pitch);
/** Copies all pixels out, top row first; row_pitch 0 means tightly packed. */
SGAPI_API sgResult sgReadImage2D(sgDevice *device, sgImage2D image, void *dst, size_t row_pitch);
/** Reports how many mipmap levels an image has (1 when it has none but level 0). */
SGAPI_API sgResult sgGetImage2DLevels(sgDevice *device, sgImage2D image, int *levels);
/** Reports an image's size and format; any out pointer may be NULL. */
SGAPI_API sgResult sgGetImage2DInfo(sgDevice *device, sgImage2D image, int *width, int *height,
                                    sgFormat *format);

/* ---- geometry ----------------------------------------------------------------------------------
 */

typedef enum sgPrimitive {
    SG_PRIMITIVE_DEFAULT = 0, /* triangles */
    SG_PRIMITIVE_TRIANGLES,   /* 3 indices each */
    SG_PRIMITIVE_QUADS,       /* 4 indices each (a b c d), drawn as triangles a b c and a c d */
    SG_PRIMITIVE_LINES, /* 2 indices each: a line list, segment a -> b (docs/api.md, "Lines") */
} sgPrimitive;

typedef enum sgStorage {
    SG_STORAGE_DEFAULT = 0, /* copy */
    SG_STORAGE_COPY,      /* the arrays are copied at creation; the caller may free them at once */
    SG_STORAGE_REFERENCE, /* the arrays are used in place: the caller keeps them alive and unchanged
                             until sgDestroyGeom (indices are validated once, at creation) */
} sgStorage;

typedef struct sgGeomDesc {
    int vertex_count;       /* >= 1 */
    const float *positions; /* required: vertex_count * 4 floats (x, y, z, w) */
    const float *colors;    /* optional: vertex_count * 4 floats (r, g, b, a); NULL: opaque white */
    const float *texcoords; /* optional: vertex_count * 2 floats (s, t) */
    const float *normals; /* optional: vertex_count * 3 floats (x, y, z), object space; read by lit
                             pipelines (SG_LIGHTING_GOURAUD and _PHONG require them) */
    /* Optional: vertex_count * 4 floats each, read only by a shader's vertex stage
     * (sgVertexBatch.attribute; 0 where NULL). */
    const float *attributes[SG_MAX_ATTRIBUTES];
    int index_count;         /* >= 1, a multiple of 3 (triangles), 4 (quads) or 2 (lines) */
    const uint32_t *indices; /* required: each < vertex_count */
    sgPrimitive primitive;
    sgStorage storage;
} sgGeomDesc;

/** Creates a geom, validating every index against vertex_count. */
SGAPI_API sgResult sgCreateGeom(sgDevice *device, const sgGeomDesc *desc, sgGeom *out_geom);
/** Destroys a geom (and its copies of the arrays, if it made them). */
SGAPI_API sgResult sgDestroyGeom(sgDevice *device, sgGeom geom);

/* ---- programmable stages (docs/api.md, "Shaders") -----------------------------------------------
 *
 * A pipeline may run C functions of its own instead of the fixed shading: a vertex stage called
 * on batches of up to SG_SHADER_LANES vertices, and a fragment stage called on whole 4 x 4 tiles,
 * each value an array of 16 lanes (structure of arrays: lane i of x is x[i]), so that a loop over
 * the lanes vectorises. Shading stays visibility first: an opaque fragment stage that discards
 * nothing runs once per visible pixel. */

/* The vertex stage's batch: up to 16 vertices of a draw's geom. */
typedef struct sgVertexBatch {
    /* in */
    int count;    /* lanes in use, 1..16; lanes past it copy lane 0 */
    int instance; /* 0 .. instance_count - 1 */
    SG_LANES_ALIGNED uint32_t index[SG_SHADER_LANES]; /* the vertices' indices in the geom */
    float position[4][SG_SHADER_LANES];               /* x, y, z, w as given */
    float color[4][SG_SHADER_LANES];    /* r, g, b, a; 1 when the geom has no colours */
    float normal[3][SG_SHADER_LANES];   /* object space; 0 when the geom has none */
    float texcoord[2][SG_SHADER_LANES]; /* s, t; 0 when the geom has none */
    float attribute[SG_MAX_ATTRIBUTES][4][SG_SHADER_LANES]; /* sgGeomDesc.attributes; 0 absent */
    const float *world_view, *proj; /* the draw's matrices, 16 floats each, row-major */
    /* out */
    SG_LANES_ALIGNED float clip[4][SG_SHADER_LANES]; /* clip space, OpenGL's (as proj gives) */
    float varying[SG_MAX_VARYINGS][SG_SHADER_LANES]; /* the first varying_count are interpolated */
} sgVertexBatch;

/* The fragment stage's batch: one whole 4 x 4 tile of a triangle (or line). */
typedef struct sgFragmentBatch {
    /* in */
    uint32_t mask; /* bit i: lane i is a fragment to shade */
    int x, y;      /* lane i is pixel (x + i % 4, y + i / 4), rows from the top */
    SG_LANES_ALIGNED float z[SG_SHADER_LANES]; /* window depth, 0 near .. 1 far */
    bool front_facing; /* the triangle faces the viewer (sgPipelineDesc.front_face); lines:
                          true */
    int primitive;     /* index of the triangle or line in the draw */
    int instance;      /* 0 .. instance_count - 1 */
    /* Perspective-correct at each lane's pixel centre (+0.5), the lanes outside mask too (as a
     * GPU's helper lanes, so that differences between neighbours are defined); flat varyings
     * hold the triangle's first vertex's value exactly. */
    SG_LANES_ALIGNED float varying[SG_MAX_VARYINGS][SG_SHADER_LANES];
    /* out */
    float color[4][SG_SHADER_LANES]; /* r, g, b, a: clamped to [0, 1], NaN written as 0 */
    uint32_t discard;                /* lanes that write nothing, depth included */
    /* sgapi's own: what sgSample reads (the draw's textures). Not to be changed. */
    const void *internal;
} sgFragmentBatch;

/* A pipeline's programmable stages (sgPipelineDesc.shader). Both functions or neither. */
typedef struct sgShaderDesc {
    /* Writes clip (and the varyings) of b->count lanes; uniforms: the draw's copy. */
    void (*vertex)(sgVertexBatch *b, const void *uniforms);
    /* Writes color (and discard) of the lanes in b->mask. */
    void (*fragment)(sgFragmentBatch *b, const void *uniforms);
    int varying_count;      /* 0 .. SG_MAX_VARYINGS */
    uint32_t flat_varyings; /* bit k: varying k is not interpolated (the first vertex's value) */
    int texture_count;      /* 0 .. SG_MAX_DRAW_TEXTURES: the draw binds at least that many */
    /* true: the fragment stage computes each lane from that lane's inputs alone (no 2 x 2
     * differences, no neighbour's values) and reads neither primitive nor instance. sgapi may
     * then shade the pixels that several triangles of the draw leave in one tile in one batch,
     * each lane interpolated from its own triangle (not with mipmaps, whose levels come from
     * 2 x 2 differences). false (default): a batch is one triangle's. */
    bool independent_lanes;
    /* true: the fragment stage computes a lane's colour and discard from that lane's varyings,
     * the uniforms and the textures alone: not from x, y, z, front_facing, primitive or instance,
     * nor from other lanes. sgapi may then run it once for a triangle whose varyings are the same
     * at its three vertices (a flat-coloured face, an instance's flat colour) and give each of its
     * pixels that result. false (default): the stage runs for every pixel. */
    bool varyings_only;
} sgShaderDesc;

/* ---- pipeline state ----------------------------------------------------------------------------
 */

typedef enum sgShade {
    SG_SHADE_DEFAULT = 0,      /* vertex colour */
    SG_SHADE_VERTEX_COLOR,     /* fragment = interpolated vertex colour */
    SG_SHADE_TEXTURE_MODULATE, /* fragment = vertex colour * texel */
} sgShade;

typedef enum sgFilter {
    SG_FILTER_DEFAULT = 0, /* nearest */
    SG_FILTER_NEAREST,
    SG_FILTER_BILINEAR,
} sgFilter;

typedef enum sgWrap {
    SG_WRAP_DEFAULT = 0, /* repeat */
    SG_WRAP_REPEAT,
    SG_WRAP_CLAMP_TO_EDGE,
} sgWrap;

/* How a pipeline picks among a texture's mipmap levels (docs/api.md, "Mipmaps"). The level of
 * detail comes from each 2 x 2 pixel quad's texel-coordinate derivatives, as in Vulkan. */
typedef enum sgMipmap {
    SG_MIPMAP_DEFAULT = 0, /* none */
    SG_MIPMAP_NONE,        /* level 0 only: the pipeline's filter, as without mipmaps */
    SG_MIPMAP_NEAREST,     /* the nearest level, sampled with the pipeline's filter */
    SG_MIPMAP_LINEAR,      /* the two nearest levels, each with the filter, blended (trilinear) */
} sgMipmap;

typedef enum sgCompare {
    SG_COMPARE_DEFAULT = 0, /* always: no depth test */
    SG_COMPARE_NEVER,
    SG_COMPARE_LESS,
    SG_COMPARE_EQUAL,
    SG_COMPARE_LESS_EQUAL,
    SG_COMPARE_GREATER,
    SG_COMPARE_NOT_EQUAL,
    SG_COMPARE_GREATER_EQUAL,
    SG_COMPARE_ALWAYS,
} sgCompare;

typedef enum sgCull {
    SG_CULL_DEFAULT = 0, /* none */
    SG_CULL_NONE,
    SG_CULL_BACK,
    SG_CULL_FRONT,
} sgCull;

typedef enum sgFrontFace {
    SG_FRONT_FACE_DEFAULT = 0, /* counter-clockwise */
    SG_FRONT_FACE_CCW,         /* counter-clockwise as seen on screen (NDC y up) */
    SG_FRONT_FACE_CW,
} sgFrontFace;

typedef enum sgBlend {
    SG_BLEND_DEFAULT = 0, /* opaque */
    SG_BLEND_OPAQUE,      /* the fragment replaces the pixel */
    /* out = src * src_alpha + dst * (1 - src_alpha) on R, G, B and A (OpenGL's
     * glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA)), in 8-bit arithmetic (docs/accuracy.md).
     * Each pixel blends the draws of a pass, and the triangles of a draw, in submission order. */
    SG_BLEND_ALPHA,
} sgBlend;

/* Lighting of a pipeline: OpenGL 1.x fixed-function lighting (docs/api.md, "Lighting"), with the
 * lights, ambient and material of each draw (sgDrawParams.lighting, .specular, .shininess). */
typedef enum sgLightingMode {
    SG_LIGHTING_DEFAULT = 0, /* none */
    SG_LIGHTING_NONE,        /* the colour is not lit */
    SG_LIGHTING_FLAT,    /* once per triangle, at its view-space centroid, with its face normal */
    SG_LIGHTING_GOURAUD, /* per vertex (needs normals); colours interpolated */
    SG_LIGHTING_PHONG,   /* per pixel (needs normals): normal and position interpolated */
} sgLightingMode;

/* How a pipeline draws triangles and quads. */
typedef enum sgPolygonMode {
    SG_POLYGON_MODE_DEFAULT = 0, /* fill */
    SG_POLYGON_MODE_FILL,
    SG_POLYGON_MODE_LINE, /* wireframe: each triangle's edges that survive culling, as lines (a
                             quad's four outer edges, not its diagonal); an edge two triangles
                             share is drawn by each */
} sgPolygonMode;

typedef struct sgPipelineDesc {
    sgShade shade;
    sgFilter filter; /* used by SG_SHADE_TEXTURE_MODULATE */
    sgWrap wrap;     /* both s and t */
    struct {
        sgCompare compare; /* anything but ALWAYS reads the depth target */
        bool write;        /* write the fragment's depth when it passes */
        /* Depth bias, for shadow maps: each triangle's depth is moved by bias_constant +
         * bias_slope * max(|dz/dx|, |dz/dy|) (window depth, per pixel) before the test and the
         * write. Finite; 0: none. */
        float bias_constant, bias_slope;
    } depth;
    sgCull cull;
    sgFrontFace front_face;
    sgBlend blend;
    sgLightingMode lighting;
    sgPolygonMode polygon_mode; /* how triangles and quads are drawn; lines are always lines */
    /* Programmable stages (both NULL: the fixed shading above). With them, shade and lighting
     * stay at their defaults; filter and wrap apply to the draw's textures. */
    sgShaderDesc shader;
    /* Mipmapping of the textures SG_SHADE_TEXTURE_MODULATE and sgSample read; a texture of one
     * level samples that level. Not with SG_LIGHTING_PHONG nor with a shadow map received
     * (SG_ERROR_UNSUPPORTED). */
    sgMipmap mipmap;
} sgPipelineDesc;

/** Creates an immutable pipeline state object and selects the code specialised for its state. */
SGAPI_API sgResult sgCreatePipelineStateObject(sgDevice *device, const sgPipelineDesc *desc,
                                               sgPipelineStateObject *out_pso);
/** Destroys a pipeline state object. */
SGAPI_API sgResult sgDestroyPipelineStateObject(sgDevice *device, sgPipelineStateObject pso);

/* ---- render pass and draws ---------------------------------------------------------------------
 */

typedef enum sgLoadOp {
    SG_LOAD_DEFAULT = 0, /* colour: clear to clear_color; depth: clear to 1.0 (the far plane) */
    SG_LOAD_CLEAR,       /* start from the clear value given in the pass */
    SG_LOAD_LOAD,        /* start from the target's current contents */
} sgLoadOp;

typedef enum sgStoreOp {
    SG_STORE_DEFAULT = 0, /* store */
    SG_STORE_STORE,       /* the target holds the pass's result after sgEndRenderPass */
    SG_STORE_DONT_CARE,   /* the target keeps its contents from before the pass (saves a write) */
} sgStoreOp;

typedef struct sgPassDesc {
    sgImage2D color; /* SG_FORMAT_RGBA8_UNORM; {0}: none, a depth-only pass (then depth is
                        required): draws only test and write depth, nothing is shaded */
    sgImage2D depth; /* optional ({0}: none), SG_FORMAT_D32_FLOAT, same size as color */
    sgLoadOp color_load;
    sgLoadOp depth_load;
    float clear_color[4];  /* r, g, b, a in [0, 1] */
    float clear_depth;     /* used when depth_load is SG_LOAD_CLEAR, in [0, 1] */
    sgStoreOp depth_store; /* whether the depth target receives the pass's depth */
    /* Samples a pixel: 0 or 1 (one, at the pixel centre) or 4 (Vulkan's standard 4x positions;
     * coverage, depth test and blending per sample, shading once per pixel and triangle at the
     * centre; the colour target receives the samples' average rounded to nearest and the depth
     * target sample 0, at sgEndRenderPass). Other counts: SG_ERROR_INVALID_VALUE. */
    int samples;
} sgPassDesc;

/* An RGBA colour, each channel in [0, 1]. */
typedef struct sgColor {
    float r, g, b, a;
} sgColor;

/* Order of a draw's triangles. */
typedef enum sgSort {
    SG_SORT_DEFAULT = 0, /* none */
    SG_SORT_NONE,        /* as the indices list them */
    /* Farthest first: by the view-space z of each triangle's centroid (the mean of the z of its
     * three worldView * position, each divided by its w when w != 1), smallest z first; triangles
     * with equal keys keep their order. Quads are split into their two triangles first. For
     * transparent non-convex meshes; the order is the same for any thread count. */
    SG_SORT_BACK_TO_FRONT,
} sgSort;

#define SG_MAX_LIGHTS 8

typedef enum sgLightType {
    SG_LIGHT_DIRECTIONAL = 1, /* from infinitely far away, along `direction` */
    SG_LIGHT_POINT,           /* from `position`, attenuated with distance */
} sgLightType;

/* One light, in view space (the space worldView maps to; the eye at the origin). */
typedef struct sgLight {
    sgLightType type;     /* required */
    float direction[3];   /* DIRECTIONAL: the way the light travels (not normalised; not zero) */
    float position[3];    /* POINT */
    float color[3];       /* r, g, b, each finite and >= 0 */
    float attenuation[3]; /* POINT: constant, linear, quadratic, each finite and >= 0; all three
                             0 (zero-initialised): (1, 0, 0), no attenuation */
} sgLight;

/* The lights of a draw: scene ambient plus up to SG_MAX_LIGHTS lights. */
typedef struct sgLighting {
    float ambient[3]; /* r, g, b, each finite and >= 0 */
    int light_count;  /* 0 .. SG_MAX_LIGHTS */
    sgLight lights[SG_MAX_LIGHTS];
} sgLighting;

/* A shadow map a draw receives: the depth, seen from a light, of everything that casts a
 * shadow, rendered in a depth-only pass (docs/api.md, "Shadows"). */
typedef struct sgShadow {
    sgImage2D map;    /* an SG_FORMAT_D32_FLOAT image, not a target of the open pass */
    float matrix[16]; /* view space (as worldView maps to) -> the light's clip space, row-major:
                         the light's projection x its view, the same for every draw */
    int light;        /* lit draws: the index in params->lighting of the light it shadows */
    bool pcf;         /* 2 x 2 percentage-closer filtering; else the one texel under the point */
} sgShadow;

typedef struct sgDrawParams {
    float world_view[16]; /* row-major */
    float proj[16];       /* row-major */
    sgImage2D texture;    /* required by SG_SHADE_TEXTURE_MODULATE, ignored otherwise */
    /* Optional: a constant colour that multiplies every vertex colour (alpha included), each
     * channel in [0, 1]. NULL: opaque white, the vertex colours as they are. */
    const sgColor *color;
    sgSort sort;
    /* Lit pipelines only (sgPipelineDesc.lighting), ignored otherwise: */
    const sgLighting *lighting; /* NULL: no light and no ambient (a lit surface is black) */
    float specular[3];          /* specular colour of the material, each finite and >= 0 */
    float shininess;            /* specular exponent, 0 .. 128 */
    /* Optional: the draw receives this shadow (NULL: none). Lit draws lose the shadowed light's
     * diffuse and specular light where it is hidden (SG_LIGHTING_PHONG only); unlit draws are
     * darkened to half their colour there. */
    const sgShadow *shadow;
    /* Shader pipelines only (sgPipelineDesc.shader): */
    const void *uniforms; /* copied by sgDraw: the stages receive the copy; NULL when size is 0 */
    size_t uniform_size;  /* bytes, 0 .. SG_MAX_UNIFORM_SIZE */
    sgImage2D textures[SG_MAX_DRAW_TEXTURES]; /* sgSample's slots; the first texture_count bound */
    int instance_count; /* the geom drawn this many times (sgVertexBatch.instance); 0: 1 */
} sgDrawParams;

/** Opens a render pass on the given targets, clearing or loading them. */
SGAPI_API sgResult sgBeginRenderPass(sgDevice *device, const sgPassDesc *pass);
/** Draws a geom with a pipeline into the open pass. */
SGAPI_API sgResult sgDraw(sgDevice *device, sgPipelineStateObject pso, sgGeom geom,
                          const sgDrawParams *params);
/** Closes the pass opened with the same targets and writes the result into them. */
SGAPI_API sgResult sgEndRenderPass(sgDevice *device, const sgPassDesc *pass);

/** In a fragment stage: the draw's texture in `slot` at (u[i], v[i]) for each lane, with the
 *  pipeline's filter, wrap and mipmap (v = 0 the bottom row; a depth image gives (d, d, d, 1),
 *  from level 0); slots past the bound textures give (0, 0, 0, 1). With mipmaps, each 2 x 2
 *  quad of lanes (lanes 0 1 4 5, 2 3 6 7, 8 9 12 13, 10 11 14 15) takes its level of detail
 *  from the differences of u and v between its lanes, as a GPU's implicit derivatives. */
SGAPI_API void sgSample(const sgFragmentBatch *b, int slot, const float u[SG_SHADER_LANES],
                        const float v[SG_SHADER_LANES], float rgba[4][SG_SHADER_LANES]);

#ifdef __cplusplus
}
#endif
#endif
