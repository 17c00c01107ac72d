/* fuzz/stb_image_impl.c — fuzz builds only: compiles stb_image from Debian's header so that the PNG
 * decoder is instrumented (coverage and ASan) too; these definitions take precedence over libstb's. */
#define STB_IMAGE_IMPLEMENTATION
#include <stb_image.h>
