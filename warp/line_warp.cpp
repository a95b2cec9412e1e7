#include "warp/line_warp.h"

#include <algorithm>
#include <cmath>

namespace rtm {

int split_index(double split_pos, int n) {
    // Sample k is in the first part when k + 0.5 < split_pos, i.e. k < split_pos - 0.5.
    const double s = std::ceil(split_pos - 0.5);
    if (!(s > 0.0)) return 0;  // also NaN
    if (s >= double(n)) return n;
    return int(s);
}

template <class P>
void warp_line(const LineInput<P>& in, int split, const LineOutput<P>& out) {
    warp_line_to(in, split, out.n, [&](int x, Rgba8 c, P a) {
        out.color[std::ptrdiff_t(x) * out.color_stride] = c;
        if (out.attr) out.attr[std::ptrdiff_t(x) * out.attr_stride] = a;
    });
}

template void warp_line<float>(const LineInput<float>&, int, const LineOutput<float>&);
template void warp_line<double>(const LineInput<double>&, int, const LineOutput<double>&);

}  // namespace rtm
