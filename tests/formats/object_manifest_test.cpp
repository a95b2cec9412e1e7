// NAME.object.json: the write_object_manifest -> load_object round trip, the face frames of the box, relief-form
// faces, and hostile manifests (missing faces, faces of different sizes, NaN and out-of-box ranges, bad boxes): one
// IoError line that starts with the manifest's path and names the face and the field.
#include "formats/object_manifest.h"

#include <glm/geometric.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "common/io_error.h"
#include "common/temp_dir.h"
#include "formats/image_io.h"
#include "formats/relief_manifest.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;
using objects_testing::expect_io_error;
using objects_testing::TempDir;
using objects_testing::write_file;

// A box 2 x 1 x 0.5 with faces of 8 texels per unit: +-x 4x8, +-y 16x4, +-z 16x8.
const Box kBox{{-1, 0, 0}, {1, 1, 0.5}};

std::array<ObjectFaceImages, kFaceCount> test_faces() {
    std::array<ObjectFaceImages, kFaceCount> faces;
    for (int f = 0; f < kFaceCount; ++f) {
        const glm::dvec3 e = kBox.extent();
        const int w = int(std::lround(8 * e[face_step_axis(f, 0)])), h = int(std::lround(8 * e[face_step_axis(f, 1)]));
        ObjectFaceImages& fi = faces[size_t(f)];
        fi.color = ImageRGBA8(w, h);
        fi.displacement_normalized = ImageF(w, h);
        for (int r = 0; r < h; ++r)
            for (int x = 0; x < w; ++x) {
                fi.color.at(x, r) = {uint8_t(30 * f), uint8_t(7 * x), uint8_t(11 * r), uint8_t((x + r) % 5 ? 255 : 0)};
                fi.displacement_normalized.at(x, r) = float((x * 3 + r) % 17) / 16.0f;
            }
        fi.range_min = -0.25 * e[face_axis(f)];
        fi.range_max = 0.0;
        if (f == 4) fi.discontinuity = 0.05;
    }
    return faces;
}

TEST(BoxFaces, FramesMatchTheTableAndNormalsPointOut) {
    const glm::dvec3 c = (kBox.lo + kBox.hi) * 0.5;
    for (int f = 0; f < kFaceCount; ++f) {
        SCOPED_TRACE(kFaceKeys[size_t(f)]);
        const ReliefGeometry g = box_face_geometry(kBox, f, 10, 20);
        glm::dvec3 n(0.0);
        n[face_axis(f)] = face_sign(f);
        EXPECT_EQ(g.f(), n);
        // The quad is the box face: its centre is the box centre moved half the extent along the normal.
        const glm::dvec3 centre = g.origin + g.a * 5.0 + g.b * 10.0;
        glm::dvec3 expect = c;
        expect[face_axis(f)] = face_sign(f) > 0 ? kBox.hi[face_axis(f)] : kBox.lo[face_axis(f)];
        EXPECT_NEAR(glm::length(centre - expect), 0.0, 1e-15);
        // |a| w and |b| h are the box's extents along their axes.
        EXPECT_DOUBLE_EQ(glm::length(g.a) * 10, kBox.extent()[face_step_axis(f, 0)]);
        EXPECT_DOUBLE_EQ(glm::length(g.b) * 20, kBox.extent()[face_step_axis(f, 1)]);
        EXPECT_EQ(face_index(kFaceKeys[size_t(f)]), f);
    }
    EXPECT_EQ(face_index("x"), -1);
}

TEST(ObjectManifest, WriteThenLoadRoundTrips) {
    TempDir dir;
    const std::string path = (dir.path() / "thing.object.json").string();
    const auto faces = test_faces();
    write_object_manifest(path, "thing", kBox, faces);
    ObjectManifest m;
    const SixFaceObject obj = load_object(path, &m);
    EXPECT_EQ(obj.name, "thing");
    EXPECT_EQ(obj.box.lo, kBox.lo);
    EXPECT_EQ(obj.box.hi, kBox.hi);
    for (int f = 0; f < kFaceCount; ++f) {
        SCOPED_TRACE(kFaceKeys[size_t(f)]);
        const ReliefTexture& t = obj.faces[size_t(f)];
        const ObjectFaceImages& fi = faces[size_t(f)];
        ASSERT_EQ(t.width, fi.color.width);
        ASSERT_EQ(t.height, fi.color.height);
        const ReliefGeometry g = box_face_geometry(kBox, f, t.width, t.height);
        EXPECT_EQ(t.geometry.origin, g.origin);
        EXPECT_EQ(t.geometry.a, g.a);
        EXPECT_EQ(t.geometry.b, g.b);
        EXPECT_EQ(t.breaks.empty(), f != 4);  // only +z has a discontinuity threshold
        for (int r = 0; r < t.height; ++r)
            for (int x = 0; x < t.width; ++x) {
                const bool empty = fi.color.at(x, r).a == 0;
                ASSERT_EQ(t.empty_at(x, r), empty);
                if (empty) continue;
                // 16-bit PNG: the displacement comes back within half a step of 1/65535 of the range.
                const double want = fi.range_min + fi.displacement_normalized.at(x, r) * (fi.range_max - fi.range_min);
                EXPECT_NEAR(t.displ(x, r), want, (fi.range_max - fi.range_min) / 65535.0 + 1e-7);
                EXPECT_LE(t.displ(x, r), 0.0f);
            }
    }
}

