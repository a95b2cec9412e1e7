// Relief mapping (Policarpo, Oliveira and Comba, I3D 2005): a linear search from A (depth 0) towards B (depth 1)
// for the first point inside the height field, then a binary search between it and the last point outside.
// With a convergence threshold the bisection stops once the sample is that close to the surface (the stopping
// rule interval mapping's paper uses to count iterations of both methods).
namespace rtm {

extern const char* const kReliefMappingGlsl;
const char* const kReliefMappingGlsl = R"(
vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters) {
    vec2 dir = V.xy / V.z;  // B = A + dir
    int n = clamp(u_linear_search_steps, 1, kMaxLoop);
    float size = 1.0 / float(n);
    float inside = 1.0;  // depth 1 is inside (or on) the height field everywhere
    // From A itself (i = 0): where the surface reaches the top of the range (depth 0), a ray entering over it has
    // hit; the first step would carry it up to 1/n of the range's depth further, over the edge of a plateau.
    for (int i = 0; i <= n; ++i) {
        float ray = float(i) * size;
        if (depth_at(A + dir * ray) <= ray) { inside = ray; break; }
    }
    float outside = max(inside - size, 0.0);
    g_linear_outside = outside;
    iters = 0;
    if (u_convergence_threshold > 0.0) {
        float mid = inside;
        for (int i = 0; i < min(u_max_iterations, kMaxLoop); ++i) {
            mid = 0.5 * (outside + inside);
            float surface = depth_at(A + dir * mid);
            ++iters;
            if (abs(surface - mid) < u_convergence_threshold) { inside = mid; break; }
            if (surface <= mid) inside = mid; else outside = mid;
        }
        return vec3(A + dir * inside, inside);
    }
    for (int i = 0; i < min(u_binary_search_steps, kMaxLoop); ++i) {
        float mid = 0.5 * (outside + inside);
        if (depth_at(A + dir * mid) <= mid) inside = mid; else outside = mid;
        ++iters;
    }
    return vec3(A + dir * inside, inside);
}
)";

}  // namespace rtm
