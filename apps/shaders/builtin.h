/* builtin.h - the shaders every program knows (apps/shaders/<name>.c, each a C shader and its
 * GLSL twin). */
#ifndef SG_BUILTIN_SHADERS_H
#define SG_BUILTIN_SHADERS_H

#include "sgapi/sgapi_shaders.h"

/** The built-in shaders for a device of instruction set `simd`: *count pointers, the same every
 *  call with the same set. SG_SIMD_DEFAULT: the copy of the best set this CPU runs; AVX2 and
 *  AVX-512: that set's copy where this CPU runs it; any other set: the baseline's. */
const sgShaderInfo *const *sg_builtin_shaders(sgSimd simd, int *count);

/** The compilations of the built-in shaders (shader_math.h), the same bits each. */
typedef enum sgs_copy {
    SGS_COPY_BASELINE,
    SGS_COPY_AVX2,
    SGS_COPY_AVX512,
    SGS_COPY_COUNT
} sgs_copy;
/** One compilation's list, in sg_builtin_shaders' order, or NULL where it is not built or this
 *  CPU cannot run it. */
const sgShaderInfo *const *sg_builtin_shaders_copy(sgs_copy copy, int *count);

/* The shaders, one file each (uniform layouts in each file's first comment). */
extern const sgShaderInfo sg_shader_unlit;        /* the fixed vertex-colour equation */
extern const sgShaderInfo sg_shader_phong;        /* the fixed per-pixel lighting */
extern const sgShaderInfo sg_shader_toon;         /* banded diffuse and a rim */
extern const sgShaderInfo sg_shader_normal_map;   /* a tangent-space normal map */
extern const sgShaderInfo sg_shader_marble;       /* 3D noise in object space */
extern const sgShaderInfo sg_shader_waves;        /* a displaced grid, analytic normals */
extern const sgShaderInfo sg_shader_dissolve;     /* discard by noise, a glowing edge */
extern const sgShaderInfo sg_shader_instanced;    /* a grid of cubes in one draw */
extern const sgShaderInfo sg_shader_phong_lights; /* the fixed Phong lighting, whole */

#endif
