// The texture-mapping stage through OSMesa (llvmpipe): what lands in which pixel.
//
// Tolerance policy. Where a pixel sees a single texel (clamped corners) or a constant colour, the result is exact.
// Where bilinear filtering mixes texels the expected value comes from a double-precision ray-cast reference, and
// a difference of up to kFilterTolerance per channel is accepted: llvmpipe filters with 8-bit fixed-point weights
// and interpolates texture coordinates in float, so its rounding differs from the reference by about 1/255, and
// other Mesa versions may round differently again. Pixels whose centre lies on an edge of the geometry or where the
// filtered alpha is close to the discard threshold of one half are left out (their coverage is a rasterization
// tie, not a property of this code).
#include "texmap/renderer.h"

#include <gtest/gtest.h>

#include <glm/geometric.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <memory>
#include <random>

#include "common/seed.h"
#include "texmap/gl_context.h"
#include "texmap/test_util.h"

namespace rtm {
namespace {

// See the tolerance policy above. Measured on Mesa 22.3.6 llvmpipe: at most 1 (in about 10% of the pixels).
constexpr int kFilterTolerance = 2;

const Rgba8 kBlack{0, 0, 0, 255};
const Rgba8 kRed{255, 0, 0, 255};
const Rgba8 kGreen{0, 255, 0, 255};
const Rgba8 kBlue{0, 0, 255, 255};
const Rgba8 kWhite{255, 255, 255, 255};

// Eye on +z at distance 1 from the origin, 90 degree field of view: the plane z = 0 shows [-1, 1] x [-1, 1], so
// pixel (px, py) of a size x size image has its centre at x = -1 + (px + 0.5) * 2 / size, y = 1 - (py + 0.5) * 2 /
// size.
Camera front_camera(int size) {
    Camera cam;
    cam.eye = {0, 0, 1};
    cam.look_at = {0, 0, 0};
    cam.up = {0, 1, 0};
    cam.fov_deg = 90.0;
    cam.width = size;
    cam.height = size;
    return cam;
}

// The full view of front_camera, as quad corners for (u, v) = (0,0), (1,0), (1,1), (0,1).
const std::array<glm::dvec3, 4> kFullView = {glm::dvec3(-1, -1, 0), glm::dvec3(1, -1, 0), glm::dvec3(1, 1, 0),
                                             glm::dvec3(-1, 1, 0)};

// 2x2 texture: top row red, green; bottom row blue, white.
ImageRGBA8 four_colours() {
    ImageRGBA8 img(2, 2);
    img.at(0, 0) = kRed;
    img.at(1, 0) = kGreen;
    img.at(0, 1) = kBlue;
    img.at(1, 1) = kWhite;
    return img;
}

struct Reference {
    ImageRGBA8 image;
    std::vector<uint8_t> mask;  // 1 where the expectation is not a rasterization or discard tie
};

// Double-precision ray cast of a textured parallelogram: coverage, bilinear filtering with clamp-to-edge (texel
// centres at (i + 0.5) / w), discard below alpha one half, opaque black background.
Reference reference_quad(const Camera& cam, const std::array<glm::dvec3, 4>& c, const ImageRGBA8& tex) {
    const int w = cam.width, h = cam.height;
    std::vector<int> state(size_t(w) * size_t(h), 0);  // 0 background, 1 drawn, 2 tie
    Reference ref{ImageRGBA8(w, h, kBlack), std::vector<uint8_t>(size_t(w) * size_t(h), 0)};
    const glm::dvec3 e1 = c[1] - c[0], e2 = c[3] - c[0], n = glm::cross(e1, e2);
    const double g11 = glm::dot(e1, e1), g12 = glm::dot(e1, e2), g22 = glm::dot(e2, e2), det = g11 * g22 - g12 * g12;
    for (int py = 0; py < h; ++py) {
        for (int px = 0; px < w; ++px) {
            glm::dvec3 o, d;
            cam.ray(px, py, o, d);
            double t = glm::dot(c[0] - o, n) / glm::dot(d, n);
            if (!(t > 0)) continue;
            glm::dvec3 q = o + t * d - c[0];
            double r1 = glm::dot(q, e1), r2 = glm::dot(q, e2);
            double u = (g22 * r1 - g12 * r2) / det, v = (g11 * r2 - g12 * r1) / det;
            if (u < 0 || u > 1 || v < 0 || v > 1) continue;
            double x = u * tex.width - 0.5, y = (1.0 - v) * tex.height - 0.5;  // texture rows count from the top
            int x0 = int(std::floor(x)), y0 = int(std::floor(y));
            double fx = x - x0, fy = y - y0;
            double acc[4] = {0, 0, 0, 0};
            for (int j = 0; j < 2; ++j)
                for (int i = 0; i < 2; ++i) {
                    int xi = std::clamp(x0 + i, 0, tex.width - 1), yi = std::clamp(y0 + j, 0, tex.height - 1);
                    double wgt = (i ? fx : 1 - fx) * (j ? fy : 1 - fy);
                    const Rgba8& p = tex.at(xi, yi);
                    acc[0] += wgt * p.r;
                    acc[1] += wgt * p.g;
                    acc[2] += wgt * p.b;
                    acc[3] += wgt * p.a;
                }
            size_t k = size_t(py) * size_t(w) + size_t(px);
            if (std::abs(acc[3] / 255.0 - 0.5) < 0.05) {
                state[k] = 2;
                continue;
            }
            if (acc[3] < 127.5) continue;
            state[k] = 1;
            ref.image.pixels[k] = {uint8_t(std::lround(acc[0])), uint8_t(std::lround(acc[1])),
                                   uint8_t(std::lround(acc[2])), 255};
        }
    }
    // Trust a pixel when it and its 8 neighbours agree on coverage: then it is not on an edge.
    for (int py = 0; py < h; ++py)
        for (int px = 0; px < w; ++px) {
            int s = state[size_t(py) * size_t(w) + size_t(px)];
            bool agree = s != 2;
            for (int dy = -1; dy <= 1 && agree; ++dy)
                for (int dx = -1; dx <= 1 && agree; ++dx) {
                    int x = std::clamp(px + dx, 0, w - 1), y = std::clamp(py + dy, 0, h - 1);
                    agree = state[size_t(y) * size_t(w) + size_t(x)] == s;
                }
            ref.mask[size_t(py) * size_t(w) + size_t(px)] = agree ? 1 : 0;
        }
    return ref;
}

size_t count(const std::vector<uint8_t>& mask) {
    size_t n = 0;
    for (uint8_t m : mask) n += m ? 1 : 0;
    return n;
}

class RendererTest : public ::testing::Test {
protected:
    void SetUp() override {
        ctx_ = GlContext::create_offscreen(128, 128);
        renderer_ = std::make_unique<Renderer>();
    }
    void TearDown() override {
        renderer_.reset();  // GL objects go before their context
        ctx_.reset();
    }
    std::unique_ptr<GlContext> ctx_;
    std::unique_ptr<Renderer> renderer_;
};

TEST_F(RendererTest, OffscreenContextDescribesItself) {
    EXPECT_EQ(ctx_->width(), 128);
    EXPECT_EQ(ctx_->height(), 128);
    std::string d = ctx_->describe();
    EXPECT_NE(d.find("OSMesa"), std::string::npos) << d;
    EXPECT_NE(d.find("OpenGL"), std::string::npos) << d;
    EXPECT_NO_THROW(check_gl("after setup"));
}

TEST_F(RendererTest, EmptyFrameIsOpaqueBlack) {
    Camera cam = front_camera(16);
    renderer_->begin_frame(cam);
    ImageRGBA8 out = renderer_->read_pixels(16, 16);
    EXPECT_EQ(test::compare_images(ImageRGBA8(16, 16, kBlack), out, 0), "");
}

// begin_frame's clear is issued with the frame's first draw or read-back (texmap/renderer.cpp): a frame that draws
// nothing after a drawn one must still read back cleared, finish() in between or not.
TEST_F(RendererTest, ClearIsNotLostWhenTheFrameDrawsNothing) {
    Camera cam = front_camera(64);
    GlTexture tex;
    tex.upload(four_colours());
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    ASSERT_EQ(renderer_->read_pixels(64, 64).at(2, 2), kRed);
    renderer_->begin_frame(cam);
    renderer_->finish();
    GlTexture empty;  // nothing uploaded: draw_textured_quad draws nothing
    renderer_->draw_textured_quad(cam, kFullView, empty);
    EXPECT_EQ(test::compare_images(ImageRGBA8(64, 64, kBlack), renderer_->read_pixels(64, 64), 0), "");
    // A draw after the clear was issued keeps what the frame drew.
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    renderer_->finish();
    renderer_->draw_textured_quad(cam, kFullView, empty);
    EXPECT_EQ(renderer_->read_pixels(64, 64).at(2, 2), kRed);
}

TEST_F(RendererTest, QuadWithTwoByTwoTexture) {
    Camera cam = front_camera(64);
    GlTexture tex;
    tex.upload(four_colours());
    EXPECT_NE(tex.id(), 0u);
    EXPECT_EQ(tex.width(), 2);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    ImageRGBA8 out = renderer_->read_pixels(64, 64);
    // Near the corners (beyond the outer texel centres) clamping leaves one texel: exact. The top image row is
    // v = 1, at the top of the view; u = 0 is on the left.
    EXPECT_EQ(out.at(2, 2), kRed);
    EXPECT_EQ(out.at(61, 2), kGreen);
    EXPECT_EQ(out.at(2, 61), kBlue);
    EXPECT_EQ(out.at(61, 61), kWhite);
    // Everywhere: bilinear filtering as the reference computes it.
    Reference ref = reference_quad(cam, kFullView, four_colours());
    EXPECT_EQ(test::compare_images(ref.image, out, kFilterTolerance), "");
}

// Side polygons cut down to the margins' content (ReliefSurface::wall_content, texmap/wall_clip.h) must draw
// what the whole side polygons draw. Random textures with margins whose texels are empty or hold a sample (a few
// blobs, as samples that left the quad lie), random quads, walls and eyes, with and without depth correction;
// seed printed, RTM_SEED overrides it. Each case draws the quad and its walls twice, into one frame each, and the
// frames are compared pixel by pixel.
// The parts are other triangles than the whole walls, so their interpolated positions round differently.
// Coverage: the same but on the quad's outline, where the quad's rasterization meets the walls' ray test (the
// fragment is discarded when its plane point is on the quad): a pixel whose ray meets the plane within
// kOutline texels of the quad's border may flip (seed 1, case 73: 0.011 texels below the quad, filtered alpha
// 0.53, drawn by the whole walls only), at most 2 per frame; none elsewhere, here or in 68 renders of the media
// (`rtm diff` against the uncut walls). Colour: within kWallRounding per channel, for the same rounding:
// llvmpipe's 8-bit bilinear weights may step once in each direction across a texel edge of up to 255 levels (1
// each) and the result rounds (1); measured on the media: at most 3 levels (bumps, azimuth 45, elevation 45, 1.2
// radii), PSNR 83 dB to identical. Leaving the quad's outermost texels out of margin_content's bands loses 4
// pixels along the outline in case 3 (seed 20261204), more than rounding may.
constexpr int kWallRounding = 3;
constexpr double kOutline = 0.05;

// Where the ray through pixel (px, row)'s centre meets the plane of `rs`, in texel units (u, v).
glm::dvec2 plane_point(const Camera& cam, const ReliefSurface& rs, int px, int row) {
    glm::dvec3 o, dir;
    cam.ray(px, row, o, dir);
    const glm::dvec3 n = glm::cross(rs.a, rs.b);
    const glm::dvec3 q = o + dir * (glm::dot(rs.origin - o, n) / glm::dot(dir, n)) - rs.origin;
    const double aa = glm::dot(rs.a, rs.a), ab = glm::dot(rs.a, rs.b), bb = glm::dot(rs.b, rs.b),
                 det = aa * bb - ab * ab;
    return {(glm::dot(q, rs.a) * bb - glm::dot(q, rs.b) * ab) / det,
            (glm::dot(q, rs.b) * aa - glm::dot(q, rs.a) * ab) / det};
}

TEST_F(RendererTest, WallsCutToTheMarginContentDrawTheSamePixels) {
    const uint64_t seed = test::test_seed(20261204);
    SCOPED_TRACE("seed " + std::to_string(seed));
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> U(-1.0, 1.0), S(0.0, 1.0);
    GlTexture color, displ;
    int fewer = 0, cases = 0;
    for (int iter = 0; iter < 120; ++iter) {
        const int w = 8 + int(S(rng) * 40), h = 8 + int(S(rng) * 40);
        auto margin = [&] { return S(rng) < 0.25 ? 0 : 1 + int(S(rng) * 12); };
        const int ml = margin(), mr = margin(), mb = margin(), mt = margin();
        ImageRGBA8 img(ml + w + mr, mb + h + mt);
        for (int row = 0; row < img.height; ++row)
            for (int x = 0; x < img.width; ++x) {
                const bool quad = x >= ml && x < ml + w && row >= mt && row < mt + h;
                img.at(x, row) = {uint8_t(x * 37), uint8_t(row * 53), 90, uint8_t(quad && S(rng) < 0.9 ? 255 : 0)};
            }
        for (int blobs = int(S(rng) * 4); blobs > 0; --blobs) {  // samples in the margins
            const int bx = int(S(rng) * img.width), by = int(S(rng) * img.height), r = 1 + int(S(rng) * 3);
            for (int y = std::max(0, by - r); y <= std::min(img.height - 1, by + r); ++y)
                for (int x = std::max(0, bx - r); x <= std::min(img.width - 1, bx + r); ++x) img.at(x, y).a = 255;
        }
        color.upload(img);
        ReliefSurface rs;
        rs.origin = {U(rng), U(rng), -0.5 * S(rng)};
        rs.a = glm::dvec3(1.6 + 0.4 * U(rng), 0.3 * U(rng), 0.2 * U(rng)) / double(w);
        rs.b = glm::dvec3(0.3 * U(rng), 1.6 + 0.4 * U(rng), 0.2 * U(rng)) / double(h);
        rs.origin -= 0.5 * (rs.a * double(w) + rs.b * double(h));
        rs.width = w, rs.height = h;
        rs.margin_left = ml, rs.margin_right = mr, rs.margin_bottom = mb, rs.margin_top = mt;
        rs.wall_low = -0.4 * S(rng), rs.wall_high = 0.6 * S(rng);
        Image2D<uint8_t> index(img.width, img.height);
        if (S(rng) < 0.3) {  // depth correction: random quantized displacements
            for (uint8_t& q : index.pixels) q = uint8_t(S(rng) * 256);
            displ.upload_gray(index);
            rs.displ = &displ;
            rs.k3 = 0.2 * U(rng), rs.dmin = rs.wall_low, rs.dmax = rs.wall_high, rs.qs = (rs.dmax - rs.dmin) / 253.0;
        }
        Camera cam;
        const glm::dvec3 f = glm::normalize(glm::cross(rs.a, rs.b));
        const glm::dvec3 centre = rs.origin + 0.5 * (rs.a * double(w) + rs.b * double(h));
        cam.eye = centre + f * (0.8 + 2.0 * S(rng)) + 1.5 * glm::dvec3(U(rng), U(rng), 0.0);
        cam.look_at = centre;
        cam.up = {0, 1, 0};
        cam.fov_deg = 70.0;
        cam.width = cam.height = 128;
        ImageRGBA8 frame[2];
        const std::vector<PlaneRect> content = margin_content(img, ml, mr, mb, mt);
        for (int cut = 0; cut < 2; ++cut) {
            if (cut) rs.wall_content = &content;
            renderer_->begin_frame(cam);
            renderer_->draw_relief(cam, rs, color);
            frame[cut] = renderer_->read_pixels(128, 128);
        }
        int coverage = 0, outline = 0, colour = 0;
        for (size_t k = 0; k < frame[0].pixels.size(); ++k) {
            const Rgba8 a = frame[0].pixels[k], b = frame[1].pixels[k];
            if ((a == kBlack) != (b == kBlack)) {  // the textures' blue is 90: a covered pixel is never black
                const glm::dvec2 p = plane_point(cam, rs, int(k % 128), int(k / 128));
                auto inside = [&](double by) { return p.x > -by && p.x < w + by && p.y > -by && p.y < h + by; };
                if (inside(kOutline) && !inside(-kOutline))
                    ++outline;
                else
                    ++coverage;
                continue;
            }
            const int d = std::max({std::abs(a.r - b.r), std::abs(a.g - b.g), std::abs(a.b - b.b)});
            colour += d > kWallRounding ? 1 : 0;
        }
        ASSERT_EQ(coverage, 0) << "iteration " << iter << ": " << coverage << " pixels covered in one frame only";
        ASSERT_LE(outline, 2) << "iteration " << iter << ": " << outline << " pixels on the quad's outline";
        ASSERT_EQ(colour, 0) << "iteration " << iter << ": " << colour << " pixels differ by more than "
                             << kWallRounding;
        ++cases;
        fewer += content.size() < 4 ? 1 : 0;
    }
    EXPECT_EQ(cases, 120);
    EXPECT_GT(fewer, 30);  // cases where some band is empty (a wall dropped or cut to nothing)
}

TEST_F(RendererTest, ObliqueQuadMatchesRayCastReference) {
    // A camera smaller than the context and not square; an 8x8 texture of random colours; a quad seen at an
    // angle, so perspective-correct interpolation matters.
    Camera cam;
    cam.eye = {1.2, 0.8, 2.0};
    cam.look_at = {0.1, 0.0, 0.0};
    cam.fov_deg = 60.0;
    cam.width = 96;
    cam.height = 64;
    std::mt19937 rng(42);
    ImageRGBA8 img(8, 8);
    for (Rgba8& p : img.pixels) {
        uint32_t v = rng();
        p = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), 255};
    }
    const std::array<glm::dvec3, 4> corners = {glm::dvec3(-1, -0.7, -0.5), glm::dvec3(1, -0.7, 0.2),
                                               glm::dvec3(1, 0.9, 0.2), glm::dvec3(-1, 0.9, -0.5)};
    GlTexture tex;
    tex.upload(img);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, corners, tex);
    ImageRGBA8 out = renderer_->read_pixels(cam.width, cam.height);
    Reference ref = reference_quad(cam, corners, img);
    ASSERT_GT(count(ref.mask), size_t(cam.width * cam.height / 2));  // the comparison covers most of the image
    EXPECT_EQ(test::compare_images(ref.image, out, kFilterTolerance, ref.mask), "");
}

