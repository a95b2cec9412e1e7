// Pre-warping an adjacent face onto a visible face's plane (paper section 4.1, Figure 15).
//
// Faces of the box are perpendicular, so a texel (u_s, v_s, d) of an adjacent face G, expressed in the frame of a
// face F it borders, has its displacement become a column (or row) coordinate of F and its column (or row) become
// F's displacement: FaceSwap is that affine map, a signed permutation with scales for two faces of one box. With
// the swapped coordinates (u', v', d'), G's texels are pre-warped onto F "as if they were F themselves" with the same
// equations 4a and 4b and F's coefficients:  u_i = (u' + k1 d') / (1 + k3 d'),  v_i = (v' + k2 d') / (1 + k3 d').
//
// warp_adjacent_face does it with the same 1-D passes as the single relief (warp/line_warp.h, warp_line_to): a pass
// along G's rows to one of F's final coordinates (carrying the other, d' and G's own displacement), then a pass along
// the intermediate columns to the other. The row pass computes the coordinate G's rows spread along: F's u when G's
// rows run along F's u (or run along F's normal while G's displacement feeds F's u), else F's v. (Always computing u
// first would collapse a row of G that runs along F's v onto one column.) Each pass keeps G's occlusion-compatible
// order: samples lie on G's parallel sampling rays, so along a line of G the ray nearer to the eye's foot on G's plane
// can hide the farther one, never the reverse, whichever side of G's plane the eye is on; the lines are warped from the
// borders towards that foot. Spans are not drawn across G's marked discontinuities (section 4.1.1). The output is
// z-tested on d' (along F's normal; for a viewer in front of F a larger d' is nearer on the same ray), so several
// adjacent faces accumulate into one buffer whatever their order. Two-pass reconstruction with point sampling. Given
// the pixels the object needs (AdjacentNeed: the holes of F's own pre-warp), the passes draw only what can reach them.
#pragma once

#include <glm/mat3x3.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "warp/image.h"
#include "warp/isa.h"
#include "warp/prewarp_coefficients.h"
#include "warp/relief_texture.h"

namespace rtm {

struct FaceSwap {
    // (u', v', d') = offset + m * (u_s, v_s, d): F's texel coordinates and displacement (world units) of G's point.
    glm::dvec3 offset{0.0};
    glm::dmat3 m{1.0};
    glm::dvec3 apply(double u_s, double v_s, double d) const { return offset + m * glm::dvec3(u_s, v_s, d); }
    // For perpendicular faces: which of G's (u_s, v_s, d) feeds F's u', v', d' (0, 1, 2), or -1 if several do.
    int source_of(int target) const;
    std::string to_string() const;
};

// The map from relief `src`'s (u_s, v_s, d) to relief `dst`'s frame; exact for any two frames whose dst a, b, f are
// independent.
FaceSwap make_face_swap(const ReliefGeometry& src, const ReliefGeometry& dst);

// Where the adjacent faces' samples land on F, accumulated: colour (alpha 255 where something landed, else 0) and
// d' per pixel (-infinity where empty). Same size and orientation as F's pre-warped texture.
struct AdjacentBuffer {
    ImageRGBA8 color;
    ImageF depth;
    void reset(int width, int height, int threads = 1);  // rows in parallel on `threads` (0: all)
};

// One pixel of the row pass's output in warp_adjacent_face: F's other coordinate, d', G's displacement, colour
// (alpha 0: nothing landed), together so that the column pass reads one cache line per sample.
struct AdjacentSample {
    double v = 0, d = 0, g = 0;
    Rgba8 c{};
};

// The pixels of F an object reads from its adjacent faces: where F's own pre-warp left a hole (the composite of
// ReliefObject::prewarp_face keeps an adjacent sample nowhere else). warp_adjacent_face given one computes the adjacent
// buffer exactly at these pixels and skips the work that can only reach the others (see there).
struct AdjacentNeed {
    // Its lines point into `pixels`: movable (the buffer moves along), not copyable.
    AdjacentNeed() = default;
    AdjacentNeed(const AdjacentNeed&) = delete;
    AdjacentNeed& operator=(const AdjacentNeed&) = delete;
    AdjacentNeed(AdjacentNeed&&) noexcept = default;
    AdjacentNeed& operator=(AdjacentNeed&&) noexcept = default;

