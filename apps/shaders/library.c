/* library.c - the built-in shader library: every apps/shaders/<name>.c, in the order listed. */
#include "builtin.h"

/* The shaders of one compilation (suffix: none, _avx512 or _avx2), in the order programs list
 * them. */
#define SGS_LIST(sfx)                                                                              \
    {                                                                                              \
        &sg_shader_unlit##sfx, &sg_shader_phong##sfx, &sg_shader_toon##sfx,                        \
            &sg_shader_normal_map##sfx, &sg_shader_marble##sfx, &sg_shader_waves##sfx,             \
            &sg_shader_dissolve##sfx, &sg_shader_instanced##sfx, &sg_shader_phong_lights##sfx,     \
    }

static const sgShaderInfo *const list[] = SGS_LIST();

#if SGS_HAVE_X86_COPIES
/* The same shaders compiled for AVX-512 and for AVX2 (shader_math.h says why), same bits. */
#define SGS_DECLARE(sfx)                                                                           \
    extern const sgShaderInfo sg_shader_unlit##sfx, sg_shader_phong##sfx, sg_shader_toon##sfx,     \
        sg_shader_normal_map##sfx, sg_shader_marble##sfx, sg_shader_waves##sfx,                    \
        sg_shader_dissolve##sfx, sg_shader_instanced##sfx, sg_shader_phong_lights##sfx
SGS_DECLARE(_avx512);
SGS_DECLARE(_avx2);
static const sgShaderInfo *const list_avx512[] = SGS_LIST(_avx512);
static const sgShaderInfo *const list_avx2[] = SGS_LIST(_avx2);
_Static_assert(sizeof list == sizeof list_avx512, "one AVX-512 copy of each shader");
_Static_assert(sizeof list == sizeof list_avx2, "one AVX2 copy of each shader");
#endif

const sgShaderInfo *const *sg_builtin_shaders_copy(sgs_copy copy, int *count) {
    *count = (int)(sizeof list / sizeof list[0]);
    switch (copy) {
    case SGS_COPY_BASELINE:
        return list;
#if SGS_HAVE_X86_COPIES
    case SGS_COPY_AVX2:
        return __builtin_cpu_supports("avx2") ? list_avx2 : NULL;
    case SGS_COPY_AVX512:
        return __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
                       __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl")
                   ? list_avx512
                   : NULL;
#endif
    default:
        return NULL;
    }
}

const sgShaderInfo *const *sg_builtin_shaders(sgSimd simd, int *count) {
    const sgShaderInfo *const *l = NULL;
    if (simd == SG_SIMD_AVX512) l = sg_builtin_shaders_copy(SGS_COPY_AVX512, count);
    if (simd == SG_SIMD_AVX2) l = sg_builtin_shaders_copy(SGS_COPY_AVX2, count);
    for (int copy = SGS_COPY_COUNT - 1; simd == SG_SIMD_DEFAULT && !l && copy > SGS_COPY_BASELINE;
         copy--)
        l = sg_builtin_shaders_copy((sgs_copy)copy, count);
    return l ? l : sg_builtin_shaders_copy(SGS_COPY_BASELINE, count);
}
