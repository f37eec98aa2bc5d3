/* test_setup.h - setup parameters for tests that drive setup and the raster directly. */
#ifndef SG_TEST_SETUP_H
#define SG_TEST_SETUP_H

#include <string.h>

#include "pipeline/setup.h"

/* The whole w x h target, no culling, counter-clockwise front faces, `nattr` attributes. */
static inline sg_setup_params sg_test_params(int w, int h, int nattr) {
    sg_setup_params p;
    memset(&p, 0, sizeof p);
    p.width = w;
    p.height = h;
    p.rect_x1 = w;
    p.rect_y1 = h;
    p.cull = SG_CULL_NONE;
    p.front_face = SG_FRONT_FACE_CCW;
    p.nattr = nattr;
    return p;
}

#endif