    int width = 0, height = 0;
    long long count = 0;          // pixels needed
    std::vector<uint8_t> pixels;  // 1 where F's pixel (x, row), row 0 at the top, is needed, at row * width + x
    // The mask as the two passes of warp_adjacent_face see it, for either pass order: lines[0] has a line per column
    // of F (n1 = width), its positions F's rows from the bottom (n2 = height); lines[1] a line per row of F from the
    // bottom (n1 = height), its positions F's columns (n2 = width). Per line c: position k needed where
    // at[c * step_line + k * step_pos] (into pixels), lo[c] .. hi[c] the needed extent (hi < lo: none), and
    // prefix[k * n1 + c] the needed positions of line c below k (k = 0 .. n2; position-major, so that one row of the
    // adjacent face tests consecutive lines in consecutive entries).
    struct Lines {
        int n1 = 0, n2 = 0;
        const uint8_t* at = nullptr;
        std::ptrdiff_t step_line = 0, step_pos = 0;
        std::vector<uint16_t> prefix;  // 16 bits: a face has at most 65535 texels a side (assign checks)
        std::vector<int> lo, hi;
        bool needed(int c, int k) const { return at[c * step_line + k * step_pos] != 0; }
        // Whether line c needs any position in k0 .. k1 (clamped to the line).
        bool any(int c, int k0, int k1) const {
            k0 = k0 < 0 ? 0 : k0;
            k1 = k1 >= n2 ? n2 - 1 : k1;
            if (k0 > k1) return false;
            return prefix[size_t(k1 + 1) * size_t(n1) + size_t(c)] > prefix[size_t(k0) * size_t(n1) + size_t(c)];
        }
    };
    std::array<Lines, 2> lines;
    std::array<bool, 2> built{};  // which of `lines` were built (a warp needs its pass orientation's)
    // F's pixel (x, row), row 0 at the top, is needed where `needed` is non-zero. The orientations asked for (each
    // adjacent face's adjacent_pass_orientation) are built on `threads` threads (0: oneTBB's default). Throws
    // std::invalid_argument for a side over 65535 pixels.
    void assign(const Image2D<uint8_t>& needed, int threads = 0, std::array<bool, 2> orientations = {true, true});
    // The holes of F's own pre-warped texture: pixels with alpha < 128 (less than half covered: the texture-mapping
    // stage discards them, so the composite takes an adjacent sample there).
    void assign_holes(const ImageRGBA8& own, int threads = 0, std::array<bool, 2> orientations = {true, true});
    bool needed(int x, int row) const { return pixels[size_t(row) * size_t(width) + size_t(x)] != 0; }

private:
    void index(int threads, std::array<bool, 2> orientations);  // lines from pixels
};

// warp_adjacent_face with a need reads each row of G in chunks of kAdjacentChunk texels, each with one neighbour on
// each side (texels 16 k - 1 .. 16 k + 16).
inline constexpr int kAdjacentChunk = 16;

// The extremes of G's column and displacement terms over the non-empty texels of one chunk; cmin > cmax when there
// are none.
struct ChunkTerms {
    double cmin = 0, cmax = 0, dmin = 0, dmax = 0;
};

// What a relief's chunks hold, whatever the view: per chunk of each row (as above), the first and last non-empty
// texel and the extremes of the displacement level and (for `exact`) of the displacement over the non-empty texels.
// warp_adjacent_face computes the same extremes from every texel of G when not given these: a six-face object keeps
// one per face and pyramid level, made once, so that a warp reads 16 chunks a row instead of every texel.
struct AdjacentChunks {
    struct Chunk {
        int first = 1, last = 0;  // first > last: no non-empty texel
        uint8_t qmin = 0, qmax = 0;
        float dmin = 0, dmax = 0;
    };
    int width = 0, height = 0, per_row = 0;
    std::vector<Chunk> chunks;  // row-major, per_row per row of the relief
    static AdjacentChunks make(const ReliefTexture& t);
};

// Which of AdjacentNeed::lines warp_adjacent_face reads for adjacent face `g` onto face `f` (0 or 1), or -1 if it
// reads none (two frames that are not faces of one box take the reference, which draws everything).
int adjacent_pass_orientation(const ReliefGeometry& g, const ReliefGeometry& f);

// Scratch for warp_adjacent_face, reused across calls.
struct AdjacentWorkspace {
    ImageRGBA8 mid_color;  // the reference's row-pass output
    Image2D<double> mid_v, mid_d, mid_g;
    Image2D<AdjacentSample> mid;  // the fast path's
    // Per row of `mid`: the extent the last row pass wrote (mid_hi < mid_lo: none). Everything outside it is the
    // empty sample, so a row pass clears only the previous extent and the column pass reads only inside it.
    std::vector<int> mid_lo, mid_hi;
    // With an AdjacentNeed: bounds of each row's two coordinates over its valid texels (the row pass's and the
    // other); an empty range (min > max) when the row has none.
    std::vector<double> row_umin, row_umax, row_vmin, row_vmax;
    std::vector<uint8_t> row_cornered;              // 1 where a row's bounds came from its terms' corners
    std::vector<ChunkTerms> chunk_terms;            // per row, per chunk of 16 texels
    std::vector<AdjacentChunks::Chunk> own_chunks;  // G's chunks when the caller keeps none
    std::vector<int> col_rows;                      // per intermediate line, the first and last row that wrote to it
};

// Runs body(begin, end) over parts of [0, n) on `threads` threads (0: all available, 1: this thread alone, in one
// call), in the task arena the adjacent faces' passes use (one per thread count, made once).
void parallel_ranges(int n, int threads, const std::function<void(int, int)>& body);

// Pre-warps relief `g` (an adjacent face) onto the plane of `f_geom` (width x height texels) for the eye in `kf`
// (compute_coefficients(f_geom, eye)), z-testing into `out` (already sized width x height). With `exact` the
// displacement is g's exact one, else its 8-bit quantized level. Returns the number of texels that could not be
// pre-warped (1 + k3*d' <= 0; none when the eye is in front of F and G lies behind F's plane).
//
// For two faces of one box (every component of the swap has one source, FaceSwap::source_of) it runs a faster
// schedule of the same computation: the swap's terms per column of G, per row and per quantization level computed
// once, a row's coordinates computed branch-free before its line warp, the row pass's output kept together
// (AdjacentSample) and cleared and read only over each row's written extent, rows and columns where nothing landed
// skipped, both passes compiled for SSE4.2 and AVX2 besides the baseline and chosen by `isa`. Its
// output is the reference's, value for value (tests/objects/face_swap_test.cpp compares them over a random sweep),
// on every instruction set `isa` names (warp/isa.h; automatic: RTM_ISA or the fastest; throws std::invalid_argument
// for one this CPU lacks).
//
// With `need` (F's size), `out` is the whole warp's at every needed pixel, value for value, and anything elsewhere
// (fewer samples, or others): the passes draw only what can reach a needed pixel. A sample of the row pass in
// intermediate line c lies within its row's range of the other coordinate [vmin, vmax] (a span interpolates between
// two of the row's texels), and the column pass joins only samples of adjacent rows: so a row's samples reach pixels
// of line c only within the range of its own row and its two neighbours, and the row pass draws line c only if that
// range holds a needed pixel of line c (a span's pixels have their centres in it, a point's pixel holds it: pixels
// floor(lo) .. floor(hi)). Every span or point of the column pass that touches a needed pixel then has both its
// samples drawn as in the whole warp, and no sample left out can start a run (a point) at a needed pixel; the column
// pass draws only the needed pixels (spans interpolate only those), and not at all on a line whose gathered samples'
// positions (the range every span and point of the line lies in) reach no needed pixel. The ranges are bounded per
// row without dividing per texel: each coordinate is (P + k Z) / (1 + k3 Z) with P and Z two of G's column, row and
// displacement terms, monotone in each on a box where
// the denominator is positive, so its extremes over the row are at the corners of the box of the row's P and Z
// (widened by far more than the rounding; a row whose box reaches a denominator <= 0 is bounded texel by texel).
// Within a row that draws, the same bound per chunk of kAdjacentChunk texels (read with one neighbour on each side)
// keeps only the chunks that reach a line to draw: every span joins two samples of one chunk so read, so a span or
// point drawing a kept line belongs to a kept chunk, and the line warp runs over the kept chunks' samples in the
// whole row's order (a kept range starts and ends one sample into a dropped chunk, whose bound holds no line drawn).
// tests/objects/face_swap_test.cpp checks it with random masks, and tests/objects/adjacent_holes_test.cpp the
// objects' faces with and without.
//
// `chunks`, if given, must be AdjacentChunks::make(g) (its size is checked: std::invalid_argument); the result is the
// same with or without.
long long warp_adjacent_face(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                             const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws, AdjacentBuffer& out,
                             int threads = 0, Isa isa = Isa::automatic, const AdjacentNeed* need = nullptr,
                             const AdjacentChunks* chunks = nullptr);

// The reference: the swap applied to every texel as a matrix, the generic schedule; any two frames.
long long warp_adjacent_face_reference(const ReliefTexture& g, const ReliefGeometry& f_geom, int width, int height,
                                       const PrewarpCoefficients& kf, bool exact, AdjacentWorkspace& ws,
                                       AdjacentBuffer& out, int threads = 0);

}  // namespace rtm
