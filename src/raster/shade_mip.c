/* shade_mip.c - the fixed textured shading of mipmapped pipelines (SG_SHADE_TEXTURE_MODULATE with
 * sgPipelineDesc.mipmap NEAREST or LINEAR), unlit or lit flat or Gouraud, opaque or blended.
 *
 * A pipeline without mipmaps never runs this file: its shading keeps the functions of shade.c and
 * its SIMD twins. Here the level of detail needs each 2 x 2 quad's texture coordinates at all four
 * pixels, covered or not (a GPU's helper pixels), so a tile's 16 coordinates are made first, from
 * the same planes and in the same IEEE operations as shade.c, then each quad's levels from their
 * differences (tex/mip.h), then the 16 lookups at once (tex/sample16.c), and the covered pixels
 * are coloured as shade.c colours them. One portable body serves every instruction set, so all
 * give the same bytes.
 */
#include "raster/shade.h"

#include "raster/framebuffer.h"
#include "tex/lanes.h"
#include "tex/mip.h"
#include "tex/sample16.h"

#define SG_LANES_BODY "raster/shade_mip_body.h"
#include "tex/lanes_copies.h"

sg_shade_fn sg_shade_mip_select(sgMipmap mipmap, sgFilter filter, sgWrap wrap, bool sec,
                                sg_isa isa) {
    const int i = (mipmap == SG_MIPMAP_LINEAR) * 8 + (filter == SG_FILTER_BILINEAR) * 4 +
                  (wrap == SG_WRAP_REPEAT) * 2 + (int)sec;
#if SG_LANES_AVX512
    if (isa == SG_ISA_AVX512) return mip_table_avx512[i];
#endif
    (void)isa;
    return mip_table_portable[i];
}
