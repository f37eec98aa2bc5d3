/* rast_msaa.h - the back end of a multisampled render pass (sgPassDesc.samples = 4): one screen
 * bin from start to finish, beside the one-sample path of rast_bin.c, which it leaves as it is.
 *
 * A pixel has four samples at Vulkan's standard positions (0.375, 0.125), (0.875, 0.375),
 * (0.125, 0.625), (0.625, 0.875): 96, 224, 32, 160 / 256 of a pixel in x and 32, 96, 160, 224 in
 * y. The edge functions are exact integers in 1/256 pixel (setup.h), so a sample's coverage is the
 * pixel-centre coverage of the triangle moved by the sample's offset from the centre: a copy of
 * the triangle whose edge values and depth plane are moved is what sample k sees. The four are
 * walked at once (sg_raster_samples_fn, depth.h): one walk over the pixels some sample covers,
 * then per tile each sample's own coverage and the ordinary visibility tile body, each sample
 * into its own plane of ids and depth.
 * Shading then runs once per pixel and triangle, at the pixel centre (the attribute planes are
 * not moved), and its colour goes to the samples of the pixel that see the triangle. Blended
 * triangles are depth tested per sample, shaded once per pixel and blended into each passing
 * sample, in submission order. Lines are not moved: they stay one pixel wide and fill the four
 * samples of the pixels they cover. At the end the colour target receives the average of the
 * four samples, rounded to nearest, and the depth target sample 0.
 */
#ifndef SG_RAST_MSAA_H
#define SG_RAST_MSAA_H

#include "raster/rast_bin.h"

enum {
    SG_MSAA_SAMPLES = SG_VIS_SAMPLES,
    /* Samples of one bin in the device's buffers between flushes (sg_bin_pass.msaa_color). */
    SG_MSAA_BIN_SAMPLES = SG_MSAA_SAMPLES * SG_BIN_SIZE * SG_BIN_SIZE
};

/** Sample k's offset from the pixel centre in 1/256 pixel: x, then y. */
static inline int sg_msaa_offset_x(int k) {
    static const int x[SG_MSAA_SAMPLES] = {96 - 128, 224 - 128, 32 - 128, 160 - 128};
    return x[k];
}
static inline int sg_msaa_offset_y(int k) {
    static const int y[SG_MSAA_SAMPLES] = {32 - 128, 96 - 128, 160 - 128, 224 - 128};
    return y[k];
}

/** Triangle t as seen by sample k: edge values and depth plane moved by the sample's offset
 *  (everything else, the attribute planes included, as in t). A line is not moved. */
void sg_msaa_sample_tri(const sg_tri *t, int k, sg_tri *out);

/** Renders bin `index` of a multisampled pass: into its targets, or into the pass's sample
 *  buffers at a flush (sg_bin_pass.msaa_store). */
void sg_rast_bin_msaa(const sg_bin_pass *pass, int index);

#endif
