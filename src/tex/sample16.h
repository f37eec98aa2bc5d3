/* sample16.h - a whole 4 x 4 tile of texture lookups at once: what sg_sample and sg_sample_mip
 * (tex/sample.h, tex/mip.h) give each lane, bit for bit, on 16-lane vectors. Lane i is the tile's
 * pixel i, row by row, so lanes 0, 1, 4, 5 are its first 2 x 2 quad. */
#ifndef SG_SAMPLE16_H
#define SG_SAMPLE16_H

#include <stdbool.h>
#include <stdint.h>

#include "tex/mip.h"

/** RGBA8 texels (top row first, width w, height h) at the 16 coordinates (s[i], t[i]): each
 *  lane's channels 0 .. 255 in texel[channel][lane], as sg_sample gives them. */
void sg_sample16(const uint8_t *texels, int w, int h, bool bilinear, bool repeat,
                 const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                 int32_t texel[4][SG_SHADER_LANES]);
/** The same from a mipmap chain, each quad q (lanes of its 2 x 2 block) with its levels pick[q],
 *  as sg_sample_mip gives them. */
void sg_sample16_mip(const sg_mip_chain *m, const sg_mip_pick pick[4], bool bilinear, bool repeat,
                     const float s[SG_SHADER_LANES], const float t[SG_SHADER_LANES],
                     int32_t texel[4][SG_SHADER_LANES]);

#endif
