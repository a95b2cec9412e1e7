// The building blocks of the Highway pre-warp kernels (warp/simd/hwy_two_pass.cpp, warp/simd/hwy_pipelined.cpp),
// compiled once per target in each of them (Highway's -inl.h convention: included after hwy/foreach_target.h, this
// header's guard toggles with HWY_TARGET_TOGGLE). A row's samples (PrepareRow), its horizontal warp (WarpRow) and
// the step of the output columns by one row of pixels (ColumnStep), each the reference's arithmetic operation by
// operation in float (no contraction: the files are compiled with -ffp-contract=off, and SSE4 has no FMA anyway),
// the colour with lerp8's integer formula. Pixels are written lane by lane (Highway 1.0.3 has no masked scatter).
#if defined(RTM_WARP_SIMD_HWY_ROW_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef RTM_WARP_SIMD_HWY_ROW_INL_H_
#undef RTM_WARP_SIMD_HWY_ROW_INL_H_
#else
#define RTM_WARP_SIMD_HWY_ROW_INL_H_
#endif

#include <hwy/highway.h>

#include <cmath>
#include <cstdint>
#include <limits>

#include "warp/line_warp.h"
#include "warp/prewarp.h"
#include "warp/relief_texture.h"
#include "warp/tables.h"

HWY_BEFORE_NAMESPACE();
namespace rtm::simd::HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

// Scratch of one row: positions, row coordinates and packed colours of the source width, in the caller's memory.
struct RowScratch {
    float* pos;
    float* v;
    uint32_t* color;
};

HWY_INLINE uint32_t pack(Rgba8 c) {
    return uint32_t(c.r) | uint32_t(c.g) << 8 | uint32_t(c.b) << 16 | uint32_t(c.a) << 24;
}

HWY_INLINE Rgba8 unpack(uint32_t u) { return {uint8_t(u), uint8_t(u >> 8), uint8_t(u >> 16), uint8_t(u >> 24)}; }

