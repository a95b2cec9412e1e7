// libFuzzer target: the bytes are a scene manifest (NAME.scene.json, formats/scene_manifest.h), parsed; what the
// parser accepts is checked against what its header promises, and written back and parsed again (the round trip
// must keep every item). Seeds: fuzz/corpus/scene_manifest/; fuzz/scene_manifest.dict gives the field names.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include <glm/geometric.hpp>

#include "formats/image_io.h"
#include "formats/scene_manifest.h"
#include "fuzz_util.h"

namespace {

using namespace rtm;

[[noreturn]] void finding(const std::string& what) {
    std::fprintf(stderr, "FINDING: %s\n", what.c_str());
    std::abort();
}

bool finite(const glm::dvec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    fuzz::init_reports();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::scratch_file("m.scene.json");
    fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
    SceneManifest m;
    if (!fuzz::expect_ok_or_io_error(path, [&] { m = parse_scene_manifest(path); })) return 0;
    if (m.items.empty()) finding("parse_scene_manifest accepted a scene without items");
    for (const SceneItem& it : m.items) {
        if (!(it.transform.scale > 0) || !std::isfinite(it.transform.scale) || !finite(it.transform.translate))
            finding("parse_scene_manifest accepted a bad transform");
        if (it.kind == SceneItem::Kind::relief && it.relief_path.empty()) finding("a relief item without a file");
        if ((it.kind == SceneItem::Kind::object || it.kind == SceneItem::Kind::mesh) && it.file_path.empty())
            finding("an object or mesh item without a file");
        if (it.kind == SceneItem::Kind::polygon) {
            if (it.vertices.size() < 3 || it.vertices.size() > 4) finding("a polygon of the wrong vertex count");
            for (const glm::dvec3& v : it.vertices)
                if (!finite(v)) finding("a polygon vertex that is not finite");
        }
    }
    if (!m.path_keys.empty()) {
        if (m.path_keys.size() < 2 || m.path_frames < 2) finding("a camera path with fewer than 2 keys or frames");
        for (int k : {0, m.path_frames / 2, m.path_frames - 1}) {
            const SceneCameraKey c = camera_path_frame(m.path_keys, k, m.path_frames);
            if (!finite(c.eye) || !finite(c.look_at) || !std::isfinite(c.fov_deg)) finding("a path frame not finite");
        }
    }
    // The writer's output parses back to the same items.
    const std::string back = fuzz::scratch_file("back.scene.json");
    m.path = back;
    SceneManifest r;
    if (!fuzz::expect_ok_or_io_error(back, [&] {
            write_scene_manifest(back, m);
            r = parse_scene_manifest(back);
        }))
        finding("a scene the reader accepted did not read back after writing");
    if (r.items.size() != m.items.size()) finding("the round trip changed the number of items");
    for (size_t i = 0; i < r.items.size() && i < m.items.size(); ++i)
        if (r.items[i].kind != m.items[i].kind) finding("the round trip changed an item's kind");
    return 0;
}
