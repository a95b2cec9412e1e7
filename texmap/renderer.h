// The texture-mapping stage: draws relief quads with their pre-warped textures (bilinear filtering; fragments
// whose texture alpha is below one half are discarded, so empty texels show the background), coloured triangle
// meshes (micro-polygons, conventional geometry), and reads the framebuffer back. Background: opaque black.
// Requires a current GlContext.
#pragma once

#include <glm/vec3.hpp>
#include <glm/vec4.hpp>

#include <array>
#include <cstdint>
#include <vector>

#include "texmap/camera.h"
#include "warp/image.h"

namespace rtm {

// A 2-D RGBA8 texture on the GPU. upload() (re)allocates when the size changes, else updates in place;
// upload_rect() updates only a sub-rectangle (rows counted from the top of `img`).
class GlTexture {
public:
    GlTexture();
    ~GlTexture();
    GlTexture(const GlTexture&) = delete;
    GlTexture& operator=(const GlTexture&) = delete;
    void upload(const ImageRGBA8& img);
    void upload_rect(const ImageRGBA8& img, int x, int row, int w, int h);
    unsigned id() const { return id_; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    unsigned id_ = 0;
    int width_ = 0, height_ = 0;
};

struct MeshVertex {
    glm::vec3 position;
    glm::u8vec4 color;
};

class Renderer {
public:
    Renderer();   // compiles shaders, creates buffers
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    void begin_frame(const Camera& cam);  // viewport, clear colour (0,0,0,1) and depth
    // corners: world positions of the texture's (u,v) = (0,0), (w,0), (w,h), (0,h) in that order; the texture's
    // top row is v = h (shared/CONVENTIONS.md).
    void draw_textured_quad(const Camera& cam, const std::array<glm::dvec3, 4>& corners, const GlTexture& tex);
    // Vertex alpha, like texture alpha, is coverage: fragments whose interpolated alpha is below one half are
    // discarded; everything drawn is written opaque. Indices must be < vertices.size() (else std::out_of_range).
    void draw_mesh(const Camera& cam, const std::vector<MeshVertex>& vertices, const std::vector<uint32_t>& indices);
    void finish();                                   // glFinish, so a timer around draw calls measures them
    ImageRGBA8 read_pixels(int width, int height);   // top row first

private:
    struct Impl;
    Impl* impl_;
};

}  // namespace rtm
