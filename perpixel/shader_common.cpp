#include "perpixel/shader_common.h"

namespace rtm {

// Positions are relative to the eye (computed in double on the CPU), as in the texture-mapping stage.
const char* const kPerPixelVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_rel;
layout(location = 1) in vec2 a_st;
uniform mat4 u_mvp_rel;
out vec3 v_rel;
out vec2 v_st;
void main() {
    v_rel = a_rel;
    v_st = a_st;
    gl_Position = u_mvp_rel * vec4(a_rel, 1.0);
}
)";

namespace {

// Declarations every method may use, before its trace().
constexpr const char* kPrelude = R"(
in vec3 v_rel;
in vec2 v_st;
uniform sampler2D u_color;   // colour, premultiplied by coverage alpha; image row 0 (top) at t = 0
uniform sampler2D u_relief;  // rgb: unit normal * 0.5 + 0.5 in (a, b, f); a: depth (254 - q) / 255
uniform sampler2D u_depth;   // r: exact depth (0 top .. 1 bottom) in float, read when RTM_FLOAT_DEPTH
uniform vec3 u_da, u_db, u_f;  // st = (dot(p - origin, u_da), dot(p - origin, u_db)); f the relief's normal
uniform float u_depth_range;   // max - min of the displacement, world units
uniform vec2 u_half_texel;     // (0.5 / width, 0.5 / height): the surface spans the texel centres
uniform vec3 u_top;            // eye-relative origin of the top plane (origin + f * max - eye)
uniform vec3 u_forward;        // the camera's view direction
uniform vec2 u_ndc;            // ndc z = u_ndc.x + u_ndc.y / Z for eye-space distance Z along u_forward
uniform vec3 u_light;          // world direction towards the light, unit
uniform float u_ambient;
uniform int u_shadow_steps;
// The methods' parameters, named as in perpixel_method.h.
uniform float u_scale, u_bias;
uniform int u_min_steps, u_max_steps;
uniform int u_linear_search_steps, u_binary_search_steps, u_max_iterations;
uniform float u_convergence_threshold;
uniform sampler2D u_steep;      // protruded displacement mapping's texture for steep slopes (RTM_STEEP), repeated
uniform vec4 u_steep_params;    // (threshold, scale_x, scale_y, s0)
layout(location = 0) out vec4 o_color;

const int kMaxLoop = 1024;  // bounds every loop whatever the uniforms say

// The linear search's last ray depth outside the height field (relief mapping's trace sets it): where protruded
// displacement mapping reads the height map that tells a steep slope (RTM_STEEP).
float g_linear_outside = 0.0;

// Depth (0 top .. 1 bottom) of the bilinearly filtered depth map at st (t up; the image's top row is t = 1).
float depth_at(vec2 st) {
#if RTM_PROTRUDED
    // No surface outside the footprint (the texel centres): rays pass by there.
    if (any(lessThan(st, u_half_texel)) || any(greaterThan(st, 1.0 - u_half_texel))) return 2.0;
#endif
#if RTM_FLOAT_DEPTH
    return textureLod(u_depth, vec2(st.x, 1.0 - st.y), 0.0).r;
#else
    return textureLod(u_relief, vec2(st.x, 1.0 - st.y), 0.0).a * (255.0 / 254.0);
#endif
}

// The number of linear steps for a view: mix(max, min, N.V), at least 1.
int steps_for(int min_steps, int max_steps, float cos_view) {
    return clamp(int(mix(float(max_steps), float(min_steps), clamp(cos_view, 0.0, 1.0)) + 0.5), 1, kMaxLoop);
}
)";

