/* image.c - Image2D objects: creation, upload, read back. */
#include "core/device.h"

#include <string.h>

#include "tex/mipgen.h"

/* Both formats are 4 bytes a pixel: RGBA8, or one float. */
static size_t format_size(sgFormat f) {
    (void)f;
    return 4;
}

static const char *format_name(sgFormat f) {
    return f == SG_FORMAT_RGBA8_UNORM ? "RGBA8_UNORM" : "D32_FLOAT";
}

void sg_image_release(sgDevice *dev, sg_image *img) {
    sg_free(dev, img->block);
    img->block = NULL;
    img->data = NULL;
    img->cleared = NULL;
}

/* Pixels start on a cache line (malloc's large blocks start 16 bytes into a page): a bin's rows
 * of a target are then whole lines of its own, never shared with the neighbouring bin that
 * another thread writes. */
enum { DATA_ALIGN = 64 };

/* Bytes from the start of level 0 to level k: each level starts on a cache line of its own. */
static size_t level_offset(int w, int h, int k) {
    size_t off = 0;
    for (int i = 0; i < k; i++) {
        off += ((size_t)w * (size_t)h * 4 + DATA_ALIGN - 1) & ~(size_t)(DATA_ALIGN - 1);
        w = sg_mip_next_side(w);
        h = sg_mip_next_side(h);
    }
    return off;
}

/* Points the image's chain at its levels (level 0 at data). */
static void set_chain(sg_image *img, int levels) {
    int w = img->width, h = img->height;
    img->mips.levels = levels;
    for (int k = 0; k < levels; k++) {
        img->mips.level[k] =
            sg_texview_of(img->data + level_offset(img->width, img->height, k), w, h);
        w = sg_mip_next_side(w);
        h = sg_mip_next_side(h);
    }
}

/* Makes levels 1.. from level 0. */
static void generate_levels(sg_image *img) {
    for (int k = 1; k < img->mips.levels; k++) {
        const sg_texview *a = &img->mips.level[k - 1];
        sg_mip_generate(a->texels, a->width, a->height, (uint8_t *)img->mips.level[k].texels);
    }
}

static bool is_pass_target(const sgDevice *dev, sgImage2D h) {
    return dev->in_pass && (dev->pass_color.id == h.id || dev->pass_depth.id == h.id);
}

/* Draws are rendered at sgEndRenderPass, so a texture a draw of the open pass samples must stay
 * as it is until then. */
static bool is_pass_texture(const sgDevice *dev, const sg_image *img) {
    return dev->in_pass && img->pass_use == dev->pass_serial;
}

sgResult sgCreateImage2D(sgDevice *dev, const sgImage2DDesc *desc, sgImage2D *out) {
    if (out) out->id = 0;
    if (!dev) return SG_ERROR_NULL_POINTER;
    if (!desc || !out)
        return sg_error(dev, SG_ERROR_NULL_POINTER, "sgCreateImage2D: %s is NULL",
                        !desc ? "desc" : "out_image");
    if (desc->format != SG_FORMAT_RGBA8_UNORM && desc->format != SG_FORMAT_D32_FLOAT)
        return sg_error(dev, SG_ERROR_INVALID_ENUM,
                        "sgCreateImage2D: format %d is not an sgFormat (RGBA8_UNORM or D32_FLOAT)",
                        (int)desc->format);
    if (desc->width < 1 || desc->height < 1 || desc->width > SG_MAX_IMAGE_SIZE ||
        desc->height > SG_MAX_IMAGE_SIZE)
        return sg_error(dev, SG_ERROR_INVALID_SIZE,
                        "sgCreateImage2D: size %dx%d is outside 1..%d in each dimension",
                        desc->width, desc->height, SG_MAX_IMAGE_SIZE);
    const int chain = sg_mip_chain_length(desc->width, desc->height);
    if (desc->mip_levels < 0 || (desc->mip_levels > chain && desc->mip_levels != SG_MIP_LEVELS_ALL))
        return sg_error(dev, SG_ERROR_INVALID_COUNT,
                        "sgCreateImage2D: mip_levels = %d; a %dx%d image has 1..%d levels (0 or "
                        "1: one, SG_MIP_LEVELS_ALL: all %d)",
                        desc->mip_levels, desc->width, desc->height, chain, chain);
    const int levels = desc->mip_levels == SG_MIP_LEVELS_ALL ? chain
                       : desc->mip_levels > 1                ? desc->mip_levels
                                                             : 1;
    if (levels > 1 && desc->format != SG_FORMAT_RGBA8_UNORM)
        return sg_error(dev, SG_ERROR_FORMAT_MISMATCH,
                        "sgCreateImage2D: mip_levels = %d on a D32_FLOAT image; only RGBA8_UNORM "
                        "images have mipmap levels",
                        desc->mip_levels);
    size_t ps = format_size(desc->format);
    size_t bytes = (size_t)desc->width * (size_t)desc->height * ps;
    const size_t all = levels > 1 ? level_offset(desc->width, desc->height, levels) : bytes;
    const size_t bins =
        desc->format == SG_FORMAT_RGBA8_UNORM ? sg_image_bins(desc->width, desc->height) : 0;
    uint8_t *block = sg_alloc(dev, all + bins + DATA_ALIGN - 1);
    if (!block)
        return sg_error(dev, SG_ERROR_OUT_OF_MEMORY, "sgCreateImage2D: out of memory (%zu bytes)",
                        all + bins);
    uint8_t *data = block + (-(uintptr_t)block & (DATA_ALIGN - 1));
    uint32_t id = sg_acquire(dev, &dev->image_pool, "sgCreateImage2D", "image_pool_size");
    if (!id) {
        sg_free(dev, block);
        return SG_ERROR_POOL_EXHAUSTED;
    }
    if (desc->data)
        memcpy(data, desc->data, bytes);
    else
        memset(data, 0, bytes);
    sg_image *img = &dev->images[id & 0xffffu];
    img->width = desc->width;
    img->height = desc->height;
    img->format = desc->format;
    img->pixel_size = ps;
    img->block = block;
    img->data = data;
    img->pass_use = 0;
    img->cleared = bins ? data + all : NULL;
    if (bins) memset(img->cleared, 0, bins);
    img->cleared_value = 0;
    set_chain(img, levels);
    if (desc->data)
        generate_levels(img);
    else
        memset(data + bytes, 0, all - bytes);
    out->id = id;
    return SG_OK;
}

