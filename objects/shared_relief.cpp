#include "objects/shared_relief.h"

#include <stdexcept>

#include "objects/level_choice.h"

namespace rtm {

void SharedRelief::check(const ReliefTexture& level0) {
    if (!have_first_) {
        first_ = level0;
        have_first_ = true;
    } else if (!same_texels(level0, first_)) {
        throw std::logic_error("SharedRelief: a relief whose texels are not those of the quads it serves");
    }
}

ReliefTexture SharedRelief::level(const ReliefTexture& level0, int i) {
    {
        std::lock_guard<std::mutex> lock(mutex_);
        check(level0);
    }
    return pyramid_.level(level0, i);  // under its own lock
}

const std::vector<double>& SharedRelief::spreads(const ReliefTexture& level0) {
    std::lock_guard<std::mutex> lock(mutex_);
    check(level0);
    if (spreads_.empty()) spreads_ = level_displacement_spreads(level0);
    return spreads_;
}

}  // namespace rtm