constexpr const char* kMain = R"(
void main() {
    vec3 V = normalize(v_rel);
    float cos_view = -dot(V, u_f);
    if (cos_view <= 1e-6) discard;  // seen from behind
    vec3 Vts = vec3(dot(V, u_da), dot(V, u_db), cos_view / u_depth_range);
#if RTM_PROTRUDED
    // A fragment of the base polygon or of a side face: its ray's point on the (extended) top plane.
    vec3 top = V * (dot(u_top, u_f) / dot(V, u_f));
    vec2 A = vec2(dot(top - u_top, u_da), dot(top - u_top, u_db));
#else
    vec3 top = v_rel;  // the fragment is on the top polygon
    vec2 A = v_st;
#endif
    int iters = 0;
    vec3 hit = trace(A, Vts, cos_view, iters);
    // Rays that leave the footprint find nothing: the relief exists over the quad only, and its surface (as the
    // ray caster's and the micro-polygons') spans the texel centres, half a texel inside the quad's border.
    if (any(lessThan(hit.xy, u_half_texel)) || any(greaterThan(hit.xy, 1.0 - u_half_texel))) discard;
    vec2 tc = vec2(hit.x, 1.0 - hit.y);
    vec4 c = textureLod(u_color, tc, 0.0);
    if (c.a < 0.5) discard;  // empty texels are holes
    vec3 rgb = c.rgb / c.a;
#if RTM_STEEP
    // Protruded displacement mapping's steep slopes (its section 4): the height map at the linear search's last point
    // outside (point 1) against the depth of the point found; far apart, the point is on a steep slope, coloured
    // from the second texture at s = (u + v) scale_x + s0, t = height scale_y. Outside the footprint (no surface:
    // depth_at says 2) point 1 counts as the bottom, so the relief's border is steep where it stands above it.
    {
        float h1 = min(depth_at(A + Vts.xy / Vts.z * g_linear_outside), 1.0);
        if (abs(h1 - hit.z) > u_steep_params.x) {
            vec2 wst = vec2((hit.x + hit.y) * u_steep_params.y + u_steep_params.w, (1.0 - hit.z) * u_steep_params.z);
            rgb = textureLod(u_steep, wst, 0.0).rgb;
        }
    }
#endif
#if RTM_SHADING
    {
        vec3 n = textureLod(u_relief, tc, 0.0).rgb * 2.0 - 1.0;  // in the (a^, b^, f) frame
        vec3 a_hat = normalize(u_da - dot(u_da, u_f) * u_f);    // a and b orthogonal (the relief quads here)
        vec3 b_hat = normalize(cross(u_f, a_hat));
        vec3 N = normalize(n.x * a_hat + n.y * b_hat + n.z * u_f);
        float lit = max(dot(N, u_light), 0.0);
#if RTM_SHADOWS
        // Relief mapping's self-shadowing: is there a surface point between where the light ray enters the
        // relief's slab (depth 0) and the point found? Linear steps from the entry point towards the point.
        float lz = dot(u_light, u_f) / u_depth_range;
        if (lz <= 0.0) {
            lit = 0.0;
        } else if (hit.z > 0.0) {
            vec2 L = vec2(dot(u_light, u_da), dot(u_light, u_db));
            vec2 C = hit.xy + L / lz * hit.z;
            int n_steps = clamp(u_shadow_steps, 1, kMaxLoop);
            for (int i = 1; i < n_steps; ++i) {
                float k = float(i) / float(n_steps);
                float d = hit.z * k;
                if (depth_at(mix(C, hit.xy, k)) < d - 0.5 / 254.0) { lit = 0.0; break; }
            }
        }
#endif
        rgb *= u_ambient + (1.0 - u_ambient) * lit;
    }
#endif
#if RTM_ITERATIONS
    o_color = vec4(vec3(float(min(iters, 255)) / 255.0), 1.0);
#else
    o_color = vec4(rgb, 1.0);
#endif
#if RTM_DEPTH
    // Depth correction: the depth of the point found, not of the polygon (relief mapping's section 3).
    vec3 p = top + V * (hit.z * u_depth_range / cos_view);
    gl_FragDepth = 0.5 * (u_ndc.x + u_ndc.y / dot(p, u_forward)) + 0.5;
#endif
}
)";

}  // namespace

extern const char* const kQuadricFragmentShader;

std::string perpixel_fragment_shader(PerPixelMethod m, const PerPixelCommon& c, bool quadric_exact, bool steep) {
    std::string s = "#version 330 core\n";
    s += "#define RTM_FLOAT_DEPTH " + std::to_string(c.float_textures ? 1 : 0) + "\n";
    s += "#define RTM_DEPTH " + std::to_string(c.depth_correction ? 1 : 0) + "\n";
    s += "#define RTM_SHADING " + std::to_string(c.shading ? 1 : 0) + "\n";
    s += "#define RTM_SHADOWS " + std::to_string(c.shading && c.self_shadowing ? 1 : 0) + "\n";
    s += "#define RTM_ITERATIONS " + std::to_string(c.iteration_counts ? 1 : 0) + "\n";
    if (m == PerPixelMethod::quadric_silhouettes) {
        s += "#define RTM_QUADRIC_EXACT " + std::to_string(quadric_exact ? 1 : 0) + "\n";
        return s + kQuadricFragmentShader;
    }
    s += "#define RTM_OFFSET_LIMITING " + std::to_string(m == PerPixelMethod::parallax_offset_limiting ? 1 : 0) + "\n";
    s += "#define RTM_PROTRUDED " + std::to_string(m == PerPixelMethod::protruded_displacement ? 1 : 0) + "\n";
    s += "#define RTM_STEEP " + std::to_string(m == PerPixelMethod::protruded_displacement && steep ? 1 : 0) + "\n";
    s += kPrelude;
    s += perpixel_trace_glsl(m);
    s += kMain;
    return s;
}

}  // namespace rtm
