// Draws a relief texture with a per-pixel method: the relief's top polygon (the quad raised to the top of the
// displacement range, where every height-field ray marcher starts) through the OpenGL 3.3 path, each fragment
// marching its eye ray down through the depth map. Keeps its textures and programs in the GL context current
// when it first draws; use it with that context only.
#pragma once

#include <map>
#include <memory>
#include <tuple>

#include "perpixel/perpixel_method.h"
#include "texmap/camera.h"
#include "texmap/renderer.h"
#include "warp/relief_texture.h"

namespace rtm {

class PerPixelQuad {
public:
    PerPixelQuad();
    ~PerPixelQuad();
    PerPixelQuad(const PerPixelQuad&) = delete;
    PerPixelQuad& operator=(const PerPixelQuad&) = delete;

    // Draws into the current frame (Renderer::begin_frame first). Throws std::invalid_argument for bad settings,
    // GlError when a shader does not compile or GL fails.
    // `t` is uploaded on the first draw: pass the same relief every time.
    void draw(Renderer& renderer, const Camera& cam, const ReliefTexture& t, PerPixelMethod m,
              const PerPixelSettings& s);
    // Compiles and links the program of `m` with `common`'s switches (what draw() does on first use);
    // quadric_exact: quadric silhouettes' exact distance; steep: protruded displacement mapping's steep texture.
    void prepare(PerPixelMethod m, const PerPixelCommon& common, bool quadric_exact = false, bool steep = false);
    // The texture protruded displacement mapping puts on steep slopes (ProtrudedDisplacementSettings::steep_texture);
    // builtin_steep_texture() until set. Kept here and uploaded by the next draw that uses it. Throws
    // std::invalid_argument for an empty image.
    void set_steep_texture(const ImageRGBA8& img);

private:
    std::unique_ptr<GlTexture> color_, color_float_, relief_map_, depth_map_, steep_;
    std::unique_ptr<ImageRGBA8> steep_image_;  // set and not yet uploaded
    unsigned vao_ = 0, vbo_ = 0;
    unsigned quadric_vao_ = 0, quadric_vbo_ = 0, quadric_ebo_ = 0;
    // Programs by (method, depth correction, shading, shadows, iteration counts, float textures, quadric exact,
    // steep texture).
    std::map<std::tuple<int, bool, bool, bool, bool, bool, bool, bool>, unsigned> programs_;
    unsigned program(PerPixelMethod m, const PerPixelCommon& c, bool quadric_exact, bool steep);
    void draw_quadric(const Camera& cam, const ReliefTexture& t, const PerPixelSettings& s, unsigned prog);
};

}  // namespace rtm
