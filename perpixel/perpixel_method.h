// The per-pixel relief methods of the comparison (issue #22): their names (as `rtm render --method` and
// results.csv spell them) and their settings, each parameter named as its paper names it, with the paper's
// recommended default. The shaders are in one file per method (perpixel/*_glsl.cpp); PerPixelQuad draws them.
#pragma once

#include <glm/vec3.hpp>

#include <optional>
#include <string>
#include <vector>

namespace rtm {

enum class PerPixelMethod {
    parallax,                  // Kaneko et al., "Detailed shape representation with parallax mapping", ICAT 2001
    parallax_offset_limiting,  // Welsh, "Parallax mapping with offset limiting", Infiniscape tech. report 2004
    steep_parallax,            // McGuire and McGuire, "Steep parallax mapping", I3D 2005 poster
    parallax_occlusion,        // Tatarchuk, "Dynamic parallax occlusion mapping with approximate soft shadows",
                               // I3D 2006
    relief_mapping,            // Policarpo, Oliveira, Comba, "Real-time relief mapping on arbitrary polygonal
                               // surfaces", I3D 2005
    interval_mapping,          // Risser, Shah, Pattanaik, "Interval mapping", I3D 2006 poster / tech. report
    protruded_displacement,    // Yoo, "Protruded displacement mapping for image-based urban representation",
                               // IEICE Electronics Express 8(13), 2011
    quadric_silhouettes,       // Oliveira and Policarpo, "An efficient representation for surface details",
                               // UFRGS tech. report RP-351, 2005
};

// "parallax", "parallax-offset-limiting", ...; nullopt for a name that is not a per-pixel method.
std::optional<PerPixelMethod> parse_perpixel_method(const std::string& name);
std::string to_string(PerPixelMethod m);
std::vector<PerPixelMethod> all_perpixel_methods();

// Parallax mapping: the texture coordinate is shifted by the displacement read at the fragment, offset =
// (depth * scale + bias) * V.xy / V.z (Kaneko et al.), or * V.xy without the division by V.z (Welsh's offset
// limiting). The polygon is drawn at the top of the relief, so depth (0 at the top, 1 at the bottom of the
// displacement range) plays the part of the papers' height and scale = 1, bias = 0 put the shift where the ray
// reaches that depth: the exact answer on a flat relief at any depth.
struct ParallaxSettings {
    float scale = 1.0f;
    float bias = 0.0f;
    bool operator==(const ParallaxSettings&) const = default;
};

// Steep parallax mapping: a linear search from the top, n steps with n going from max_steps at grazing views
// to min_steps at normal incidence (n = mix(max_steps, min_steps, N.V)); the first sample under the surface is
// the answer (no refinement).
struct SteepParallaxSettings {
    int min_steps = 10;
    int max_steps = 60;
    bool operator==(const SteepParallaxSettings&) const = default;
};

// Parallax occlusion mapping: the same linear search with nMinSamples..nMaxSamples (mixed by N.V as above,
// Tatarchuk's defaults 8 and 50), then the intersection of the ray with the segment joining the last two height
// samples.
struct ParallaxOcclusionSettings {
    int nMinSamples = 8;
    int nMaxSamples = 50;
    bool operator==(const ParallaxOcclusionSettings&) const = default;
};

// Relief mapping: a linear search of linear_search_steps equal steps from depth 0 to 1 ("no more than 32"),
// then binary_search_steps bisections of the last interval ("eight steps of binary subdivision is sufficient").
// convergence_threshold > 0 instead stops the bisection once |surface depth - ray depth| at the last sample is
// below it (at most max_iterations): the stopping rule under which interval mapping's paper counts iterations.
struct ReliefMappingSettings {
    int linear_search_steps = 32;
    int binary_search_steps = 8;
    float convergence_threshold = 0.0f;
    int max_iterations = 10;
    bool operator==(const ReliefMappingSettings&) const = default;
};

// Interval mapping: the same linear search, then the bracketing interval is reduced by intersecting the ray with
// the line through the two surface samples at its ends (the paper's listing: at most 10 iterations, until
// |surface depth - ray depth| < 0.01).
struct IntervalMappingSettings {
    int linear_search_steps = 32;
    int max_iterations = 10;
    float convergence_threshold = 0.01f;
    bool operator==(const IntervalMappingSettings&) const = default;
};

// Protruded displacement mapping: the base polygon at the bottom of the displacement range plus four faces
// perpendicular to it along its border, from the bottom to the top of the range. Each fragment, on the base or on
// a side face, maps its eye ray to where it meets the (extended) base plane and searches it from the top of the
// range down with relief mapping's linear then binary search; outside the footprint there is no surface, so rays
// that enter or leave through the border find the relief standing out beyond the base polygon (the paper's
// "displacement overflow").
// The paper's extra texture for steep slopes (its section 4), with steep_texture: where the height map at the
// linear search's last point outside the surface differs from the depth of the point found by more than
// steep_threshold (depth units, 0 to 1), the point is on a steep slope and takes its colour from a second texture
// (PerPixelQuad::set_steep_texture; a built-in brick course, perpixel/steep_texture.h, unless set), repeated, at
// s = (u + v) * steep_scale_x + steep_s0, t = height * steep_scale_y (height = 1 - depth).
struct ProtrudedDisplacementSettings {
    int linear_search_steps = 32;
    int binary_search_steps = 8;
    bool steep_texture = false;
    float steep_threshold = 0.1f;
    float steep_scale_x = 4.0f, steep_scale_y = 1.0f, steep_s0 = 0.0f;
    bool operator==(const ProtrudedDisplacementSettings&) const = default;
};

// The curved base of quadric silhouettes (perpixel/curved_patch.h): a cylinder (one principal curvature, the
// paper's Figure 7 (c)) or a sphere (two, a paraboloid locally: Figure 7 (a)).
enum class CurvedShape { cylinder, sphere };

// Relief mapping with quadric silhouettes: the relief on a cylinder or sphere patch (perpixel/curved_patch.h) bent
// through `angle` radians along a, `segments` x `rows` quads with per-vertex quadric coefficients; the search is
// relief mapping's (linear, then binary) over the part of the ray inside the quadric shell; rays that leave it are
// silhouettes.
// Shading uses the relief map's normal in the fragment's frame; self-shadowing tests the light ray inside the quadric
// shell (docs/PERPIXEL.md); iteration counts write the binary steps.
struct QuadricSilhouettesSettings {
    int linear_search_steps = 32;
    int binary_search_steps = 8;
    // The ray-quadric distance: false, the paper's faster approximate one (its equation 7, section 3.2, which it
    // uses); true, its exact one (equation 6, section 3.1, along the unit vector perpendicular to the ray), with
    // equation 7 where equation 6 has no root and the search range from equation 5 (perpixel/quadric_distance.h).
    bool exact_distance = false;
    CurvedShape base = CurvedShape::cylinder;
    double angle = 1.2;
    int segments = 32;
    int rows = 4;  // the sphere needs more than the cylinder's 4 (it curves along b too): 32 x 32 is a fine mesh
    // false: the quadric coefficients are zero, the original relief mapping on the curved mesh (the paper's
    // Figure 9, left): no ray leaves, the silhouette is the mesh's.
    bool quadric = true;
    // The patch `shape` with its mesh's rows: the cylinder's default 4, as many as the segments on the sphere (what
    // rtm render --curved-base, the viewer's panel and rtm compare draw).
    void set_base(CurvedShape shape) {
        base = shape;
        rows = shape == CurvedShape::sphere ? segments : QuadricSilhouettesSettings{}.rows;
    }
    bool operator==(const QuadricSilhouettesSettings&) const = default;
};

// What every method shares. The comparison shows unlit colour (as the pre-warp does); `shading` multiplies it by
// a Lambert term from normals derived from the displacement, `self_shadowing` (relief mapping's section 3.2, used
// by every method here) tests the segment towards the light for an occluder with shadow_steps linear steps.
struct PerPixelCommon {
    bool depth_correction = true;  // gl_FragDepth at the found point, as relief mapping's paper describes
    bool shading = false;
    bool self_shadowing = false;
    int shadow_steps = 32;
    glm::dvec3 light_dir{0.3, 0.5, 0.8};  // world direction towards the light (normalized when used)
    float ambient = 0.25f;
    // Write the number of refinement iterations per pixel (grey level = count, 0..255) instead of the colour:
    // the images of interval mapping's Figure 5. Methods without refinement write their linear steps.
    bool iteration_counts = false;
    // Colour and depth from float textures, filtered in float: the colour's 8-bit values in GL_RGBA32F, the depth
    // from the exact displacement in GL_R32F. false: the papers' textures, colour in RGBA8 and depth in the relief
    // map's 8-bit alpha (254 quantization levels), both filtered in 8 bits by llvmpipe (docs/PERPIXEL.md).
    bool float_textures = true;
    bool operator==(const PerPixelCommon&) const = default;
};

struct PerPixelSettings {
    PerPixelCommon common;
    ParallaxSettings parallax;
    SteepParallaxSettings steep_parallax;
    ParallaxOcclusionSettings parallax_occlusion;
    ReliefMappingSettings relief_mapping;
    IntervalMappingSettings interval_mapping;
    ProtrudedDisplacementSettings protruded_displacement;
    QuadricSilhouettesSettings quadric_silhouettes;
    // Throws std::invalid_argument naming the first bad value (steps < 1, thresholds < 0, non-finite).
    void validate() const;
    bool operator==(const PerPixelSettings&) const = default;
};

}  // namespace rtm
