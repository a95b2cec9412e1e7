// Relief mapping with quadric silhouettes (Oliveira and Policarpo 2005) on a curved base mesh. Each vertex carries
// its tangent frame and the coefficients (a, b) of the quadric z = a x^2 + b y^2 fitted to the mesh around it,
// interpolated over the triangles. A fragment's eye ray, in texture space (equation 9: V_t = (V.T / s_x, V.B / s_y,
// V.N / s_z)), goes deeper into the relief's shell by D(t) = -V_t.z t - (alpha V_t.x^2 + beta V_t.y^2) t^2 below the
// quadric (equation 7, the paper's faster approximate distance, with alpha = a s_x^2 / s_z and beta = b s_y^2 / s_z,
// equation 8), or, with RTM_QUADRIC_EXACT, by the exact distance of equation 6 (along the unit vector perpendicular
// to the ray in the plane of the ray and the normal), falling back to equation 7 where it has no root. The search
// runs over [0, t_max] (section 3.3: where D reaches 1, or returns to 0), linear then binary as in relief mapping; a
// ray that returns to depth 0 without meeting the relief is a silhouette and is discarded. perpixel/quadric_distance.h
// is the reference of both distances and of the range: the functions below are its steps in float.
namespace rtm {

extern const char* const kQuadricVertexShader;
const char* const kQuadricVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_rel;
layout(location = 1) in vec3 a_normal;
layout(location = 2) in vec3 a_tangent;
layout(location = 3) in vec3 a_binormal;
layout(location = 4) in vec2 a_st;
layout(location = 5) in vec2 a_quadric;
layout(location = 6) in vec2 a_tile;
uniform mat4 u_mvp_rel;
out vec3 v_rel, v_normal, v_tangent, v_binormal;
out vec2 v_st, v_quadric, v_tile;
void main() {
    v_tile = a_tile;
    v_rel = a_rel;
    v_normal = a_normal;
    v_tangent = a_tangent;
    v_binormal = a_binormal;
    v_st = a_st;
    v_quadric = a_quadric;
    gl_Position = u_mvp_rel * vec4(a_rel, 1.0);
}
)";

extern const char* const kQuadricFragmentShader;
const char* const kQuadricFragmentShader = R"(
in vec3 v_rel, v_normal, v_tangent, v_binormal;
in vec2 v_st, v_quadric, v_tile;
uniform sampler2D u_color;
uniform sampler2D u_relief;
uniform sampler2D u_depth;
uniform float u_depth_range;  // s_z: the relief's depth (the tile's width and height s_x, s_y come per vertex)
uniform vec2 u_half_texel;
uniform vec3 u_forward;
uniform vec2 u_ndc;
uniform int u_linear_search_steps, u_binary_search_steps;
uniform vec3 u_light;  // world direction towards the light, unit
uniform float u_ambient;
uniform int u_shadow_steps;
layout(location = 0) out vec4 o_color;

const int kMaxLoop = 1024;

// The roots of a x^2 + b x + c = 0 in the stable form; false when there is none (quadric_distance.cpp's roots()).
bool roots(float a, float b, float c, out float r1, out float r2) {
    if (a == 0.0) {
        if (b == 0.0) return false;
        r1 = r2 = -c / b;
        return true;
    }
    float disc = b * b - 4.0 * a * c;
    if (disc < 0.0) return false;
    float q = -0.5 * (b + (b >= 0.0 ? 1.0 : -1.0) * sqrt(disc));
    r1 = q / a;
    r2 = q != 0.0 ? c / q : r1;
    return true;
}

// Equation 6 at P = v t, or equation 7's depth C where it has no root of the right sign (exact = false): see
// quadric_depth_exact().
float depth_exact(vec3 v, vec3 U, float alpha, float beta, float t, out bool exact) {
    vec3 P = v * t;
    float C = alpha * P.x * P.x + beta * P.y * P.y - P.z;
    exact = false;
    if (!(U.z > 0.0)) return C;
    exact = true;
    if (C == 0.0) return 0.0;
    float A = alpha * U.x * U.x + beta * U.y * U.y;
    float B = 2.0 * (alpha * P.x * U.x + beta * P.y * U.y) - U.z;
    float r1, r2;
    float best = 0.0;
    if (roots(A, B, C, r1, r2)) {
        if ((C > 0.0 ? r1 > 0.0 : r1 < 0.0)) best = r1;
        if ((C > 0.0 ? r2 > 0.0 : r2 < 0.0) && (best == 0.0 || abs(r2) < abs(best))) best = r2;
    }
    exact = best != 0.0;
    return exact ? best : C;
}

