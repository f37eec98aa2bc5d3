/* geom.c - Geom objects: vertex arrays and indices, copied or referenced, validated once. */
#include "core/device.h"

#include <string.h>

void sg_geom_release(sgDevice *dev, sg_geom *g) {
    sg_free(dev, g->copy);
    g->copy = NULL;
}

/* Copies an optional array to *cursor and moves the cursor past it; NULL stays NULL. */
static const float *take(float **cursor, const float *src, size_t count) {
    if (!src) return NULL;
    float *dst = *cursor;
    memcpy(dst, src, count * sizeof(float));
    *cursor += count;
    return dst;
}

sgResult sgCreateGeom(sgDevice *dev, const sgGeomDesc *desc, sgGeom *out) {
    if (out) out->id = 0;
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!desc || !out)
        return sg_error(dev, SG_ERROR_NULL_POINTER, "sgCreateGeom: %s is NULL",
                        !desc ? "desc" : "out_geom");
    if ((int)desc->primitive < SG_PRIMITIVE_DEFAULT || desc->primitive > SG_PRIMITIVE_LINES)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgCreateGeom: primitive %d is not an sgPrimitive", (int)desc->primitive);
    if ((int)desc->storage < SG_STORAGE_DEFAULT || desc->storage > SG_STORAGE_REFERENCE)
        return sg_error(dev, SG_ERROR_INVALID_ENUM, "sgCreateGeom: storage %d is not an sgStorage",
                        (int)desc->storage);
    if (!desc->positions)
        return sg_error(dev, SG_ERROR_NULL_POINTER, "sgCreateGeom: positions is NULL");
    if (!desc->indices)
        return sg_error(dev, SG_ERROR_NULL_POINTER, "sgCreateGeom: indices is NULL");
    const sgPrimitive prim = desc->primitive ? desc->primitive : SG_PRIMITIVE_TRIANGLES;
    const int per = prim == SG_PRIMITIVE_QUADS ? 4 : prim == SG_PRIMITIVE_LINES ? 2 : 3;
    if (desc->vertex_count < 1)
        return sg_error(dev, SG_ERROR_INVALID_COUNT, "sgCreateGeom: vertex_count %d is below 1",
                        desc->vertex_count);
    if (desc->index_count < 1 || desc->index_count % per != 0)
        return sg_error(dev, SG_ERROR_INVALID_COUNT,
                        "sgCreateGeom: index_count %d is not a positive multiple of %d (%s)",
                        desc->index_count, per,
                        prim == SG_PRIMITIVE_QUADS   ? "quads"
                        : prim == SG_PRIMITIVE_LINES ? "lines"
                                                     : "triangles");
    for (int i = 0; i < desc->index_count; i++)
        if (desc->indices[i] >= (uint32_t)desc->vertex_count)
            return sg_error(dev, SG_ERROR_INDEX_OUT_OF_RANGE,
                            "sgCreateGeom: indices[%d] = %u is not below vertex_count %d", i,
                            desc->indices[i], desc->vertex_count);

    sg_geom g;
    memset(&g, 0, sizeof g);
    g.vertex_count = desc->vertex_count;
    g.index_count = desc->index_count;
    g.primitive = prim;
    if (desc->storage == SG_STORAGE_REFERENCE) {
        g.positions = desc->positions;
        g.colors = desc->colors;
        g.texcoords = desc->texcoords;
        g.normals = desc->normals;
        for (int k = 0; k < SG_MAX_ATTRIBUTES; k++) g.attributes[k] = desc->attributes[k];
        g.indices = desc->indices;
    } else {
        size_t n = (size_t)desc->vertex_count;
        size_t floats = n * 4 + (desc->colors ? n * 4 : 0) + (desc->texcoords ? n * 2 : 0) +
                        (desc->normals ? n * 3 : 0);
        for (int k = 0; k < SG_MAX_ATTRIBUTES; k++) floats += desc->attributes[k] ? n * 4 : 0;
        size_t bytes = floats * sizeof(float) + (size_t)desc->index_count * sizeof(uint32_t);
        uint8_t *block = sg_alloc(dev, bytes);
        if (!block)
            return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgCreateGeom: out of memory (%zu bytes)",
                            bytes);
        float *f = (float *)(void *)block;
        g.positions = take(&f, desc->positions, n * 4);
        g.colors = take(&f, desc->colors, n * 4);
        g.texcoords = take(&f, desc->texcoords, n * 2);
        g.normals = take(&f, desc->normals, n * 3);
        for (int k = 0; k < SG_MAX_ATTRIBUTES; k++)
            g.attributes[k] = take(&f, desc->attributes[k], n * 4);
        memcpy(f, desc->indices, (size_t)desc->index_count * sizeof(uint32_t));
        g.indices = (const uint32_t *)(void *)f;
        g.copy = block;
    }
    uint32_t id = sg_acquire(dev, &dev->geom_pool, "sgCreateGeom", "geom_pool_size");
    if (!id) {
        sg_free(dev, g.copy);
        return SG_ERROR_POOL_EXHAUSTED;
    }
    dev->geoms[id & 0xffffu] = g;
    out->id = id;
    return SG_OK;
}

sgResult sgDestroyGeom(sgDevice *dev, sgGeom h) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    sg_geom *g = sg_lookup_geom(dev, h);
    if (!g)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgDestroyGeom: geom id 0x%08x is not a live geom", h.id);
    sg_geom_release(dev, g);
    sg_pool_release(&dev->geom_pool, h.id);
    return SG_OK;
}
