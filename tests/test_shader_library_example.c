/* test_shader_library_example.c - the shader library example (apps/examples/shader_library),
 * built by its documented command, loads: the symbol is there, of this ABI version, with its one
 * shader, whose stages run on a hand-made batch.
 *
 *   test_shader_library_example LIB.so
 */
#include <dlfcn.h>
#include <stdio.h>
#include <string.h>

#include "sgapi/sgapi_shaders.h"

/* The program that loads a library provides sgSample; this one is never called (the example
 * samples no texture). */
void sgSample(const sgFragmentBatch *b, int slot, const float u[SG_SHADER_LANES],
              const float v[SG_SHADER_LANES], float rgba[4][SG_SHADER_LANES]) {
    (void)b, (void)slot, (void)u, (void)v;
    memset(rgba, 0, 4 * SG_SHADER_LANES * sizeof(float));
}

#define EXPECT(c)                                                                                  \
    do {                                                                                           \
        if (!(c)) {                                                                                \
            fprintf(stderr, "test_shader_library_example: failed: %s\n", #c);                      \
            return 1;                                                                              \
        }                                                                                          \
    } while (0)

int main(int argc, char **argv) {
    EXPECT(argc == 2);
    void *h = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!h) fprintf(stderr, "%s\n", dlerror());
    EXPECT(h != NULL);
    sgShaderLibraryFn fn;
    void *sym = dlsym(h, SGAPI_SHADER_LIBRARY_SYMBOL);
    EXPECT(sym != NULL);
    memcpy(&fn, &sym, sizeof fn);
    const sgShaderLibrary *lib = fn();
    EXPECT(lib && lib->abi_version == SGAPI_SHADER_ABI_VERSION && lib->count == 1);
    const sgShaderInfo *s = &lib->shaders[0];
    EXPECT(strcmp(s->name, "stripes") == 0 && s->uniform_count == 4);
    EXPECT(s->desc.vertex && s->desc.fragment && s->glsl_vertex && s->glsl_fragment);
    static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    const float u[4] = {1, 0.9f, 0.2f, 0.1f};
    sgVertexBatch v;
    memset(&v, 0, sizeof v);
    v.count = SG_SHADER_LANES;
    v.world_view = id, v.proj = id;
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        v.position[0][i] = 0.25f * (float)i, v.position[3][i] = 1.0f; /* x + y = i / 4 */
        for (int k = 0; k < 4; k++) v.color[k][i] = 0.5f;
    }
    s->desc.vertex(&v, u);
    sgFragmentBatch f;
    memset(&f, 0, sizeof f);
    f.mask = 0xffffu;
    memcpy(f.varying, v.varying, sizeof f.varying);
    s->desc.fragment(&f, u);
    for (int i = 0; i < SG_SHADER_LANES; i++) {
        EXPECT(v.clip[0][i] == v.position[0][i] && v.clip[3][i] == 1.0f);
        int odd = (i / 4) % 2; /* bands of width 1 in x + y */
        EXPECT(f.color[0][i] == (odd ? 0.9f : 0.5f) && f.color[2][i] == (odd ? 0.1f : 0.5f));
    }
    dlclose(h);
    printf("test_shader_library_example: %s loads; stripes runs\n", argv[1]);
    return 0;
}
