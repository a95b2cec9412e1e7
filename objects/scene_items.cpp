#include "objects/scene_items.h"

#include <glm/geometric.hpp>
#include <glm/mat3x3.hpp>
#include <glm/matrix.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "mesh/mesh_renderer.h"
#include "truth/micromesh.h"
#include "texmap/renderer.h"

namespace rtm {

double similarity_scale(const glm::dmat4& m) {
    const glm::dmat3 l(m);
    const double s = glm::length(l[0]);
    // Orthogonal columns of one length, no mirror (which would turn a relief's displacement direction f against
    // its transformed quad).
    const double tol = 1e-9 * s;
    const bool similar = s > 0 && std::abs(glm::length(l[1]) - s) <= tol && std::abs(glm::length(l[2]) - s) <= tol &&
                         std::abs(glm::dot(l[0], l[1])) <= tol * s && std::abs(glm::dot(l[0], l[2])) <= tol * s &&
                         std::abs(glm::dot(l[1], l[2])) <= tol * s && glm::determinant(l) > 0;
    if (!similar)
        throw std::invalid_argument("the transform must be a rotation, a translation and a uniform scale > 0");
    return s;
}

Camera object_frame_camera(const Camera& cam, const glm::dmat4& world_from_object) {
    const double s = similarity_scale(world_from_object);
    const glm::dmat4 inv = glm::inverse(world_from_object);
    Camera c = cam;
    c.eye = glm::dvec3(inv * glm::dvec4(cam.eye, 1.0));
    c.look_at = glm::dvec3(inv * glm::dvec4(cam.look_at, 1.0));
    c.up = glm::dmat3(inv) * cam.up * s;  // the rotation's inverse (the length does not matter)
    c.z_near = cam.z_near / s;
    c.z_far = cam.z_far / s;
    return c;
}

namespace {

SixFaceObject checked_placement(SixFaceObject object, const glm::dmat4& world_from_object) {
    (void)similarity_scale(world_from_object);
    return object;
}

}  // namespace

PlacedObject::PlacedObject(SixFaceObject object, const glm::dmat4& world_from_object,
                           const ReliefObject::FaceShares& shared)
    : object_(checked_placement(std::move(object), world_from_object), shared), world_from_object_(world_from_object) {}

Bounds PlacedObject::bounds() const {
    const Bounds local = object_.bounds();
    Bounds b;
    for (int k = 0; k < 8; ++k) {
        const glm::dvec3 p((k & 1) ? local.hi.x : local.lo.x, (k & 2) ? local.hi.y : local.lo.y,
                           (k & 4) ? local.hi.z : local.lo.z);
        b.extend(glm::dvec3(world_from_object_ * glm::dvec4(p, 1.0)));
    }
    return b;
}

void PlacedObject::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                        const DrawOptions& draw, StageTimes& times, ObjectReport* report) {
    const Camera local = object_frame_camera(cam, world_from_object_);
    if (method == RenderMethod::micromesh) {
        for (int f = 0; f < kFaceCount; ++f) {
            const MicroMesh& mm = object_.face(f).micromesh();
            draw_mesh(renderer, local, mm);
        }
        return;
    }
    // The per-pixel methods apply to single reliefs: an object is drawn by relief texture mapping among them.
    object_.draw(renderer, local, perpixel_method(method) ? RenderMethod::two_pass : method, options, times, draw,
                 report);
}

PlacedMesh::PlacedMesh(TriangleMesh mesh, const glm::dmat4& world_from_mesh) : mesh_(std::move(mesh)) {
    if (world_from_mesh == glm::dmat4(1.0)) return;
    mesh_.lo = glm::dvec3(std::numeric_limits<double>::infinity());
    mesh_.hi = -mesh_.lo;
    for (MeshVertexAttribs& v : mesh_.vertices) {
        const glm::dvec3 p(world_from_mesh * glm::dvec4(glm::dvec3(v.position), 1.0));
        v.position = glm::vec3(p);
    }
    for (uint32_t i : mesh_.indices) {
        mesh_.lo = glm::min(mesh_.lo, glm::dvec3(mesh_.vertices[i].position));
        mesh_.hi = glm::max(mesh_.hi, glm::dvec3(mesh_.vertices[i].position));
    }
}

PlacedMesh::~PlacedMesh() = default;
PlacedMesh::PlacedMesh(PlacedMesh&&) noexcept = default;

Bounds PlacedMesh::bounds() const { return Bounds{mesh_.lo, mesh_.hi}; }

void PlacedMesh::draw(Renderer& renderer, const Camera& cam) {
    renderer.clear_if_pending();
    if (!gl_) gl_ = std::make_unique<MeshRenderer>(mesh_);
    gl_->draw(cam.projection() * cam.view());
}

}  // namespace rtm
