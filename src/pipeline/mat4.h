/* mat4.h - 4x4 matrices, row-major (m[r * 4 + c]), acting on column vectors. */
#ifndef SG_MAT4_H
#define SG_MAT4_H

/** out = a * b (out may alias neither a nor b). */
void sg_mat4_mul(float out[16], const float a[16], const float b[16]);
/** out = m * (x, y, z, w). */
void sg_mat4_transform(float out[4], const float m[16], const float v[4]);

#endif
