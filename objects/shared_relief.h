// What the relief quads holding copies of one relief compute once and share: a scene's placements of one file at one
// scale, or of one six-face object, differ only in geometry (objects/scene.cpp). Their pyramid levels' texels
// (SharedPyramid, warp/pyramid.h) and their levels' displacement spreads (level_displacement_spreads,
// objects/level_choice.h, which `--level auto` reads) depend on neither the view nor the placement: 8,000 placements
// of one 256x256 relief spent 1.4 s of their first frame computing the same spreads 8,000 times (docs/SCENES.md,
// "Memory"). Safe to call from several threads at once.
#pragma once

#include <mutex>
#include <vector>

#include "warp/pyramid.h"
#include "warp/relief_texture.h"

namespace rtm {

class SharedRelief {
public:
    // Every level0 passed must hold the same texels as the first one passed to either call (same_texels,
    // warp/pyramid.h): std::logic_error otherwise.
    // Level i >= 1 of level0's pyramid with level0's geometry (SharedPyramid::level).
    ReliefTexture level(const ReliefTexture& level0, int i);
    // level_displacement_spreads(level0), computed on the first call.
    const std::vector<double>& spreads(const ReliefTexture& level0);

private:
    std::mutex mutex_;
    bool have_first_ = false;
    ReliefTexture first_;  // the first level0 passed, its arrays shared
    SharedPyramid pyramid_;
    std::vector<double> spreads_;  // empty until computed

    void check(const ReliefTexture& level0);  // with mutex_ held
};

}  // namespace rtm
