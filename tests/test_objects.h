/* test_objects.h - the objects the API tests make over and over, each asserted to succeed. */
#ifndef SG_TEST_OBJECTS_H
#define SG_TEST_OBJECTS_H

#include "test_common.h"

#include "sgapi/sgapi.h"

/** A w x h image of format f. */
static inline sgImage2D test_image(sgDevice *dev, int w, int h, sgFormat f) {
    sgImage2D img;
    assert_int_equal(
        sgCreateImage2D(dev, &(sgImage2DDesc){.width = w, .height = h, .format = f}, &img), SG_OK);
    return img;
}

/** A pipeline of desc d. */
static inline sgPipelineStateObject test_pso(sgDevice *dev, sgPipelineDesc d) {
    sgPipelineStateObject p;
    assert_int_equal(sgCreatePipelineStateObject(dev, &d, &p), SG_OK);
    return p;
}

#endif
