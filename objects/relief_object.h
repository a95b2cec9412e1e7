// A six-face image-based object (paper section 4.1) drawn as at most three relief quads.
//
// For a view, classify_region (objects/object_region.h) says which faces are visible (one, two or three). For each
// visible face F: the adjacent faces whose samples can land on F (faces_warped_onto) are pre-warped onto F's plane
// with their axes swapped (objects/face_swap.h, Figure 15), and F itself with the single relief's kernels
// (warp/prewarp.h); F's samples win, the adjacent samples are kept only where F left a hole (the paper's order:
// adjacent faces first, F over them). F is pre-warped first, so that the adjacent faces are warped only where it left
// holes (AdjacentNeed; the same texture as warping them whole, DrawOptions::adjacent_holes_only). The
// result is texture-mapped onto F's quad, after closing the cracks one pixel wide that the line warp leaves where a
// surface seen by F meets one seen by an adjacent face (half a texel is missing on each side of a discontinuity).
// Samples of F that leave its quad are not lost: they land on the neighbouring visible face when that face pre-warps F,
// so no side polygons are needed (nor drawn) for an object.
//
// Skips (names as for a single relief, objects/relief_quad.h), planned per face by plan_object_face
// (objects/object_plan.h): back-facing (the faces not visible: not pre-warped, not drawn), outside-frustum (per
// visible face), subpixel-parallax (per visible face: when the box's whole depth moves by less than the threshold the
// face is drawn as a plain texture), reuse-prewarp (per visible face: the eye barely moved for every point of the box
// behind it, and the same faces are pre-warped onto it: neither pre-warped nor uploaded again), partial-upload
// (reported when a face's texture already holds what is drawn: nothing is uploaded; a new pre-warp is uploaded whole),
// inside-slab-micromesh (the eye inside the box: the six faces' micro-polygon meshes are drawn). Depth correction
// (section 4.2): the depth seen at each pixel of F's pre-warped texture (F's own or an adjacent face's, along F's
// normal) is quantized over the box's depth behind F and scales the fragment depth by 1 + k3*d, so the faces occlude
// each other and other geometry.
//
// Limitations: the adjacent faces are reconstructed two-pass with point sampling whatever the face's own method and
// filter, in double precision (objects/face_swap.h); they are most of an object's pre-warp time
// (docs/BENCHMARKS.md, docs/OBJECTS.md).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "objects/bounds.h"
#include "objects/face_swap.h"
#include "objects/object_plan.h"
#include "objects/object_region.h"
#include "objects/relief_quad.h"
#include "warp/box_faces.h"

namespace rtm {

// One visible face's pre-warped texture (Figure 17), the same size as the face at its pyramid level.
// A crack closed in a face's composite texture: the pixel (index into the image), its colour and depth level.
struct CrackFill {
    size_t at = 0;
    Rgba8 color;
    uint8_t displ = 0;
};

struct ObjectFacePrewarp {
    int face = -1;
    int level = 0;
    std::vector<int> adjacent;  // the faces pre-warped onto it first
    ImageRGBA8 image;           // alpha 0 where nothing landed
    Image2D<uint8_t> displ;     // with depth correction: depth along F's normal, quantized by depth_quant (255 none)
    Quantizer depth_quant;
    PrewarpCoefficients k;
    Isa isa = Isa::generic;         // the target the face's own pre-warp ran on (PrewarpStats::isa)
    double prewarp_ms = 0.0;        // adjacent faces and the face itself
    double adjacent_ms = 0.0;       // of which the adjacent faces
    long long texels = 0;           // source texels visited (the face and its adjacent faces)
    long long adjacent_pixels = 0;  // pixels filled by adjacent faces' samples
    long long crack_pixels = 0;     // one-pixel cracks closed between the face's and the adjacent faces' samples
};

struct ObjectFaceReport {
    int face = -1;
    int level = 0;
    std::vector<int> adjacent;
    double prewarp_ms = 0.0;
    double adjacent_ms = 0.0;  // of which pre-warping the adjacent faces onto it
    std::vector<std::string> skips;
};

struct ObjectReport {
    ObjectRegion region;
    std::vector<ObjectFaceReport> faces;  // the faces drawn (visible and not skipped), in kFaceKeys order
    std::vector<std::string> skips;       // every skip that fired, once
    // Skip name -> the faces it fired for (back-facing: the faces not visible; inside-slab-micromesh: all six; the
    // others per visible face), as a scene's --json counts them.
    std::map<std::string, int> skip_faces;
};

class ReliefObject {
public:
    // With `shared`, face k's pyramid levels and spreads come from shared[k] (shared with the other placements of the
    // same object in a scene: objects/shared_relief.h); null entries make their own.
    using FaceShares = std::array<std::shared_ptr<SharedRelief>, kFaceCount>;
    explicit ReliefObject(SixFaceObject object, const FaceShares& shared = {});
    ~ReliefObject();
    ReliefObject(ReliefObject&&) noexcept;

