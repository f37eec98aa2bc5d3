/* library.c - the built-in shader library: every apps/shaders/<name>.c, in the order listed. */
#include "builtin.h"

/* The shaders, in the order programs list them. */
static const sgShaderInfo *const list[] = {
    &sg_shader_unlit,      &sg_shader_phong,     &sg_shader_toon,
    &sg_shader_normal_map, &sg_shader_marble,    &sg_shader_waves,
    &sg_shader_dissolve,   &sg_shader_instanced, &sg_shader_phong_lights,
};

#if SGS_HAVE_AVX512
/* The same shaders compiled for AVX-512 (shader_math.h says why), same bits. */
extern const sgShaderInfo sg_shader_unlit_avx512, sg_shader_phong_avx512, sg_shader_toon_avx512,
    sg_shader_normal_map_avx512, sg_shader_marble_avx512, sg_shader_waves_avx512,
    sg_shader_dissolve_avx512, sg_shader_instanced_avx512, sg_shader_phong_lights_avx512;
static const sgShaderInfo *const list_avx512[] = {
    &sg_shader_unlit_avx512,      &sg_shader_phong_avx512,     &sg_shader_toon_avx512,
    &sg_shader_normal_map_avx512, &sg_shader_marble_avx512,    &sg_shader_waves_avx512,
    &sg_shader_dissolve_avx512,   &sg_shader_instanced_avx512, &sg_shader_phong_lights_avx512,
};
_Static_assert(sizeof list == sizeof list_avx512, "one AVX-512 copy of each shader");
#endif

const sgShaderInfo *const *sg_builtin_shaders(int *count) {
    *count = (int)(sizeof list / sizeof list[0]);
#if SGS_HAVE_AVX512
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512bw") &&
        __builtin_cpu_supports("avx512dq") && __builtin_cpu_supports("avx512vl"))
        return list_avx512;
#endif
    return list;
}
