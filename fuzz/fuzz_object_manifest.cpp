// libFuzzer target: the bytes are an object manifest (NAME.object.json, formats/object_manifest.h).
//
// They are written to a file in a scratch folder that also holds small valid face images for a box 2 x 1 x 1 at two
// texels per unit (px/nx 2x2, py/ny 4x2, pz/nz 4x2: c_*.png, d_*.png), a mismatched one (d33.png, 3x3) and a
// relief manifest of face +z (pz.relief.json), so that a manifest naming them gets past the parser into
// load_object: image reading, the size, spacing and frame checks, displacement mapping and make_relief.
// Seeds: fuzz/corpus/object_manifest/; fuzz/object_manifest.dict gives the field names.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <string_view>

#include "formats/image_io.h"
#include "formats/object_manifest.h"
#include "fuzz_util.h"

namespace {

using namespace rtm;

void write_images() {
    const int sizes[3][2] = {{2, 2}, {4, 2}, {4, 2}};  // per axis x, y, z: width x height of the faces
    for (int axis = 0; axis < 3; ++axis) {
        const int w = sizes[axis][0], h = sizes[axis][1];
        ImageRGBA8 c(w, h);
        ImageF d(w, h);
        for (int r = 0; r < h; ++r)
            for (int x = 0; x < w; ++x) {
                c.at(x, r) = {uint8_t(60 * x), uint8_t(80 * r), 200, uint8_t(x == 1 && r == 1 ? 0 : 255)};
                d.at(x, r) = float(x + w * r) / float(w * h);
            }
        const std::string tag = std::string(1, "xyz"[axis]);
        write_rgba8(fuzz::scratch_file("c_" + tag + ".png"), c);
        write_gray(fuzz::scratch_file("d_" + tag + ".png"), d);
    }
    write_gray(fuzz::scratch_file("d33.png"), ImageF(3, 3));
    fuzz::write_file(fuzz::scratch_file("pz.relief.json"),
                     "{\"color\": \"c_z.png\", \"displacement\": \"d_z.png\", \"displacement_range\": [-0.5, 0],"
                     " \"origin\": [0, 0, 1], \"a\": [0.5, 0, 0], \"b\": [0, 0.5, 0]}");
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    fuzz::init_reports();
    write_images();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::scratch_file("m.object.json");
    fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
    ObjectManifest m;
    if (!fuzz::expect_ok_or_io_error(path, [&] { m = parse_object_manifest(path); })) return 0;
    // What the parser accepted must be what its header promises.
    for (int f = 0; f < kFaceCount; ++f) {
        const ObjectFaceEntry& e = m.faces[size_t(f)];
        const double depth = m.box.extent()[face_axis(f)];
        if (!(e.range_min <= e.range_max && e.range_max <= 0.0 && e.range_min >= -depth * (1 + 1e-9)) || !(depth > 0) ||
            !std::isfinite(depth) || e.color_path.empty() || e.displacement_path.empty()) {
            std::fprintf(stderr, "FINDING: parse_object_manifest accepted an invalid face %s: range [%g, %g]\n",
                         kFaceKeys[size_t(f)], e.range_min, e.range_max);
            std::abort();
        }
    }
    SixFaceObject obj;
    if (fuzz::expect_ok_or_io_error(path, [&] { obj = load_object(path); })) {
        for (const ReliefTexture& t : obj.faces) {
            const size_t n = size_t(t.width) * size_t(t.height);
            bool ok = t.width > 0 && t.height > 0 && t.texels.size() == n && t.displacement.size() == n;
            for (size_t i = 0; ok && i < n; ++i)
                ok = t.texels[i].q == kEmptyIndex || (std::isfinite(t.displacement[i]) && t.displacement[i] <= 0.0f);
            if (!ok) {
                std::fprintf(stderr, "FINDING: load_object returned an inconsistent face: %s\n", t.to_string().c_str());
                std::abort();
            }
        }
    }
    return 0;
}
