/* library.c - the built-in shader library: every apps/shaders/<name>.c, in the order listed. */
#include "builtin.h"

/* The shaders, in the order programs list them. */
static const sgShaderInfo *const list[] = {
    &sg_shader_unlit,  &sg_shader_phong, &sg_shader_toon,     &sg_shader_normal_map,
    &sg_shader_marble, &sg_shader_waves, &sg_shader_dissolve, &sg_shader_instanced,
};

const sgShaderInfo *const *sg_builtin_shaders(int *count) {
    *count = (int)(sizeof list / sizeof list[0]);
    return list;
}
