#include "perpixel/perpixel_method.h"

#include <cmath>
#include <stdexcept>

#include "perpixel/shader_common.h"

namespace rtm {

extern const char* const kParallaxGlsl;
extern const char* const kSteepParallaxGlsl;
extern const char* const kParallaxOcclusionGlsl;
extern const char* const kReliefMappingGlsl;
extern const char* const kIntervalMappingGlsl;

namespace {

struct Named {
    PerPixelMethod method;
    const char* name;
};
constexpr Named kNames[] = {
    {PerPixelMethod::parallax, "parallax"},
    {PerPixelMethod::parallax_offset_limiting, "parallax-offset-limiting"},
    {PerPixelMethod::steep_parallax, "steep-parallax"},
    {PerPixelMethod::parallax_occlusion, "parallax-occlusion"},
    {PerPixelMethod::relief_mapping, "relief-mapping"},
    {PerPixelMethod::interval_mapping, "interval-mapping"},
    {PerPixelMethod::protruded_displacement, "protruded-displacement"},
    {PerPixelMethod::quadric_silhouettes, "quadric-silhouettes"},
};

void check_steps(const char* what, int n) {
    if (n < 1 || n > 1024)
        throw std::invalid_argument(std::string(what) + ": expected 1..1024 steps, found " + std::to_string(n));
}

void check_nonneg(const char* what, float x) {
    if (!(x >= 0.0f) || !std::isfinite(x))
        throw std::invalid_argument(std::string(what) + ": expected a finite value >= 0, found " + std::to_string(x));
}

void check_finite(const char* what, float x) {
    if (!std::isfinite(x)) throw std::invalid_argument(std::string(what) + ": not finite");
}

}  // namespace

std::optional<PerPixelMethod> parse_perpixel_method(const std::string& name) {
    for (const Named& n : kNames)
        if (name == n.name) return n.method;
    return std::nullopt;
}

std::string to_string(PerPixelMethod m) {
    for (const Named& n : kNames)
        if (m == n.method) return n.name;
    return "?";
}

std::vector<PerPixelMethod> all_perpixel_methods() {
    std::vector<PerPixelMethod> out;
    for (const Named& n : kNames) out.push_back(n.method);
    return out;
}

const char* perpixel_trace_glsl(PerPixelMethod m) {
    switch (m) {
        case PerPixelMethod::parallax:
        case PerPixelMethod::parallax_offset_limiting: return kParallaxGlsl;
        case PerPixelMethod::steep_parallax: return kSteepParallaxGlsl;
        case PerPixelMethod::parallax_occlusion: return kParallaxOcclusionGlsl;
        case PerPixelMethod::relief_mapping:
        case PerPixelMethod::protruded_displacement: return kReliefMappingGlsl;  // the paper's search
        case PerPixelMethod::quadric_silhouettes: return "";  // a shader of its own (quadric_silhouettes_glsl.cpp)
        case PerPixelMethod::interval_mapping: return kIntervalMappingGlsl;
    }
    throw std::logic_error("perpixel_trace_glsl: unknown method");
}

void PerPixelSettings::validate() const {
    check_finite("parallax scale", parallax.scale);
    check_finite("parallax bias", parallax.bias);
    check_steps("steep-parallax min_steps", steep_parallax.min_steps);
    check_steps("steep-parallax max_steps", steep_parallax.max_steps);
    check_steps("parallax-occlusion nMinSamples", parallax_occlusion.nMinSamples);
    check_steps("parallax-occlusion nMaxSamples", parallax_occlusion.nMaxSamples);
    check_steps("relief-mapping linear_search_steps", relief_mapping.linear_search_steps);
    if (relief_mapping.binary_search_steps < 0 || relief_mapping.binary_search_steps > 1024)
        throw std::invalid_argument("relief-mapping binary_search_steps: expected 0..1024, found " +
                                    std::to_string(relief_mapping.binary_search_steps));
    check_nonneg("relief-mapping convergence_threshold", relief_mapping.convergence_threshold);
    check_steps("relief-mapping max_iterations", relief_mapping.max_iterations);
    check_steps("interval-mapping linear_search_steps", interval_mapping.linear_search_steps);
    check_steps("interval-mapping max_iterations", interval_mapping.max_iterations);
    check_nonneg("interval-mapping convergence_threshold", interval_mapping.convergence_threshold);
    check_steps("protruded-displacement linear_search_steps", protruded_displacement.linear_search_steps);
    const ProtrudedDisplacementSettings& pd = protruded_displacement;
    if (!(pd.steep_threshold >= 0.0f && std::isfinite(pd.steep_threshold)))
        throw std::invalid_argument("protruded-displacement steep_threshold: expected a finite value >= 0, found " +
                                    std::to_string(pd.steep_threshold));
    for (const auto& [name, v] :
         {std::pair{"steep_scale_x", pd.steep_scale_x}, {"steep_scale_y", pd.steep_scale_y}, {"steep_s0", pd.steep_s0}})
        if (!std::isfinite(v))
            throw std::invalid_argument(std::string("protruded-displacement ") + name +
                                        ": expected a finite value, found " + std::to_string(v));
    if (protruded_displacement.binary_search_steps < 0 || protruded_displacement.binary_search_steps > 1024)
        throw std::invalid_argument("protruded-displacement binary_search_steps: expected 0..1024, found " +
                                    std::to_string(protruded_displacement.binary_search_steps));
    check_steps("quadric-silhouettes linear_search_steps", quadric_silhouettes.linear_search_steps);
    if (quadric_silhouettes.binary_search_steps < 0 || quadric_silhouettes.binary_search_steps > 1024)
        throw std::invalid_argument("quadric-silhouettes binary_search_steps: expected 0..1024, found " +
                                    std::to_string(quadric_silhouettes.binary_search_steps));
    if (!(quadric_silhouettes.angle > 0.0 && quadric_silhouettes.angle < 6.0))
        throw std::invalid_argument("quadric-silhouettes angle: expected 0 < angle < 6 radians, found " +
                                    std::to_string(quadric_silhouettes.angle));
    if (quadric_silhouettes.segments < 1 || quadric_silhouettes.segments > 4096 || quadric_silhouettes.rows < 1 ||
        quadric_silhouettes.rows > 4096)
        throw std::invalid_argument("quadric-silhouettes segments x rows: expected 1..4096 each, found " +
                                    std::to_string(quadric_silhouettes.segments) + "x" +
                                    std::to_string(quadric_silhouettes.rows));
    check_steps("shadow_steps", common.shadow_steps);
    check_nonneg("ambient", common.ambient);
    const glm::dvec3& l = common.light_dir;
    if (!std::isfinite(l.x) || !std::isfinite(l.y) || !std::isfinite(l.z) || (l.x == 0 && l.y == 0 && l.z == 0))
        throw std::invalid_argument("light_dir: expected a finite non-zero direction");
}

}  // namespace rtm
