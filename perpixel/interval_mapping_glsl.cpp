// Interval mapping (Risser, Shah and Pattanaik 2006): the linear search of relief mapping finds an interval
// [upper, lower] of the ray that brackets the first intersection; each iteration intersects the ray with the line
// through the surface samples at the interval's ends (a secant step kept inside the bracket) and makes that point
// the new upper or lower bound, until the surface there is within the threshold of the ray (at most
// max_iterations). In (ray depth, surface depth) the paper's 2-D ray-line intersection is the root of the linear
// interpolation of g = surface - ray between the bounds, which is what is computed here.
namespace rtm {

extern const char* const kIntervalMappingGlsl;
const char* const kIntervalMappingGlsl = R"(
vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters) {
    vec2 dir = V.xy / V.z;
    int n = clamp(u_linear_search_steps, 1, kMaxLoop);
    float size = 1.0 / float(n);
    float lower_d = 1.0, lower_s = depth_at(A + dir);
    for (int i = 0; i <= n; ++i) {  // from A itself, as relief mapping's search (relief_mapping_glsl.cpp)
        float ray = float(i) * size;
        float s = depth_at(A + dir * ray);
        if (s <= ray) { lower_d = ray; lower_s = s; break; }
    }
    if (lower_d <= 0.0) { iters = 1; return vec3(A, 0.0); }  // the surface at the top, where the ray enters
    float upper_d = max(lower_d - size, 0.0);
    float upper_s = depth_at(A + dir * upper_d);
    float best = lower_d;
    iters = 0;
    for (int i = 0; i < min(u_max_iterations, kMaxLoop); ++i) {
        float gu = upper_s - upper_d, gl = lower_s - lower_d;  // gu > 0 (outside), gl <= 0 (inside)
        float t = gu - gl > 1e-7 ? upper_d + gu * (lower_d - upper_d) / (gu - gl) : lower_d;
        float s = depth_at(A + dir * t);
        ++iters;
        best = t;
        if (abs(s - t) < u_convergence_threshold) break;
        if (s > t) { upper_d = t; upper_s = s; } else { lower_d = t; lower_s = s; }
    }
    return vec3(A + dir * best, best);
}
)";

}  // namespace rtm
