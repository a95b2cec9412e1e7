// A six-face object (objects/relief_object.h) against the mesh it was baked from (mesh/bake_object.h): both
// rendered from the same cameras, the mesh conventionally (mesh/mesh_renderer.h, the ground truth), the object by
// relief texture mapping with each reconstruction; per view coverage IoU and PSNR over the pixels covered in both
// (measure/image_diff.h), and per method the mean and the worst over the views. Used by `rtm compare --mesh`
// (apps/cmd_compare.cpp) and the guard test tests/measure/object_accuracy_test.cpp. docs/ACCURACY.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "measure/compare.h"
#include "measure/image_diff.h"
#include "mesh/triangle_mesh.h"
#include "objects/relief_object.h"

namespace rtm {

// The ring of views around an object: azimuths every 45 degrees (0 looks straight onto the +z face, 45 onto the
// edge between +z and +x) at elevations -30, 0, 35 (az 45 / el 35: onto the corner +x+y+z of a cube) and 60: 32
// views, 2.5 bounding radii away (the whole bounding sphere in the 45-degree field of view).
std::vector<CompareView> object_ring_views();

struct ObjectAccuracyMethod {
    std::string name;  // "two-pass", "pipelined"
    RenderMethod method = RenderMethod::two_pass;
};

// two-pass and pipelined, point sampling (the defaults of rtm render --object).
std::vector<ObjectAccuracyMethod> default_object_accuracy_methods();

struct ObjectAccuracyOptions {
    int width = 512, height = 512;
    int threads = 0;
    std::vector<CompareView> views = object_ring_views();
    std::vector<ObjectAccuracyMethod> methods = default_object_accuracy_methods();
    // Called per view with the mesh's picture ("mesh"), each method's picture and its heat map against the mesh
    // ("METHOD_error", measure/image_diff.h); may be empty.
    std::function<void(const std::string& view, const std::string& what, const ImageRGBA8&)> on_image;
    std::function<void(const std::string&)> on_progress;  // one line per finished view
};

struct ObjectAccuracyRow {
    std::string view, method;
    DiffResult error;  // the object's picture against the mesh's
};

// Cameras orbit the mesh's bounding sphere (as rtm render --mesh --orbit). Needs no current GL context: creates
// an offscreen one.
std::vector<ObjectAccuracyRow> measure_object_against_mesh(const TriangleMesh& mesh, ReliefObject& object,
                                                           const ObjectAccuracyOptions& options);

struct ObjectAccuracySummary {
    std::string method;
    int views = 0;
    double mean_iou = 0, worst_iou = 1, mean_psnr = 0, worst_psnr = 0;
    std::string worst_iou_view, worst_psnr_view;
};

// Per method, in the order of first appearance. A view whose PSNR is not finite counts as 99 dB (identical) when
// nothing differs and 0 dB when nothing is covered in both.
std::vector<ObjectAccuracySummary> summarize_object_accuracy(const std::vector<ObjectAccuracyRow>& rows);

// The per-view table and the summary per method, Markdown.
std::string object_accuracy_markdown(const std::string& title, const std::vector<ObjectAccuracyRow>& rows);

}  // namespace rtm
