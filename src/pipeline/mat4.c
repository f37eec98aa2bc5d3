/* mat4.c - the matrix maths of the vertex stage. */
#include "pipeline/mat4.h"

void sg_mat4_mul(float out[16], const float a[16], const float b[16]) {
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            /* Accumulate in double: the product is formed once per draw, so this costs nothing and
             * keeps the combined matrix as close as possible to the exact product. */
            double s = 0.0;
            for (int k = 0; k < 4; k++) s += (double)a[r * 4 + k] * (double)b[k * 4 + c];
            out[r * 4 + c] = (float)s;
        }
}

void sg_mat4_transform(float out[4], const float m[16], const float v[4]) {
    for (int r = 0; r < 4; r++)
        out[r] =
            m[r * 4 + 0] * v[0] + m[r * 4 + 1] * v[1] + m[r * 4 + 2] * v[2] + m[r * 4 + 3] * v[3];
}