// The spans of lanes `span` (pa != pb, from sample a to sample b) into one row: each lane's pixels lo .. hi as
// raster_span computes them (centres in (pa, pb] or [pb, pa), clamped to [0, n_out)), colour by lerp8's integer
// formula and the carried row coordinate by attr_lerp at each centre, handed to emit(x, packed colour, v). The
// lanes' pixels must not overlap (the caller checks it), so the order in which they are emitted does not matter.
template <class DF, class DI, class MF, class Emit>
HWY_INLINE void SpanLanes(DF df, DI di, MF span, hn::Vec<DF> pa, hn::Vec<DF> pb, hn::Vec<DI> ca, hn::Vec<DI> cb,
                          hn::Vec<DF> va, hn::Vec<DF> vb, int n_out, const Emit& emit) {
    using VF = hn::Vec<DF>;
    using VI = hn::Vec<DI>;
    const size_t N = hn::Lanes(df);
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f), zero = hn::Zero(df);
    const VF last = hn::Set(df, float(n_out - 1));
    const VI alpha = hn::Set(di, int32_t(0xFF000000u)), byte = hn::Set(di, 0xFF);
    const VI w_one = hn::Set(di, 16384), w_max = hn::Set(di, 16383), round = hn::Set(di, 8192);
    const auto inc = hn::And(span, hn::Gt(pb, pa));
    const VF pah = hn::Sub(pa, half), pbh = hn::Sub(pb, half);
    VF lo = hn::IfThenElse(inc, hn::Add(hn::Floor(pah), one), hn::Ceil(pbh));
    VF hi = hn::IfThenElse(inc, hn::Floor(pbh), hn::Sub(hn::Ceil(pah), one));
    lo = hn::IfThenElse(hn::Lt(lo, zero), zero, lo);
    hi = hn::IfThenElse(hn::Lt(last, hi), last, hi);
    const auto todo = hn::RebindMask(di, hn::And(span, hn::Le(lo, hi)));
    if (hn::AllFalse(di, todo)) return;
    const VI xlo = hn::ConvertTo(di, lo), xhi = hn::ConvertTo(di, hi);
    const VF inv = hn::Div(one, hn::Sub(pb, pa));
    HWY_ALIGN int32_t lane_x[HWY_MAX_BYTES / 4], lane_c[HWY_MAX_BYTES / 4], lane_on[HWY_MAX_BYTES / 4];
    HWY_ALIGN float lane_v[HWY_MAX_BYTES / 4];
    VI x = xlo;
    VF xc = hn::Add(hn::ConvertTo(df, xlo), half);
    auto on = todo;
    while (!hn::AllFalse(di, on)) {
        VF tt = hn::Mul(hn::Sub(xc, pa), inv);
        tt = hn::IfThenElse(hn::Lt(tt, zero), zero, hn::IfThenElse(hn::Lt(one, tt), one, tt));  // std::clamp
        VI wt = hn::Min(hn::Or(hn::ConvertTo(di, hn::Mul(tt, hn::Set(df, 16384.0f))), hn::Set(di, 1)), w_max);
        wt = hn::IfThenElse(hn::RebindMask(di, hn::Ge(tt, zero)), wt, w_max);
        const VI wa = hn::Sub(w_one, wt);
        auto channel = [&](int shift) {
            const VI p = hn::And(hn::ShiftRightSame(ca, shift), byte);
            const VI q = hn::And(hn::ShiftRightSame(cb, shift), byte);
            return hn::ShiftRight<14>(hn::Add(hn::Add(hn::Mul(p, wa), hn::Mul(q, wt)), round));
        };
        const VI col = hn::Or(hn::Or(channel(0), hn::ShiftLeft<8>(channel(8))),
                              hn::Or(hn::ShiftLeft<16>(channel(16)), alpha));
        const VF v = hn::Add(hn::Mul(va, hn::Sub(one, tt)), hn::Mul(vb, tt));  // attr_lerp, no contraction
        hn::Store(x, di, lane_x);
        hn::Store(col, di, lane_c);
        hn::Store(v, df, lane_v);
        hn::Store(hn::VecFromMask(di, on), di, lane_on);
        for (size_t i = 0; i < N; ++i)
            if (lane_on[i]) emit(int(lane_x[i]), uint32_t(lane_c[i]), lane_v[i]);
        x = hn::Add(x, hn::Set(di, 1));
        xc = hn::Add(xc, one);
        on = hn::AndNot(hn::Lt(xhi, x), on);
    }
}

