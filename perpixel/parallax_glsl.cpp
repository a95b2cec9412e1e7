// Parallax mapping (Kaneko et al., ICAT 2001) and parallax mapping with offset limiting (Welsh 2004): one depth
// look-up at the fragment, then a shift of the texture coordinate along the view direction. Kaneko divides by
// V.z (the shift where the ray reaches the depth read); Welsh drops the division so the shift never exceeds the
// depth itself (no swimming at grazing angles, at the price of too small a shift there).
namespace rtm {

extern const char* const kParallaxGlsl;
const char* const kParallaxGlsl = R"(
vec3 trace(vec2 A, vec3 V, float cos_view, inout int iters) {
    float d = depth_at(A);
    iters = 1;
    float h = d * u_scale + u_bias;  // the papers' (height * scale + bias), here measured down from the top
#if RTM_OFFSET_LIMITING
    vec2 offset = h * u_depth_range * V.xy;  // V.xy: st per world length along the ray; h * range world units
#else
    vec2 offset = h * V.xy / V.z;
#endif
    return vec3(A + offset, d);
}
)";

}  // namespace rtm
