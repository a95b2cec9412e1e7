// rtm bake --planes (mesh/bake_planes.h): views onto given rectangles, their files and the planes file's checks.
#include <gtest/gtest.h>

#include "common/io_error.h"
#include "common/temp_dir.h"
#include "formats/image_io.h"
#include "formats/relief_manifest.h"
#include "mesh/bake_object.h"
#include "mesh/bake_planes.h"
#include "mesh/mesh_test_util.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

using objects_testing::TempDir;
using objects_testing::write_file;

class BakePlanesTest : public ::testing::Test {
protected:
    void SetUp() override { ctx_ = GlContext::create_offscreen(16, 16); }
    std::unique_ptr<GlContext> ctx_;
};

TEST_F(BakePlanesTest, TopPlaneMatchesTheObjectsTopFaceAndLoadsAsARelief) {
    TempDir dir;
    const TriangleMesh mesh = load_mesh(mesh_testing::write_bump_obj(dir.path().string()));
    write_file(dir.file("p.json"), R"({ "planes": [
        { "name": "top", "origin": [0, 0, 0.75], "a": [0.125, 0, 0], "b": [0, 0.125, 0], "size": [8, 8] },
        { "name": "floor_only", "origin": [0, 0, 0.75], "a": [0.125, 0, 0], "b": [0, 0.125, 0], "size": [8, 8],
          "range": [-0.6, -0.4], "comment": "unknown fields are ignored" } ] })");
    const std::vector<BakePlane> planes = parse_bake_planes(dir.file("p.json"));
    ASSERT_EQ(planes.size(), 2u);
    const std::vector<std::string> out = bake_planes(mesh, planes, dir.file("out"), "bump");
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0], dir.file("out/bump_top.relief.json"));

    const BakedObject obj = bake_object(mesh, 8);
    const BakedFace& pz = obj.faces[4];
    ASSERT_EQ(pz.key, "+z");
    const ReliefTexture top = load_relief(out[0]);
    ASSERT_EQ(top.width, 8);
    ASSERT_EQ(top.height, 8);
    for (int r = 0; r < 8; ++r)
        for (int i = 0; i < 8; ++i) {
            const ReliefTexel& t = top.texel(i, r);
            EXPECT_EQ(Rgba8({t.r, t.g, t.b, 255}), pz.color.at(i, r)) << i << "," << r;
            // Both exact up to float rounding (1e-6) and the 16-bit quantization of the range 0.5.
            EXPECT_NEAR(top.displ(i, r), pz.displacement.at(i, r), 0.5 / 65535 + 1e-6) << i << "," << r;
        }
    // The texel (2, 5) (v-row 2) lies on the bump: its 3-D point is at the plane, above (0.3125, 0.3125).
    const glm::dvec3 x = top.point(2, 5);
    EXPECT_NEAR(x.x, 0.3125, 1e-12);
    EXPECT_NEAR(x.y, 0.3125, 1e-12);
    EXPECT_NEAR(x.z, 0.75, 1e-6);

    // The slab [-0.6, -0.4] leaves the bump out: the floor everywhere, 0.5 below the plane.
    ReliefManifest m;
    const ReliefTexture floor = load_relief(out[1], &m);
    EXPECT_NEAR(m.range_min, -0.5, 1e-6);
    EXPECT_NEAR(m.range_max, -0.5, 1e-6);
    for (const ReliefTexel& t : floor.texels) EXPECT_EQ(Rgba8({t.r, t.g, t.b, 255}), (Rgba8{51, 102, 153, 255}));
}

TEST_F(BakePlanesTest, SlantedPlaneSeesTheFloorAlongItsNormal) {
    // A plane through the floor's diagonal, looking straight down its own normal (0, 0, 1) but with a and b
    // rotated 45 degrees about z: texel centres map to rotated floor points.
    TempDir dir;
    const TriangleMesh mesh = load_mesh(mesh_testing::write_bump_obj(dir.path().string()));
    const double s = 0.1 / std::sqrt(2.0);
    BakePlane p;
    p.name = "rot";
    p.geometry.origin = {0.5, 0.0, 1.0};
    p.geometry.a = {s, s, 0};
    p.geometry.b = {-s, s, 0};
    p.width = p.height = 7;
    const std::vector<std::string> out = bake_planes(mesh, {p}, dir.file("out"), "bump");
    const ReliefTexture t = load_relief(out[0]);
    for (int r = 0; r < 7; ++r)
        for (int i = 0; i < 7; ++i) {
            const glm::dvec3 centre = p.geometry.origin + p.geometry.a * (i + 0.5) + p.geometry.b * (6 - r + 0.5);
            const bool on_bump = centre.x > 0.25 && centre.x < 0.75 && centre.y > 0.25 && centre.y < 0.75;
            const bool on_floor = centre.x > 0 && centre.x < 1 && centre.y > 0 && centre.y < 1;
            if (!on_floor) {
                EXPECT_TRUE(t.empty_at(i, r)) << i << "," << r;
                continue;
            }
            ASSERT_FALSE(t.empty_at(i, r)) << i << "," << r;
            // 16-bit quantization over the range 0.5 seen (from -0.75 to -0.25), plus float rounding.
            EXPECT_NEAR(t.displ(i, r), on_bump ? -0.25 : -0.75, 0.5 / 65535 + 1e-6) << i << "," << r;
        }
}