// warp_line_to (warp/line_warp.h) of one row, each pixel handed to emit(x, packed colour, final row coordinate) in
// the reference's order, for samples whose position is NaN where they do not take part. Where a whole vector of
// consecutive samples are spans of one orientation that follows the processing direction (positions non-decreasing
// along the row: no foldover), their pixels are disjoint and are drawn together (SpanLanes); everything else goes
// sample by sample through the reference's raster_point / raster_span, in the reference's order.
template <class Emit>
void WarpRow(const float* pos, const uint32_t* col, const float* attr, int n, int split, int n_out, const Emit& emit) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    const int N = int(hn::Lanes(df));
    auto put = [&](int x, Rgba8 c, float v) { emit(x, pack(c), v); };
    auto ok = [&](int k) { return std::isfinite(pos[k]); };
    // Sample k after sample `prev` (-1: none) in processing order: the reference's part loop body.
    auto one_sample = [&](int k, int prev) {
        if (!ok(k)) return -1;
        if (prev < 0)
            raster_point(pos[k], unpack(col[k]), attr[k], n_out, put);
        else
            raster_span(pos[prev], unpack(col[prev]), attr[prev], pos[k], unpack(col[k]), attr[k], n_out, put);
        return k;
    };
    // Left part: k = 0 .. split - 1, spans k - 1 -> k.
    int prev = -1, k = 0;
    while (k < split) {
        if (prev == k - 1 && prev >= 0 && k + N <= split) {
            const auto pa = hn::LoadU(df, pos + k - 1), pb = hn::LoadU(df, pos + k);
            const auto fine = hn::And(hn::IsFinite(pa), hn::And(hn::IsFinite(pb), hn::Ge(pb, pa)));
            if (hn::AllTrue(df, fine)) {
                SpanLanes(df, di, hn::Ne(pb, pa), pa, pb, hn::LoadU(di, reinterpret_cast<const int32_t*>(col + k - 1)),
                          hn::LoadU(di, reinterpret_cast<const int32_t*>(col + k)), hn::LoadU(df, attr + k - 1),
                          hn::LoadU(df, attr + k), n_out, emit);
                k += N;
                prev = k - 1;
                continue;
            }
        }
        prev = one_sample(k, prev);
        ++k;
    }
    const int left_last = prev;
    // Right part: k = n - 1 down to split, spans k + 1 -> k.
    prev = -1;
    k = n - 1;
    while (k >= split) {
        if (prev == k + 1 && k - N + 1 >= split) {
            const int b = k - N + 1;  // lanes: samples b .. k, each after sample + 1
            const auto pb = hn::LoadU(df, pos + b), pa = hn::LoadU(df, pos + b + 1);
            const auto fine = hn::And(hn::IsFinite(pa), hn::And(hn::IsFinite(pb), hn::Le(pb, pa)));
            if (hn::AllTrue(df, fine)) {
                SpanLanes(df, di, hn::Ne(pb, pa), pa, pb, hn::LoadU(di, reinterpret_cast<const int32_t*>(col + b + 1)),
                          hn::LoadU(di, reinterpret_cast<const int32_t*>(col + b)), hn::LoadU(df, attr + b + 1),
                          hn::LoadU(df, attr + b), n_out, emit);
                k -= N;
                prev = k + 1;
                continue;
            }
        }
        prev = one_sample(k, prev);
        --k;
    }
    const int right_last = prev;
    if (left_last >= 0 && right_last >= 0 && left_last == split - 1 && right_last == split)
        raster_span(pos[left_last], unpack(col[left_last]), attr[left_last], pos[right_last], unpack(col[right_last]),
                    attr[right_last], n_out, put);
}

// The reference's row_samples (lookup-table path) of storage row r into s: position (NaN where the texel does not
// take part, which WarpRow treats as the reference treats an invalid sample), final row coordinate and colour
// (alpha 255) of every texel. Returns the texels dropped (not empty, but 1 + k3*d <= 0).
inline long long PrepareRow(const ReliefTexture& t, const PrewarpTables& tab, const PrewarpExtent& e, int r,
                            const RowScratch& s) {
    const int w = t.width, h = t.height;
    const float vs = float(h - 1 - r) + 0.5f;
    const ReliefTexel* src = &t.texels[size_t(r) * size_t(w)];
    const float ou = float(e.left), ov = float(e.bottom);
    const float nan = std::numeric_limits<float>::quiet_NaN();
    long long dropped = 0;
    for (int x = 0; x < w; ++x) {
        const ReliefTexel tx = src[x];
        const float us = float(x) + 0.5f;
        s.color[size_t(x)] = pack({tx.r, tx.g, tx.b, 255});
        s.pos[size_t(x)] = tab.valid[tx.q] ? (us + tab.k1d[tx.q]) * tab.rcp[tx.q] + ou : nan;
        s.v[size_t(x)] = (vs + tab.k2d[tx.q]) * tab.rcp[tx.q] + ov;
        dropped += tx.q != kEmptyIndex && !tab.valid[tx.q];
    }
    return dropped;
}

// The state of the output columns: each column's last sample (final row coordinate, packed colour) and, in ok, -1
// where it has one and 0 elsewhere. Arrays of the output width, readable a whole vector past it.
struct Columns {
    float* v;
    int32_t* ok;
    uint32_t* c;
};

