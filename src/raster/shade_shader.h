/* shade_shader.h - the fragment stage of shader pipelines: the varyings of a 4 x 4 tile
 * interpolated into an sgFragmentBatch, the pipeline's fragment function called once for the
 * tile, its colours converted to RGBA8. Visibility first, like the fixed shading (sg_shade_shader,
 * an sg_shade_fn), or in place (sg_shader_in_place_select): blended draws, and draws whose
 * fragments discard, test depth, shade, then write depth and colour only where nothing was
 * discarded. One C body for every instruction set, its 16-lane parts (the batch's set-up and
 * conversion, the in-place walks with their depth test and writes) in copies per set: the user's
 * function is the work. */
#ifndef SG_SHADE_SHADER_H
#define SG_SHADE_SHADER_H

#include <stdbool.h>
#include <stdint.h>

#include "raster/depth.h"
#include "raster/shade.h"

/** Shades the lanes of `mask` of the tile at (x0, y0) into dst[lane] as RGBA8 and returns those
 *  not discarded (dst untouched elsewhere). */
uint32_t sg_shader_fragments(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                             uint32_t *dst);
/** The sg_shade_fn of shader draws shaded visibility first: a discarded lane is recorded in the
 *  draw and the pass (sg_shader_state), and the bin is then redone in place (rast_bin.c). */
void sg_shade_shader(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, uint32_t mask,
                     uint32_t *dst);
/** Their sg_shade2_fn: two whole tiles of a triangle, each as sg_shade_shader shades it. */
void sg_shade_shader2(const sg_shade_ctx *c, const sg_tri *t, int x0, int y0, int x1, int y1,
                      uint32_t *dst0, uint32_t *dst1);
/** The sg_shade_mixed_fn of shader draws whose lanes are independent (sgShaderDesc): the
 *  triangles of a tile that share a facing in one batch, each lane interpolated
 *  from its own triangle; the same bytes as sg_shade_shader on each triangle's pixels. */
void sg_shade_shader_shared(const sg_shade_ctx *c, const sg_mixed_tile *tiles, int count);
/** The raster function shading a shader draw in place: blended, or its fragments put (with
 *  `defer`, an opaque draw with independent lanes: its fragments wait in the bin's ids and are
 *  shaded a tile at a time, see shade_shader.c); isa: the device's. */
sg_raster_fn sg_shader_in_place_select(bool blend, sgCompare compare, bool depth_write, bool defer,
                                       sg_isa isa);
/** The kinds of those functions. */
enum { SG_SHADER_PUT, SG_SHADER_BLEND, SG_SHADER_DEFER };
/** AVX-512's and AVX2's (blend_avx512.c, blend_avx2.c; NULL where not built); depth_test: the
 *  draw's compare is not ALWAYS. */
sg_raster_fn sg_shader_in_place_avx512(int kind, bool depth_test, bool depth_write);
sg_raster_fn sg_shader_in_place_avx2(int kind, bool depth_test, bool depth_write);
/** What sg_shader_constant shades with: the draw's shading state and its uniforms (the draw's
 *  copy, while sgDraw runs). */
typedef struct sg_shader_konst {
    const sg_shade_ctx *ctx;
    const void *uniforms;
} sg_shader_konst;
/** The sg_assembly.konst of a draw whose stage reads its varyings alone: the stage run once with
 *  every lane holding `varyings` (x, y, z, primitive and instance 0, front_facing true), lane 0's
 * colour as RGBA8, converted as a tile's; *discarded: the stage discarded it. */
uint32_t sg_shader_constant(const void *user, const float *varyings, int *discarded);
/** The put-off fragments of tile `tile` of the bin v shaded, their depth and colour written. */
void sg_shader_flush_tile(const sg_vis_ctx *v, int tile);
/** Every tile's (the bin's sg_blend_pending.flush). */
void sg_shader_flush_waiting(sg_blend_pending *w, const sg_vis_ctx *v);

#endif