TEST_F(RendererTest, TexelWithAlphaZeroShowsTheBackground) {
    Camera cam = front_camera(64);
    ImageRGBA8 img = four_colours();
    img.at(0, 0) = {255, 0, 0, 0};  // the red texel is empty
    GlTexture tex;
    tex.upload(img);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    ImageRGBA8 out = renderer_->read_pixels(64, 64);
    EXPECT_EQ(out.at(2, 2), kBlack);
    EXPECT_EQ(out.at(12, 12), kBlack);
    EXPECT_EQ(out.at(61, 2), kGreen);
    EXPECT_EQ(out.at(2, 61), kBlue);
    Reference ref = reference_quad(cam, kFullView, img);
    EXPECT_EQ(test::compare_images(ref.image, out, kFilterTolerance, ref.mask), "");
    // Drawn pixels are opaque: alpha is coverage, not translucency.
    for (const Rgba8& p : out.pixels) ASSERT_EQ(p.a, 255);
}

TEST_F(RendererTest, ReadPixelsPutsTheTopOfTheViewInRowZero) {
    Camera cam = front_camera(64);
    GlTexture tex;
    tex.upload(ImageRGBA8(1, 1, kGreen));
    const std::array<glm::dvec3, 4> upper_half = {glm::dvec3(-1, 0, 0), glm::dvec3(1, 0, 0), glm::dvec3(1, 1, 0),
                                                  glm::dvec3(-1, 1, 0)};
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, upper_half, tex);
    ImageRGBA8 out = renderer_->read_pixels(64, 64);
    for (int r = 0; r < 64; ++r)
        for (int x = 0; x < 64; ++x) ASSERT_EQ(out.at(x, r), r < 32 ? kGreen : kBlack) << "x=" << x << " row=" << r;
}

