// What `rtm compare` renders: one relief texture, one six-face object or one scene, behind one interface so the
// comparison loop does not care which. A relief renders every method of the sweep (measure/compare_sweep.h) and
// has both truths (raycast, micromesh); an object or a scene renders flat, the pre-warp and micromesh only: the
// per-pixel methods and the ray caster trace one height field, so their rows are omitted there, and micromesh is
// the truth the errors are measured against. Only a relief renders the curved bases (CompareEntry::curved()): the
// relief bent over the cylinder or the sphere patch of quadric silhouettes, and their truths, the curved
// micro-polygon meshes.
#pragma once

#include <memory>
#include <string>

#include "measure/compare_sweep.h"
#include "objects/bounds.h"
#include "objects/relief_quad.h"
#include "texmap/renderer.h"

namespace rtm {

class CompareSource {
public:
    virtual ~CompareSource() = default;
    std::string name;           // the manifest's name (unique within a run: the caller appends "-2", ... to repeats)
    std::string kind;           // "relief", "object" or "scene"
    std::string path;           // the manifest as given
    int width = 0, height = 0;  // texels: the relief's; an object's first face's; a scene's first relief's

    virtual Bounds bounds() const = 0;
    virtual bool renders(const CompareEntry& e) const = 0;
    // Whether the ray caster renders it (else micromesh is the reference of the errors).
    bool has_raycast() const { return kind == "relief"; }
    // One frame (begin_frame included) read back; `times` accumulates the stage times. `output_scale` > 1 (reliefs
    // only: renders() is false for it elsewhere) draws the relief resampled onto a finer grid (warp/upsample.h).
    virtual ImageRGBA8 render(Renderer& renderer, const Camera& cam, const RenderSettings& s, int output_scale,
                              StageTimes& times) = 0;
    // A truth of a curved base, the relief displaced over the `shape` patch (cylinder or sphere) bent through
    // `angle` radians: `method` micromesh draws it as micro-polygons (perpixel/curved_patch.h, curved_micromesh),
    // raycast casts it on the CPU with `threads` (measure/curved_raycast.h); one frame, `times` accumulates its
    // time. Reliefs only (renders() is false for the curved entries elsewhere): throws std::logic_error otherwise.
    virtual ImageRGBA8 render_curved_truth(Renderer& renderer, const Camera& cam, RenderMethod method,
                                           CurvedShape shape, double angle, int threads, StageTimes& times);
    // The relief quad (for the page's step-by-step section); null for objects and scenes.
    virtual ReliefQuad* relief() { return nullptr; }
};

// Load the manifest (IoError naming the file and what is wrong).
std::unique_ptr<CompareSource> load_relief_source(const std::string& path);
std::unique_ptr<CompareSource> load_object_source(const std::string& path);
std::unique_ptr<CompareSource> load_scene_source(const std::string& path);

}  // namespace rtm