// Where a column step draws: an image ow x oh (v-row y in storage row oh - 1 - y), only v-rows [y0, y1).
struct ColumnTarget {
    uint32_t* pixels;
    int ow, oh, y0, y1;
};

// The column step of one row of pixels rc (packed colour, alpha 0 where not written) and rv (final row
// coordinate) for columns [x0, x1): in every column whose pixel was written with a finite row coordinate, the span
// from the column's last sample to it (raster_span) or, where the column had none, the point (raster_point), only
// their pixels in v-rows [y0, y1); the column keeps it as its last sample, and the others lose theirs. With kSkip,
// the columns where skip is not 0 are left alone (their state too). rc, rv and skip are read a whole vector past x1.
template <bool kSkip>
HWY_INLINE void ColumnStep(const Columns& col, const ColumnTarget& o, const uint32_t* rc, const float* rv,
                           const int32_t* skip, int x0, int x1) {
    const hn::ScalableTag<float> df;
    const hn::RebindToSigned<decltype(df)> di;
    using VF = hn::Vec<decltype(df)>;
    using VI = hn::Vec<decltype(di)>;
    const size_t N = hn::Lanes(df);
    const VF half = hn::Set(df, 0.5f), one = hn::Set(df, 1.0f), zero = hn::Zero(df);
    const VF first = hn::Set(df, float(o.y0)), last = hn::Set(df, float(o.y1 - 1)), end = hn::Set(df, float(o.y1));
    const VI alpha = hn::Set(di, int32_t(0xFF000000u)), byte = hn::Set(di, 0xFF), izero = hn::Zero(di);
    const VI w_one = hn::Set(di, 16384), w_max = hn::Set(di, 16383), round = hn::Set(di, 8192);
    HWY_ALIGN int32_t lane_y[HWY_MAX_BYTES / 4], lane_c[HWY_MAX_BYTES / 4], lane_on[HWY_MAX_BYTES / 4];
    for (int x = x0; x < x1; x += int(N)) {
        auto mi = hn::RebindMask(di, hn::FirstN(df, size_t(x1 - x)));
        if (kSkip) mi = hn::And(mi, hn::Eq(hn::LoadU(di, skip + x), izero));
        const auto m = hn::RebindMask(df, mi);
        const VF v = hn::MaskedLoad(m, df, rv + x);
        const VI c = hn::MaskedLoad(mi, di, reinterpret_cast<const int32_t*>(rc + x));
        const auto fin = hn::And(mi, hn::And(hn::Ne(hn::And(c, alpha), izero), hn::RebindMask(di, hn::IsFinite(v))));
        const VI okv = hn::MaskedLoad(mi, di, col.ok + x);
        const auto pok = hn::And(fin, hn::Ne(okv, izero));
        hn::BlendedStore(hn::VecFromMask(di, fin), mi, di, col.ok + x);
        if (hn::AllFalse(di, fin)) continue;
        const VF pv = hn::MaskedLoad(m, df, col.v + x);
        const VI pc = hn::MaskedLoad(mi, di, reinterpret_cast<const int32_t*>(col.c + x));
        hn::BlendedStore(v, hn::RebindMask(df, fin), df, col.v + x);
        hn::BlendedStore(c, fin, di, reinterpret_cast<int32_t*>(col.c + x));
        // raster_span's rows in float: lo .. hi, clamped to [0, oh - 1].
        const auto pokf = hn::RebindMask(df, pok);
        const auto inc = hn::And(pokf, hn::Gt(v, pv)), dec = hn::And(pokf, hn::Lt(v, pv));
        const VF pvh = hn::Sub(pv, half), vh = hn::Sub(v, half);
        VF lo = hn::IfThenElse(inc, hn::Add(hn::Floor(pvh), one), hn::Ceil(vh));
        VF hi = hn::IfThenElse(inc, hn::Floor(vh), hn::Sub(hn::Ceil(pvh), one));
        lo = hn::IfThenElse(hn::Lt(lo, first), first, lo);  // std::max(lo, 0), and y0
        hi = hn::IfThenElse(hn::Lt(last, hi), last, hi);    // std::min(hi, oh - 1), and y1 - 1
        const auto span = hn::And(hn::Or(inc, dec), hn::Le(lo, hi));
        // raster_point: row int(v) where 0 <= v < oh, and y0 <= int(v) < y1.
        const auto point = hn::AndNot(pokf,
                                      hn::And(hn::RebindMask(df, fin), hn::And(hn::Ge(v, first), hn::Lt(v, end))));
        const auto todo = hn::RebindMask(di, hn::Or(span, point));
        if (hn::AllFalse(di, todo)) continue;
        const auto pointi = hn::RebindMask(di, point);
        const VI ylo = hn::ConvertTo(di, hn::IfThenElse(point, v, lo));
        const VI yhi = hn::IfThenElse(pointi, ylo, hn::ConvertTo(di, hi));
        // Pixel k of every lane: y = ylo + k, colour at the centre y + 0.5 (steps by 1 exactly) as
        // raster_span_pixels computes it; a point's colour is its own with alpha 255.
        const VF inv = hn::Div(one, hn::Sub(v, pv));
        const VI cpoint = hn::Or(c, alpha);
        VI y = ylo;
        VF yc = hn::Add(hn::ConvertTo(df, ylo), half);
        auto on = todo;
        while (!hn::AllFalse(di, on)) {
            VF tt = hn::Mul(hn::Sub(yc, pv), inv);
            tt = hn::IfThenElse(hn::Lt(tt, zero), zero, hn::IfThenElse(hn::Lt(one, tt), one, tt));  // std::clamp
            // lerp8's weight: floor(t * 2^14) made odd, at most 2^14 - 1 (also for NaN).
            VI wt = hn::Min(hn::Or(hn::ConvertTo(di, hn::Mul(tt, hn::Set(df, 16384.0f))), hn::Set(di, 1)), w_max);
            wt = hn::IfThenElse(hn::RebindMask(di, hn::Ge(tt, zero)), wt, w_max);
            const VI wa = hn::Sub(w_one, wt);
            // One channel (shift 0, 8, 16) of the packed colours: (a * (2^14 - w) + b * w + 2^13) >> 14.
            auto channel = [&](int shift) {
                const VI a = hn::And(hn::ShiftRightSame(pc, shift), byte);
                const VI bb = hn::And(hn::ShiftRightSame(c, shift), byte);
                return hn::ShiftRight<14>(hn::Add(hn::Add(hn::Mul(a, wa), hn::Mul(bb, wt)), round));
            };
            const VI r = channel(0), g = channel(8), b = channel(16);
            const VI col = hn::Or(hn::Or(r, hn::ShiftLeft<8>(g)), hn::Or(hn::ShiftLeft<16>(b), alpha));
            hn::Store(y, di, lane_y);
            hn::Store(hn::IfThenElse(pointi, cpoint, col), di, lane_c);
            hn::Store(hn::VecFromMask(di, on), di, lane_on);
            for (size_t i = 0; i < N; ++i)
                if (lane_on[i])
                    o.pixels[size_t(o.oh - 1 - lane_y[i]) * size_t(o.ow) + size_t(x) + i] = uint32_t(lane_c[i]);
            y = hn::Add(y, hn::Set(di, 1));
            yc = hn::Add(yc, one);
            on = hn::AndNot(hn::Lt(yhi, y), on);
        }
    }
}

}  // namespace rtm::simd::HWY_NAMESPACE
HWY_AFTER_NAMESPACE();

#endif  // RTM_WARP_SIMD_HWY_ROW_INL_H_
