/* lanes_copies.h - compiles the body SG_LANES_BODY names (a header) once for each copy the lane
 * code has, on vectors of the copy's registers' width (lanes.h says why): portable on 4 lanes
 * (functions named name_portable), and on x86-64 AVX2 on 8 (name_avx2, target avx2) and AVX-512
 * on 16 (name_avx512, target SG_LANES_AVX512_ATTR), the copies sample16.h's SG_SAMPLE16_CALL
 * chooses from. The body names its functions SG_LANES_FN(name), gives them SG_LANES_ATTR and
 * works on vectors of SG_LANES_W lanes. No include guard: each file that includes it makes its
 * copies. */
#define SG_LANES_W        4
#define SG_LANES_FN(name) name##_portable
#define SG_LANES_ATTR
#include SG_LANES_BODY
#undef SG_LANES_W
#undef SG_LANES_FN
#undef SG_LANES_ATTR

#if SG_LANES_AVX512
#define SG_LANES_W        8
#define SG_LANES_FN(name) name##_avx2
#define SG_LANES_ATTR     __attribute__((target("avx2")))
#include SG_LANES_BODY
#undef SG_LANES_W
#undef SG_LANES_FN
#undef SG_LANES_ATTR

#define SG_LANES_W        16
#define SG_LANES_FN(name) name##_avx512
#define SG_LANES_ATTR     SG_LANES_AVX512_ATTR
#include SG_LANES_BODY
#undef SG_LANES_W
#undef SG_LANES_FN
#undef SG_LANES_ATTR
#endif
#undef SG_LANES_BODY