// The ray's depth under the quadric at t: equation 6 or equation 7.
float depth(vec3 v, vec3 U, float alpha, float beta, float c1, float k, float t) {
#if RTM_QUADRIC_EXACT
    bool exact;
    return depth_exact(v, U, alpha, beta, t, exact);
#else
    return c1 * t - k * t * t;
#endif
}

float depth_at(vec2 st) {
#if RTM_FLOAT_DEPTH
    return textureLod(u_depth, vec2(st.x, 1.0 - st.y), 0.0).r;
#else
    return textureLod(u_relief, vec2(st.x, 1.0 - st.y), 0.0).a * (255.0 / 254.0);
#endif
}

void main() {
    vec3 V = normalize(v_rel);
    vec3 N = normalize(v_normal), T = normalize(v_tangent), B = normalize(v_binormal);
    vec3 size = vec3(v_tile, u_depth_range);  // (s_x, s_y, s_z), section 3.4
    vec3 Vt = vec3(dot(V, T) / size.x, dot(V, B) / size.y, dot(V, N) / size.z);
    float c1 = -Vt.z;
    if (c1 <= 1e-9) discard;  // seen from behind
    float alpha = v_quadric.x * size.x * size.x / size.z;
    float beta = v_quadric.y * size.y * size.y / size.z;
    float k = -(alpha * Vt.x * Vt.x + beta * Vt.y * Vt.y);  // equation 7: D(t) = c1 t - k t^2
    // The search range (quadric_search_range()): back at depth 0 at t_leave (k > 0), at the bottom at t_bottom.
    float t_leave = k > 0.0 ? c1 / k : -1.0;
    float disc7 = c1 * c1 - 4.0 * k;  // equation 7 at depth 1; none when the ray comes back out first
    float t7 = disc7 >= 0.0 ? 2.0 / (c1 + sqrt(disc7)) : -1.0;
    float t_bottom = t7;
#if RTM_QUADRIC_EXACT
    // U: perpendicular to the ray in the plane of the ray and the normal (0, 0, 1), outwards; none along the normal.
    vec3 vn = normalize(Vt);
    vec3 w = vec3(0.0, 0.0, 1.0) - vn.z * vn;
    float sin_angle = length(w);
    vec3 U = sin_angle < 1e-6 ? vec3(0.0) : w / sin_angle;
    if (U.z > 0.0) {
        // The first t where s = 1 solves equation 5 with P inside and 1 the nearest root of its side (the other is
        // C / A), or equation 7's bottom where equation 7 stands in for equation 6.
        float A = alpha * U.x * U.x + beta * U.y * U.y;
        t_bottom = -1.0;
        float r[2];
        if (roots(-k, 2.0 * (alpha * Vt.x * U.x + beta * Vt.y * U.y) - Vt.z, A - U.z, r[0], r[1]))
            for (int i = 0; i < 2; ++i) {
                float t = r[i];
                vec3 P = Vt * t;
                float C = alpha * P.x * P.x + beta * P.y * P.y - P.z;
                bool nearest = !(A != 0.0 && C / A > 0.0 && C / A < 1.0);
                if (t > 0.0 && C > 0.0 && nearest && (t_bottom < 0.0 || t < t_bottom)) t_bottom = t;
            }
        bool exact7;
        if (t7 > 0.0) {
            depth_exact(Vt, U, alpha, beta, t7, exact7);  // only whether equation 6 answers at t7
            if (!exact7 && (t_bottom < 0.0 || t7 < t_bottom)) t_bottom = t7;
        }
        if (t_bottom < 0.0 && t_leave < 0.0) t_bottom = t7;  // neither found: equation 7's range
    }
#else
    vec3 U = vec3(0.0);
#endif
    bool leaves = t_leave > 0.0 && (t_bottom < 0.0 || t_leave < t_bottom);
    float t_max = leaves ? t_leave : t_bottom;
    int n = clamp(u_linear_search_steps, 1, kMaxLoop);
    float t_in = -1.0, t_out = 0.0;
    for (int i = 0; i <= n; ++i) {  // from the entry point itself (i = 0), as in relief_mapping_glsl.cpp
        float t = t_max * float(i) / float(n);
        float D = depth(Vt, U, alpha, beta, c1, k, t);
        // The last sample of a ray that does not leave is at depth 1, the bottom: inside whatever rounding says.
        if (D >= depth_at(v_st + Vt.xy * t) || (i == n && !leaves)) { t_in = t; break; }
        t_out = t;
    }
    if (t_in < 0.0) discard;  // the ray left the surface: silhouette
    for (int i = 0; i < min(u_binary_search_steps, kMaxLoop); ++i) {
        float t = 0.5 * (t_in + t_out);
        float D = depth(Vt, U, alpha, beta, c1, k, t);
        if (D >= depth_at(v_st + Vt.xy * t)) t_in = t; else t_out = t;
    }
    vec2 st = v_st + Vt.xy * t_in;
    if (any(lessThan(st, u_half_texel)) || any(greaterThan(st, 1.0 - u_half_texel))) discard;
    vec2 tc = vec2(st.x, 1.0 - st.y);
    vec4 c = textureLod(u_color, tc, 0.0);
    if (c.a < 0.5) discard;
    vec3 rgb = c.rgb / c.a;
#if RTM_SHADING
    {
        // The relief map's normal (in the relief's (a, b, f) frame) in the fragment's frame on the curved surface.
        vec3 nm = textureLod(u_relief, tc, 0.0).rgb * 2.0 - 1.0;
        vec3 Nw = normalize(nm.x * T + nm.y * B + nm.z * N);
        float lit = max(dot(Nw, u_light), 0.0);
#if RTM_SHADOWS
        // Relief mapping's shadow test on the curved shell: from the point found, H = Vt t_in in the fragment's
        // texture space, towards the light (L_t, texture space as the view ray) until the light ray leaves the
        // quadric shell (its depth, equation 7 at any point, back at 0): shadowed where the surface stands above it.
        vec3 Lt = vec3(dot(u_light, T) / size.x, dot(u_light, B) / size.y, dot(u_light, N) / size.z);
        vec3 H = Vt * t_in;
        float dH = alpha * H.x * H.x + beta * H.y * H.y - H.z;
        if (Lt.z <= 0.0) {
            lit = 0.0;  // the light is below the base surface here
        } else if (dH > 0.0) {
            // depth(u) = qa u^2 + qb u + dH along P = H + Lt u: its first zero after 0 (none: the shell's bottom,
            // depth 1, ends the test instead).
            float qa = alpha * Lt.x * Lt.x + beta * Lt.y * Lt.y;
            float qb = 2.0 * (alpha * H.x * Lt.x + beta * H.y * Lt.y) - Lt.z;
            float u_exit = -1.0, r1, r2;
            if (roots(qa, qb, dH, r1, r2)) {
                if (r1 > 0.0) u_exit = r1;
                if (r2 > 0.0 && (u_exit < 0.0 || r2 < u_exit)) u_exit = r2;
            }
            if (u_exit > 0.0) {
                int n_steps = clamp(u_shadow_steps, 1, kMaxLoop);
                for (int i = 1; i < n_steps; ++i) {
                    float u = u_exit * float(n_steps - i) / float(n_steps);  // from the exit towards H
                    vec3 P = H + Lt * u;
                    float d = alpha * P.x * P.x + beta * P.y * P.y - P.z;
                    vec2 sp = v_st + P.xy;
                    bool inside = all(greaterThanEqual(sp, u_half_texel)) && all(lessThanEqual(sp, 1.0 - u_half_texel));
                    if (inside && depth_at(sp) < d - 0.5 / 254.0) { lit = 0.0; break; }
                }
            }
        }
#endif
        rgb *= u_ambient + (1.0 - u_ambient) * lit;
    }
#endif
#if RTM_ITERATIONS
    o_color = vec4(vec3(float(u_binary_search_steps) / 255.0), 1.0);
#else
    o_color = vec4(rgb, 1.0);
#endif
#if RTM_DEPTH
    vec3 p = v_rel + V * t_in;  // t is the distance along the unit view direction
    gl_FragDepth = 0.5 * (u_ndc.x + u_ndc.y / dot(p, u_forward)) + 0.5;
#endif
}
)";

}  // namespace rtm