TEST(ObjectManifest, ReliefFormFaceIsAccepted) {
    TempDir dir;
    const std::string path = (dir.path() / "o.object.json").string();
    write_object_manifest(path, "o", kBox, test_faces());
    // Replace face -y by a relief manifest with the same images and the box face's frame.
    ReliefManifest rm;
    rm.name = "ny";
    rm.range_min = -0.1;
    rm.range_max = 0.0;
    rm.geometry = box_face_geometry(kBox, 3, 16, 4);
    write_relief((dir.path() / "ny.relief.json").string(), rm, test_faces()[3].color,
                 test_faces()[3].displacement_normalized);
    std::string text = objects_testing::read_file(path);
    const size_t a = text.find("\"-y\": {"), b = text.find('}', a);
    text.replace(a, b - a + 1, "\"-y\": { \"relief\": \"ny.relief.json\" }");
    write_file(path, text);
    const SixFaceObject obj = load_object(path);
    EXPECT_EQ(obj.faces[3].quant.min, -0.1);
    // The same relief with a frame that is not the box face's is refused, naming the face.
    rm.geometry.origin.x += 0.01;
    write_relief((dir.path() / "ny.relief.json").string(), rm, test_faces()[3].color,
                 test_faces()[3].displacement_normalized);
    expect_io_error([&] { load_object(path); }, path, {"face \"-y\"", "frame"}, "relief frame off the box");
}

