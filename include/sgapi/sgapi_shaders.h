/* sgapi_shaders.h - shader libraries: named shaders (sgShaderDesc) with their GLSL twins, built
 * into a program or loaded from a shared object.
 *
 * A shared object exports
 *     const sgShaderLibrary *sgapi_shader_library(void);
 * and builds with the headers alone:
 *     cc -O2 -shared -fPIC -I include lib.c -o lib.so -lm
 * sgSample comes from the program that loads it. Programs refuse a library whose abi_version is
 * not SGAPI_SHADER_ABI_VERSION. The GLSL twins are what the reference renderer (sgapi-ref) runs
 * on the GPU API in the shader's place; docs/api.md, "Shaders", gives the contract they follow.
 */
#ifndef SGAPI_SHADERS_H
#define SGAPI_SHADERS_H

#include "sgapi/sgapi.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Changes whenever sgVertexBatch, sgFragmentBatch, sgShaderDesc or the structs below change. */
#define SGAPI_SHADER_ABI_VERSION 4

typedef struct sgShaderInfo {
    const char *name; /* what a scene file's "shader" key names: [A-Za-z0-9_]+ */
    sgShaderDesc desc;
    int uniform_count; /* floats of uniforms a draw gives (a scene's "uniforms" array) */
    const char *glsl_vertex, *glsl_fragment; /* the twins: GLSL 450 source text */
} sgShaderInfo;

typedef struct sgShaderLibrary {
    int abi_version; /* SGAPI_SHADER_ABI_VERSION */
    int count;
    const sgShaderInfo *shaders;
} sgShaderLibrary;

/* The name a shared object's library function is looked up by. */
#define SGAPI_SHADER_LIBRARY_SYMBOL "sgapi_shader_library"

/** What a shader library shared object exports. */
typedef const sgShaderLibrary *(*sgShaderLibraryFn)(void);

#ifdef __cplusplus
}
#endif
#endif
