// Parallax occlusion mapping (Tatarchuk, I3D 2006): a linear search of nMinSamples..nMaxSamples steps (mixed by
// N.V), then the ray is intersected with the straight segment joining the height samples on either side of the
// crossing.
namespace rtm {

extern const char* const kParallaxOcclusionGlsl;
const char* const kParallaxOcclusionGlsl = R"(
vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters) {
    int n = steps_for(u_min_steps, u_max_steps, cos_view);
    float step = 1.0 / float(n);
    vec2 dir = V.xy / V.z;
    float prev_ray = 0.0, prev_surface = depth_at(A);
    iters = 1;
    if (prev_surface <= 0.0) return vec3(A, 0.0);
    float ray = 0.0, surface = prev_surface;
    for (int i = 0; i < n; ++i) {
        prev_ray = ray;
        prev_surface = surface;
        ray = float(i + 1) * step;
        surface = depth_at(A + dir * ray);
        ++iters;
        if (surface <= ray) break;
    }
    // g = surface - ray goes from > 0 to <= 0 over [prev_ray, ray]: where the straight segments cross.
    float g0 = prev_surface - prev_ray, g1 = surface - ray;
    float t = g0 - g1 > 1e-7 ? g0 / (g0 - g1) : 1.0;
    float d = mix(prev_ray, ray, t);
    return vec3(A + dir * d, d);
}
)";

}  // namespace rtm