    const std::string& name() const { return name_; }
    const Box& box() const { return box_; }
    Bounds bounds() const;
    ReliefQuad& face(int f) { return quads_[size_t(f)]; }
    ObjectRegion region(const glm::dvec3& eye) const { return classify_region(box_, eye); }
    // Texels at level 0 over the six faces.
    long long texels() const;

    // Pre-warps visible face `face` for `eye` at pyramid `level` (clamped): the face itself and its adjacent faces,
    // keeping the adjacent samples where the face left holes (the paper's order: adjacent faces first, the face over
    // them). With `adjacent_holes_only` the face is pre-warped first and the adjacent faces only where it left holes
    // (AdjacentNeed, objects/face_swap.h): the same result, value for value, as warping them whole (false).
    // options.keep_outliers is ignored (no side polygons). Throws std::invalid_argument if the face is not visible
    // from `eye`.
    void prewarp_face(int face, const glm::dvec3& eye, int level, const PrewarpOptions& options, bool with_displ,
                      ObjectFacePrewarp& out, bool adjacent_holes_only = true);

    // Draws with `method` (flat, two_pass or pipelined) into the current frame; requires a current GL context.
    void draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
              StageTimes& times, const DrawOptions& draw = {}, ObjectReport* report = nullptr);
    // The ground truth: the six faces' micro-polygon meshes. With `tiles`, from copies kept on the GPU, only their
    // tiles not wholly outside the frustum (ReliefQuad::draw_micromesh): the same picture.
    void draw_micromesh(Renderer& renderer, const Camera& cam, bool tiles = false);
    // What the last draw() mapped on face f (for the viewer's insets): the texture (null before the face was first
    // drawn) and the pre-warp it holds.
    const GlTexture* face_texture(int f) const { return textures_[size_t(f)].get(); }
    const ObjectFacePrewarp& face_prewarp(int f) const { return warped_[size_t(f)]; }

private:
    std::string name_;
    Box box_;
    std::vector<ReliefQuad> quads_;
    PrewarpWorkspace workspace_;
    AdjacentWorkspace adjacent_ws_;
    AdjacentBuffer adjacent_;
    AdjacentNeed need_;
    std::array<std::vector<AdjacentChunks>, kFaceCount> chunks_;  // per face and pyramid level, made on first use
    Image2D<uint8_t> own_displ_;
    std::vector<std::vector<CrackFill>> cracks_;  // per block of 16 rows, the cracks a face's composite closes
    std::array<ObjectFacePrewarp, kFaceCount> warped_;
    std::array<std::unique_ptr<GlTexture>, kFaceCount> textures_, displ_textures_;
    // Per face: the pre-warp warped_ holds (for the reuse skip), how many pre-warps it has had, and what its texture
    // holds (content and pre-warp count when uploaded; none after a draw with skips off).
    std::array<LastFacePrewarp, kFaceCount> last_;
    std::array<long long, kFaceCount> versions_{}, uploaded_versions_{};
    std::array<TextureContent, kFaceCount> uploaded_;
};

// One frame of an object with any method (flat, two-pass, pipelined, micromesh), begin_frame included; returns
// the image read back. `times` accumulates the stage times.
ImageRGBA8 render_object_frame(ReliefObject& object, Renderer& renderer, const Camera& cam, RenderMethod method,
                               const PrewarpOptions& options, const DrawOptions& draw, StageTimes& times,
                               ObjectReport* report = nullptr);

}  // namespace rtm
