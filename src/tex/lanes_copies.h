/* lanes_copies.h - compiles the body SG_LANES_BODY names (a header) once for each copy the lane
 * code has: portable (functions named name_portable), and on x86-64 for AVX-512 (name_avx512,
 * target SG_LANES_AVX512_ATTR; lanes.h says why). The body names its functions SG_LANES_FN(name)
 * and gives them SG_LANES_ATTR. No include guard: each file that includes it makes its copies. */
#define SG_LANES_FN(name) name##_portable
#define SG_LANES_ATTR
#include SG_LANES_BODY
#undef SG_LANES_FN
#undef SG_LANES_ATTR

#if SG_LANES_AVX512
#define SG_LANES_FN(name) name##_avx512
#define SG_LANES_ATTR     SG_LANES_AVX512_ATTR
#include SG_LANES_BODY
#undef SG_LANES_FN
#undef SG_LANES_ATTR
#endif
#undef SG_LANES_BODY
