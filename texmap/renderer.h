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
#include "texmap/wall_clip.h"
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
    // One 8-bit channel (GL_R8), nearest filtering: quantized displacement indices for depth correction.
    void upload_gray(const Image2D<uint8_t>& img);
    // One 32-bit float channel (GL_R32F), bilinear filtering: the per-pixel methods' exact depth map.
    void upload_float(const ImageF& img);
    // The 8-bit values of `img` (v / 255) in a GL_RGBA32F texture, bilinear: filtered in float, not in 8 bits.
    void upload_as_float(const ImageRGBA8& img);
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

// A triangle mesh kept on the GPU: vertices and 32-bit indices uploaded once (upload() validates the indices:
// std::out_of_range naming the first bad one), then drawn every frame by Renderer::draw_mesh_ranges without
// crossing the bus again. Only whole triangles are kept (a trailing partial one is dropped, as in draw_mesh).
class GlMesh {
public:
    GlMesh();
    ~GlMesh();
    GlMesh(const GlMesh&) = delete;
    GlMesh& operator=(const GlMesh&) = delete;
    void upload(const std::vector<MeshVertex>& vertices, const std::vector<uint32_t>& indices);
    size_t index_count() const { return index_count_; }
    unsigned vertex_array() const { return vao_; }

private:
    unsigned vao_ = 0, vbo_ = 0, ebo_ = 0;
    size_t index_count_ = 0;
};

// A range of a mesh's indices, in indices (a multiple of 3 for whole triangles).
struct IndexRange {
    uint32_t first = 0, count = 0;
};

// A relief quad with its pre-warped texture, for draw_relief. The texture covers the quad plus margins (samples
// kept beyond the quad, paper section 4): texel units u in [-margin_left, width + margin_right), v likewise.
struct ReliefSurface {
    glm::dvec3 origin{0.0}, a{1, 0, 0}, b{0, 1, 0};  // the relief plane (docs/FORMATS.md)
    int width = 0, height = 0;                       // the quad, in texels
    int margin_left = 0, margin_right = 0, margin_bottom = 0, margin_top = 0;
    // wall_low < wall_high: side polygons perpendicular to the quad, spanning these displacements along f, along
    // each border that has a margin. Their fragments show the samples that left the quad through that border:
    // standing-out texels leave it on the side away from the epipole, recessed texels (d < 0) towards it.
    double wall_low = 0.0, wall_high = 0.0;
    // When set, the texture's margin_content (texmap/wall_clip.h): the side polygons are cut down to what can
    // show a texel of it; empty, they are not drawn. Null, they are drawn whole (less the quad's cone).
    const std::vector<PlaneRect>* wall_content = nullptr;
    // Depth correction (paper section 4.2): when `displ` is set, each fragment's eye-space depth is the plane
    // point's depth scaled by 1 + k3*d, d decoded from the index texture (min + q*qs, 254 = max, 255 = none).
    const GlTexture* displ = nullptr;
    double k3 = 0.0, dmin = 0.0, dmax = 0.0, qs = 0.0;
};

class Renderer {
public:
    Renderer();  // compiles shaders, creates buffers
    ~Renderer();
    Renderer(const Renderer&) = delete;
    Renderer& operator=(const Renderer&) = delete;

    // Viewport, clear colour (0,0,0,1) and depth. The clear is issued with the frame's first draw (or read_pixels),
    // not here: llvmpipe then clears in the draw's own pass over the tiles instead of in a pass of its own that a
    // finish() between them (the upload's timer) would force, 0.15 to 0.18 ms a frame at 512x512.
    void begin_frame(const Camera& cam);
    // Issues begin_frame's clear now if no draw has yet: for drawing code outside this class (perpixel/).
    void clear_if_pending();
    // corners: world positions of the texture's (u,v) = (0,0), (w,0), (w,h), (0,h) in that order; the texture's
    // top row is v = h (docs/FORMATS.md).
    void draw_textured_quad(const Camera& cam, const std::array<glm::dvec3, 4>& corners, const GlTexture& tex);
    // Vertex alpha, like texture alpha, is coverage: fragments whose interpolated alpha is below one half are
    // discarded; everything drawn is written opaque. Indices must be < vertices.size() (else std::out_of_range).
    // Draws the relief quad (and its side polygons) for a camera whose eye is the pre-warp's centre of
    // projection. Each fragment looks up the texture where its eye ray meets the relief plane, so the side
    // polygons show exactly what the plane's extension would, clipped to the walls. Texture convention: empty
    // texels are (0, 0, 0, 0), so bilinear filtering divided by alpha gives no dark fringe at silhouettes.
    void draw_relief(const Camera& cam, const ReliefSurface& surface, const GlTexture& color);
    // Positions are relative to `origin` (world point = origin + position; the offset is applied in double).
    void draw_mesh(const Camera& cam, const std::vector<MeshVertex>& vertices, const std::vector<uint32_t>& indices,
                   const glm::dvec3& origin = glm::dvec3(0.0));
    // Draws these ranges of a mesh on the GPU in one call (glMultiDrawElements), the same fragments as draw_mesh of
    // the same triangles. A range past the mesh's indices or not of whole triangles is std::out_of_range.
    void draw_mesh_ranges(const Camera& cam, const GlMesh& mesh, const std::vector<IndexRange>& ranges,
                          const glm::dvec3& origin = glm::dvec3(0.0));
    void finish();  // glFinish, so a timer around draw calls measures them
    // While not timed, finish() returns at once: the stage timers then measure only the CPU's side, and llvmpipe
    // renders a frame's draws without waiting between them. Timed by default; the viewer times 1 frame in 16.
    void set_timed(bool timed);
    bool timed() const;
    ImageRGBA8 read_pixels(int width, int height);  // top row first
    int max_texture_size() const;                   // GL_MAX_TEXTURE_SIZE of this context (16384 on llvmpipe)

private:
    struct Impl;
    Impl* impl_;
};

}  // namespace rtm
