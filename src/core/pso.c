/* pso.c - pipeline state objects: validated and specialised once, at creation. */
#include "core/device.h"

#include <math.h>
#include <string.h>

#include "raster/blend.h"
#include "raster/depth.h"
#include "raster/shade.h"
#include "raster/shade_shader.h"

#define CHECK_ENUM(field, lo, hi, type)                                                            \
    if ((int)desc->field < (int)(lo) || (int)desc->field > (int)(hi))                              \
        return sg_error(dev, SG_ERROR_INVALID_ENUM,                                                \
                        "sgCreatePipelineStateObject: " #field " = %d is not an " type,            \
                        (int)desc->field);

sgResult sgCreatePipelineStateObject(sgDevice *dev, const sgPipelineDesc *desc,
                                     sgPipelineStateObject *out) {
    if (out) out->id = 0;
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!desc || !out)
        return sg_error(dev, SG_ERROR_NULL_POINTER, "sgCreatePipelineStateObject: %s is NULL",
                        !desc ? "desc" : "out_pso");
    CHECK_ENUM(shade, SG_SHADE_DEFAULT, SG_SHADE_TEXTURE_MODULATE, "sgShade")
    CHECK_ENUM(filter, SG_FILTER_DEFAULT, SG_FILTER_BILINEAR, "sgFilter")
    CHECK_ENUM(wrap, SG_WRAP_DEFAULT, SG_WRAP_CLAMP_TO_EDGE, "sgWrap")
    CHECK_ENUM(depth.compare, SG_COMPARE_DEFAULT, SG_COMPARE_ALWAYS, "sgCompare")
    CHECK_ENUM(cull, SG_CULL_DEFAULT, SG_CULL_FRONT, "sgCull")
    CHECK_ENUM(front_face, SG_FRONT_FACE_DEFAULT, SG_FRONT_FACE_CW, "sgFrontFace")
    CHECK_ENUM(blend, SG_BLEND_DEFAULT, SG_BLEND_ALPHA, "sgBlend")
    CHECK_ENUM(lighting, SG_LIGHTING_DEFAULT, SG_LIGHTING_PHONG, "sgLightingMode")
    CHECK_ENUM(polygon_mode, SG_POLYGON_MODE_DEFAULT, SG_POLYGON_MODE_LINE, "sgPolygonMode")
    CHECK_ENUM(mipmap, SG_MIPMAP_DEFAULT, SG_MIPMAP_LINEAR, "sgMipmap")
    if (desc->mipmap > SG_MIPMAP_NONE && desc->lighting == SG_LIGHTING_PHONG)
        return sg_error(
            dev, SG_ERROR_UNSUPPORTED,
            "sgCreatePipelineStateObject: mipmap = %d with SG_LIGHTING_PHONG: per-pixel "
            "lighting samples its texture without mipmaps in this version; use "
            "SG_MIPMAP_NONE, or flat or Gouraud lighting",
            (int)desc->mipmap);
    if (!isfinite(desc->depth.bias_constant) || !isfinite(desc->depth.bias_slope))
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgCreatePipelineStateObject: depth.bias_constant = %g, depth.bias_slope = "
                        "%g: both must be finite",
                        (double)desc->depth.bias_constant, (double)desc->depth.bias_slope);

    const sgShaderDesc *sh = &desc->shader;
    const bool shader = sh->vertex || sh->fragment;
    if (shader && (!sh->vertex || !sh->fragment))
        return sg_error(dev, SG_ERROR_NULL_POINTER,
                        "sgCreatePipelineStateObject: shader.%s is NULL but shader.%s is set: give "
                        "both stages, or neither for the fixed shading",
                        sh->vertex ? "fragment" : "vertex", sh->vertex ? "vertex" : "fragment");
    if (shader && (desc->shade != SG_SHADE_DEFAULT || desc->lighting != SG_LIGHTING_DEFAULT))
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgCreatePipelineStateObject: shade = %d and lighting = %d with a shader: "
                        "the shader's stages replace the fixed shading and lighting; leave both "
                        "at their defaults",
                        (int)desc->shade, (int)desc->lighting);
    if (sh->varying_count < 0 || sh->varying_count > SG_MAX_VARYINGS)
        return sg_error(dev, SG_ERROR_INVALID_COUNT,
                        "sgCreatePipelineStateObject: shader.varying_count = %d is outside 0..%d",
                        sh->varying_count, SG_MAX_VARYINGS);
    if (sh->texture_count < 0 || sh->texture_count > SG_MAX_DRAW_TEXTURES)
        return sg_error(dev, SG_ERROR_INVALID_COUNT,
                        "sgCreatePipelineStateObject: shader.texture_count = %d is outside 0..%d",
                        sh->texture_count, SG_MAX_DRAW_TEXTURES);
    if (sh->varying_count < 32 && sh->flat_varyings >> sh->varying_count)
        return sg_error(dev, SG_ERROR_INVALID_VALUE,
                        "sgCreatePipelineStateObject: shader.flat_varyings = 0x%x names varyings "
                        "past varying_count = %d",
                        sh->flat_varyings, sh->varying_count);
    if (!shader && (sh->varying_count || sh->texture_count))
        return sg_error(dev, SG_ERROR_NULL_POINTER,
                        "sgCreatePipelineStateObject: shader.varying_count or texture_count is "
                        "set but shader.vertex and shader.fragment are NULL");

    sg_pso p;
    memset(&p, 0, sizeof p);
    p.desc = *desc;
    sgPipelineDesc *d = &p.desc;
    if (!d->shade) d->shade = SG_SHADE_VERTEX_COLOR;
    if (!d->filter) d->filter = SG_FILTER_NEAREST;
    if (!d->wrap) d->wrap = SG_WRAP_REPEAT;
    if (!d->depth.compare) d->depth.compare = SG_COMPARE_ALWAYS;
    if (!d->cull) d->cull = SG_CULL_NONE;
    if (!d->front_face) d->front_face = SG_FRONT_FACE_CCW;
    if (!d->blend) d->blend = SG_BLEND_OPAQUE;
    if (!d->lighting) d->lighting = SG_LIGHTING_NONE;
    if (!d->polygon_mode) d->polygon_mode = SG_POLYGON_MODE_FILL;
    if (!d->mipmap) d->mipmap = SG_MIPMAP_NONE;
    const bool lit = d->lighting != SG_LIGHTING_NONE;
    /* Opaque draws find the visible triangle first; blended ones blend as they go (blend.h),
     * with the unlit shading inlined where the instruction set allows. */
    const int variant = sg_shade_variant(d->shade, d->filter, d->wrap);
    p.depth_fn = sg_depth_select(d->depth.compare, d->depth.write, dev->isa);
    p.raster_fn = d->blend == SG_BLEND_ALPHA ? sg_blend_select(lit ? -1 : variant, d->depth.compare,
                                                               d->depth.write, dev->isa)
                                             : p.depth_fn;
    /* Flat and Gouraud lighting make colours the unlit shading takes as vertex colours, unless
     * the draw's material has a specular colour (sgDraw picks shade_sec then). */
    p.shade_fn = d->lighting == SG_LIGHTING_PHONG
                     ? sg_shade_phong_select(SG_PIXEL_PHONG + variant, dev->isa)
                     : sg_shade_select_variant(variant, dev->isa);
    p.shade_sec = sg_shade_select_variant(variant + SG_SHADE_SECONDARY, dev->isa);
    p.shade2_fn =
        d->lighting == SG_LIGHTING_PHONG ? NULL : sg_shade2_select_variant(variant, dev->isa);
    p.shade2_sec = sg_shade2_select_variant(variant + SG_SHADE_SECONDARY, dev->isa);
    p.runs_fn =
        d->lighting == SG_LIGHTING_PHONG ? NULL : sg_shade_runs_select_variant(variant, dev->isa);
    p.runs_sec = sg_shade_runs_select_variant(variant + SG_SHADE_SECONDARY, dev->isa);
    p.mixed_fn =
        d->lighting == SG_LIGHTING_PHONG ? NULL : sg_shade_mixed_select_variant(variant, dev->isa);
    /* Draws that receive a shadow map shade from each pixel's view position (shade_phong.c; flat
     * and Gouraud ones with their split colours);
     * blended ones then call that shading from the blend (its unlit shading is not inlined). */
    const int shadow_kind = d->lighting == SG_LIGHTING_PHONG ? SG_PIXEL_PHONG_SHADOW
                            : lit                            ? SG_PIXEL_SPLIT_SHADOW
                                                             : SG_PIXEL_SHADOW;
    p.shade_shadow = sg_shade_phong_select(shadow_kind + variant, dev->isa);
    p.raster_shadow = d->blend == SG_BLEND_ALPHA
                          ? sg_blend_select(-1, d->depth.compare, d->depth.write, dev->isa)
                          : p.depth_fn;
    /* A blend that tests depth without writing it: the same functions without the test, for
     * triangles in front of a whole bin's depth (rast_bin.c). */
    const sgCompare c = d->depth.compare;
    if (d->blend == SG_BLEND_ALPHA && !d->depth.write &&
        (c == SG_COMPARE_LESS || c == SG_COMPARE_LESS_EQUAL || c == SG_COMPARE_GREATER ||
         c == SG_COMPARE_GREATER_EQUAL)) {
        p.raster_pass = sg_blend_select(lit ? -1 : variant, SG_COMPARE_ALWAYS, false, dev->isa);
        p.raster_shadow_pass = sg_blend_select(-1, SG_COMPARE_ALWAYS, false, dev->isa);
    }
    /* Opaque line draws are shaded as they are rasterised (blend.h); Phong lighting, a specular
     * material and a shadow map keep them visibility first (sgDraw), and so do wireframes. */
    if (d->blend == SG_BLEND_OPAQUE && d->lighting != SG_LIGHTING_PHONG)
        p.raster_line = sg_put_select(variant, d->depth.compare, d->depth.write, dev->isa);
    /* Mipmapped texturing has its own shading (shade_mip.c; AVX-512's in its fixed shading, with
     * pairs of whole tiles and, unlit, its own blends); lines go visibility first, as that
     * shading is not inlined in the line raster. */
    const bool mip = d->mipmap != SG_MIPMAP_NONE && d->shade == SG_SHADE_TEXTURE_MODULATE;
    if (mip && !shader) {
        p.shade_fn = sg_shade_mip_select(d->mipmap, d->filter, d->wrap, false, dev->isa);
        p.shade_sec = sg_shade_mip_select(d->mipmap, d->filter, d->wrap, true, dev->isa);
        p.shade2_fn = sg_shade2_mip_select(d->mipmap, d->filter, d->wrap, false, dev->isa);
        p.shade2_sec = sg_shade2_mip_select(d->mipmap, d->filter, d->wrap, true, dev->isa);
        p.runs_fn = sg_shade_runs_mip_select(d->mipmap, d->filter, d->wrap, false, dev->isa);
        p.runs_sec = sg_shade_runs_mip_select(d->mipmap, d->filter, d->wrap, true, dev->isa);
        p.mixed_fn = NULL;
        p.raster_line = NULL;
        if (d->blend == SG_BLEND_ALPHA) { /* lit: a specular colour, chosen per draw */
            p.raster_fn = lit ? sg_blend_select(-1, d->depth.compare, d->depth.write, dev->isa)
                              : sg_blend_mip_select(d->mipmap, d->filter, d->wrap, d->depth.compare,
                                                    d->depth.write, dev->isa);
            if (p.raster_pass)
                p.raster_pass = lit ? sg_blend_select(-1, SG_COMPARE_ALWAYS, false, dev->isa)
                                    : sg_blend_mip_select(d->mipmap, d->filter, d->wrap,
                                                          SG_COMPARE_ALWAYS, false, dev->isa);
        }
    }
    p.nattr = sg_shade_attr_count(d->shade);
    if (shader) { /* visibility first, or in place when blended (and when seen discarding) */
        p.shader = true;
        p.nattr = sh->varying_count;
        p.raster_fn = p.depth_fn;
        p.shade_fn = sg_shade_shader;
        p.shade2_fn = sg_shade_shader2;
        p.shade2_sec = NULL;
        p.runs_fn = p.runs_sec = NULL;
        /* Tiles several triangles share in one batch where lanes are independent; mipmapped
         * sampling takes its levels from 2 x 2 differences, which need one triangle a batch. */
        p.mixed_fn =
            sh->independent_lanes && d->mipmap == SG_MIPMAP_NONE ? sg_shade_shader_shared : NULL;
        p.raster_line = NULL;
        p.raster_pass = NULL;
        p.shader_in_place = sg_shader_in_place_select(d->blend == SG_BLEND_ALPHA, d->depth.compare,
                                                      d->depth.write, p.mixed_fn != NULL, dev->isa);
    }
    p.uses_depth = d->depth.compare != SG_COMPARE_ALWAYS || d->depth.write;

    uint32_t id =
        sg_acquire(dev, &dev->pso_pool, "sgCreatePipelineStateObject", "pipeline_pool_size");
    if (!id) return SG_ERROR_POOL_EXHAUSTED;
    dev->psos[id & 0xffffu] = p;
    out->id = id;
    return SG_OK;
}

sgResult sgDestroyPipelineStateObject(sgDevice *dev, sgPipelineStateObject h) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!sg_lookup_pso(dev, h))
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgDestroyPipelineStateObject: pipeline id 0x%08x is not a live pipeline",
                        h.id);
    sg_pool_release(&dev->pso_pool, h.id);
    return SG_OK;
}