TEST_F(RendererTest, DepthTestKeepsTheNearerQuad) {
    Camera cam = front_camera(32);
    GlTexture red, green;
    red.upload(ImageRGBA8(1, 1, kRed));
    green.upload(ImageRGBA8(1, 1, kGreen));
    // Red is nearer (z = 0.2) and covers the left 3/4; green is behind (z = -0.2) and covers the right 3/4.
    const std::array<glm::dvec3, 4> near_quad = {glm::dvec3(-2, -2, 0.2), glm::dvec3(0.3, -2, 0.2),
                                                 glm::dvec3(0.3, 2, 0.2), glm::dvec3(-2, 2, 0.2)};
    const std::array<glm::dvec3, 4> far_quad = {glm::dvec3(-0.5, -2, -0.2), glm::dvec3(2, -2, -0.2),
                                                glm::dvec3(2, 2, -0.2), glm::dvec3(-0.5, 2, -0.2)};
    for (bool near_first : {true, false}) {
        renderer_->begin_frame(cam);
        if (near_first) renderer_->draw_textured_quad(cam, near_quad, red);
        renderer_->draw_textured_quad(cam, far_quad, green);
        if (!near_first) renderer_->draw_textured_quad(cam, near_quad, red);
        ImageRGBA8 out = renderer_->read_pixels(32, 32);
        EXPECT_EQ(out.at(2, 16), kRed) << "near_first=" << near_first;
        EXPECT_EQ(out.at(16, 16), kRed) << "near_first=" << near_first;  // overlap
        EXPECT_EQ(out.at(30, 16), kGreen) << "near_first=" << near_first;
    }
}

