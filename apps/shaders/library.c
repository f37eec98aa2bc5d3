/* library.c - the built-in shader library: every apps/shaders/<name>.c, in the order listed. */
#include "builtin.h"

#include <pthread.h>

/* The shaders, in the order programs list them. */
static const sgShaderInfo *const list[] = {
    &sg_shader_unlit,
};
enum { COUNT = sizeof list / sizeof list[0] };

/* A library holds its shaders by value, and C cannot copy another file's const objects in a
 * constant initialiser: the array is filled once, under pthread_once, and only read afterwards. */
static sgShaderInfo shaders[COUNT];
static pthread_once_t filled = PTHREAD_ONCE_INIT;

static void fill(void) {
    for (int i = 0; i < COUNT; i++) shaders[i] = *list[i];
}

const sgShaderLibrary *sg_builtin_shader_library(void) {
    static const sgShaderLibrary lib = {SGAPI_SHADER_ABI_VERSION, COUNT, shaders};
    pthread_once(&filled, fill);
    return &lib;
}
