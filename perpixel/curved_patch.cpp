#include "perpixel/curved_patch.h"

#include <glm/geometric.hpp>

#include <cmath>
#include <set>

namespace rtm {

namespace {
double azimuth(const CurvedPatch& p, double s) { return (s - 0.5) * p.angle; }
double latitude(const CurvedPatch& p, double t) {
    return p.shape == CurvedPatch::Shape::sphere ? (t - 0.5) * p.angle_b : 0.0;
}
}  // namespace

glm::dvec3 CurvedPatch::normal(double s, double t) const {
    const double th = azimuth(*this, s), ph = latitude(*this, t);
    return std::cos(ph) * (std::sin(th) * a_hat + std::cos(th) * f) + std::sin(ph) * b_hat;
}

glm::dvec3 CurvedPatch::tangent(double s, double t) const {
    (void)t;
    const double th = azimuth(*this, s);
    return std::cos(th) * a_hat - std::sin(th) * f;
}

glm::dvec3 CurvedPatch::binormal(double s, double t) const {
    if (shape == Shape::cylinder) return b_hat;
    const double th = azimuth(*this, s), ph = latitude(*this, t);
    return std::cos(ph) * b_hat - std::sin(ph) * (std::sin(th) * a_hat + std::cos(th) * f);
}

glm::dvec2 CurvedPatch::tile(double s, double t) const {
    (void)s;
    return {width * std::cos(latitude(*this, t)), height};
}

glm::dvec3 CurvedPatch::point(double s, double t, double d) const {
    const double r = radius - d * depth;
    if (shape == Shape::sphere) return centre + normal(s, t) * r;
    return centre + b_hat * ((t - 0.5) * height) + normal(s, t) * r;
}

CurvedPatch curved_patch_for(const ReliefTexture& t, CurvedPatch::Shape shape, double angle) {
    const ReliefGeometry& g = t.geometry;
    CurvedPatch p;
    p.shape = shape;
    p.f = g.f();
    p.a_hat = glm::normalize(g.a);
    p.b_hat = glm::normalize(glm::cross(p.f, p.a_hat));
    p.width = glm::length(g.a) * t.width;
    p.height = glm::length(g.b) * t.height;  // a and b orthogonal (the reliefs here)
    p.angle = angle;
    p.radius = p.width / angle;
    p.angle_b = p.height / p.radius;
    p.depth = t.quant.max - t.quant.min;
    const glm::dvec3 mid = g.origin + 0.5 * (g.a * double(t.width) + g.b * double(t.height)) + p.f * t.quant.max;
    p.centre = mid - p.f * p.radius;
    return p;
}

std::optional<CurvedPatch::Shape> parse_curved_shape(const std::string& name) {
    if (name == "cylinder") return CurvedPatch::Shape::cylinder;
    if (name == "sphere") return CurvedPatch::Shape::sphere;
    return std::nullopt;
}

std::string to_string(CurvedPatch::Shape shape) { return shape == CurvedPatch::Shape::sphere ? "sphere" : "cylinder"; }

void curved_base_mesh(const CurvedPatch& p, int segments, int rows, std::vector<QuadricVertex>& vertices,
                      std::vector<uint32_t>& indices, const glm::dvec3& origin) {
    vertices.clear();
    indices.clear();
    const int nx = segments + 1, ny = rows + 1;
    auto id = [&](int i, int j) { return uint32_t(j * nx + i); };
    for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) {
            const double s = double(i) / segments, t = double(j) / rows;
            QuadricVertex v;
            v.position = glm::vec3(p.point(s, t) - origin);
            v.normal = glm::vec3(p.normal(s, t));
            v.tangent = glm::vec3(p.tangent(s, t));
            v.binormal = glm::vec3(p.binormal(s, t));
            v.st = glm::vec2(float(s), float(t));
            v.tile = glm::vec2(p.tile(s, t));
            vertices.push_back(v);
        }
    for (int j = 0; j < rows; ++j)
        for (int i = 0; i < segments; ++i) {
            indices.insert(indices.end(), {id(i, j), id(i + 1, j), id(i + 1, j + 1)});
            indices.insert(indices.end(), {id(i, j), id(i + 1, j + 1), id(i, j + 1)});
        }
    // The paper's equation 2: least squares of z' = a x'^2 + b y'^2 over the vertices of the triangles sharing the
    // vertex, in its tangent frame (x along the tangent, y the binormal, z the outward normal), in double.
    std::vector<std::set<uint32_t>> ring(vertices.size());
    for (size_t k = 0; k + 2 < indices.size(); k += 3)
        for (int e = 0; e < 3; ++e)
            for (int o = 0; o < 3; ++o) ring[indices[k + size_t(e)]].insert(indices[k + size_t(o)]);
    for (size_t k = 0; k < vertices.size(); ++k) {
        const double s = vertices[k].st.x, t = vertices[k].st.y;
        const glm::dvec3 o = p.point(s, t), T = p.tangent(s, t), N = p.normal(s, t), B = p.binormal(s, t);
        double xx = 0, xy = 0, yy = 0, xz = 0, yz = 0;  // A^T A and A^T b with rows (x^2, y^2)
        for (uint32_t n : ring[k]) {
            if (n == k) continue;
            const glm::dvec3 d = p.point(vertices[n].st.x, vertices[n].st.y) - o;
            const double x2 = std::pow(glm::dot(d, T), 2), y2 = std::pow(glm::dot(d, B), 2), z = glm::dot(d, N);
            xx += x2 * x2;
            xy += x2 * y2;
            yy += y2 * y2;
            xz += x2 * z;
            yz += y2 * z;
        }
        const double det = xx * yy - xy * xy;
        double a = 0, b = 0;
        if (std::abs(det) > 1e-30 * (xx * yy + 1e-300)) {
            a = (yy * xz - xy * yz) / det;
            b = (xx * yz - xy * xz) / det;
        } else if (xx > 0) {
            a = xz / xx;
        }
        vertices[k].quadric = glm::vec2(float(a), float(b));
    }
}

void curved_micromesh(const ReliefTexture& t, const CurvedPatch& p, std::vector<MeshVertex>& vertices,
                      std::vector<uint32_t>& indices, const glm::dvec3& origin) {
    vertices.clear();
    indices.clear();
    const double range = t.quant.max - t.quant.min;
    for (int row = 0; row < t.height; ++row)
        for (int i = 0; i < t.width; ++i) {
            const double s = (i + 0.5) / t.width, tt = (t.height - 1 - row + 0.5) / t.height;
            const ReliefTexel& x = t.texel(i, row);
            const double d = x.q == kEmptyIndex || range <= 0 ? 1.0 : (t.quant.max - t.displ(i, row)) / range;
            vertices.push_back({glm::vec3(p.point(s, tt, d) - origin),
                                glm::u8vec4(x.r, x.g, x.b, x.q == kEmptyIndex ? 0 : 255)});
        }
    auto id = [&](int i, int row) { return uint32_t(row * t.width + i); };
    for (int row = 0; row + 1 < t.height; ++row)
        for (int i = 0; i + 1 < t.width; ++i) {
            if (t.empty_at(i, row) || t.empty_at(i + 1, row) || t.empty_at(i, row + 1) || t.empty_at(i + 1, row + 1))
                continue;
            indices.insert(indices.end(), {id(i, row), id(i + 1, row), id(i + 1, row + 1)});
            indices.insert(indices.end(), {id(i, row), id(i + 1, row + 1), id(i, row + 1)});
        }
}

}  // namespace rtm
