/* stb_image_fuzz.c - the decoder of the system stb_image header, compiled into the fuzz targets so
 * that it is instrumented too: the prebuilt library is neither covered nor checked by ASan. */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
