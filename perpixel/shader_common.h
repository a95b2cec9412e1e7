// The GLSL shared by the per-pixel methods: the vertex shader of the relief's top polygon, and the fragment
// shader's frame (tangent-space view ray, depth map look-up, hole and footprint tests, colour, optional shading,
// self-shadowing, iteration counts, depth correction). Each method supplies one function (perpixel/*_glsl.cpp):
//     vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters)
// A: the fragment's texture coordinates on the top polygon (st in [0,1]^2, t up as v is); V: the view ray's
// direction in (s, t, depth) units per world length, V.z > 0 (depth 0 at the top of the displacement range, 1 at
// the bottom); cos_view: N.V. It returns (s, t, depth) of the point found and counts its iterations.
#pragma once

#include <string>

#include "perpixel/perpixel_method.h"

namespace rtm {

extern const char* const kPerPixelVertexShader;
// The method's function, by method (perpixel/<method>_glsl.cpp).
const char* perpixel_trace_glsl(PerPixelMethod m);
// The complete fragment shader: #version, the switches of `common` as #defines, the frame and the method.
// quadric_exact: quadric silhouettes' exact distance (QuadricSilhouettesSettings::exact_distance); steep: protruded
// displacement mapping's texture for steep slopes (ProtrudedDisplacementSettings::steep_texture).
std::string perpixel_fragment_shader(PerPixelMethod m, const PerPixelCommon& common, bool quadric_exact = false,
                                     bool steep = false);

}  // namespace rtm