TEST_F(RendererTest, MeshTriangleCoversTheExpectedPixels) {
    Camera cam = front_camera(32);
    const glm::u8vec4 colour{10, 200, 30, 255};
    // Lower-left half of the view: the centre of pixel (px, py) is inside when px < py.
    std::vector<MeshVertex> v = {{{-1, -1, 0}, colour}, {{1, -1, 0}, colour}, {{-1, 1, 0}, colour}};
    renderer_->begin_frame(cam);
    renderer_->draw_mesh(cam, v, {0, 1, 2});
    ImageRGBA8 out = renderer_->read_pixels(32, 32);
    for (int py = 0; py < 32; ++py)
        for (int px = 0; px < 32; ++px) {
            if (px == py) continue;  // pixel centre on the hypotenuse: a rasterization tie
            ASSERT_EQ(out.at(px, py), px < py ? (Rgba8{10, 200, 30, 255}) : kBlack) << "px=" << px << " py=" << py;
        }
}

TEST_F(RendererTest, MeshColoursAreInterpolated) {
    Camera cam = front_camera(32);
    std::vector<MeshVertex> v = {{{-1, -1, 0}, {255, 0, 0, 255}},
                                 {{1, -1, 0}, {0, 255, 0, 255}},
                                 {{-1, 1, 0}, {0, 0, 255, 255}}};
    renderer_->begin_frame(cam);
    renderer_->draw_mesh(cam, v, {0, 1, 2});
    ImageRGBA8 out = renderer_->read_pixels(32, 32);
    // Pixel (px, py): x = -1 + (px + 0.5)/16, y = 1 - (py + 0.5)/16; barycentric weights of the three vertices are
    // green = (x + 1)/2, blue = (y + 1)/2, red = the rest (a fronto-parallel triangle: no perspective effect).
    for (auto [px, py] : {std::pair{2, 29}, {10, 20}, {5, 12}, {20, 25}}) {
        double x = -1 + (px + 0.5) / 16, y = 1 - (py + 0.5) / 16;
        double g = (x + 1) / 2, b = (y + 1) / 2, r = 1 - g - b;
        ImageRGBA8 expected(1, 1,
                            Rgba8{uint8_t(std::lround(255 * r)), uint8_t(std::lround(255 * g)),
                                  uint8_t(std::lround(255 * b)), 255});
        ImageRGBA8 got(1, 1, out.at(px, py));
        // Colour interpolation in float and conversion to 8 bits: within kFilterTolerance of the exact value.
        EXPECT_EQ(test::compare_images(expected, got, kFilterTolerance), "") << "px=" << px << " py=" << py;
    }
}

