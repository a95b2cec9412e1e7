// How the tools place a camera: orbiting a centre (the --orbit AZ,EL,D convention of the command line, the viewer's
// drag and the comparison views) or aimed from an eye at a point. One formula for all of them.
#pragma once

#include <glm/vec3.hpp>

#include "texmap/camera.h"

namespace rtm {

// A position on a sphere about a centre: azimuth about +y from +z towards +x and elevation above the xz plane, in
// degrees; distance in radii of what is looked at.
struct OrbitPose {
    double azimuth = 0.0, elevation = 0.0, distance = 1.0;
};

// The eye of pose `o` about `centre` for a scene of bounding radius `radius` (at least 1e-12).
glm::dvec3 orbit_eye(const glm::dvec3& centre, double radius, const OrbitPose& o);

// A width x height camera at `eye` looking at `look_at`, up +y, 45-degree vertical field of view, clip planes not
// fitted (z_near = 0 until fit_clip_planes).
Camera aimed_camera(const glm::dvec3& eye, const glm::dvec3& look_at, int width, int height);

// aimed_camera from orbit_eye at the centre, with clip planes fitted to the sphere (centre, radius).
Camera orbit_camera(const glm::dvec3& centre, double radius, const OrbitPose& o, int width, int height);

}  // namespace rtm
