// Techniques that shade at 1/k resolution shade, for low-resolution texel `lo`, this
// full-resolution pixel; passes/upsample.h restores the image from exactly these pixels.
#ifndef GIQ_LOW_RESOLUTION_GLSL
#define GIQ_LOW_RESOLUTION_GLSL

ivec2 full_resolution_pixel(ivec2 lo, int k, ivec2 size) { return min(lo * k + k / 2, size - 1); }

#endif