// Three triangles seen by front_camera: a transparent one in front, an opaque blue one behind, a red one in front
// of that on the right.
std::vector<MeshVertex> three_triangles() {
    return {
        {{-2, -2, 0.5f}, {255, 255, 255, 0}},  {{2, -2, 0.5f}, {255, 255, 255, 0}}, {{0, 2, 0.5f}, {255, 255, 255, 0}},
        {{-2, -2, -0.5f}, {0, 0, 255, 255}},   {{2, -2, -0.5f}, {0, 0, 255, 255}},  {{0, 2, -0.5f}, {0, 0, 255, 255}},
        {{0.25f, -2, 0.0f}, {255, 0, 0, 255}}, {{2, -2, 0.0f}, {255, 0, 0, 255}},   {{2, 2, 0.0f}, {255, 0, 0, 255}},
    };
}

TEST_F(RendererTest, MeshAlphaBelowOneHalfIsDiscardedAndDepthWorks) {
    Camera cam = front_camera(32);
    const std::vector<MeshVertex> v = three_triangles();
    renderer_->begin_frame(cam);
    renderer_->draw_mesh(cam, v, {0, 1, 2, 3, 4, 5, 6, 7, 8});
    ImageRGBA8 out = renderer_->read_pixels(32, 32);
    EXPECT_EQ(out.at(14, 28), kBlue);  // under the transparent triangle
    EXPECT_EQ(out.at(29, 28), kRed);   // the red one is nearer than the blue one
}

