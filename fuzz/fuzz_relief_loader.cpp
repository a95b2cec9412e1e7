// libFuzzer target: the bytes are the colour or the displacement image of an otherwise valid relief.
//
// Input layout: byte 0 chooses, bit by bit,
//   bit 0      0 = the rest is the colour image, 1 = the displacement image;
//   bits 1..4  the file's extension (kExtensions), which is how OpenImageIO picks the reader it tries first;
//   bit 5      the manifest has a "discontinuity_threshold" (mark_discontinuities runs);
//   bit 6      displacement_range [-1000, 1000] instead of [0, 0.25].
// The rest is written to img.<ext>, and load_relief reads it through a manifest whose other image is a valid 6x4
// one (c.ppm or d.pfm, in formats OpenImageIO reads without conversion, so that the run's time goes to the fuzzed
// file). The seeds are 6x4 too (scripts/fuzz.sh writes one per format, with both choices of bit 0): mutations
// that keep the size get past the size check into the displacement checks, make_relief and mark_discontinuities.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

#include "fuzz_util.h"
#include "formats/relief_manifest.h"
#include "formats/image_io.h"

namespace {

using namespace rtm;

// 16 entries: bits 1..4 of byte 0. "" leaves the extension off, so OpenImageIO has to guess from the contents.
constexpr const char* kExtensions[16] = {"png", "ppm", "pgm", "pfm", "jpg",  "tif", "exr", "bmp",
                                         "tga", "hdr", "gif", "sgi", "webp", "psd", "dds", ""};
constexpr int kWidth = 6, kHeight = 4;

std::string pfm(int w, int h, const std::vector<float>& values) {
    std::string s = "Pf\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
    const size_t off = s.size();
    s.resize(off + values.size() * sizeof(float));
    std::memcpy(&s[off], values.data(), values.size() * sizeof(float));
    return s;
}

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    fuzz::init_reports();
    // The valid partners, 6x4: colour with one empty texel, displacement 0..1.
    std::string ppm = "P3\n" + std::to_string(kWidth) + " " + std::to_string(kHeight) + "\n255\n";
    std::vector<float> disp;
    for (int i = 0; i < kWidth * kHeight; ++i) {
        ppm += std::to_string(i * 10) + " " + std::to_string(255 - i * 10) + " 90\n";
        disp.push_back(float(i) / float(kWidth * kHeight - 1));
    }
    fuzz::write_file(fuzz::scratch_file("c.ppm"), ppm);
    fuzz::write_file(fuzz::scratch_file("d.pfm"), pfm(kWidth, kHeight, disp));
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size < 1) return 0;
    const uint8_t sel = data[0];
    const bool is_displacement = sel & 1;
    const std::string ext = kExtensions[(sel >> 1) & 15];
    const bool threshold = sel & 32;
    const bool wide_range = sel & 64;

    const std::string image_name = ext.empty() ? "img" : "img." + ext;
    fuzz::write_file(fuzz::scratch_file(image_name),
                     std::string_view(reinterpret_cast<const char*>(data + 1), size - 1));
    std::string json = "{\"color\": \"" + (is_displacement ? std::string("c.ppm") : image_name) +
                       "\", \"displacement\": \"" + (is_displacement ? image_name : std::string("d.pfm")) +
                       "\", \"displacement_range\": " + (wide_range ? "[-1000, 1000]" : "[0, 0.25]") +
                       ", \"origin\": [0, 0, 0], \"a\": [0.01, 0, 0], \"b\": [0, 0.01, 0]";
    if (threshold) json += ", \"discontinuity_threshold\": 0.05";
    json += "}\n";
    const std::string manifest = fuzz::scratch_file("loader.relief.json");
    fuzz::write_file(manifest, json);

    ReliefTexture t;
    if (fuzz::expect_ok_or_io_error(manifest, [&] { t = load_relief(manifest); })) {
        // Accepted: then it is exactly the partner's size, and every displacement is finite and in range.
        const size_t n = size_t(kWidth) * size_t(kHeight);
        bool ok = t.width == kWidth && t.height == kHeight && t.texels.size() == n && t.displacement.size() == n &&
                  (!threshold || t.breaks.size() == n);
        const double lo = wide_range ? -1000 : 0, hi = wide_range ? 1000 : 0.25, slack = 1e-3 * (hi - lo);
        for (float d : t.displacement) ok = ok && std::isfinite(d) && d >= lo - slack && d <= hi + slack;
        if (!ok) {
            std::fprintf(stderr, "FINDING: load_relief returned an inconsistent texture: %s\n", t.to_string().c_str());
            std::abort();
        }
    }
    return 0;
}
