#include "measure/bench.h"

#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <thread>
#include <utility>

#include "procedural/synthetic_object.h"
#include "objects/relief_object.h"
#include <glm/trigonometric.hpp>
#include "procedural/procedural_media.h"
#include "objects/relief_quad.h"
#include "warp/timing.h"
#include "objects/render_relief.h"
#include "texmap/gl_context.h"
#include "warp/simd/schedule.h"
#include "warp/task_arenas.h"

namespace rtm {

namespace {

std::string read_first_line(const char* path) {
    std::ifstream f(path);
    std::string line;
    std::getline(f, line);
    return line;
}

}  // namespace

std::string machine_description() {
    std::string model = "unknown CPU";
    std::ifstream cpu("/proc/cpuinfo");
    for (std::string line; std::getline(cpu, line);)
        if (line.rfind("model name", 0) == 0) {
            model = line.substr(line.find(':') + 2);
            break;
        }
    long long mem_kb = 0;
    std::ifstream mem("/proc/meminfo");
    for (std::string line; std::getline(mem, line);)
        if (line.rfind("MemTotal:", 0) == 0) {
            mem_kb = std::atoll(line.c_str() + 9);
            break;
        }
    char buf[256];
    std::snprintf(buf, sizeof buf, "%s, %u logical CPUs, %.1f GiB memory", model.c_str(),
                  std::thread::hardware_concurrency(), double(mem_kb) / (1024.0 * 1024.0));
    return buf;
}

std::string to_string(CoordinatePath p) { return p == CoordinatePath::exact ? "exact" : "lut"; }
std::string to_string(BenchKernel k) { return k == BenchKernel::fast ? "fast" : "reference"; }

namespace {

// Runs `once` (returning milliseconds) after one warm-up until min_seconds and min_repeats are reached.
template <class Fn>
std::vector<double> repeat_timed(const BenchConfig& c, Fn&& once) {
    once();
    std::vector<double> ms;
    const auto t0 = Clock::now();
    while (int(ms.size()) < c.max_repeats && (int(ms.size()) < c.min_repeats || ms_since(t0) < c.min_seconds * 1000.0))
        ms.push_back(once());
    return ms;
}

// Buffers of the streaming copy, kept from one measurement to the next.
struct CopyBuffers {
    std::unique_ptr<char[]> src, dst;
    size_t src_size = 0, dst_size = 0;
    void reserve(size_t r, size_t w) {
        if (r > src_size) {
            src.reset(new char[r]);
            std::memset(src.get(), 1, r);
            src_size = r;
        }
        if (w > dst_size) {
            dst.reset(new char[w]);
            std::memset(dst.get(), 0, w);
            dst_size = w;
        }
    }
};

CopyBuffers& copy_buffers() {
    static CopyBuffers b;
    return b;
}

}  // namespace

void prewarp_traffic(Reconstruction method, bool exact, bool fast, int w, int h, int ow, int oh, double& read,
                     double& written) {
    const double src = double(w) * h, mid = double(ow) * h, out = double(ow) * oh;
    // Texels are 4 bytes; --exact also reads the 4-byte exact displacement.
    const double in = src * (exact ? 8.0 : 4.0);
    // The pipelined reconstruction has no intermediate image; nor have the fast two-pass kernels, which hand each
    // band of rows to the vertical pass while it is in the cache (warp/simd/two_pass_job.h).
    if (method == Reconstruction::pipelined || (fast && !exact)) {
        read = in;
        written = out * 4.0;
        return;
    }
    // The generic kernels' intermediate image per pixel: colour, final row coordinate and carried displacement
    // (float: 4 + 4 + 4 bytes; exact: v and d in double, 4 + 8 + 8).
    const double per = exact ? 20.0 : 12.0;
    read = in + mid * per;
    written = mid * per + out * 4.0;
}

double streaming_copy_ms(double read, double written, int threads, double min_seconds, int min_repeats) {
    const size_t r = size_t(read), w = size_t(written);
    CopyBuffers& b = copy_buffers();
    b.reserve(r, w);
    const int chunks = 256;
    volatile unsigned long long sink = 0;
    auto chunk = [&](int i) {
        const size_t r0 = r * i / chunks, r1 = r * (i + 1) / chunks, w0 = w * i / chunks, w1 = w * (i + 1) / chunks;
        const size_t n = std::min(r1 - r0, w1 - w0);
        std::memcpy(b.dst.get() + w0, b.src.get() + r0, n);
        if (w1 - w0 > n) std::memset(b.dst.get() + w0 + n, int(i & 0xFF), w1 - w0 - n);
        if (r1 - r0 > n) {  // read the rest
            unsigned long long s = 0;
            const char* p = b.src.get() + r0 + n;
            for (size_t k = 0; k + 8 <= r1 - r0 - n; k += 8) {
                unsigned long long v;
                std::memcpy(&v, p + k, 8);
                s += v;
            }
            sink = sink + s;
        }
    };
    tbb::task_arena& arena = task_arena_for(std::max(threads, 1));
    auto once = [&] {
        const auto t0 = Clock::now();
        if (threads == 1) {
            for (int i = 0; i < chunks; ++i) chunk(i);
        } else {
            arena.execute([&] { tbb::parallel_for(0, chunks, [&](int i) { chunk(i); }); });
        }
        return ms_since(t0);
    };
    BenchConfig c;
    c.min_seconds = min_seconds;
    c.min_repeats = min_repeats;
    return median(repeat_timed(c, once));
}

BenchConfig default_bench_config(bool full) {
    BenchConfig c;
    c.sizes = full ? std::vector<int>{128, 256, 512, 1024, 2048, 4096} : std::vector<int>{128, 256, 512, 1024};
    c.reliefs = {"bumps", "bricks", "ridges"};
    const int n = std::max(1, int(std::thread::hardware_concurrency()));
    for (int t = 1; t <= n; t *= 2) c.threads.push_back(t);
    if (c.threads.back() != n) c.threads.push_back(n);
    // The generic kernels at 4096^2 would take minutes (the pipelined reconstruction of the ridges writes about
    // 400 pixels a texel there): they stop at 2048^2.
    c.exact_max_size = full ? 2048 : 1024;
    c.reference_max_size = full ? 2048 : 1024;
    return c;
}

namespace {

// Six-face objects next to Table 1 (docs/OBJECTS.md): every frame pre-warps every visible face and its adjacent
// faces and uploads them (no skips). Table 1's single relief frame (its first relief, two-pass) is measured again
// with each view, in blocks alternating with the object's (kBlock frames each, the first kWarm of each block left
// out: after a switch each frame takes 6 to 10 frames to come down to its steady time, 1.2-1.7x the first, as the
// other's data leaves the caches), and each view's ratio is of the two medians: a machine whose speed drifts during the
// run (a shared host) then moves both alike, where the ratio to Table 1's own measurement, seconds earlier, moved with
// the drift.
constexpr int kBlock = 30, kWarm = 10;

template <class Progress>
void bench_objects(const BenchConfig& c, Renderer& renderer, int threads, BenchResult& res, Progress&& progress) {
    std::unique_ptr<ReliefQuad> relief;
    Camera relief_cam;
    RenderSettings relief_settings;
    if (!c.reliefs.empty()) {
        relief = std::make_unique<ReliefQuad>(to_relief(make_procedural(c.reliefs.front(), c.table1_size)));
        relief_cam = compare_camera(*relief, c.view, c.view_width, c.view_height);
        relief_settings.method = RenderMethod::two_pass;
        relief_settings.prewarp.method = Reconstruction::two_pass;
        relief_settings.prewarp.keep_outliers = true;  // as Table 1
        relief_settings.prewarp.threads = threads;
        relief_settings.draw.skips = false;
    }
    struct View {
        const char* name;
        double az, el;
    };
    const View views[] = {{"one face", 0, 0}, {"two faces", 45, 0}, {"three faces", 45, 35}};
    for (SyntheticShape shape : {SyntheticShape::sphere, SyntheticShape::cross_box}) {
        ReliefObject object(make_synthetic_object(shape, c.table1_size));
        for (const View& v : views) {
            Camera cam;
            const Bounds b = object.bounds();
            const double az = glm::radians(v.az), el = glm::radians(v.el), d = 2.5 * b.radius();
            cam.look_at = b.centre();
            cam.eye = b.centre() +
                      d * glm::dvec3(std::sin(az) * std::cos(el), std::sin(el), std::cos(az) * std::cos(el));
            cam.width = c.view_width;
            cam.height = c.view_height;
            cam.fit_clip_planes(b.centre(), b.radius());
            PrewarpOptions o;
            o.threads = threads;
            DrawOptions dr;
            dr.skips = false;
            dr.adjacent_holes_only = c.object_adjacent_holes_only;
            std::vector<double> pre, adj, up, map, total, single;
            std::vector<std::vector<double>> per_face(kFaceCount);
            std::vector<int> drawn;
            auto frame = [&](bool keep) {
                StageTimes st;
                ObjectReport rep;
                render_object_frame(object, renderer, cam, RenderMethod::two_pass, o, dr, st, &rep);
                if (!keep) return;
                pre.push_back(st.prewarp_ms);
                up.push_back(st.upload_ms);
                map.push_back(st.texture_map_ms);
                total.push_back(st.total_ms);
                drawn.clear();
                double a = 0.0;
                for (const ObjectFaceReport& f : rep.faces) {
                    per_face[size_t(f.face)].push_back(f.prewarp_ms);
                    a += f.adjacent_ms;
                    drawn.push_back(f.face);
                }
                adj.push_back(a);
            };
            auto relief_frame = [&](bool keep) {
                StageTimes rs;
                render_relief_frame(*relief, &renderer, relief_cam, relief_settings, rs);
                if (keep) single.push_back(rs.total_ms);
            };
            for (int i = 0; i < 2; ++i) frame(false);  // warm-up
            // Blocks of each until at least 0.5 s (or --min-time) and 20 kept object frames, at most 400 kept.
            const double min_seconds = std::max(c.min_seconds, 0.5);
            const auto t_begin = Clock::now();
            while ((total.size() < 20 || ms_since(t_begin) < 1000.0 * min_seconds) && total.size() < 400) {
                if (relief)
                    for (int i = 0; i < kBlock; ++i) relief_frame(i >= kWarm);
                for (int i = 0; i < kBlock; ++i) frame(i >= kWarm);
            }
            ObjectFrameRow r;
            r.object = to_string(shape);
            r.view = v.name;
            r.az = v.az;
            r.el = v.el;
            r.distance = 2.5;
            r.size = c.table1_size;
            r.faces = int(drawn.size());
            r.frames = int(total.size());
            for (int f : drawn) r.face_prewarp_ms.emplace_back(kFaceKeys[size_t(f)], median(per_face[size_t(f)]));
            r.prewarp_ms = median(pre);
            r.adjacent_ms = median(adj);
            r.upload_ms = median(up);
            r.texture_map_ms = median(map);
            r.total_ms = median(total);
            r.fps = 1000.0 / r.total_ms;
            r.relief_ms = single.empty() ? 0.0 : median(single);
            r.single_ratio = r.relief_ms > 0 ? r.total_ms / r.relief_ms : 0.0;
            res.objects.push_back(r);
            char buf[256];
            std::snprintf(buf, sizeof buf,
                          "object: %s 6x%d^2, %s, in %dx%d: %.3f ms a frame (%.0f fps, %.2fx the relief)",
                          r.object.c_str(), r.size, r.view.c_str(), c.view_width, c.view_height, r.total_ms, r.fps,
                          r.single_ratio);
            progress(buf);
        }
    }
}

}  // namespace

BenchResult run_bench(const BenchConfig& c) {
    BenchResult res;
    res.machine = machine_description();
    res.load_before = read_first_line("/proc/loadavg");
    char vbuf[128];
    std::snprintf(vbuf, sizeof vbuf, "orbit azimuth %.0f, elevation %.0f, distance %.1f radii", c.view.azimuth,
                  c.view.elevation, c.view.distance);
    res.view = vbuf;
    res.discontinuity = c.discontinuity;
    auto progress = [&](const std::string& s) {
        if (c.progress) c.progress(s);
    };
    const int max_threads = c.threads.empty() ? 1 : *std::max_element(c.threads.begin(), c.threads.end());
    std::map<std::tuple<double, double, int>, double> bounds;  // streaming copies already measured

    for (int size : c.sizes) {
        for (const std::string& name : c.reliefs) {
            ReliefTexture relief = to_relief(make_procedural(name, size));
            if (c.discontinuity > 0.0)
                mark_discontinuities(relief, c.discontinuity * (relief.quant.max - relief.quant.min));
            ReliefQuad quad(std::move(relief));
            const ReliefTexture& t = quad.relief();
            const Camera cam = compare_camera(quad, c.view, c.view_width, c.view_height);
            const PrewarpCoefficients k = compute_coefficients(t.geometry, cam.eye);
            for (Reconstruction method : c.methods) {
                struct Variant {
                    bool exact;
                    Isa isa;
                    int threads;
                };
                std::vector<Variant> variants;
                const std::vector<Isa> isas = c.isas.empty() ? std::vector<Isa>{Isa::automatic} : c.isas;
                for (int th : c.threads)
                    for (Isa isa : isas)
                        if (isa != Isa::generic) variants.push_back({false, isa, th});
                if (c.reference && size <= c.reference_max_size) variants.push_back({false, Isa::generic, 1});
                if (c.exact && size <= c.exact_max_size) variants.push_back({true, Isa::generic, max_threads});
                for (const Variant& v : variants) {
                    PrewarpOptions o;
                    o.method = method;
                    o.exact = v.exact;
                    o.isa = v.isa;
                    o.threads = v.threads;
                    PrewarpWorkspace ws;
                    ImageRGBA8 out;
                    PrewarpStats st;
                    const std::vector<double> ms = repeat_timed(c, [&] {
                        const auto t0 = Clock::now();
                        st = prewarp(t, k, o, ws, out);
                        return ms_since(t0);
                    });
                    BenchRow row;
                    row.relief = name;
                    row.size = size;
                    row.method = method;
                    row.path = v.exact ? CoordinatePath::exact : CoordinatePath::lut;
                    row.kernel = st.isa != Isa::generic ? BenchKernel::fast : BenchKernel::reference;
                    row.isa = isa_name(st.isa);
                    row.threads = v.threads;
                    row.texels = st.texels;
                    row.out_width = out.width;
                    row.out_height = out.height;
                    row.repeats = int(ms.size());
                    row.ms_min = *std::min_element(ms.begin(), ms.end());
                    row.ms_median = median(ms);
                    row.mtexels_per_s = double(row.texels) / (row.ms_median * 1e3);
                    row.prewarps_per_s = 1000.0 / row.ms_median;
                    prewarp_traffic(method, v.exact, row.kernel == BenchKernel::fast, t.width, t.height, out.width,
                                    out.height, row.bytes_read, row.bytes_written);
                    const auto key = std::make_tuple(row.bytes_read, row.bytes_written, v.threads);
                    auto it = bounds.find(key);
                    if (it == bounds.end())
                        it = bounds
                                 .emplace(key, streaming_copy_ms(row.bytes_read, row.bytes_written, v.threads,
                                                                 c.min_seconds, c.min_repeats))
                                 .first;
                    row.bound_ms = it->second;
                    row.bound_ratio = row.ms_median / row.bound_ms;
                    row.row_pixels = st.row_pixels;
                    row.column_samples = st.column_samples;
                    res.rows.push_back(row);
                    char buf[256];
                    std::snprintf(buf, sizeof buf, "%s %d^2 %s %s %s %d thread%s: %.3f ms, %.0f Mtexel/s (%.1fx bound)",
                                  name.c_str(), size, to_string(row.method).c_str(), to_string(row.path).c_str(),
                                  row.isa.c_str(), v.threads, v.threads == 1 ? "" : "s", row.ms_median,
                                  row.mtexels_per_s, row.bound_ratio);
                    progress(buf);
                }
            }
        }
    }

    if (c.table1) {
        try {
            auto ctx = GlContext::create_offscreen(c.view_width, c.view_height, {.pin_llvmpipe_threads = true});
            res.gl_renderer = ctx->describe();
            Renderer renderer;
            for (const std::string& name : c.reliefs) {
                ReliefQuad quad(to_relief(make_procedural(name, c.table1_size)));
                const Camera cam = compare_camera(quad, c.view, c.view_width, c.view_height);
                for (Reconstruction method : c.methods) {
                    RenderSettings s;
                    s.method = method == Reconstruction::two_pass ? RenderMethod::two_pass : RenderMethod::pipelined;
                    s.prewarp.method = method;
                    s.prewarp.keep_outliers = true;  // as `rtm render` draws it: with the side polygons
                    s.prewarp.threads = max_threads;
                    s.draw.skips = false;  // every frame pre-warps and uploads everything
                    std::vector<double> pre, up, map, total, readback;
                    auto frame = [&] {
                        StageTimes st;
                        const auto t0 = Clock::now();
                        render_relief_frame(quad, &renderer, cam, s, st);
                        const double all = ms_since(t0);
                        pre.push_back(st.prewarp_ms);
                        up.push_back(st.upload_ms);
                        map.push_back(st.texture_map_ms);
                        total.push_back(st.total_ms);
                        readback.push_back(all - st.total_ms);
                        return st.total_ms;
                    };
                    for (int i = 0; i < 5; ++i) frame();  // warm-up: shaders, texture allocation
                    pre.clear();
                    up.clear();
                    map.clear();
                    total.clear();
                    readback.clear();
                    BenchConfig fc = c;
                    fc.min_repeats = std::max(c.min_repeats, 50);
                    fc.max_repeats = std::max(c.max_repeats, 2000);
                    fc.min_seconds = std::max(c.min_seconds, 0.5);
                    repeat_timed(fc, frame);
                    Table1Row r;
                    r.relief = name;
                    r.method = method;
                    r.size = c.table1_size;
                    r.threads = max_threads;
                    r.frames = int(total.size());
                    r.prewarp_ms = median(pre);
                    r.upload_ms = median(up);
                    r.texture_map_ms = median(map);
                    r.total_ms = median(total);
                    r.other_ms = std::max(0.0, r.total_ms - r.prewarp_ms - r.upload_ms - r.texture_map_ms);
                    r.readback_ms = median(readback);
                    r.fps = 1000.0 / r.total_ms;
                    res.table1.push_back(r);
                    char buf[256];
                    std::snprintf(buf, sizeof buf, "table 1: %s %d^2 %s in %dx%d: %.3f ms a frame (%.0f fps)",
                                  name.c_str(), c.table1_size, to_string(r.method).c_str(), c.view_width, c.view_height,
                                  r.total_ms, r.fps);
                    progress(buf);
                }
            }
            if (c.objects) bench_objects(c, renderer, max_threads, res, progress);
        } catch (const std::exception& e) {
            res.gl_renderer = std::string("no OpenGL context: ") + e.what();
            progress("table 1 skipped: " + res.gl_renderer);
        }
    }
    res.load_after = read_first_line("/proc/loadavg");
    return res;
}

std::vector<PipelinedRatio> pipelined_ratios(const BenchResult& r) {
    std::vector<PipelinedRatio> out;
    const double nan = std::numeric_limits<double>::quiet_NaN();
    auto find = [&](const std::string& relief, int size, Reconstruction method, BenchKernel kernel, int threads) {
        for (const BenchRow& x : r.rows)
            if (x.relief == relief && x.size == size && x.method == method && x.path == CoordinatePath::lut &&
                x.kernel == kernel && (threads == 0 || x.threads == threads))
                return &x;
        return static_cast<const BenchRow*>(nullptr);
    };
    bool any_fast = false;
    for (const BenchRow& x : r.rows) any_fast = any_fast || x.kernel == BenchKernel::fast;
    const BenchKernel timed_kernel = any_fast ? BenchKernel::fast : BenchKernel::reference;
    constexpr Reconstruction two_pass = Reconstruction::two_pass, pipelined = Reconstruction::pipelined;
    constexpr BenchKernel fast = BenchKernel::fast, reference = BenchKernel::reference;
    for (const BenchRow& x : r.rows) {
        if (x.method != two_pass || x.path != CoordinatePath::lut) continue;
        bool seen = false;
        for (const PipelinedRatio& p : out) seen = seen || (p.relief == x.relief && p.size == x.size);
        const bool pipelined_too = find(x.relief, x.size, pipelined, fast, 0) ||
                                   find(x.relief, x.size, pipelined, reference, 0);
        if (seen || !pipelined_too) continue;
        PipelinedRatio p;
        p.relief = x.relief;
        p.size = x.size;
        const BenchRow* rt = find(x.relief, x.size, two_pass, reference, 1);
        const BenchRow* rp = find(x.relief, x.size, pipelined, reference, 1);
        const bool counted = rt && rp && rt->texels > 0 && rp->row_pixels > 0;
        p.row_pixels_per_texel = counted ? double(rt->row_pixels) / double(rt->texels) : nan;
        p.two_pass_samples_per_texel = counted ? double(rt->column_samples) / double(rt->texels) : nan;
        p.pipelined_samples_per_texel = counted ? double(rp->column_samples) / double(rp->texels) : nan;
        // The fast kernels' times; on a CPU without them, the generic kernels' (the first row per thread count).
        for (const BenchRow& t : r.rows) {
            if (t.relief != x.relief || t.size != x.size || t.method != two_pass || t.path != CoordinatePath::lut ||
                t.kernel != timed_kernel)
                continue;
            bool have = false;
            for (const auto& [threads, ratio] : p.time_ratio) have = have || threads == t.threads;
            if (have) continue;
            if (const BenchRow* q = find(x.relief, x.size, pipelined, timed_kernel, t.threads))
                p.time_ratio.emplace_back(t.threads, q->ms_median / t.ms_median);
        }
        out.push_back(p);
    }
    return out;
}

std::string bench_isa_markdown(const BenchResult& r) {
    std::vector<std::string> isas;  // in the order of the rows
    for (const BenchRow& x : r.rows)
        if (x.path == CoordinatePath::lut && std::find(isas.begin(), isas.end(), x.isa) == isas.end())
            isas.push_back(x.isa);
    if (isas.size() < 2) return "";
    auto find = [&](const BenchRow& like, const std::string& isa, int threads) {
        for (const BenchRow& x : r.rows)
            if (x.relief == like.relief && x.size == like.size && x.method == like.method &&
                x.path == CoordinatePath::lut && x.isa == isa && x.threads == threads)
                return &x;
        return static_cast<const BenchRow*>(nullptr);
    };
    std::ostringstream s;
    char buf[256];
    s << "\n### SIMD targets\n\n";
    s << "Median ms of the lookup-table kernels per target (the target that ran: a reconstruction a target does not "
         "implement runs on the generic kernels and is listed there); x avx512 = the avx512 target's time / this "
         "one's (higher is faster), x generic = the generic kernels' time at one thread / this one's.\n\n";
    s << "| relief | size | method | threads | target | median ms | x avx512 | x generic |\n";
    s << "|---|---:|---|---:|---|---:|---:|---:|\n";
    for (const BenchRow& x : r.rows) {
        if (x.path != CoordinatePath::lut) continue;
        const BenchRow* a = find(x, "avx512", x.threads);
        const BenchRow* g = find(x, "generic", 1);
        std::string ra = a ? "" : "-", rg = g ? "" : "-";
        if (a) std::snprintf(buf, sizeof buf, "%.2f", a->ms_median / x.ms_median), ra = buf;
        if (g) std::snprintf(buf, sizeof buf, "%.2f", g->ms_median / x.ms_median), rg = buf;
        std::snprintf(buf, sizeof buf, "| %s | %d^2 | %s | %d | %s | %.3f | %s | %s |\n", x.relief.c_str(), x.size,
                      to_string(x.method).c_str(), x.threads, x.isa.c_str(), x.ms_median, ra.c_str(), rg.c_str());
        s << buf;
    }
    return s.str();
}

std::string bench_markdown(const BenchResult& r) {
    std::ostringstream s;
    char buf[512];
    s << "Machine: " << r.machine << "  \n";
    s << "Load average (1, 5, 15 min) before: " << r.load_before << "; after: " << r.load_after << "  \n";
    s << "View: " << r.view << (r.discontinuity > 0.0 ? "  \n" : "\n\n");
    if (r.discontinuity > 0.0)
        s << "Discontinuity marks: the throughput rows' reliefs marked at a threshold of " << r.discontinuity
          << " of their displacement range (paper section 4.1.1)\n\n";
    s << "### Pre-warp throughput\n\n";
    s << "Median of the repeats; Mtexel/s = source texels / median time. Bound: a streaming copy of the bytes the "
         "passes read and write, with the same threads, measured in the same run.\n\n";
    s << "| relief | size | method | path | kernel | threads | median ms | min ms | Mtexel/s | pre-warps/s | "
         "bound ms | x bound |\n";
    s << "|---|---:|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const BenchRow& x : r.rows) {
        std::snprintf(buf, sizeof buf, "| %s | %d^2 | %s | %s | %s | %d | %.3f | %.3f | %.1f | %.1f | %.3f | %.2f |\n",
                      x.relief.c_str(), x.size, to_string(x.method).c_str(), to_string(x.path).c_str(),
                      (x.kernel == BenchKernel::fast ? "fast " + x.isa : to_string(x.kernel)).c_str(), x.threads,
                      x.ms_median, x.ms_min, x.mtexels_per_s, x.prewarps_per_s, x.bound_ms, x.bound_ratio);
        s << buf;
    }
    s << bench_isa_markdown(r);
    const std::vector<PipelinedRatio> ratios = pipelined_ratios(r);
    if (!ratios.empty()) {
        s << "\n### Pipelined against two-pass\n\n";
        s << "Work a texel, counted by the reference kernels (one row of each reconstruction's lookup-table run; "
             "empty without it): the pixels the row warp produces, overwrites included (the same in both), and the "
             "samples the column warp rasterizes: two-pass one per intermediate pixel that survives its row's "
             "overwrites, pipelined every pixel the row warp produces (paper section 3.2.2). Time: the fast "
             "kernels' median pipelined / two-pass (the generic kernels' on a CPU without the fast ones); per column "
             "sample: that time ratio over the ratio of column samples, the cost of one column sample pipelined "
             "against two-pass (target: <= 1.5 on every relief).\n\n";
        s << "| relief | size | row pixels a texel | column samples a texel, two-pass | pipelined | ratio | "
             "time pipelined / two-pass | per column sample |\n";
        s << "|---|---:|---:|---:|---:|---:|---|---|\n";
        for (const PipelinedRatio& p : ratios) {
            const double samples = p.pipelined_samples_per_texel / p.two_pass_samples_per_texel;
            std::string times, per_sample;
            for (const auto& [threads, ratio] : p.time_ratio) {
                std::snprintf(buf, sizeof buf, "%s%.2f (%d thread%s)", times.empty() ? "" : ", ", ratio, threads,
                              threads == 1 ? "" : "s");
                times += buf;
                std::snprintf(buf, sizeof buf, "%s%.2f", per_sample.empty() ? "" : ", ", ratio / samples);
                per_sample += buf;
            }
            if (std::isnan(p.row_pixels_per_texel))
                std::snprintf(buf, sizeof buf, "| %s | %d^2 | | | | | %s | |\n", p.relief.c_str(), p.size,
                              times.c_str());
            else
                std::snprintf(buf, sizeof buf, "| %s | %d^2 | %.2f | %.2f | %.2f | %.2f | %s | %s |\n",
                              p.relief.c_str(), p.size, p.row_pixels_per_texel, p.two_pass_samples_per_texel,
                              p.pipelined_samples_per_texel, samples, times.c_str(), per_sample.c_str());
            s << buf;
        }
    }
    if (!r.table1.empty() || !r.gl_renderer.empty()) {
        s << "\n### Table 1: one relief quad in a "
          << "512x512 view\n\n";
        s << "OpenGL: " << r.gl_renderer << "  \n";
        s << "Median milliseconds per frame (every frame pre-warps and uploads the whole texture; side polygons on); "
             "percentages of the frame as in the paper's Table 1. Read-back of the image is not part of the frame.\n\n";
        s << "| relief | size | method | threads | pre-warping and resampling | upload | texture mapping | other | "
             "frame | frames/s | read-back |\n";
        s << "|---|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const Table1Row& t : r.table1) {
            auto pct = [&](double v) { return 100.0 * v / t.total_ms; };
            std::snprintf(buf, sizeof buf,
                          "| %s | %d^2 | %s | %d | %.3f (%.1f%%) | %.3f (%.1f%%) | %.3f (%.1f%%) | %.3f (%.1f%%) | "
                          "%.3f | %.0f | %.3f |\n",
                          t.relief.c_str(), t.size, to_string(t.method).c_str(), t.threads, t.prewarp_ms,
                          pct(t.prewarp_ms), t.upload_ms, pct(t.upload_ms), t.texture_map_ms, pct(t.texture_map_ms),
                          t.other_ms, pct(t.other_ms), t.total_ms, t.fps, t.readback_ms);
            s << buf;
        }
    }
    if (!r.objects.empty()) {
        s << "\n### Six-face objects in a 512x512 view, next to Table 1\n\n";
        s << "Median milliseconds per frame of a synthetic object with 6 faces of the Table 1 size (every frame "
             "pre-warps each visible face after its adjacent faces, and uploads; two-pass), from one-, two- and "
             "three-face views (orbit AZ,EL,2.5 about the box's bounding sphere); pre-warp: all faces, with each "
             "face's time; of which adjacent: the adjacent faces pre-warped onto them (Figure 15); relief: Table 1's "
             "two-pass frame of the first relief, measured again with the view, in blocks of "
          << kBlock << " frames alternating with the object's, the first " << kWarm
          << " of each block left out; x relief: the object frame over it (the two medians).\n\n";
        s << "| object | faces | view | pre-warp (per face) | of which adjacent | upload | texture mapping | frame | "
             "frames/s | relief | x relief |\n";
        s << "|---|---:|---|---|---:|---:|---:|---:|---:|---:|---:|\n";
        for (const ObjectFrameRow& o : r.objects) {
            std::string per;
            for (const auto& [face, ms] : o.face_prewarp_ms) {
                char b[64];
                std::snprintf(b, sizeof b, "%s%s %.2f", per.empty() ? "" : ", ", face.c_str(), ms);
                per += b;
            }
            std::snprintf(buf, sizeof buf,
                          "| %s | 6x%d^2 | %s (%g,%g) | %.3f (%s) | %.3f | %.3f | %.3f | %.3f | %.0f | %.3f | %.2f |\n",
                          o.object.c_str(), o.size, o.view.c_str(), o.az, o.el, o.prewarp_ms, per.c_str(),
                          o.adjacent_ms, o.upload_ms, o.texture_map_ms, o.total_ms, o.fps, o.relief_ms, o.single_ratio);
            s << buf;
        }
    }
    return s.str();
}