TEST_F(BakePlanesTest, CullBackFacesSeesPastSurfacesSeenFromBehind) {
    // Two unit squares above each other, wound counter-clockwise seen from their front: the lower one (z = 0,
    // red) faces the plane (+z), the upper one (z = 0.5, blue) faces away from it, as a ceiling does seen from
    // above. Without culling the bake records the upper one (seen from behind); with it, the lower one.
    TriangleMesh mesh;
    auto square = [&](double z, bool up, glm::u8vec4 c) {
        const auto base = uint32_t(mesh.vertices.size());
        for (const glm::vec2 q : {glm::vec2(0, 0), glm::vec2(1, 0), glm::vec2(1, 1), glm::vec2(0, 1)})
            mesh.vertices.push_back({glm::vec3(q.x, q.y, float(z)), {0, 0}, c});
        if (up)
            mesh.indices.insert(mesh.indices.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
        else
            mesh.indices.insert(mesh.indices.end(), {base, base + 2, base + 1, base, base + 3, base + 2});
    };
    square(0.0, true, {255, 0, 0, 255});
    square(0.5, false, {0, 0, 255, 255});
    mesh.materials.push_back({"m", glm::vec4(1.0f), {}});
    mesh.parts.push_back({0, uint32_t(mesh.indices.size()), 0, false, true});
    mesh.lo = {0, 0, 0};
    mesh.hi = {1, 1, 0.5};
    TempDir dir;
    write_file(dir.file("p.json"), R"({ "planes": [
        { "name": "both", "origin": [0, 0, 1], "a": [0.25, 0, 0], "b": [0, 0.25, 0], "size": [4, 4] },
        { "name": "front", "origin": [0, 0, 1], "a": [0.25, 0, 0], "b": [0, 0.25, 0], "size": [4, 4],
          "cull_back_faces": true } ] })");
    const std::vector<BakePlane> planes = parse_bake_planes(dir.file("p.json"));
    ASSERT_EQ(planes.size(), 2u);
    EXPECT_FALSE(planes[0].cull_back_faces);
    EXPECT_TRUE(planes[1].cull_back_faces);
    const std::vector<std::string> out = bake_planes(mesh, planes, dir.file("out"), "sq");
    const ReliefTexture both = load_relief(out[0]), front = load_relief(out[1]);
    for (int r = 0; r < 4; ++r)
        for (int i = 0; i < 4; ++i) {
            EXPECT_EQ(Rgba8({both.texel(i, r).r, both.texel(i, r).g, both.texel(i, r).b, 255}),
                      (Rgba8{0, 0, 255, 255}));
            EXPECT_NEAR(both.displ(i, r), -0.5, 1e-6);
            EXPECT_EQ(Rgba8({front.texel(i, r).r, front.texel(i, r).g, front.texel(i, r).b, 255}),
                      (Rgba8{255, 0, 0, 255}));
            EXPECT_NEAR(front.displ(i, r), -1.0, 1e-6);
        }
}

TEST(BakePlanesParse, RefusesMalformedPlanesNamingTheField) {
    TempDir dir;
    struct Case {
        const char* text;
        const char* want;
    };
    const Case cases[] = {
        {"{", "truncated JSON"},
        {R"({"planes": []})", "planes"},
        {R"({"planes": [{"name": "a b", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2]}]})", "name"},
        {R"({"planes": [{"name": "p", "origin": [0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2]}]})", "origin"},
        {R"({"planes": [{"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [2,0,0], "size": [2,2]}]})", "plane 0"},
        {R"({"planes": [{"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [0,2]}]})", "size"},
        {R"({"planes": [{"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2],
             "range": [1, 0]}]})",
         "range"},
        {R"({"planes": [{"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2],
             "cull_back_faces": 1}]})",
         "cull_back_faces"},
        {R"({"planes": [{"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2]},
                        {"name": "p", "origin": [0,0,0], "a": [1,0,0], "b": [0,1,0], "size": [2,2]}]})",
         "twice"},
    };
    for (const Case& c : cases) {
        write_file(dir.file("p.json"), c.text);
        try {
            (void)parse_bake_planes(dir.file("p.json"));
            ADD_FAILURE() << "accepted " << c.text;
        } catch (const IoError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(dir.file("p.json"), 0), 0u) << msg;
            EXPECT_NE(msg.find(c.want), std::string::npos) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

// The planes file is read like a manifest: a FIFO (reading it would block until a writer comes, for ever) and a
// device (/dev/zero never ends) are refused without being opened, a folder is named as one.
TEST(BakePlanesParse, RefusesWhatIsNotARegularFile) {
    TempDir dir;
    objects_testing::expect_refuses_non_regular_files([](const std::string& p) { (void)parse_bake_planes(p); },
                                                      dir.path().string());
}

}  // namespace
}  // namespace rtm
