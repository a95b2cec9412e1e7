// The pre-warp benchmark behind `rtm bench` (docs/BENCHMARKS.md): throughput of the pre-warp over texture sizes,
// reconstructions (two-pass, pipelined), coordinate paths (lookup tables, exact), kernels (fast, generic reference)
// and thread counts, on three kinds of relief (smooth bumps, mostly flat bricks, foldover-heavy ridges), each next
// to its memory bound measured in the same run; and the paper's Table 1 (the split of one frame of one relief quad
// in a 512x512 view between pre-warping, upload, texture mapping and the rest).
//
// Benchmarks are programs, not tests: nothing here asserts a time.
#pragma once

#include <nlohmann/json.hpp>

#include <functional>
#include <string>
#include <vector>

#include "measure/compare.h"
#include "warp/prewarp.h"

namespace rtm {

struct BenchConfig {
    std::vector<int> sizes;            // square reliefs, texels per side
    std::vector<std::string> reliefs;  // procedural relief names (procedural/procedural_media.h)
    std::vector<Reconstruction> methods = {Reconstruction::two_pass, Reconstruction::pipelined};
    std::vector<int> threads;  // thread counts of the lookup-table fast kernels
    // SIMD targets of the lookup-table kernels (warp/isa.h), each measured at every thread count; empty: the one
    // PrewarpOptions::isa's automatic picks. With more than one, the report compares them (bench_markdown).
    std::vector<Isa> isas;
    bool exact = true;  // also --exact (double precision, generic kernels) at the largest thread count
    int exact_max_size = 1024;
    bool reference = true;  // also the generic lookup-table kernels (fast = false), one thread
    int reference_max_size = 1024;
    double min_seconds = 0.25;  // per configuration: repeat at least this long ...
    int min_repeats = 3;        // ... and at least this often (after one warm-up), at most max_repeats
    int max_repeats = 400;
    CompareView view = orbit_view(30.0, 20.0);  // the eye (orbit convention, about the relief's bounds)
    // > 0: the throughput rows' reliefs carry surface-discontinuity marks (paper section 4.1.1, mark_discontinuities)
    // at this fraction of their displacement range as threshold, as every six-face object's face does; 0: none.
    double discontinuity = 0.0;
    bool table1 = true;
    int table1_size = 256;
    bool objects = true;  // with table1: six-face objects of table1_size^2 faces from one-, two- and three-face views
    bool object_adjacent_holes_only = true;  // DrawOptions::adjacent_holes_only of the objects' frames
    int view_width = 512, view_height = 512;
    std::function<void(const std::string&)> progress;  // one line per finished measurement; may be empty
};

// The default run (about a minute on two cores: sizes 128 to 1024) or the full one (128 to 4096).
BenchConfig default_bench_config(bool full);

// The coordinate path of a pre-warp: the lookup tables, or --exact (double precision).
enum class CoordinatePath { lut, exact };
// The kernels that ran: the fast ones (warp/simd/schedule.h) or the generic reference kernels.
enum class BenchKernel { fast, reference };
std::string to_string(CoordinatePath p);  // "lut", "exact"
std::string to_string(BenchKernel k);     // "fast", "reference"

struct BenchRow {
    std::string relief;
    int size = 0;
    Reconstruction method = Reconstruction::two_pass;
    CoordinatePath path = CoordinatePath::lut;
    BenchKernel kernel = BenchKernel::fast;
    std::string isa;  // the target whose kernels ran (PrewarpStats::isa: "generic" for the reference kernels)
    int threads = 0;
    long long texels = 0;
    int out_width = 0, out_height = 0;
    int repeats = 0;
    double ms_min = 0, ms_median = 0;
    double mtexels_per_s = 0;                  // texels / median time
    double prewarps_per_s = 0;                 // 1 / median time
    double bytes_read = 0, bytes_written = 0;  // what the passes read and write (their buffers, once each)
    double bound_ms = 0;     // median time of a streaming copy of the same bytes with the same threads
    double bound_ratio = 0;  // ms_median / bound_ms
    // The reference kernels' work counts (PrewarpStats; 0 for the fast kernels, which do not count).
    long long row_pixels = 0, column_samples = 0;
};

// Pipelined against two-pass for one relief and size: the work each does per texel, from the reference kernels
// (NaN where the run has no reference row), and the fast kernels' median time ratio per thread count.
struct PipelinedRatio {
    std::string relief;
    int size = 0;
    double row_pixels_per_texel = 0;         // the same row warp in both
    double two_pass_samples_per_texel = 0;   // column samples: one per surviving intermediate pixel
    double pipelined_samples_per_texel = 0;  // column samples: every pixel of the row warp
    // (threads, pipelined ms / two-pass ms), lookup tables, the fast kernels (the generic ones on a CPU without)
    std::vector<std::pair<int, double>> time_ratio;
};

struct Table1Row {
    std::string relief;
    Reconstruction method = Reconstruction::two_pass;
    int size = 0;
    int threads = 0;
    int frames = 0;
    // Medians over the frames, in milliseconds; other = total - the three stages (frame set-up, clearing,
    // skip tests, ...). The read-back of the image is not part of the frame.
    double prewarp_ms = 0, upload_ms = 0, texture_map_ms = 0, other_ms = 0, total_ms = 0;
    double readback_ms = 0;  // reading the image back, for reference
    double fps = 0;          // 1000 / total_ms
};

// A frame of a six-face object (paper section 4.1) in the same view size as Table 1, next to the single relief frame
// of Table 1 (two-pass, the first relief) measured in the same run.
struct ObjectFrameRow {
    std::string object;                   // synthetic object (procedural/synthetic_object.h)
    std::string view;                     // "one face", "two faces", "three faces"
    double az = 0, el = 0, distance = 0;  // orbit about the box's bounding sphere
    int size = 0;                         // texels per face side
    int faces = 0;                        // faces drawn
    int frames = 0;
    std::vector<std::pair<std::string, double>> face_prewarp_ms;  // per face drawn: median pre-warp time
    double prewarp_ms = 0, upload_ms = 0, texture_map_ms = 0, total_ms = 0, fps = 0;
    double adjacent_ms = 0;  // of prewarp_ms: the adjacent faces pre-warped onto the faces drawn (median of the sum)
    // The single relief frame of Table 1 (its first relief, two-pass), rendered between this view's object frames so
    // that both see the same state of the machine: its median, and total_ms over it (0 when there is none).
    double relief_ms = 0;
    double single_ratio = 0;
};

struct BenchResult {
    std::string machine;                  // CPU model, cores, memory
    std::string gl_renderer;              // the OpenGL context of Table 1, or why there is none
    std::string load_before, load_after;  // /proc/loadavg at the start and the end
    std::string view;                     // the eye used
    double discontinuity = 0.0;           // BenchConfig::discontinuity
    std::vector<BenchRow> rows;
    std::vector<Table1Row> table1;
    std::vector<ObjectFrameRow> objects;
};

// "CPU model, N logical CPUs, M GiB memory" of this machine (/proc/cpuinfo, /proc/meminfo).
std::string machine_description();

BenchResult run_bench(const BenchConfig& config);
// The relief and size pairs of `result` that have both reconstructions, in the order of the rows.
std::vector<PipelinedRatio> pipelined_ratios(const BenchResult& result);
// The SIMD targets of `result` side by side: per relief, size, reconstruction and thread count, each target's median
// time and its speed against the avx512 target and the generic kernels (one thread). Empty with fewer than two.
std::string bench_isa_markdown(const BenchResult& result);
std::string bench_markdown(const BenchResult& result);
nlohmann::json bench_json(const BenchResult& result);

// The bytes the pre-warp of a w x h relief into an ow x oh output reads and writes (intermediate buffers included).
void prewarp_traffic(Reconstruction method, bool exact, bool fast, int w, int h, int ow, int oh, double& read,
                     double& written);

// Median milliseconds of a streaming copy that reads `read` bytes and writes `written` bytes with `threads` threads.
double streaming_copy_ms(double read, double written, int threads, double min_seconds, int min_repeats);

}  // namespace rtm
