// The six-face bake (mesh/bake_object.h) and the mesh renderer behind it, on meshes of known geometry.
#include <gtest/gtest.h>

#include <glm/geometric.hpp>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <fstream>

#include "common/temp_dir.h"
#include "formats/image_io.h"
#include "mesh/bake_object.h"
#include "mesh/mesh_renderer.h"
#include "mesh/mesh_test_util.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

using objects_testing::TempDir;
using objects_testing::write_file;

const BakedFace& face_of(const BakedObject& o, const std::string& key) {
    for (const BakedFace& f : o.faces)
        if (f.key == key) return f;
    throw std::out_of_range(key);
}

TEST(BakeBox, FaceFramesFollowTheTable) {
    const BakeBox box = bake_box({0, 0, 0}, {2, 1, 0.5}, 8, nullptr);
    EXPECT_EQ(box.texels, (std::array<int, 3>{8, 4, 2}));
    struct Want {
        const char* key;
        glm::dvec3 origin, a, b;
        int w, h;
    };
    const Want want[] = {{"+z", {0, 0, 0.5}, {0.25, 0, 0}, {0, 0.25, 0}, 8, 4},
                         {"-z", {2, 0, 0}, {-0.25, 0, 0}, {0, 0.25, 0}, 8, 4},
                         {"+x", {2, 0, 0.5}, {0, 0, -0.25}, {0, 0.25, 0}, 2, 4},
                         {"-x", {0, 0, 0}, {0, 0, 0.25}, {0, 0.25, 0}, 2, 4},
                         {"+y", {0, 1, 0.5}, {0.25, 0, 0}, {0, 0, -0.25}, 8, 2},
                         {"-y", {0, 0, 0}, {0.25, 0, 0}, {0, 0, 0.25}, 8, 2}};
    for (const Want& w : want) {
        int width = 0, height = 0;
        const ReliefGeometry g = face_geometry(box, w.key, &width, &height);
        EXPECT_EQ(g.origin, w.origin) << w.key;
        EXPECT_EQ(g.a, w.a) << w.key;
        EXPECT_EQ(g.b, w.b) << w.key;
        EXPECT_EQ(width, w.w) << w.key;
        EXPECT_EQ(height, w.h) << w.key;
        // f = cross(a, b) points out of the box: from the box centre to the face's plane.
        EXPECT_GT(glm::dot(g.f(), g.origin - glm::dvec3(1, 0.5, 0.25)), 0.0) << w.key;
    }
}

TEST(BakeBox, FlatAndDegenerateBounds) {
    std::vector<std::string> warnings;
    const BakeBox box = bake_box({0, 0, 3}, {4, 2, 3}, 16, &warnings);
    ASSERT_EQ(warnings.size(), 1u);
    EXPECT_NE(warnings[0].find("flat along z"), std::string::npos) << warnings[0];
    EXPECT_EQ(box.lo.z, 3 - 0.125);
    EXPECT_EQ(box.hi.z, 3 + 0.125);
    EXPECT_EQ(box.texels, (std::array<int, 3>{16, 8, 1}));
    EXPECT_THROW(bake_box({1, 1, 1}, {1, 1, 1}, 16, nullptr), std::invalid_argument);
    EXPECT_THROW(bake_box({0, 0, 0}, {1, 1, 1}, 0, nullptr), std::invalid_argument);
}

class BakeTest : public ::testing::Test {
protected:
    void SetUp() override { ctx_ = GlContext::create_offscreen(16, 16); }
    std::unique_ptr<GlContext> ctx_;
};

