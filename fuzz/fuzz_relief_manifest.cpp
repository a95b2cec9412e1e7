// libFuzzer target: the bytes are a relief manifest (NAME.relief.json, formats/relief_manifest.h).
//
// They are written to a file in a scratch folder that also holds small valid images (c.png, d.png, c.ppm, d.pgm,
// d.pfm, 4x3 texels, and a 2x2 one, d22.png, for size mismatches), so that a manifest naming them gets past the
// parser into load_relief: image reading, the size check, displacement mapping, make_relief and
// mark_discontinuities. Seeds: scripts/fuzz.sh writes fuzz/corpus/relief_manifest/ into the run's corpus folder;
// fuzz/relief_manifest.dict gives the mutator the field names.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_util.h"
#include "formats/relief_manifest.h"
#include "formats/image_io.h"

namespace {

using namespace rtm;

std::string pfm(int w, int h, const std::vector<float>& values) {
    std::string s = "Pf\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
    const size_t off = s.size();
    s.resize(off + values.size() * sizeof(float));
    std::memcpy(&s[off], values.data(), values.size() * sizeof(float));
    return s;
}

void write_images() {
    ImageRGBA8 c(4, 3);
    ImageF d(4, 3);
    for (int r = 0; r < 3; ++r)
        for (int x = 0; x < 4; ++x) {
            c.at(x, r) = {uint8_t(60 * x), uint8_t(80 * r), 200, uint8_t(x == 1 && r == 1 ? 0 : 255)};
            d.at(x, r) = float(x + 4 * r) / 11.0f;
        }
    write_rgba8(fuzz::scratch_file("c.png"), c);
    write_gray(fuzz::scratch_file("d.png"), d);
    write_gray(fuzz::scratch_file("d22.png"), ImageF(2, 2));
    fuzz::write_file(fuzz::scratch_file("c.ppm"),
                     "P3\n4 3\n255\n10 20 30 40 50 60 70 80 90 1 2 3\n4 5 6 7 8 9 10 11 12 13 14 15\n"
                     "16 17 18 19 20 21 22 23 24 25 26 27\n");
    fuzz::write_file(fuzz::scratch_file("d.pgm"), "P2\n4 3\n255\n0 10 20 30\n40 50 60 70\n80 90 100 255\n");
    fuzz::write_file(fuzz::scratch_file("d.pfm"),
                     pfm(4, 3, {0, 0.1f, 0.2f, 0.3f, 0.4f, 0.5f, 0.6f, 0.7f, 0.8f, 0.9f, 1, 1}));
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    fuzz::init_reports();
    write_images();
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const std::string path = fuzz::scratch_file("m.relief.json");
    fuzz::write_file(path, std::string_view(reinterpret_cast<const char*>(data), size));
    ReliefManifest m;
    const bool parsed = fuzz::expect_ok_or_io_error(path, [&] { m = parse_relief_manifest(path); });
    if (!parsed) return 0;
    // What the parser accepted must be what its header promises.
    if (!(m.range_min <= m.range_max) || !std::isfinite(m.range_min) || !std::isfinite(m.range_max) ||
        !m.geometry.validate().empty() || m.color_path.empty() || m.displacement_path.empty() ||
        (m.discontinuity_threshold &&
         !(std::isfinite(*m.discontinuity_threshold) && *m.discontinuity_threshold >= 0))) {
        std::fprintf(stderr, "FINDING: parse_relief_manifest accepted an invalid manifest: range [%g, %g], %s\n",
                     m.range_min, m.range_max, m.geometry.to_string().c_str());
        std::abort();
    }
    ReliefTexture t;
    if (fuzz::expect_ok_or_io_error(path, [&] { t = load_relief(path); })) {
        const size_t n = size_t(t.width) * size_t(t.height);
        bool finite = true;
        for (float d : t.displacement) finite = finite && std::isfinite(d);
        if (t.width <= 0 || t.height <= 0 || t.texels.size() != n || t.displacement.size() != n || !finite) {
            std::fprintf(stderr, "FINDING: load_relief returned an inconsistent texture: %s\n", t.to_string().c_str());
            std::abort();
        }
    }
    return 0;
}
