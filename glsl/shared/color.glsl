// Rec. 709 luminance, the one definition on the GPU (C++: lgh::luminance in lgh/light.h). The
// hierarchy weights its centres and normals by it ("importance"), VPL paths stop at zero luminance,
// and the shadow selection and filter compare contributions by it.
#ifndef LGH_COLOR_GLSL
#define LGH_COLOR_GLSL
float luminance(vec3 rgb) { return dot(rgb, vec3(0.2126, 0.7152, 0.0722)); }
#endif