sgResult sgDestroyImage2D(sgDevice *dev, sgImage2D h) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    sg_image *img = sg_lookup_image(dev, h);
    if (!img)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgDestroyImage2D: image id 0x%08x is not a live image", h.id);
    if (is_pass_target(dev, h))
        return sg_error(dev, SG_ERROR_IN_USE,
                        "sgDestroyImage2D: image 0x%08x is a target of the open render pass", h.id);
    if (is_pass_texture(dev, img))
        return sg_error(dev, SG_ERROR_IN_USE,
                        "sgDestroyImage2D: image 0x%08x is sampled by a draw of the open render "
                        "pass; destroy it after sgEndRenderPass",
                        h.id);
    sg_image_release(dev, img);
    sg_pool_release(&dev->image_pool, h.id);
    return SG_OK;
}

/* Upload (caller -> image) or read back (image -> caller), row by row, after the same checks. */
static sgResult transfer(sgDevice *dev, const char *fn, sgImage2D h, const void *src, void *dst,
                         size_t row_pitch) {
    sg_image *img = sg_lookup_image(dev, h);
    if (!img)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE, "%s: image id 0x%08x is not a live image", fn,
                        h.id);
    if (!src && !dst) return sg_error(dev, SG_ERROR_NULL_POINTER, "%s: data pointer is NULL", fn);
    size_t row = (size_t)img->width * img->pixel_size;
    if (row_pitch != 0 && row_pitch < row)
        return sg_error(dev, SG_ERROR_INVALID_SIZE,
                        "%s: row_pitch %zu is smaller than one row of the %s image (%zu bytes)", fn,
                        row_pitch, format_name(img->format), row);
    if (is_pass_target(dev, h))
        return sg_error(dev, SG_ERROR_IN_USE,
                        "%s: image 0x%08x is a target of the open render pass; its contents are "
                        "defined after sgEndRenderPass",
                        fn, h.id);
    if (src && is_pass_texture(dev, img))
        return sg_error(dev, SG_ERROR_IN_USE,
                        "%s: image 0x%08x is sampled by a draw of the open render pass, which is "
                        "rendered at sgEndRenderPass; upload before the draw or after the pass",
                        fn, h.id);
    size_t pitch = row_pitch ? row_pitch : row;
    for (int y = 0; y < img->height; y++) {
        uint8_t *pixels = img->data + (size_t)y * row;
        if (src)
            memcpy(pixels, (const uint8_t *)src + (size_t)y * pitch, row);
        else
            memcpy((uint8_t *)dst + (size_t)y * pitch, pixels, row);
    }
    if (src) {
        generate_levels(img);
        if (img->cleared) memset(img->cleared, 0, sg_image_bins(img->width, img->height));
    }
    return SG_OK;
}

sgResult sgUploadImage2D(sgDevice *dev, sgImage2D h, const void *data, size_t row_pitch) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    return transfer(dev, "sgUploadImage2D", h, data, NULL, row_pitch);
}

sgResult sgReadImage2D(sgDevice *dev, sgImage2D h, void *dst, size_t row_pitch) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    return transfer(dev, "sgReadImage2D", h, NULL, dst, row_pitch);
}

sgResult sgGetImage2DLevels(sgDevice *dev, sgImage2D h, int *levels) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    sg_image *img = sg_lookup_image(dev, h);
    if (!img)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgGetImage2DLevels: image id 0x%08x is not a live image", h.id);
    if (!levels) return sg_error(dev, SG_ERROR_NULL_POINTER, "sgGetImage2DLevels: levels is NULL");
    *levels = img->mips.levels;
    return SG_OK;
}

sgResult sgGetImage2DInfo(sgDevice *dev, sgImage2D h, int *width, int *height, sgFormat *format) {
    if (!dev) return SG_ERROR_NULL_POINTER;
    sg_image *img = sg_lookup_image(dev, h);
    if (!img)
        return sg_error(dev, SG_ERROR_INVALID_HANDLE,
                        "sgGetImage2DInfo: image id 0x%08x is not a live image", h.id);
    if (width) *width = img->width;
    if (height) *height = img->height;
    if (format) *format = img->format;
    return SG_OK;
}