TEST_F(BakeTest, BumpDepthsAndColoursAtKnownTexels) {
    TempDir dir;
    const TriangleMesh mesh = load_mesh(mesh_testing::write_bump_obj(dir.path().string()));
    const BakedObject obj = bake_object(mesh, 8);
    EXPECT_TRUE(obj.warnings.empty());
    EXPECT_EQ(obj.box.texels, (std::array<int, 3>{8, 8, 4}));
    const Rgba8 floor{51, 102, 153, 255}, bump{255, 204, 0, 255};
    // +z: 8x8 texels of 1/8; texel (i, r) has centre x = (i + 0.5)/8, y = (7 - r + 0.5)/8. The bump covers
    // x, y in (0.25, 0.75): columns and v-rows 2..5, at the face (d = 0); the floor lies 0.5 below it.
    const BakedFace& pz = face_of(obj, "+z");
    ASSERT_EQ(pz.color.width, 8);
    ASSERT_EQ(pz.color.height, 8);
    for (int r = 0; r < 8; ++r)
        for (int i = 0; i < 8; ++i) {
            const int j = 7 - r;
            const bool on_bump = i >= 2 && i <= 5 && j >= 2 && j <= 5;
            EXPECT_EQ(pz.color.at(i, r), on_bump ? bump : floor) << i << "," << r;
            // Single-precision interpolation of the distance: within 1e-6 of the exact 0 or -0.5.
            EXPECT_NEAR(pz.displacement.at(i, r), on_bump ? 0.0 : -0.5, 1e-6) << i << "," << r;
        }
    EXPECT_NEAR(pz.range_lo, -0.5, 1e-6);
    EXPECT_NEAR(pz.range_hi, 0.0, 1e-6);
    // -z looks up from below: the floor, at the face itself, hides the bump.
    const BakedFace& nz = face_of(obj, "-z");
    for (size_t p = 0; p < nz.color.pixels.size(); ++p) {
        EXPECT_EQ(nz.color.pixels[p], floor);
        EXPECT_NEAR(nz.displacement.pixels[p], 0.0, 1e-6);
    }
    // The side faces see both quads edge-on: nothing, alpha 0 everywhere.
    for (const char* key : {"+x", "-x", "+y", "-y"}) {
        const BakedFace& f = face_of(obj, key);
        for (const Rgba8& c : f.color.pixels) EXPECT_EQ(c.a, 0) << key;
        EXPECT_EQ(f.range_lo, 0.0);
        EXPECT_EQ(f.range_hi, 0.0);
    }
}

