// stb_image's implementation, once for the test binary (the tests read back the PNGs the
// tool writes: png_check.h).
#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>
