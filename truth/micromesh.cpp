// Micro-polygon mesh of a relief texture (paper section 3.2.1, "rendered as meshes of micro-polygons").
//
// Cell (x, row) is the square of texel centres (x, row), (x+1, row), (x, row+1), (x+1, row+1), rows counted from
// the top. In (u, v) (v up) its corners are
//     c00 = (x, row+1)  (u, v)        c10 = (x+1, row+1)  (u+1, v)
//     c01 = (x, row)    (u, v+1)      c11 = (x+1, row)    (u+1, v+1)
// Diagonal: always c00-c11, the one from low (u, v) to high (u, v) (bottom-left to top-right as the image file is
// looked at). Triangles (c00, c10, c11) and (c00, c11, c01) are counter-clockwise seen from +f, so an OpenGL
// front face is the side the relief stands out towards (the renderer does not cull; this only fixes the order).
// With discontinuity marks (ReliefTexture::breaks) triangles crossing a marked pair are left out.
#include "truth/micromesh.h"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace rtm {

MicroMesh build_micromesh(const ReliefTexture& t, std::vector<uint32_t>* triangle_cells) {
    MicroMesh m;
    if (triangle_cells) triangle_cells->clear();
    const int w = t.width, h = t.height;
    if (w <= 0 || h <= 0) return m;
    constexpr uint32_t kNone = std::numeric_limits<uint32_t>::max();
    if (size_t(w) * size_t(h) >= size_t(kNone))
        throw std::invalid_argument("relief of " + std::to_string(w) + "x" + std::to_string(h) +
                                    " texels is too large for 32-bit mesh indices");
    std::vector<uint32_t> index(size_t(w) * size_t(h), kNone);
    m.origin = t.geometry.origin;
    for (int row = 0; row < h; ++row)
        for (int x = 0; x < w; ++x) {
            if (t.empty_at(x, row)) continue;
            const ReliefTexel& tx = t.texel(x, row);
            index[size_t(row) * size_t(w) + size_t(x)] = uint32_t(m.vertices.size());
            m.vertices.push_back({glm::vec3(t.point(x, row) - m.origin), glm::u8vec4(tx.r, tx.g, tx.b, 255)});
        }
    for (int row = 0; row + 1 < h; ++row)
        for (int x = 0; x + 1 < w; ++x) {
            const uint32_t c01 = index[size_t(row) * size_t(w) + size_t(x)];
            const uint32_t c11 = index[size_t(row) * size_t(w) + size_t(x + 1)];
            const uint32_t c00 = index[size_t(row + 1) * size_t(w) + size_t(x)];
            const uint32_t c10 = index[size_t(row + 1) * size_t(w) + size_t(x + 1)];
            if (c00 == kNone || c10 == kNone || c01 == kNone || c11 == kNone) continue;  // a hole
            const size_t before = m.indices.size();
            if (t.breaks.empty()) {
                m.indices.insert(m.indices.end(), {c00, c10, c11, c00, c11, c01});
            } else {
                // Surface discontinuities (section 4.1.1): the same cut as the pre-warp makes. A triangle is kept
                // only when none of its edges crosses a marked pair; the diagonal is tested against the threshold.
                auto br = [&](int xx, int rr) { return t.breaks[size_t(rr) * size_t(w) + size_t(xx)]; };
                const bool diag_ok = std::abs(t.displ(x, row + 1) - t.displ(x + 1, row)) <= t.discontinuity_threshold;
                const bool lower_ok = diag_ok && !(br(x, row + 1) & kBreakRight) && !(br(x + 1, row + 1) & kBreakUp);
                const bool upper_ok = diag_ok && !(br(x, row) & kBreakRight) && !(br(x, row + 1) & kBreakUp);
                if (lower_ok) m.indices.insert(m.indices.end(), {c00, c10, c11});
                if (upper_ok) m.indices.insert(m.indices.end(), {c00, c11, c01});
            }
            if (triangle_cells)
                triangle_cells->insert(triangle_cells->end(), (m.indices.size() - before) / 3,
                                       uint32_t(size_t(row) * size_t(w) + size_t(x)));
        }
    return m;
}

}  // namespace rtm
