// Steep parallax mapping (McGuire and McGuire, I3D 2005 poster): march down the ray in equal depth steps, the
// number of steps growing as the view gets more oblique, and take the first sample below the surface as it is.
namespace rtm {

extern const char* const kSteepParallaxGlsl;
const char* const kSteepParallaxGlsl = R"(
vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters) {
    int n = steps_for(u_min_steps, u_max_steps, cos_view);
    float step = 1.0 / float(n);
    vec2 dst = V.xy / V.z * step;
    float ray = 0.0;
    vec2 st = A;
    float surface = depth_at(st);
    iters = 1;
    for (int i = 0; i < n && surface > ray; ++i) {
        ray += step;
        st += dst;
        surface = depth_at(st);
        ++iters;
    }
    return vec3(st, ray);
}
)";

}  // namespace rtm