TEST_F(RendererTest, MeshRejectsIndicesOutOfRange) {
    Camera cam = front_camera(8);
    std::vector<MeshVertex> v = {{{0, 0, 0}, {1, 1, 1, 255}}, {{1, 0, 0}, {1, 1, 1, 255}}};
    renderer_->begin_frame(cam);
    EXPECT_THROW(renderer_->draw_mesh(cam, v, {0, 1, 2}), std::out_of_range);
    EXPECT_NO_THROW(renderer_->draw_mesh(cam, {}, {}));
    EXPECT_NO_THROW(check_gl("after draw_mesh"));
}

// A mesh kept on the GPU (GlMesh) drawn by ranges: all of it gives draw_mesh's picture; a range leaves out the
// other triangles; bad indices and ranges are refused naming them.
TEST_F(RendererTest, GpuMeshRangesDrawWhatDrawMeshDraws) {
    Camera cam = front_camera(32);
    const std::vector<MeshVertex> v = three_triangles();
    const std::vector<uint32_t> idx = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    renderer_->begin_frame(cam);
    renderer_->draw_mesh(cam, v, idx);
    const ImageRGBA8 whole = renderer_->read_pixels(32, 32);
    GlMesh mesh;
    mesh.upload(v, idx);
    EXPECT_EQ(mesh.index_count(), 9u);
    renderer_->begin_frame(cam);
    renderer_->draw_mesh_ranges(cam, mesh, {{0, 3}, {3, 6}});
    EXPECT_EQ(renderer_->read_pixels(32, 32).pixels, whole.pixels);
    renderer_->begin_frame(cam);
    renderer_->draw_mesh_ranges(cam, mesh, {{3, 3}});  // the blue triangle alone
    const ImageRGBA8 blue = renderer_->read_pixels(32, 32);
    EXPECT_EQ(blue.at(14, 28), kBlue);
    EXPECT_EQ(blue.at(29, 28), kBlue);
    for (const IndexRange& bad : {IndexRange{6, 6}, IndexRange{1, 3}, IndexRange{0, 4}}) {
        try {
            renderer_->draw_mesh_ranges(cam, mesh, {bad});
            ADD_FAILURE() << "range " << bad.first << "+" << bad.count << " accepted";
        } catch (const std::out_of_range& e) {
            EXPECT_NE(std::string(e.what()).find("first " + std::to_string(bad.first)), std::string::npos) << e.what();
        }
    }
    GlMesh short_mesh;
    EXPECT_THROW(short_mesh.upload({v[0], v[1]}, {0, 1, 2}), std::out_of_range);
    EXPECT_NO_THROW(renderer_->draw_mesh_ranges(cam, mesh, {}));
    EXPECT_NO_THROW(check_gl("after draw_mesh_ranges"));
}

