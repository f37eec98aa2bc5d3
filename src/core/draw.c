/* draw.c - sgDraw: validates a draw, then runs the stages in order:
 * vertex (vertex.c) -> assembly, clipping, setup (assemble.c, clip.c, setup.c) -> raster
 * (rast_tile.c) with the pipeline's specialised shading (shade.c). */
#include "core/device.h"

#include "pipeline/assemble.h"
#include "pipeline/mat4.h"
#include "pipeline/vertex.h"
#include "raster/shade.h"

/* Setup hands each triangle to the binner; the bins are rasterised once the draw's front end is
 * done. */
static void bin_emit(const sg_tri *tri, void *user) {
    sg_binner_add(user, tri);
}

typedef struct raster_job {
    const sg_binner *binner;
    const int *bins; /* the non-empty bins */
    sg_tile_fn tile_fn;
    const sg_shade_ctx *ctx;
} raster_job;

/* One bin: its triangles in submission order, clipped to the bin. Bins share no pixels, so the
 * result is the same whichever thread runs which bin. */
static void raster_bin(void *vjob, int job) {
    const raster_job *r = vjob;
    int index = r->bins[job];
    const sg_bin *bin = &r->binner->bins[index];
    int x0 = (index % r->binner->bins_x) << SG_BIN_SHIFT;
    int y0 = (index / r->binner->bins_x) << SG_BIN_SHIFT;
    for (uint32_t i = 0; i < bin->count; i++)
        sg_rast_triangle_in(&r->binner->tris[bin->tris[i]], x0, y0, x0 + SG_BIN_SIZE,
                            y0 + SG_BIN_SIZE, r->tile_fn, r->ctx);
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

    if (!sg_binner_reset(&dev->binner, fb->width, fb->height))
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for screen bins");
    int nbins = dev->binner.bins_x * dev->binner.bins_y;
    if (nbins > dev->bin_jobs_capacity) {
        int *jobs = sg_alloc(dev, (size_t)nbins * sizeof *jobs);
        if (!jobs) return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for bins");
        sg_free(dev, dev->bin_jobs);
        dev->bin_jobs = jobs;
        dev->bin_jobs_capacity = nbins;
    }
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
    a.emit = bin_emit;
    a.user = &dev->binner;
    sg_assemble(&a);
    if (dev->binner.out_of_memory) /* nothing of the draw has reached the framebuffer yet */
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgDraw: out of memory for %zu triangles",
                        dev->binner.tri_count);

    int jobs = 0;
    for (int i = 0; i < nbins; i++)
        if (dev->binner.bins[i].count) dev->bin_jobs[jobs++] = i;
    raster_job rj = {&dev->binner, dev->bin_jobs, pso->tile_fn, &ctx};
    sg_workers_run(&dev->workers, jobs, raster_bin, &rj);
    return SG_OK;
}