TEST(ObjectManifest, HostileManifestsGiveOneLineNamingTheFaceAndField) {
    TempDir dir;
    const std::string good = (dir.path() / "good.object.json").string();
    write_object_manifest(good, "good", kBox, test_faces());
    const std::string text = objects_testing::read_file(good);
    struct Case {
        std::string label, from, to;
        std::vector<std::string> parts;
    };
    auto face_json = [&](const char* key) {
        const size_t a = text.find(std::string("\"") + key + "\": {"), b = text.find('}', a);
        return text.substr(a, b - a + 1);
    };
    const std::vector<Case> cases = {
        {"missing face", face_json("+y") + ",", "", {"faces", "\"+y\""}},
        {"a seventh face", face_json("+y"), face_json("+y") + ", \"+w\": {}", {"faces", "\"+w\"", "exactly"}},
        {"face not an object", face_json("-z"), "\"-z\": 3", {"face \"-z\"", "object"}},
        {"NaN range", "[-0.5, 0.0]", "[\"nan\", 0]", {"face \"+x\"", "displacement_range"}},
        {"overflowing range", "[-0.5, 0.0]", "[-1e999, 0]", {"overflows"}},
        {"null range", "[-0.5, 0.0]", "null", {"face \"+x\"", "displacement_range"}},
        {"positive range", "[-0.5, 0.0]", "[-0.125, 0.1]", {"face \"+x\"", "displacement_range", "hi <= 0"}},
        {"range deeper than the box", "[-0.5, 0.0]", "[-2.5, 0]", {"face \"+x\"", "displacement_range", "lo >="}},
        {"inverted range", "[-0.5, 0.0]", "[-0.1, -0.2]", {"face \"+x\"", "displacement_range"}},
        {"missing colour", "{ \"color\": \"good_pz_color.png\", ", "{ ", {"face \"+z\"", "\"color\""}},
        {"bad discontinuity", "\"discontinuity\": 0.05", "\"discontinuity\": -1", {"face \"+z\"", "discontinuity"}},
        {"flat box", "\"max\": [1.0, 1.0, 0.5]", "\"max\": [1.0, 0.0, 0.5]", {"box", "min < max"}},
        {"box not numbers", "\"max\": [1.0, 1.0, 0.5]", "\"max\": [1.0, 1.0]", {"box", "\"max\""}},
        // The coordinate limit (+-1e30), named before any face's frame is made of the box.
        {"box beyond the limit",
         "\"min\": [-1.0, 0.0, 0.0], \"max\": [1.0, 1.0, 0.5]",
         "\"min\": [-1e300, -1e300, -1e300], \"max\": [1e300, 1e300, 1e300]",
         {"field \"box\": field \"min\" [-1e+300, -1e+300, -1e+300] has a coordinate beyond +-1e30"}},
        {"box max just beyond the limit",
         "\"max\": [1.0, 1.0, 0.5]",
         "\"max\": [1.0, 1.0, 2e30]",
         {"field \"box\": field \"max\" [1.0, 1.0, 2e+30] has a coordinate beyond +-1e30"}},
        // Each face is a relief: its sides must be at least 1e-9 of the largest coordinate (the relief's rule).
        {"box extent lost in rounding",
         "\"max\": [1.0, 1.0, 0.5]",
         "\"max\": [1e30, 1.0, 0.5]",
         {"field \"box\": the extent 1.0 along y is lost in rounding", "1e-9", "1e+30", "1e+21"}},
        {"missing image", "good_nx_disp.png", "nothing.png", {"face \"-x\"", "nothing.png"}},
        {"truncated", text, text.substr(0, text.size() / 2), {"truncated JSON"}},
    };
    for (const Case& c : cases) {
        std::string t = text;
        const size_t at = t.find(c.from);
        ASSERT_NE(at, std::string::npos) << c.label;
        t.replace(at, c.from.size(), c.to);
        const std::string path = (dir.path() / "bad.object.json").string();
        write_file(path, t);
        expect_io_error([&] { load_object(path); }, path, c.parts, c.label);
    }
    // Faces of different sizes: +x drawn at twice the resolution of the rest (8x16).
    auto faces = test_faces();
    ImageRGBA8 big(8, 16);
    ImageF big_d(8, 16);
    write_rgba8((dir.path() / "big_color.png").string(), big);
    write_gray((dir.path() / "big_disp.png").string(), big_d);
    std::string t = text;
    t.replace(t.find("good_px_color.png"), 17, "big_color.png");
    t.replace(t.find("good_px_disp.png"), 16, "big_disp.png");
    const std::string path = (dir.path() / "sizes.object.json").string();
    write_file(path, t);
    expect_io_error([&] { load_object(path); }, path, {"faces", "\"+x\"", "texel spacing"}, "faces of different sizes");
    // Colour and displacement of one face of different sizes.
    t = text;
    t.replace(t.find("good_py_disp.png"), 16, "big_disp.png");
    write_file(path, t);
    expect_io_error([&] { load_object(path); }, path, {"face \"+y\"", "big_disp.png", "8x16"},
                    "colour vs displacement");
    // Not JSON, not an object, not there.
    write_file(path, "[1, 2]");
    expect_io_error([&] { load_object(path); }, path, {"top level"}, "array");
    expect_io_error([&] { load_object(path + ".none"); }, path + ".none", {"cannot open"}, "missing file");
}

TEST(ObjectManifest, WriterRefusesWhatTheReaderWould) {
    TempDir dir;
    const std::string path = (dir.path() / "w.object.json").string();
    auto faces = test_faces();
    faces[2].range_max = 0.5;
    expect_io_error([&] { write_object_manifest(path, "w", kBox, faces); }, path, {"face \"+y\"", "hi <= 0"}, "hi");
    faces = test_faces();
    faces[5].range_min = std::nan("");
    expect_io_error([&] { write_object_manifest(path, "w", kBox, faces); }, path, {"face \"-z\""}, "nan");
    faces = test_faces();
    faces[1].color = ImageRGBA8(3, 8);
    expect_io_error([&] { write_object_manifest(path, "w", kBox, faces); }, path, {"face \"-x\""}, "size");
    const Box far{{-1, 0, 0}, {1, 1, 2e30}};
    expect_io_error([&] { write_object_manifest(path, "w", far, test_faces()); }, path,
                    {"cannot write: box: field \"max\" [1.0, 1.0, 2e+30] has a coordinate beyond +-1e30"}, "far");
    EXPECT_FALSE(fs::exists(path));
}

// Far from the origin, within the rule (every extent >= 1e-9 of the largest coordinate), a box loads: the test box
// moved to x = 1e8 (its thinnest extent 0.5 against the rule's 0.1).
TEST(ObjectManifest, BoxFarFromTheOriginWithinTheRuleLoads) {
    TempDir dir;
    const std::string path = (dir.path() / "far.object.json").string();
    const glm::dvec3 shift(1e8, 0, 0);
    const Box far{kBox.lo + shift, kBox.hi + shift};
    write_object_manifest(path, "far", far, test_faces());
    const SixFaceObject obj = load_object(path);
    EXPECT_EQ(obj.box.lo, far.lo);
    EXPECT_EQ(obj.faces[0].geometry.origin.x, 1e8 + 1);
}

}  // namespace
}  // namespace rtm