TEST_F(BakeTest, TexelCentresSampleTheTexture) {
    // An 8x8 texture mapped once onto the unit square at z = 0, baked at 8 texels: each texel centre is a texture
    // texel centre, so each texel shows its texture texel (within 1 level: interpolated coordinates round).
    TempDir dir;
    ImageRGBA8 tex(8, 8);
    for (int r = 0; r < 8; ++r)
        for (int i = 0; i < 8; ++i) tex.at(i, r) = Rgba8{uint8_t(30 * i), uint8_t(30 * r), 77, 255};
    write_rgba8(dir.file("tex.png"), tex);
    write_file(dir.file("t.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd tex.png\n");
    write_file(dir.file("t.obj"),
               "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\n"
               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\nf 1/1 3/3 4/4\n");
    const TriangleMesh mesh = load_mesh(dir.file("t.obj"));
    std::vector<std::string> warnings;
    const BakedObject obj = bake_object(mesh, 8);
    ASSERT_EQ(obj.warnings.size(), 1u);  // flat along z
    const BakedFace& pz = face_of(obj, "+z");
    ASSERT_EQ(pz.color.width, 8);
    for (int r = 0; r < 8; ++r)
        for (int i = 0; i < 8; ++i) {
            const Rgba8 c = pz.color.at(i, r), t = tex.at(i, r);
            EXPECT_LE(std::abs(c.r - t.r), 1) << i << "," << r;
            EXPECT_LE(std::abs(c.g - t.g), 1) << i << "," << r;
            EXPECT_LE(std::abs(c.b - t.b), 1) << i << "," << r;
            // The plane lies in the middle of the one-texel-thick box: half a texel (1/16) below the face.
            EXPECT_NEAR(pz.displacement.at(i, r), -1.0 / 16, 1e-6);
        }
}

TEST_F(BakeTest, DuckSixFacesAndWrittenObject) {
    const std::string duck = mesh_testing::duck_path();
    if (duck.empty()) GTEST_SKIP() << "assimp-testmodels is not installed (scripts/setup.sh installs it)";
    const TriangleMesh mesh = load_mesh(duck);
    int calls = 0;
    const BakedObject obj = bake_object(mesh, 64, [&](int done, int total) {
        EXPECT_EQ(done, ++calls);
        EXPECT_EQ(total, 6);
    });
    EXPECT_EQ(calls, 6);
    const glm::dvec3 e = obj.box.extent();
    for (const BakedFace& f : obj.faces) {
        size_t seen = 0;
        for (const Rgba8& c : f.color.pixels) seen += c.a == 255;
        // The duck fills a good part of every view of its own bounding box.
        EXPECT_GT(double(seen), 0.3 * double(f.color.pixels.size())) << f.key;
        const double depth = std::abs(glm::dot(e, f.geometry.f()));
        EXPECT_LE(f.range_hi, 0.0);
        EXPECT_GE(f.range_lo, -depth);
        // Some texel touches the face: the box is the mesh's bounds (within a texel of the rasterized samples).
        EXPECT_GT(f.range_hi, -depth / 32) << f.key;
    }
    TempDir dir;
    const std::string manifest = write_object(dir.file("out"), "duck", obj, "duck.dae");
    std::ifstream in(manifest);
    const nlohmann::json j = nlohmann::json::parse(in);
    EXPECT_EQ(j["name"], "duck");
    ASSERT_EQ(j["faces"].size(), 6u);
    for (const BakedFace& f : obj.faces) {
        const auto& jf = j["faces"][f.key];
        const std::string color = dir.file("out/" + jf["color"].get<std::string>());
        const std::string disp = dir.file("out/" + jf["displacement"].get<std::string>());
        EXPECT_EQ(read_rgba8(color), f.color) << f.key;
        const ImageF d = read_gray(disp);
        const double lo = jf["displacement_range"][0], hi = jf["displacement_range"][1];
        EXPECT_EQ(lo, f.range_lo);
        EXPECT_EQ(hi, f.range_hi);
        // Discontinuities (section 4.1.1): 12 spacings of the face's larger texel, read back by the object reader.
        const double spacing = std::max(glm::length(f.geometry.a), glm::length(f.geometry.b));
        EXPECT_DOUBLE_EQ(f.discontinuity, kBakeDiscontinuityTexels * spacing) << f.key;
        EXPECT_DOUBLE_EQ(jf["discontinuity"].get<double>(), f.discontinuity) << f.key;
        for (size_t p = 0; p < d.pixels.size(); ++p) {
            if (f.color.pixels[p].a != 255) continue;
            // 16-bit quantization over the face's range: half a step, plus float rounding.
            ASSERT_NEAR(lo + d.pixels[p] * (hi - lo), f.displacement.pixels[p], (hi - lo) / 65535 * 0.5 + 1e-6)
                << f.key << " texel " << p;
        }
    }
    EXPECT_FALSE(std::filesystem::exists(manifest + ".tmp"));
}

TEST_F(BakeTest, PerspectiveRenderOfTheBump) {
    TempDir dir;
    const TriangleMesh mesh = load_mesh(mesh_testing::write_bump_obj(dir.path().string()));
    MeshRenderer renderer(mesh);
    Camera cam;
    cam.eye = {0.5, 0.5, 3};
    cam.look_at = {0.5, 0.5, 0.5};
    cam.width = cam.height = 64;
    cam.fit_clip_planes({0.5, 0.5, 0.5}, 1.0);
    const ImageRGBA8 img = renderer.render(cam);
    EXPECT_EQ(img.at(32, 32), (Rgba8{255, 204, 0, 255}));  // the bump, in the middle
    EXPECT_EQ(img.at(0, 0), (Rgba8{0, 0, 0, 255}));        // background: opaque black
    // Between the bump's edge and the floor's: the floor. The floor's edge x = 0 at distance 2.75 lies at
    // 0.5/2.75/tan(22.5 deg) = 0.44 of the half-width from the centre, the bump's at 0.25/2.25/tan(22.5) = 0.27.
    EXPECT_EQ(img.at(32 - 11, 32), (Rgba8{51, 102, 153, 255}));
}

}  // namespace
}  // namespace rtm
