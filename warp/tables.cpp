#include "warp/tables.h"

#include <cstdio>

namespace rtm {

PrewarpTables PrewarpTables::build(const PrewarpCoefficients& k, const Quantizer& quant) {
    PrewarpTables t;
    for (int q = 0; q < kQuantLevels; ++q) {
        const double d = quant.decode(uint8_t(q));
        const double den = 1.0 + k.k3 * d;
        const bool ok = den > 0.0;
        t.valid[q] = ok;
        t.still[q] = d == 0.0;
        t.displ[q] = float(d);
        t.k1d[q] = ok ? float(k.k1 * d) : 0.0f;
        t.k2d[q] = ok ? float(k.k2 * d) : 0.0f;
        t.rcp[q] = ok ? float(1.0 / den) : 0.0f;
    }
    t.valid[kEmptyIndex] = 0;
    t.still[kEmptyIndex] = 0;
    return t;
}

std::string PrewarpTables::to_string() const {
    int nvalid = 0;
    for (int q = 0; q < 256; ++q) nvalid += valid[q];
    char buf[256];
    std::snprintf(buf, sizeof buf, "PrewarpTables{valid levels=%d, K1[0]=%g K1[254]=%g, R[0]=%g R[254]=%g}", nvalid,
                  k1d[0], k1d[254], rcp[0], rcp[254]);
    return buf;
}

}  // namespace rtm
