/* shader_lib.h - the shaders a program knows by name: the built-in library (apps/shaders) and the
 * shared objects given with --shaders (sgapi/sgapi_shaders.h). Scene files name shaders; they
 * never load code themselves. */
#ifndef SC_SHADER_LIB_H
#define SC_SHADER_LIB_H

#include <stdbool.h>

#include "msg.h"
#include "scene.h"
#include "sgapi/sgapi_shaders.h"

typedef struct sc_shaders sc_shaders;

/** The built-in shaders, in their copy for a device of instruction set `simd` (sgDeviceDesc.simd:
 *  the set shows in no image); false (err set) when out of memory. */
bool sc_shaders_open(sc_shaders **out, sgSimd simd, sc_msg *err);
/** Adds the shaders of a shared object (dlopen): false, with a message naming the path, when it
 *  is missing, not a shared object, lacks sgapi_shader_library, or is of another ABI version. A
 *  name already known is an error too. */
bool sc_shaders_load(sc_shaders *s, const char *path, sc_msg *err);
/** The shader of that name, or NULL. */
const sgShaderInfo *sc_shaders_find(const sc_shaders *s, const char *name);
/** Checks every shader draw of a loaded scene file: a known name (the message lists the known
 *  ones) and exactly its uniform_count uniforms; false with a message naming file, scene and
 *  draw. Programs exit 2 on it, before rendering. */
bool sc_shaders_check(const sc_shaders *s, const sc_file *f, sc_msg *err);
/** The built-in shaders (sc_shaders_open), then each library of libs[0..nlibs), then
 *  sc_shaders_check of each file of files[0..nfiles): the set-up every program runs before
 *  rendering (false: err set, *out NULL, the program exits 2). */
bool sc_shaders_prepare(sc_shaders **out, sgSimd simd, const char *const *libs, int nlibs,
                        const sc_file *files, int nfiles, sc_msg *err);
/** Unloads the libraries and frees s (NULL: nothing). */
void sc_shaders_close(sc_shaders *s);

#endif
