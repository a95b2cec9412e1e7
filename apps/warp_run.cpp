// rtm-warp-run: pre-warps one procedural relief (procedural/procedural_media.h) a given number of times on one SIMD
// target, with nothing but warp/ (no image files, no OpenGL): the program that the instruction counts of
// scripts/count_instructions.sh run under qemu-user, on x86-64 and on aarch64 (where the build is warp/ alone,
// RTM_WARP_ONLY). It prints the target that ran and the times of the pre-warps after one warm-up (wall clock: under
// qemu they are not the CPU's).
//
//   rtm-warp-run RELIEF SIZE METHOD ISA REPEAT [THREADS]
//
// RELIEF bricks, facade, bumps or ridges, or lifted-bricks (the brick wall with every displacement + 0.05, nothing
// still: the relief of `rtm bench-skips`' lifted wall); SIZE 16 to 4096; METHOD two-pass or pipelined; ISA a --isa name
// (auto, avx512, ..., generic); REPEAT 0 to 100000 pre-warps after the warm-up; THREADS 1 by default (0 = all). The eye
// is `rtm bench`'s for bumps (orbit azimuth 30, elevation 20, 2.2 bounding radii: docs/BENCHMARKS.md), for every
// relief. Bad arguments: one line on stderr naming the value, exit 1.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "procedural/procedural_media.h"
#include "warp/isa.h"
#include "warp/prewarp.h"
#include "warp/prewarp_coefficients.h"

namespace {

// `text` as an integer in [lo, hi], or an error naming `what`.
int parse_int(const char* what, const char* text, int lo, int hi) {
    char* end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi)
        throw std::invalid_argument(std::string(what) + " '" + text + "' is not an integer from " + std::to_string(lo) +
                                    " to " + std::to_string(hi));
    return int(v);
}

volatile int mark = 0;  // what the markers below write, so that their code differs

}  // namespace

// Each timed pre-warp runs between these two calls: scripts/count_instructions.py counts the instructions executed
// from the first to the second (qemu names each translated block's function). Not inlined; not merged either.
extern "C" [[gnu::noinline]] void rtm_warp_run_begin() { mark = 1; }
extern "C" [[gnu::noinline]] void rtm_warp_run_end() { mark = 2; }

int main(int argc, char** argv) {
    using namespace rtm;
    if (argc < 6 || argc > 7) {
        std::fprintf(stderr,
                     "usage: rtm-warp-run RELIEF SIZE METHOD ISA REPEAT [THREADS] (RELIEF one of %s, lifted-bricks)\n",
                     procedural_names_list().c_str());
        return 1;
    }
    try {
        const int size = parse_int("SIZE", argv[2], 16, 4096);
        PrewarpOptions o;
        const std::string method = argv[3];
        if (method == "two-pass")
            o.method = Reconstruction::two_pass;
        else if (method == "pipelined")
            o.method = Reconstruction::pipelined;
        else
            throw std::invalid_argument("METHOD '" + method + "' is neither two-pass nor pipelined");
        if (!parse_isa(argv[4], o.isa))
            throw std::invalid_argument(std::string("ISA '") + argv[4] + "' is none of auto, " + isa_names());
        const int repeat = parse_int("REPEAT", argv[5], 0, 100000);
        o.threads = argc > 6 ? parse_int("THREADS", argv[6], 0, 1024) : 1;
        const std::string name = argv[1];
        const ReliefTexture relief = to_relief(name == "lifted-bricks" ? make_shifted_brick_wall(size, 0.05)
                                                                       : make_procedural(name, size));
        const PrewarpCoefficients k = compute_coefficients(relief.geometry, glm::dvec3(0.735, 0.535, 1.348));
        PrewarpWorkspace ws;
        ImageRGBA8 out;
        const PrewarpStats first = prewarp(relief, k, o, ws, out);  // warm-up; names the target (throws if absent)
        std::vector<double> ms;
        for (int i = 0; i < repeat; ++i) {
            const auto t0 = std::chrono::steady_clock::now();
            rtm_warp_run_begin();
            prewarp(relief, k, o, ws, out);
            rtm_warp_run_end();
            ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        std::printf("%s %d %s isa %s: %d pre-warps after a warm-up", argv[1], size, method.c_str(), isa_name(first.isa),
                    repeat);
        if (!ms.empty()) std::printf(", min %.3f ms, median %.3f ms", ms.front(), ms[ms.size() / 2]);
        std::printf("\n");
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtm-warp-run: %s\n", e.what());
        return 1;
    }
    return 0;
}
