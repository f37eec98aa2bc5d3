/* draw.c - sgDraw: validates a draw, then runs the stages in order:
 * vertex (vertex.c) -> assembly, clipping, setup (assemble.c, clip.c, setup.c) -> raster
 * (rast_tile.c) with the pipeline's specialised shading (shade.c). */
#include "core/device.h"

#include "pipeline/assemble.h"
#include "pipeline/mat4.h"
#include "pipeline/vertex.h"
#include "raster/shade.h"

typedef struct raster_sink {
    sg_tile_fn tile_fn;
    const sg_shade_ctx *ctx;
} raster_sink;

/* Triangles are rasterised as they leave setup; binning will slot in here. */
static void raster_emit(const sg_tri *tri, void *user) {
    const raster_sink *sink = user;
    sg_rast_triangle(tri, sink->tile_fn, sink->ctx);
}

static bool grow_vertex_arenas(sgDevice *dev, size_t n) {
    if (dev->vertex_capacity >= n) return true;
    size_t cap = dev->vertex_capacity ? dev->vertex_capacity : 1024;
    while (cap < n) cap *= 2;
    sg_free(dev, dev->clip);
    sg_free(dev, dev->outcodes);
    dev->clip = sg_alloc(dev, cap * sizeof *dev->clip);
    dev->outcodes = sg_alloc(dev, cap * sizeof *dev->outcodes);
    if (!dev->clip || !dev->outcodes) {
        sg_free(dev, dev->clip);
        sg_free(dev, dev->outcodes);
        dev->clip = NULL;
        dev->outcodes = NULL;
        dev->vertex_capacity = 0;
        return false;
    }
    dev->vertex_capacity = cap;
    return true;
}

sgResult sgDraw(sgDevice *dev, sgPipelineStateObject pso_h, sgGeom geom_h,
                const sgDrawParams *params) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!params) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgDraw: params is NULL");
    if (!dev->in_pass)
        return sg_error(dev, SG_ERROR_NOT_IN_PASS,
                        "sgDraw: no render pass is open (call sgBeginRenderPass first)");
    sg_pso *pso = sg_lookup_pso(dev, pso_h);
    if (!pso)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgDraw: pipeline id 0x%08x is not a live pipeline", pso_h.id);
    sg_geom *geom = sg_lookup_geom(dev, geom_h);
    if (!geom)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE, "sgDraw: geom id 0x%08x is not a live geom",
                        geom_h.id);
    if (pso->uses_depth && !dev->pass_depth.id)
        return sg_error(
            dev, SG_ERROR_MISSING_DEPTH,
            "sgDraw: the pipeline tests or writes depth but the pass has no depth target");
    sg_shade_ctx ctx = {0};
    if (pso->desc.shade == SG_SHADE_TEXTURE_MODULATE) {
        if (!params->texture.id)
            return sg_error(dev, SG_ERROR_MISSING_TEXTURE,
                            "sgDraw: the pipeline samples a texture but params->texture is 0");
        sg_image *tex = sg_lookup_image(dev, params->texture);
        if (!tex)
            return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                            "sgDraw: texture id 0x%08x is not a live image", params->texture.id);
        if (tex->format != SG_FORMAT_RGBA8_UNORM)
            return sg_error(dev, SG_ERROR_NOT_SAMPLEABLE,
                            "sgDraw: texture 0x%08x is D32_FLOAT, which cannot be sampled",
                            params->texture.id);
        if (params->texture.id == dev->pass_color.id)
            return sg_error(dev, SG_ERROR_IN_USE,
                            "sgDraw: texture 0x%08x is the color target of the open pass",
                            params->texture.id);
        if (!geom->texcoords)
            return sg_error(dev, SG_ERROR_MISSING_ATTRIBUTE,
                            "sgDraw: the pipeline samples a texture but the geom has no texcoords");
        ctx.tex.texels = tex->data;
        ctx.tex.width = tex->width;
        ctx.tex.height = tex->height;
    }
    if (!grow_vertex_arenas(dev, (size_t)geom->vertex_count))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for %d vertices",
                        geom->vertex_count);

    const sg_fb *fb = &dev->fb;
    ctx.color = fb->color;
    ctx.depth = dev->pass_depth.id ? fb->depth : NULL;
    ctx.tiles_x = fb->tiles_x;
    ctx.compare = pso->desc.depth.compare;

    float mvp[16];
    sg_mat4_mul(mvp, params->proj, params->world_view);
    sg_assembly a = {0};
    a.guard = sg_guard_for_viewport(fb->width, fb->height);
    sg_vertex_transform(mvp, geom->positions, geom->vertex_count, dev->clip, dev->outcodes,
                        &a.guard);

    raster_sink sink = {pso->tile_fn, &ctx};
    a.indices = geom->indices;
    a.index_count = geom->index_count;
    a.quads = geom->primitive == SG_PRIMITIVE_QUADS;
    a.clip = (const float(*)[4])dev->clip;
    a.outcodes = dev->outcodes;
    a.colors = geom->colors;
    a.texcoords = geom->texcoords;
    a.rebase_texcoords =
        pso->desc.shade == SG_SHADE_TEXTURE_MODULATE && pso->desc.wrap == SG_WRAP_REPEAT;
    a.setup.width = fb->width;
    a.setup.height = fb->height;
    a.setup.rect_x0 = 0;
    a.setup.rect_y0 = 0;
    a.setup.rect_x1 = fb->width;
    a.setup.rect_y1 = fb->height;
    a.setup.cull = pso->desc.cull;
    a.setup.front_face = pso->desc.front_face;
    a.setup.nattr = pso->nattr;
    a.emit = raster_emit;
    a.user = &sink;
    sg_assemble(&a);
    return SG_OK;
}