TEST_F(RendererTest, UploadUpdatesInPlaceAndUploadRectOnlyItsRectangle) {
    Camera cam = front_camera(64);
    ImageRGBA8 img(4, 4, kRed);
    GlTexture tex;
    tex.upload(img);
    const unsigned id = tex.id();

    // Same size: updated in place (same texture object), new content.
    img = ImageRGBA8(4, 4, kBlue);
    tex.upload(img);
    EXPECT_EQ(tex.id(), id);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    EXPECT_EQ(renderer_->read_pixels(64, 64).at(32, 32), kBlue);

    // Change the top-right 2x2 texels and the bottom-left one in the CPU image, upload only the top-right.
    for (int r = 0; r < 2; ++r)
        for (int x = 2; x < 4; ++x) img.at(x, r) = kGreen;
    img.at(0, 3) = kWhite;
    tex.upload_rect(img, 2, 0, 2, 2);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    ImageRGBA8 out = renderer_->read_pixels(64, 64);
    EXPECT_EQ(out.at(60, 3), kGreen);  // top right: the uploaded rectangle, rows counted from the top
    EXPECT_EQ(out.at(3, 3), kBlue);    // top left: untouched
    EXPECT_EQ(out.at(3, 60), kBlue);   // bottom left: changed on the CPU but not uploaded
    EXPECT_EQ(out.at(60, 60), kBlue);

    EXPECT_THROW(tex.upload_rect(img, 3, 0, 2, 1), std::invalid_argument);
    EXPECT_THROW(tex.upload_rect(img, 0, -1, 1, 1), std::invalid_argument);

    // A new size re-allocates.
    tex.upload(ImageRGBA8(3, 5, kWhite));
    EXPECT_EQ(tex.width(), 3);
    EXPECT_EQ(tex.height(), 5);
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    EXPECT_EQ(renderer_->read_pixels(64, 64).at(32, 32), kWhite);
}

