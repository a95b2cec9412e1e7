// Conventional OpenGL 3.3 core rendering of a TriangleMesh (mesh/triangle_mesh.h): unlit colour, depth test, no
// culling (unless asked for), no multisampling (each pixel shows the surface at its centre), into an offscreen
// framebuffer. With a distance plane it also returns, per pixel, the signed distance of the visible surface from
// that plane (single precision, interpolated linearly across each triangle: exact up to rounding for an
// orthographic view).
// Requires a current GlContext (texmap/gl_context.h); the size of its own framebuffer does not matter.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>

#include <optional>

#include "mesh/triangle_mesh.h"
#include "texmap/camera.h"
#include "warp/image.h"

namespace rtm {

struct MeshFrame {
    ImageRGBA8 color;  // top row first; background where nothing was drawn, drawn pixels opaque
    ImageF distance;   // when a plane was given: dot(n, X) + w of the visible point; empty otherwise
};

class MeshRenderer {
public:
    explicit MeshRenderer(const TriangleMesh& mesh);  // uploads vertices, indices and textures
    ~MeshRenderer();
    MeshRenderer(const MeshRenderer&) = delete;
    MeshRenderer& operator=(const MeshRenderer&) = delete;

    // clip_from_world maps world positions to OpenGL clip space. plane = (n, w): see MeshFrame::distance.
    // cull_back_faces: triangles wound clockwise on screen (their back seen, for a mesh whose faces are wound
    // counter-clockwise seen from outside, as glTF, OBJ and PLY files usually are) are not drawn.
    MeshFrame render(const glm::dmat4& clip_from_world, int width, int height, Rgba8 background,
                     const std::optional<glm::dvec4>& plane = std::nullopt, bool cull_back_faces = false);
    // Perspective view of the camera (texmap/camera.h), opaque black background (shared conventions).
    ImageRGBA8 render(const Camera& cam);
    // Draws into the framebuffer that is bound, with its viewport and depth test as they are (no clear, no read
    // back): a mesh among other geometry sharing one depth buffer (objects/scene_items.h).
    void draw(const glm::dmat4& clip_from_world);

private:
    struct Impl;
    Impl* impl_;
};

}  // namespace rtm
