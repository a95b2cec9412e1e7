// Per-view lookup tables (paper section 3.1): for each quantization level q in 0..254,
//     K1[q] = k1*d'(q),  K2[q] = k2*d'(q),  R[q] = 1 / (1 + k3*d'(q)),
// so a texel costs two additions, two multiplications and three lookups:
//     u_i = (u_s + K1[q]) * R[q],  v_i = (v_s + K2[q]) * R[q].
// Levels whose denominator 1 + k3*d' <= 0 cannot be pre-warped (viewer below those texels): valid[q] = 0 and
// the texel is dropped. Index 255 (empty) is also invalid. Tables are values, built once per view.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "prewarp_coefficients.h"
#include "relief_texture.h"

namespace rtm {

struct PrewarpTables {
    std::array<float, 256> k1d{};
    std::array<float, 256> k2d{};
    std::array<float, 256> rcp{};
    std::array<float, 256> displ{};  // d'(q) itself, carried for discontinuities and depth correction
    std::array<uint8_t, 256> valid{};
    std::array<uint8_t, 256> still{};  // 1 where d'(q) == 0: the texel does not move

    static PrewarpTables build(const PrewarpCoefficients& k, const Quantizer& quant);
    std::string to_string() const;
};

}  // namespace rtm
