#include "objects/object_region.h"

namespace rtm {

ObjectRegion classify_region(const Box& box, const glm::dvec3& eye) {
    ObjectRegion r;
    for (int i = 0; i < 3; ++i) r.side[size_t(i)] = eye[i] > box.hi[i] ? 1 : eye[i] < box.lo[i] ? -1 : 0;
    return r;
}

std::vector<int> ObjectRegion::visible_faces() const {
    std::vector<int> v;
    for (int f = 0; f < kFaceCount; ++f)
        if (visible(f)) v.push_back(f);
    return v;
}

std::string ObjectRegion::to_string() const {
    static const char* axes = "xyz";
    std::string s = "region " + std::to_string(index()) + " (";
    for (int i = 0; i < 3; ++i) {
        if (i) s += ' ';
        s += side[size_t(i)] == 0 ? std::string("0") : std::string(side[size_t(i)] > 0 ? "+" : "-") + axes[i];
    }
    s += "): faces";
    for (int f : visible_faces()) s += std::string(" ") + kFaceKeys[size_t(f)];
    return s;
}

std::vector<int> faces_warped_onto(const ObjectRegion& region, int face) {
    std::vector<int> out;
    if (!region.visible(face)) return out;
    for (int g = 0; g < kFaceCount; ++g) {
        if (face_axis(g) == face_axis(face)) continue;
        if (region.visible(opposite_face(g))) continue;
        out.push_back(g);
    }
    return out;
}

}  // namespace rtm
