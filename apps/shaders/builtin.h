/* builtin.h - the shaders every program knows (apps/shaders/<name>.c, each a C shader and its
 * GLSL twin). */
#ifndef SG_BUILTIN_SHADERS_H
#define SG_BUILTIN_SHADERS_H

#include "sgapi/sgapi_shaders.h"

/* The shaders, one file each (apps/shaders/<name>.c; uniforms described at the top of each). */
extern const sgShaderInfo sg_shader_phong;
extern const sgShaderInfo sg_shader_toon;
extern const sgShaderInfo sg_shader_normal_map;
extern const sgShaderInfo sg_shader_marble;
extern const sgShaderInfo sg_shader_waves;
extern const sgShaderInfo sg_shader_dissolve;
extern const sgShaderInfo sg_shader_instanced;

/** The built-in library. */
const sgShaderLibrary *sg_builtin_shader_library(void);

/* The shaders, one file each. */
extern const sgShaderInfo sg_shader_unlit; /* the fixed vertex-colour equation: 4 varyings */

#endif
