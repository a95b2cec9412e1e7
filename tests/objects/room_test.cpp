// The registered room (procedural/room.h, media/room.scene.json; the paper's Figures 22 and 23): four relief walls
// baked from a generated mesh plus plain floor and ceiling polygons. Against the source mesh drawn conventionally
// from 8 views of its camera path: coverage and PSNR at least 8 dB above flat texture mapping of the walls' own
// texture maps (media/room_walls.scene.json); along the seams where two relief walls meet no background shows
// through (registration by depth alone); a six-face object standing in the window niche crosses the relief walls
// where the micro-polygon truth says; scenes with object and mesh items.
#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "common/temp_dir.h"
#include "measure/image_diff.h"
#include "mesh/mesh_renderer.h"
#include "objects/scene.h"
#include "procedural/room.h"
#include "texmap/gl_context.h"

namespace rtm {
namespace {

using objects_testing::TempDir;

const std::string kRoom = std::string(RTM_SOURCE_DIR) + "/media/room.scene.json";
// The same room baked onto the walls' own planes: the walls' conventional texture maps.
const std::string kRoomWalls = std::string(RTM_SOURCE_DIR) + "/media/room_walls.scene.json";
constexpr int kW = 320, kH = 240;

// The 8 views: frames 0, 12, ..., 84 of the room's camera path.
std::vector<Camera> room_views(const Scene& scene) {
    const SceneManifest& m = scene.manifest();
    const Bounds b = scene.bounds();
    std::vector<Camera> cams;
    for (int k = 0; k < 8; ++k) {
        Camera size;
        size.width = kW;
        size.height = kH;
        Camera c = key_camera(camera_path_frame(m.path_keys, k * 12, m.path_frames), size);
        c.fit_clip_planes(b.centre(), b.radius());
        cams.push_back(c);
    }
    return cams;
}

ImageRGBA8 frame(Scene& scene, Renderer& renderer, const Camera& cam, RenderMethod method) {
    PrewarpOptions opt;
    opt.keep_outliers = true;
    DrawOptions draw;
    draw.depth_correction = true;
    SceneFrameReport rep;
    scene.draw(renderer, cam, method, opt, draw, rep);
    return renderer.read_pixels(cam.width, cam.height);
}

TEST(ShippedRoom, FourReliefWallsAndTwoPolygons) {
    Scene scene = Scene::load(kRoom), walls = Scene::load(kRoomWalls);
    for (Scene* s : {&scene, &walls}) {
        EXPECT_EQ(s->quads().size(), 4u);
        EXPECT_EQ(s->polygons().size(), 2u);
        EXPECT_GE(s->manifest().path_frames, 85);
        EXPECT_EQ(s->manifest().path_keys.size(), scene.manifest().path_keys.size());
    }
    ASSERT_EQ(scene.quads().size(), 4u);
    ASSERT_EQ(walls.quads().size(), 4u);
    // On the walls' own planes: shelves, frames, sill and trims stand out; the window niche and the door are
    // recessed.
    for (ReliefQuad& q : walls.quads()) EXPECT_GT(q.relief().quant.max, 0.07);
    EXPECT_LT(walls.quads()[1].relief().quant.min, -0.35);
    EXPECT_LT(walls.quads()[2].relief().quant.min, -0.15);
    // The room's reliefs look down at their walls by RoomOptions::look_down_deg: f tilted up from the wall's
    // normal by that angle, the texel steps the walls' own projected onto the plane (same texel columns).
    const double down = RoomOptions{}.look_down_deg * M_PI / 180.0;
    for (size_t i = 0; i < 4; ++i) {
        const ReliefTexture& t = scene.quads()[i].relief();
        const ReliefTexture& w = walls.quads()[i].relief();
        EXPECT_NEAR(glm::dot(t.geometry.f(), glm::dvec3(0, 1, 0)), std::sin(down), 1e-9) << i;
        EXPECT_NEAR(glm::dot(t.geometry.f(), w.geometry.f()), std::cos(down), 1e-9) << i;
        EXPECT_EQ(t.width, w.width);
        EXPECT_EQ(t.height, w.height);
        EXPECT_GT(t.quant.max, w.quant.max);  // the wall itself rises to kRoomHeight * sin(down) towards the ceiling
    }
}

// The room's relief walls against the mesh they were baked from, drawn conventionally with the same camera. Flat
// texture mapping draws the walls' own texture maps (room_walls, baked onto the walls' planes) on the walls: a
// relief looking down at its wall, mapped flat onto its tilted quad, would be a worse flat picture (1 to 2 dB) and
// flatter the gap.
TEST(ShippedRoom, ReliefIsCloseToTheSourceMeshAndFarBetterThanFlat) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene scene = Scene::load(kRoom), walls = Scene::load(kRoomWalls);
    MeshRenderer source(load_mesh(std::string(RTM_SOURCE_DIR) + "/media/room.ply"));
    const std::vector<Camera> views = room_views(scene);
    double gap_sum = 0;
    for (size_t k = 0; k < views.size(); ++k) {
        const ImageRGBA8 truth = source.render(views[k]);
        const DiffResult relief = diff_images(truth, frame(scene, renderer, views[k], RenderMethod::two_pass));
        const DiffResult flat = diff_images(truth, frame(walls, renderer, views[k], RenderMethod::flat));
        std::printf("room view %zu (path frame %zu): relief psnr %.2f iou %.4f, flat psnr %.2f iou %.4f\n", k, k * 12,
                    relief.psnr, relief.iou, flat.psnr, flat.iou);
        // The scenes issue's targets: coverage IoU >= 0.95 and at least 8 dB above flat texture mapping per view.
        // The room reaches 8.6 to 11.1 dB, 9.6 on average (docs/ACCURACY.md); held: 8 dB every view, 9.3 on average.
        EXPECT_GE(relief.iou, 0.95) << "view " << k;
        EXPECT_GE(flat.iou, 0.95) << "view " << k;
        EXPECT_GE(relief.psnr, flat.psnr + 8.0) << "view " << k;
        gap_sum += relief.psnr - flat.psnr;
    }
    std::printf("room: mean gap %.2f dB\n", gap_sum / double(views.size()));
    EXPECT_GE(gap_sum / double(views.size()), 9.3);
}

// Registration by depth alone: on the projected corner lines, where the walls' quads meet, every pixel shows a
// surface (the background is opaque black, a colour the room does not have).
TEST(ShippedRoom, NoBackgroundShowsAlongTheSeamsBetweenReliefWalls) {
    auto ctx = GlContext::create_offscreen(kW, kH);
    Renderer renderer;
    Scene scene = Scene::load(kRoom);
    long long checked = 0, background = 0;
    const std::vector<std::array<glm::dvec3, 2>> seams = room_seams();
    std::vector<int> seam_seen(seams.size(), 0);
    for (const Camera& cam : room_views(scene)) {
        for (RenderMethod method : {RenderMethod::two_pass, RenderMethod::pipelined}) {
            const ImageRGBA8 img = frame(scene, renderer, cam, method);
            const glm::dmat4 clip = cam.projection() * cam.view();
            for (size_t s = 0; s < seams.size(); ++s) {
                const auto& seam = seams[s];
                long long view_background = 0, view_checked = 0;
                int last_x = -1, last_row = -1;
                for (int i = 0; i <= 4000; ++i) {
                    const glm::dvec3 p = glm::mix(seam[0], seam[1], i / 4000.0);
                    const glm::dvec4 c = clip * glm::dvec4(p, 1.0);
                    if (!(c.w > cam.z_near)) continue;  // behind the eye
                    const double x = (c.x / c.w + 1) * 0.5 * cam.width, y = (1 - c.y / c.w) * 0.5 * cam.height;
                    // Inside the picture, one pixel away from its border (the ceiling and floor corners are
                    // seams with the polygons, not between relief walls).
                    const int px = int(std::floor(x)), row = int(std::floor(y));
                    if (px < 1 || row < 1 || px >= cam.width - 1 || row >= cam.height - 1) continue;
                    if (p.y < 0.02 || p.y > kRoomHeight - 0.02) continue;
                    if (px == last_x && row == last_row) continue;
                    last_x = px;
                    last_row = row;
                    const Rgba8 v = img.at(px, row);
                    ++view_checked;
                    if (v.r == 0 && v.g == 0 && v.b == 0) ++view_background;
                }
                checked += view_checked;
                background += view_background;
                seam_seen[s] += view_checked > 0;
                EXPECT_EQ(view_background, 0) << "seam " << s << " at eye " << cam.to_string();
            }
        }
    }
    std::printf("seams: %lld pixels checked over 8 views and 2 methods, %lld show background\n", checked, background);
    for (size_t s = 0; s < seam_seen.size(); ++s) EXPECT_GT(seam_seen[s], 0) << "seam " << s << " never in view";
    EXPECT_GT(checked, 1000);
}

// A six-face object (the shipped sphere, scaled to 0.2 radius) standing on the window niche's sill and pushed into
// its glass and its side: its outline, crossing lines included, against the micro-polygon truth of the same scene.
TEST(RoomObject, ObjectInTheNicheMeetsTheWallsWhereTheTruthDoes) {
    SceneManifest m = parse_scene_manifest(kRoom);
    SceneManifest with = m;
    SceneItem sphere;
    sphere.kind = SceneItem::Kind::object;
    sphere.file_path = std::string(RTM_SOURCE_DIR) + "/media/sphere.object.json";
    sphere.transform.translate = {-kRoomHalf - 0.27, 1.07, 0.34};
    sphere.transform.rotate = {{0, 1, 0, 25}};
    sphere.transform.scale = 0.2;
    with.items.push_back(sphere);
    Scene plain(m), placed(with);
    Camera cam;
    cam.eye = {-0.4, 1.35, -0.5};
    cam.look_at = {-2.15, 1.1, 0.3};
    cam.fov_deg = 40;
    cam.width = cam.height = 256;
    const Bounds b = placed.bounds();
    cam.fit_clip_planes(b.centre(), b.radius());
    auto ctx = GlContext::create_offscreen(256, 256);
    Renderer renderer;
    // Per row, the first and last pixel where the sphere changes the picture.
    auto outline = [&](RenderMethod method) {
        const ImageRGBA8 a = frame(plain, renderer, cam, method), c = frame(placed, renderer, cam, method);
        std::vector<std::array<int, 2>> rows(256, {-1, -1});
        for (int row = 0; row < 256; ++row)
            for (int x = 0; x < 256; ++x) {
                const Rgba8 p = a.at(x, row), q = c.at(x, row);
                if (p.r == q.r && p.g == q.g && p.b == q.b) continue;
                if (rows[size_t(row)][0] < 0) rows[size_t(row)][0] = x;
                rows[size_t(row)][1] = x;
            }
        return rows;
    };
    const auto truth = outline(RenderMethod::micromesh);
    const auto relief = outline(RenderMethod::two_pass);
    double sum = 0;
    int n = 0, worst = 0, only_one = 0;
    for (size_t r = 0; r < 256; ++r) {
        if ((truth[r][0] < 0) != (relief[r][0] < 0)) ++only_one;
        if (truth[r][0] < 0 || relief[r][0] < 0) continue;
        for (int side : {0, 1}) {
            const int d = std::abs(truth[r][size_t(side)] - relief[r][size_t(side)]);
            sum += d;
            worst = std::max(worst, d);
            ++n;
        }
    }
    std::printf("object in the niche: %d row ends, mean distance %.2f px, worst %d px, %d rows in one only\n", n,
                n ? sum / n : 0.0, worst, only_one);
    ASSERT_GT(n, 60);
    // The scenes issue's bound: the crossing line within 1.5 pixels of the truth's (mean over the row ends).
    EXPECT_LE(sum / n, 1.5);
    EXPECT_LE(only_one, 3);
}

// Object and mesh items are placed by their transforms: an object drawn in its own frame with the camera moved
// lands where its transformed micro-polygons do; a mesh item's vertices move with the transform.
TEST(SceneItems, ObjectFrameCameraGivesTheSameClipPositions) {
    SceneTransform t;
    t.translate = {1, -2, 0.5};
    t.rotate = {{0, 1, 0, 40}, {1, 0, 1, -20}};
    t.scale = 0.3;
    const glm::dmat4 m = t.matrix();
    Camera cam;
    cam.eye = {2, 1, 4};
    cam.look_at = {0.5, -1, 0};
    cam.width = 200;
    cam.height = 150;
    cam.z_near = 0.5;
    cam.z_far = 20;
    const Camera local = object_frame_camera(cam, m);
    for (const glm::dvec3& p : {glm::dvec3(0.1, 0.2, -0.3), glm::dvec3(-1, 1, 1), glm::dvec3(1, -1, 0.5)}) {
        const glm::dvec4 world = cam.projection() * cam.view() * m * glm::dvec4(p, 1.0);
        const glm::dvec4 own = local.projection() * local.view() * glm::dvec4(p, 1.0);
        const glm::dvec3 a = glm::dvec3(world) / world.w, b2 = glm::dvec3(own) / own.w;
        EXPECT_NEAR(glm::length(a - b2), 0.0, 1e-9);  // the same NDC position and depth
    }
    EXPECT_THROW(object_frame_camera(cam, glm::scale(glm::dmat4(1.0), glm::dvec3(1, 2, 1))), std::invalid_argument);
}

TEST(SceneItems, MeshItemIsDrawnWhereTheMeshRendererDrawsItAndIsItsOwnTruth) {
    TempDir dir;
    // The room mesh as a scene item, moved and scaled; seen from inside it, every method draws the same picture,
    // the one MeshRenderer draws of the transformed mesh.
    SceneManifest m;
    m.path = (dir.path() / "m.scene.json").string();
    SceneItem item;
    item.kind = SceneItem::Kind::mesh;
    item.file_path = std::string(RTM_SOURCE_DIR) + "/media/room.ply";
    item.transform.translate = {3, 0, 0};
    item.transform.scale = 0.5;
    m.items.push_back(item);
    write_scene_manifest(m.path, m);
    Scene scene = Scene::load(m.path);
    ASSERT_EQ(scene.meshes().size(), 1u);
    const Bounds b = scene.bounds();
    EXPECT_NEAR(b.lo.x, 3 - kRoomHalf * 0.5 - 0.2, 1e-6);           // the window niche reaches 0.4 beyond the wall
    EXPECT_NEAR(b.hi.y, (kRoomHeight + kWallOverlap) * 0.5, 1e-6);  // the walls reach above the ceiling
    Camera cam;
    cam.eye = {3.3, 0.7, 0.6};
    cam.look_at = {2.6, 0.6, -1};
    cam.width = 160;
    cam.height = 120;
    cam.fit_clip_planes(b.centre(), b.radius());
    auto ctx = GlContext::create_offscreen(160, 120);
    Renderer renderer;
    TriangleMesh moved = load_mesh(item.file_path);
    const glm::dmat4 to_world = item.transform.matrix();  // as the scene does it: in double, then to float
    for (MeshVertexAttribs& v : moved.vertices)
        v.position = glm::vec3(to_world * glm::dvec4(glm::dvec3(v.position), 1.0));
    MeshRenderer direct(moved);
    const ImageRGBA8 want = direct.render(cam);
    const ImageRGBA8 first = frame(scene, renderer, cam, RenderMethod::flat);
    // The scene's frame has the OSMesa framebuffer's 24-bit depth buffer, MeshRenderer's own a 32-bit float one:
    // surfaces a hair apart (the eye inside the scene's bounds puts the near plane at 1e-4 of the far one) may
    // resolve differently in a few pixels, so against it: the same coverage and a small RMSE.
    const DiffResult d = diff_images(want, first);
    std::printf("mesh item against MeshRenderer: rmse %.3f over %lld pixels, iou %.4f\n", d.rmse, d.both, d.iou);
    EXPECT_EQ(d.iou, 1.0);
    EXPECT_LT(d.rmse, 2.0);
    // A mesh is its own truth: every method draws the same picture, to the bit.
    for (RenderMethod method : {RenderMethod::two_pass, RenderMethod::micromesh}) {
        const DiffResult same = diff_images(first, frame(scene, renderer, cam, method));
        EXPECT_EQ(same.rmse, 0.0) << to_string(method);
        EXPECT_EQ(same.iou, 1.0) << to_string(method);
    }
}

}  // namespace
}  // namespace rtm
