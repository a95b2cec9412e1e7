#include "warp/box_faces.h"

#include <sstream>

namespace rtm {

int face_index(const std::string& key) {
    for (int i = 0; i < kFaceCount; ++i)
        if (key == kFaceKeys[size_t(i)]) return i;
    return -1;
}

std::string Box::to_string() const {
    std::ostringstream o;
    o << "Box{min (" << lo.x << ", " << lo.y << ", " << lo.z << "), max (" << hi.x << ", " << hi.y << ", " << hi.z
      << ")}";
    return o.str();
}

int face_step_axis(int face, int which) {
    // a: +x,-x step along z; +y,-y,+z,-z along x.  b: +y,-y along z; the others along y.
    static constexpr int a_axis[kFaceCount] = {2, 2, 0, 0, 0, 0};
    static constexpr int b_axis[kFaceCount] = {1, 1, 2, 2, 1, 1};
    return which == 0 ? a_axis[face] : b_axis[face];
}

ReliefGeometry box_face_geometry(const Box& box, int face, int width, int height) {
    const glm::dvec3 lo = box.lo, hi = box.hi, e = box.extent();
    const double w = double(width), h = double(height);
    ReliefGeometry g;
    switch (face) {
        case 0:  // +x
            g.origin = {hi.x, lo.y, hi.z};
            g.a = {0, 0, -e.z / w};
            g.b = {0, e.y / h, 0};
            break;
        case 1:  // -x
            g.origin = {lo.x, lo.y, lo.z};
            g.a = {0, 0, e.z / w};
            g.b = {0, e.y / h, 0};
            break;
        case 2:  // +y
            g.origin = {lo.x, hi.y, hi.z};
            g.a = {e.x / w, 0, 0};
            g.b = {0, 0, -e.z / h};
            break;
        case 3:  // -y
            g.origin = {lo.x, lo.y, lo.z};
            g.a = {e.x / w, 0, 0};
            g.b = {0, 0, e.z / h};
            break;
        case 4:  // +z
            g.origin = {lo.x, lo.y, hi.z};
            g.a = {e.x / w, 0, 0};
            g.b = {0, e.y / h, 0};
            break;
        default:  // -z
            g.origin = {hi.x, lo.y, lo.z};
            g.a = {-e.x / w, 0, 0};
            g.b = {0, e.y / h, 0};
            break;
    }
    return g;
}

}  // namespace rtm
