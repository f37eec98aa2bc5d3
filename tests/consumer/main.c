/* Draws one triangle through the installed library and checks a pixel. */
#include <sgapi/sgapi.h>
#include <stdio.h>

int main(void) {
    sgDevice *dev;
    if (sgCreateDevice(NULL, &dev) != SG_OK) return 1;
    sgImage2D color;
    sgImage2DDesc idesc = {.width = 8, .height = 8, .format = SG_FORMAT_RGBA8_UNORM};
    const float pos[] = {-1, -1, 0, 1, 3, -1, 0, 1, -1, 3, 0, 1};
    const float col[] = {0, 1, 0, 1, 0, 1, 0, 1, 0, 1, 0, 1};
    const uint32_t idx[] = {0, 1, 2};
    sgGeomDesc gdesc = {
        .vertex_count = 3, .positions = pos, .colors = col, .index_count = 3, .indices = idx};
    sgGeom geom;
    sgPipelineDesc pdesc = {0};
    sgPipelineStateObject pso;
    sgDrawParams params = {.world_view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1},
                           .proj = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}};
    unsigned char px[8 * 8 * 4];
    if (sgCreateImage2D(dev, &idesc, &color) || sgCreateGeom(dev, &gdesc, &geom) ||
        sgCreatePipelineStateObject(dev, &pdesc, &pso))
        return 1;
    sgPassDesc pass = {.color = color};
    if (sgBeginRenderPass(dev, &pass) || sgDraw(dev, pso, geom, &params) ||
        sgEndRenderPass(dev, &pass) || sgReadImage2D(dev, color, px, 0))
        return 1;
    sgDestroyDevice(dev);
    printf("pixel 0: %d %d %d %d\n", px[0], px[1], px[2], px[3]);
    return !(px[0] == 0 && px[1] == 255 && px[2] == 0 && px[3] == 255);
}
