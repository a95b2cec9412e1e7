#include "objects/relief_object.h"

#include <glm/geometric.hpp>

#include <algorithm>
#include <atomic>
#include <bit>
#include <cmath>
#include <cstddef>
#include <stdexcept>

#include "objects/object_plan.h"
#include "objects/view_analysis.h"
#include "truth/micromesh.h"
#include "warp/timing.h"

namespace rtm {

namespace {

void add_skip(std::vector<std::string>& skips, const std::string& s) {
    if (std::find(skips.begin(), skips.end(), s) == skips.end()) skips.push_back(s);
}

// Finds the cracks one pixel wide in a face's composite texture. The line warp covers a surface only between its
// samples' centres, so where two surfaces meet at a marked discontinuity (a step: the top of the step seen by the
// face, its wall by an adjacent face) half a texel is missing on each side. An empty pixel whose two neighbours
// along a row, or along a column, are both filled takes their average colour (and the nearer depth). Reads rows
// [r0, r1) of the image as it is and appends the fills to `out` (few: hundreds of a face's 65,536 pixels), to be
// written after every row range is read, so nothing spreads further than one pixel and ranges run in parallel.
void find_cracks(const ImageRGBA8& img, const Image2D<uint8_t>* displ, int r0, int r1, std::vector<CrackFill>& out) {
    const int w = img.width, h = img.height;
    auto avg = [](const Rgba8& a, const Rgba8& b) {
        return Rgba8{uint8_t((a.r + b.r + 1) / 2), uint8_t((a.g + b.g + 1) / 2), uint8_t((a.b + b.b + 1) / 2), 255};
    };
    // Per row, first the candidates branch-free (an empty pixel with both neighbours along the row, or both along the
    // column, filled), a loop that vectorizes; then the few candidates one by one. (Pixel by pixel with branches it
    // was 5% of an object's pre-warp.)
    std::vector<uint8_t> cand(static_cast<size_t>(w));
    static_assert(sizeof(Rgba8) == 4 && offsetof(Rgba8, a) == 3);
    const uint8_t* alpha = reinterpret_cast<const uint8_t*>(img.pixels.data()) + 3;  // pixel i's alpha at [4 * i]
    for (int row = r0; row < r1; ++row) {
        const Rgba8* s = &img.pixels[size_t(row) * size_t(w)];
        {
            const uint8_t* __restrict a = alpha + 4 * size_t(row) * size_t(w);
            const bool vertical = row > 0 && row + 1 < h;
            const uint8_t* __restrict up = vertical ? a - 4 * size_t(w) : a;
            const uint8_t* __restrict dn = vertical ? a + 4 * size_t(w) : a;
            uint8_t* __restrict c = cand.data();
            for (int x = 0; x < w; ++x)
                c[x] = uint8_t(a[4 * x] == 0) & uint8_t(vertical) & uint8_t(up[4 * x] == 255) &
                       uint8_t(dn[4 * x] == 255);
            for (int x = 1; x + 1 < w; ++x)
                c[x] |= uint8_t(a[4 * x] == 0) & uint8_t(a[4 * x - 4] == 255) & uint8_t(a[4 * x + 4] == 255);
        }
        for (int x = 0; x < w; ++x) {
            if (!cand[size_t(x)]) continue;
            int ax = -1, ar = -1, bx = -1, br = -1;
            if (x > 0 && x + 1 < w && s[x - 1].a == 255 && s[x + 1].a == 255) {
                ax = x - 1, ar = row, bx = x + 1, br = row;
            } else if (row > 0 && row + 1 < h && img.at(x, row - 1).a == 255 && img.at(x, row + 1).a == 255) {
                ax = x, ar = row - 1, bx = x, br = row + 1;
            } else {
                continue;
            }
            CrackFill f{size_t(row) * size_t(w) + size_t(x), avg(img.at(ax, ar), img.at(bx, br)), kEmptyIndex};
            if (displ) {
                const uint8_t qa = displ->at(ax, ar), qb = displ->at(bx, br);
                f.displ = qa == kEmptyIndex ? qb : qb == kEmptyIndex ? qa : std::max(qa, qb);
            }
            out.push_back(f);
        }
    }
}

}  // namespace

ReliefObject::ReliefObject(SixFaceObject object, const FaceShares& shared)
    : name_(std::move(object.name)), box_(object.box) {
    quads_.reserve(kFaceCount);
    for (size_t k = 0; k < object.faces.size(); ++k) quads_.emplace_back(std::move(object.faces[k]), shared[k]);
}
ReliefObject::~ReliefObject() = default;
ReliefObject::ReliefObject(ReliefObject&&) noexcept = default;

Bounds ReliefObject::bounds() const { return Bounds{box_.lo, box_.hi}; }

long long ReliefObject::texels() const {
    long long n = 0;
    for (const ReliefQuad& q : quads_) n += (long long)q.relief().width * q.relief().height;
    return n;
}

void ReliefObject::prewarp_face(int face, const glm::dvec3& eye, int level, const PrewarpOptions& options,
                                bool with_displ, ObjectFacePrewarp& out, bool adjacent_holes_only) {
    const ObjectRegion region = classify_region(box_, eye);
    if (!region.visible(face))
        throw std::invalid_argument(std::string("ReliefObject::prewarp_face: face ") + kFaceKeys[size_t(face)] +
                                    " is not visible from " + region.to_string());
    const auto t0 = Clock::now();
    ReliefQuad& q = quads_[size_t(face)];
    level = std::clamp(level, 0, q.levels() - 1);
    const ReliefTexture& ft = q.level(level);
    const int w = ft.width, h = ft.height;
    const PrewarpCoefficients k = compute_coefficients(ft.geometry, eye);
    out.face = face;
    out.level = level;
    out.k = k;
    out.adjacent = faces_warped_onto(region, face);
    out.texels = (long long)w * h;

    // The face itself (its own samples win wherever it has any) ...
    PrewarpOptions o = options;
    o.keep_outliers = false;
    out.isa = prewarp(ft, k, o, workspace_, out.image, with_displ ? &own_displ_ : nullptr).isa;
    // ... and the adjacent faces onto F's plane, z-tested among themselves, where F left holes (or whole).
    const auto t_adjacent = Clock::now();
    const AdjacentNeed* need = nullptr;
    if (adjacent_holes_only && !out.adjacent.empty()) {
        // Only the orientations of the need the adjacent faces' passes read.
        std::array<bool, 2> orientations{};
        for (int g : out.adjacent) {
            const int o = adjacent_pass_orientation(quads_[size_t(g)].level(level).geometry, ft.geometry);
            if (o >= 0) orientations[size_t(o)] = true;
        }
        need_.assign_holes(out.image, options.threads, orientations);
        need = &need_;
    }
    adjacent_.reset(w, h, options.threads);
    for (int g : out.adjacent) {
        const ReliefTexture& gt = quads_[size_t(g)].level(level);
        if (!need || need->count > 0) {
            // The adjacent face's chunks (view-independent), made the first time it is warped at this level.
            const AdjacentChunks* chunks = nullptr;
            if (need) {
                std::vector<AdjacentChunks>& per_level = chunks_[size_t(g)];
                if (per_level.size() <= size_t(level)) per_level.resize(size_t(level) + 1);
                if (per_level[size_t(level)].width == 0) per_level[size_t(level)] = AdjacentChunks::make(gt);
                chunks = &per_level[size_t(level)];
            }
            warp_adjacent_face(gt, ft.geometry, w, h, k, options.exact, adjacent_ws_, adjacent_, options.threads,
                               options.isa, need, chunks);
        }
        out.texels += (long long)gt.width * gt.height;
    }
    out.adjacent_ms = ms_since(t_adjacent);
    const double depth = box_.extent()[face_axis(face)];
    out.depth_quant = Quantizer::from_range(-depth, 0.0);
    if (with_displ && (out.displ.width != w || out.displ.height != h)) out.displ = Image2D<uint8_t>(w, h);
    // The face's own depth level re-quantized over the box's depth: a function of the 8-bit level alone, so one table
    // (encode and its rounding per pixel were 6% of an object's pre-warp in a profile, docs/perf-history.md).
    std::array<uint8_t, 256> own_level{};
    if (with_displ)
        for (int q = 0; q < 256; ++q)
            own_level[size_t(q)] = q == kEmptyIndex ? kEmptyIndex : out.depth_quant.encode(ft.quant.decode(uint8_t(q)));
    // The composite, then the cracks, each over rows in parallel (every pixel on its own: the same image on any
    // number of threads).
    std::atomic<long long> filled{0};
    parallel_ranges(h, options.threads, [&](int r0, int r1) {
        long long n = 0;
        if constexpr (std::endian::native == std::endian::little && sizeof(Rgba8) == 4) {
            if (!with_displ) {
                // The same without depth levels, branch-free over whole pixels (the loop vectorizes): a hole (alpha,
                // the top byte, below 128) takes the adjacent sample where one landed (alpha not 0).
                uint32_t* __restrict img = reinterpret_cast<uint32_t*>(out.image.pixels.data());
                const uint32_t* __restrict adj = reinterpret_cast<const uint32_t*>(adjacent_.color.pixels.data());
                const uint32_t force = o.filter == Filter::coverage ? 0xFF000000u : 0u;
                for (size_t i = size_t(r0) * size_t(w); i < size_t(r1) * size_t(w); ++i) {
                    const uint32_t p = img[i], a = adj[i];
                    const bool take = (p >> 31) == 0 && (a >> 24) != 0;
                    img[i] = take ? (a | force) : p;
                    n += take;
                }
                filled += n;
                return;
            }
        }
        for (size_t i = size_t(r0) * size_t(w); i < size_t(r1) * size_t(w); ++i) {
            Rgba8& p = out.image.pixels[i];
            // A pixel the face covers less than half (the coverage filter's fractional alpha; the texture-mapping
            // stage discards it) is a hole too.
            bool own = p.a >= 128;
            if (!own && adjacent_.color.pixels[i].a != 0) {
                p = adjacent_.color.pixels[i];
                if (o.filter == Filter::coverage) p = {p.r, p.g, p.b, 255};
                ++n;
            } else if (!own && p.a != 0) {
                own = true;  // the face's own partial coverage stays (no adjacent sample to prefer)
            }
            if (!with_displ) continue;
            uint8_t& dq = out.displ.pixels[i];
            if (own)
                dq = own_level[own_displ_.pixels[i]];
            else if (p.a != 0)
                dq = out.depth_quant.encode(adjacent_.depth.pixels[i]);
            else
                dq = kEmptyIndex;
        }
        filled += n;
    });
    out.adjacent_pixels = filled;
    if (!out.adjacent.empty()) {
        // Rows in blocks of 16, each block's fills in its own list (the same lists on any number of threads).
        const int blocks = (h + 15) / 16;
        if (cracks_.size() < size_t(blocks)) cracks_.resize(size_t(blocks));
        parallel_ranges(blocks, options.threads, [&](int b0, int b1) {
            for (int b = b0; b < b1; ++b) {
                cracks_[size_t(b)].clear();
                find_cracks(out.image, with_displ ? &out.displ : nullptr, b * 16, std::min(h, b * 16 + 16),
                            cracks_[size_t(b)]);
            }
        });
        long long cracks = 0;
        for (int b = 0; b < blocks; ++b)
            for (const CrackFill& f : cracks_[size_t(b)]) {
                out.image.pixels[f.at] = f.color;
                if (with_displ) out.displ.pixels[f.at] = f.displ;
                ++cracks;
            }
        out.crack_pixels = cracks;
    }
    if (o.filter == Filter::coverage) premultiply_alpha(out.image);
    out.prewarp_ms = ms_since(t0);
}

void ReliefObject::draw(Renderer& renderer, const Camera& cam, RenderMethod method, const PrewarpOptions& options,
                        StageTimes& times, const DrawOptions& d, ObjectReport* report) {
    const auto t_start = Clock::now();
    ObjectReport rep;
    rep.region = classify_region(box_, cam.eye);
    auto done = [&] {
        times.total_ms += ms_since(t_start);
        if (report) *report = std::move(rep);
    };
    const bool warp_method = prewarps(method);
    if (!warp_method && method != RenderMethod::flat)
        throw std::invalid_argument("ReliefObject::draw: method " + to_string(method) + " is not a texture method");
    if (rep.region.inside()) {  // the eye inside the box: nothing can be pre-warped for it
        add_skip(rep.skips, kSkipInsideSlab);
        rep.skip_faces[kSkipInsideSlab] = kFaceCount;
        const auto t0 = Clock::now();
        draw_micromesh(renderer, cam, d.skips && d.micromesh_tiles);
        times.texture_map_ms += ms_since(t0);
        return done();
    }
    if (rep.region.visible_faces().size() < size_t(kFaceCount)) {
        add_skip(rep.skips, kSkipBackFacing);
        rep.skip_faces[kSkipBackFacing] = kFaceCount - int(rep.region.visible_faces().size());
    }

    // Every face is pre-warped and uploaded first, then all are drawn: one wait for the OpenGL pipeline after the
    // uploads and one after the draws, not one per face (llvmpipe's threads wake for each, which a loaded machine makes
    // expensive). The same draws in the same order: the same image.
    std::vector<std::pair<ReliefSurface, const GlTexture*>> quads;
    double upload_ms = 0.0;
    for (int f : rep.region.visible_faces()) {
        ReliefQuad& q = quads_[size_t(f)];
        const ObjectFacePlan plan = plan_object_face(
            cam, method, options, d, rep.region, f, q.relief(),
            [&](int i) -> const ReliefTexture& { return q.level(i); }, box_.extent()[face_axis(f)], last_[size_t(f)],
            d.level < 0 ? &q.spreads() : nullptr);
        for (const std::string& s : plan.skips) {
            add_skip(rep.skips, s);
            ++rep.skip_faces[s];
        }
        if (plan.action == FrameAction::nothing) continue;
        ObjectFaceReport fr;
        fr.face = f;
        fr.level = plan.level;
        fr.skips = plan.skips;
        const ReliefTexture& ft = q.level(plan.level);
        ObjectFacePrewarp& warped = warped_[size_t(f)];
        TextureContent content;
        if (plan.action == FrameAction::flat) {
            if (!(uploaded_[size_t(f)].source == TextureContent::Source::flat &&
                  uploaded_[size_t(f)].level == plan.level)) {
                warped.image = flat_texture(ft);
                warped.face = f;
            }
            last_[size_t(f)].valid = false;  // warped.image no longer holds the pre-warp
            content = {TextureContent::Source::flat, plan.level};
        } else {
            if (plan.action == FrameAction::prewarp) {
                prewarp_face(f, cam.eye, plan.level, plan.prewarp, d.depth_correction, warped, d.adjacent_holes_only);
                last_[size_t(f)] = {true, plan.setup, plan.k};
                ++versions_[size_t(f)];
                fr.prewarp_ms = warped.prewarp_ms;
                fr.adjacent_ms = warped.adjacent_ms;
                times.prewarp_ms += warped.prewarp_ms;
            }
            fr.adjacent = warped.adjacent;
            content = {TextureContent::Source::prewarp, plan.level};
        }
        ReliefSurface rs;
        rs.origin = ft.geometry.origin;
        rs.a = ft.geometry.a;
        rs.b = ft.geometry.b;
        rs.width = ft.width;
        rs.height = ft.height;
        const auto t0 = Clock::now();
        // A reused pre-warp, or the same flat level again, is already in the texture (with skips on).
        const bool same = d.skips && textures_[size_t(f)] && uploaded_[size_t(f)] == content &&
                          uploaded_versions_[size_t(f)] == versions_[size_t(f)];
        if (!textures_[size_t(f)]) textures_[size_t(f)] = std::make_unique<GlTexture>();
        const bool depth = plan.action != FrameAction::flat && d.depth_correction;
        if (!same) {
            textures_[size_t(f)]->upload(warped.image);
            if (depth) {
                if (!displ_textures_[size_t(f)]) displ_textures_[size_t(f)] = std::make_unique<GlTexture>();
                displ_textures_[size_t(f)]->upload_gray(warped.displ);
            }
            uploaded_[size_t(f)] = d.skips ? content : TextureContent{};
            uploaded_versions_[size_t(f)] = versions_[size_t(f)];
        } else {
            fr.skips.push_back(kSkipPartialUpload);
            add_skip(rep.skips, kSkipPartialUpload);
            ++rep.skip_faces[kSkipPartialUpload];
        }
        if (depth) {
            rs.displ = displ_textures_[size_t(f)].get();
            rs.k3 = warped.k.k3;
            rs.dmin = warped.depth_quant.min;
            rs.dmax = warped.depth_quant.max;
            rs.qs = warped.depth_quant.qs;
        }
        upload_ms += ms_since(t0);
        quads.emplace_back(rs, textures_[size_t(f)].get());
        rep.faces.push_back(std::move(fr));
    }
    auto t0 = Clock::now();
    renderer.finish();
    times.upload_ms += upload_ms + ms_since(t0);
    t0 = Clock::now();
    for (const auto& [rs, tex] : quads) renderer.draw_relief(cam, rs, *tex);
    renderer.finish();
    times.texture_map_ms += ms_since(t0);
    done();
}

void ReliefObject::draw_micromesh(Renderer& renderer, const Camera& cam, bool tiles) {
    for (ReliefQuad& q : quads_) q.draw_micromesh(renderer, cam, tiles);
    renderer.finish();
}

ImageRGBA8 render_object_frame(ReliefObject& object, Renderer& renderer, const Camera& cam, RenderMethod method,
                               const PrewarpOptions& options, const DrawOptions& draw, StageTimes& times,
                               ObjectReport* report) {
    const auto t0 = Clock::now();
    renderer.begin_frame(cam);
    if (method == RenderMethod::micromesh) {
        object.draw_micromesh(renderer, cam);
        times.texture_map_ms += ms_since(t0);
        times.total_ms += ms_since(t0);
        if (report) *report = ObjectReport{object.region(cam.eye), {}, {}, {}};
    } else {
        StageTimes st;
        object.draw(renderer, cam, method, options, st, draw, report);
        times.prewarp_ms += st.prewarp_ms;
        times.upload_ms += st.upload_ms;
        times.texture_map_ms += st.texture_map_ms;
        times.total_ms += ms_since(t0);
    }
    return renderer.read_pixels(cam.width, cam.height);
}

}  // namespace rtm