// A small composite scene (oblique textured quad with an empty corner, crossed by a coloured triangle) against a
// golden image, as a regression guard for the whole pipeline. Tolerance: kFilterTolerance, for bilinear and
// colour-interpolation rounding that may differ between Mesa versions. RTM_UPDATE_GOLDEN=1 rewrites the golden.
TEST_F(RendererTest, CompositeSceneMatchesGolden) {
    Camera cam;
    cam.eye = {0.6, 0.9, 2.2};
    cam.look_at = {0, 0, 0};
    cam.fov_deg = 45.0;
    cam.width = 48;
    cam.height = 40;
    cam.fit_clip_planes({0, 0, 0}, 1.5);
    ImageRGBA8 img(4, 4);
    for (int r = 0; r < 4; ++r)
        for (int x = 0; x < 4; ++x) img.at(x, r) = {uint8_t(60 * x + 40), uint8_t(60 * r + 40), 128, 255};
    img.at(0, 0).a = 0;
    GlTexture tex;
    tex.upload(img);
    std::vector<MeshVertex> tri = {{{-0.8f, -0.6f, -0.4f}, {255, 0, 0, 255}},
                                   {{0.9f, -0.2f, 0.5f}, {0, 255, 0, 255}},
                                   {{0.0f, 0.8f, 0.1f}, {0, 0, 255, 255}}};
    renderer_->begin_frame(cam);
    renderer_->draw_textured_quad(cam, kFullView, tex);
    renderer_->draw_mesh(cam, tri, {0, 1, 2});
    renderer_->finish();
    ImageRGBA8 out = renderer_->read_pixels(cam.width, cam.height);
    EXPECT_EQ(test::check_golden("composite_scene", out, kFilterTolerance), "");
}

// --- Window back end ---------------------------------------------------------------------------------------------

TEST(GlContextWindow, WithoutADisplaySaysSo) {
    std::string display = std::getenv("DISPLAY") ? std::getenv("DISPLAY") : "";
    std::string wayland = std::getenv("WAYLAND_DISPLAY") ? std::getenv("WAYLAND_DISPLAY") : "";
    unsetenv("DISPLAY");
    unsetenv("WAYLAND_DISPLAY");
    try {
        GlContext::create_window(32, 32, "rtm test", false);
        ADD_FAILURE() << "no GlError without a display";
    } catch (const GlError& e) {
        EXPECT_NE(std::string(e.what()).find("no display"), std::string::npos) << e.what();
    }
    if (!display.empty()) setenv("DISPLAY", display.c_str(), 1);
    if (!wayland.empty()) setenv("WAYLAND_DISPLAY", wayland.c_str(), 1);
}

TEST(GlContextWindow, HiddenWindowRenders) {
    const char* display = std::getenv("DISPLAY");
    if (!display || !*display) GTEST_SKIP() << "no DISPLAY (run under xvfb-run to test the window back end)";
    auto ctx = GlContext::create_window(32, 32, "rtm test", false);
    EXPECT_NE(ctx->describe().find("GLFW"), std::string::npos) << ctx->describe();
    EXPECT_NE(ctx->native_window(), nullptr);
    {
        Renderer renderer;
        GlTexture tex;
        tex.upload(four_colours());
        Camera cam = front_camera(32);
        renderer.begin_frame(cam);
        renderer.draw_textured_quad(cam, kFullView, tex);
        ImageRGBA8 out = renderer.read_pixels(32, 32);
        EXPECT_EQ(out.at(0, 0), kRed);
        EXPECT_EQ(out.at(31, 31), kWhite);
    }
    ctx->swap_buffers();
    ctx->poll_events();
    EXPECT_FALSE(ctx->should_close());
}

TEST(GlContextOffscreen, RejectsImpossibleSizes) {
    EXPECT_THROW(GlContext::create_offscreen(0, 10), GlError);
    EXPECT_THROW(GlContext::create_offscreen(10, -1), GlError);
    EXPECT_THROW(GlContext::create_offscreen(100000, 10), GlError);
}

}  // namespace
}  // namespace rtm