nlohmann::json bench_json(const BenchResult& r) {
    nlohmann::json rows = nlohmann::json::array();
    for (const BenchRow& x : r.rows)
        rows.push_back({{"relief", x.relief},
                        {"size", x.size},
                        {"method", to_string(x.method)},
                        {"path", to_string(x.path)},
                        {"kernel", to_string(x.kernel)},
                        {"isa", x.isa},
                        {"threads", x.threads},
                        {"texels", x.texels},
                        {"out_size", {x.out_width, x.out_height}},
                        {"repeats", x.repeats},
                        {"prewarp_ms", {{"min", x.ms_min}, {"median", x.ms_median}}},
                        {"mtexels_per_s", x.mtexels_per_s},
                        {"prewarps_per_s", x.prewarps_per_s},
                        {"bytes_read", x.bytes_read},
                        {"bytes_written", x.bytes_written},
                        {"bound_ms", x.bound_ms},
                        {"bound_ratio", x.bound_ratio},
                        {"row_pixels", x.row_pixels},
                        {"column_samples", x.column_samples}});
    // NaN (no reference row) goes out as null.
    auto num = [](double v) { return std::isnan(v) ? nlohmann::json() : nlohmann::json(v); };
    nlohmann::json ratios = nlohmann::json::array();
    for (const PipelinedRatio& p : pipelined_ratios(r)) {
        nlohmann::json times = nlohmann::json::array();
        const double samples = p.pipelined_samples_per_texel / p.two_pass_samples_per_texel;
        for (const auto& [threads, ratio] : p.time_ratio)
            times.push_back({{"threads", threads}, {"ratio", ratio}, {"per_column_sample", num(ratio / samples)}});
        ratios.push_back({{"relief", p.relief},
                          {"size", p.size},
                          {"row_pixels_per_texel", num(p.row_pixels_per_texel)},
                          {"two_pass_column_samples_per_texel", num(p.two_pass_samples_per_texel)},
                          {"pipelined_column_samples_per_texel", num(p.pipelined_samples_per_texel)},
                          {"time_ratio", times}});
    }
    nlohmann::json t1 = nlohmann::json::array();
    for (const Table1Row& t : r.table1)
        t1.push_back({{"relief", t.relief},
                      {"size", t.size},
                      {"method", to_string(t.method)},
                      {"threads", t.threads},
                      {"frames", t.frames},
                      {"prewarp_ms", t.prewarp_ms},
                      {"upload_ms", t.upload_ms},
                      {"texture_map_ms", t.texture_map_ms},
                      {"other_ms", t.other_ms},
                      {"total_ms", t.total_ms},
                      {"readback_ms", t.readback_ms},
                      {"fps", t.fps}});
    nlohmann::json objs = nlohmann::json::array();
    for (const ObjectFrameRow& o : r.objects) {
        nlohmann::json faces = nlohmann::json::array();
        for (const auto& [face, ms] : o.face_prewarp_ms) faces.push_back({{"face", face}, {"prewarp_ms", ms}});
        objs.push_back({{"object", o.object},
                        {"view", o.view},
                        {"orbit", {o.az, o.el, o.distance}},
                        {"size", o.size},
                        {"faces_drawn", o.faces},
                        {"frames", o.frames},
                        {"faces", faces},
                        {"prewarp_ms", o.prewarp_ms},
                        {"adjacent_ms", o.adjacent_ms},
                        {"upload_ms", o.upload_ms},
                        {"texture_map_ms", o.texture_map_ms},
                        {"total_ms", o.total_ms},
                        {"fps", o.fps},
                        {"relief_ms", o.relief_ms},
                        {"relief_frame_ratio", o.single_ratio}});
    }
    return {{"command", "bench"},
            {"machine", r.machine},
            {"gl_renderer", r.gl_renderer},
            {"load_before", r.load_before},
            {"load_after", r.load_after},
            {"view", r.view},
            {"discontinuity", r.discontinuity},
            {"rows", rows},
            {"pipelined_vs_two_pass", ratios},
            {"table1", t1},
            {"objects", objs}};
}

}  // namespace rtm
