// NAME.relief.json: parsing, the error contract (one line, starting with the manifest's path, naming the field and
// what was expected vs found), loading with images, and the write_relief -> load_relief round trip.
//
// The corpus of bad manifests is generated at run time into a fresh temporary folder; each entry carries the
// substrings its error message must contain.
#include "formats/relief_manifest.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "common/io_error.h"
#include "common/temp_dir.h"
#include "formats/image_io.h"

namespace rtm {
namespace {

namespace fs = std::filesystem;
using objects_testing::expect_io_error;
using objects_testing::read_file;
using objects_testing::TempDir;
using objects_testing::write_file;

ImageRGBA8 test_color(int w, int h) {
    ImageRGBA8 c(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) c.at(x, r) = {uint8_t(40 * x + 3), uint8_t(50 * r + 7), uint8_t(x * r + 11), 255};
    return c;
}

ImageF test_disp(int w, int h) {
    ImageF d(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) d.at(x, r) = float((x + r * w) % 255) / 254.0f;
    return d;
}

// The valid manifest's fields in order, as raw JSON text; a change replaces, appends or (kDrop) removes one.
const std::string kDrop = "\x01";
std::string manifest(const std::vector<std::pair<std::string, std::string>>& changes = {}) {
    std::vector<std::pair<std::string, std::string>> f = {
        {"color", "\"c.png\""},  {"displacement", "\"d.png\""}, {"displacement_range", "[0.0, 0.25]"},
        {"origin", "[0, 0, 0]"}, {"a", "[0.01, 0, 0]"},         {"b", "[0, 0.01, 0]"}};
    for (const auto& change : changes) {
        const std::string& key = change.first;  // not a structured binding: clang 14 cannot capture one
        const std::string& raw = change.second;
        auto it = std::find_if(f.begin(), f.end(), [&](const auto& kv) { return kv.first == key; });
        if (raw == kDrop) {
            if (it != f.end()) f.erase(it);
        } else if (it != f.end()) {
            it->second = raw;
        } else {
            f.emplace_back(key, raw);
        }
    }
    std::string s = "{";
    for (size_t i = 0; i < f.size(); ++i) s += (i ? ",\n  \"" : "\n  \"") + f[i].first + "\": " + f[i].second;
    return s + "\n}\n";
}

// A PFM (portable float map) file: OpenImageIO reads it, and unlike PNG it can hold NaN and infinity.
std::string pfm(int w, int h, const std::vector<float>& values) {
    std::string s = "Pf\n" + std::to_string(w) + " " + std::to_string(h) + "\n-1.0\n";
    const size_t off = s.size();
    s.resize(off + values.size() * 4);
    std::memcpy(&s[off], values.data(), values.size() * 4);  // little endian (scale -1), rows bottom to top
    return s;
}

struct BadCase {
    std::string label;                      // file stem
    std::string text;                       // manifest contents
    std::vector<std::string> must_contain;  // substrings of the error message
};

std::vector<BadCase> bad_manifest_corpus() {
    std::string deep = "[";
    for (int i = 0; i < 10000; ++i) deep += "[";
    for (int i = 0; i < 10001; ++i) deep += "]";
    return {
        // The file and the JSON itself.
        {"empty", "", {"empty", "expected a JSON object"}},
        {"blank", " \n\t\r\n", {"empty"}},
        {"truncated", "{\"color\": \"c.png\", \"displacement\"", {"truncated JSON", "line 1, column", "byte"}},
        {"truncated_string", "{\"color\": \"c.p", {"truncated JSON", "line 1"}},
        {"malformed", "{\"color\": \"c.png\",, }", {"malformed JSON", "line 1, column 19"}},
        {"trailing_garbage", manifest() + "x", {"malformed JSON", "line 9"}},
        {"nan_literal", manifest({{"a", "[NaN, 0, 0]"}}), {"malformed JSON"}},
        {"bad_utf8", manifest({{"name", "\"\xff\xfe\""}}), {"malformed JSON"}},
        {"top_array", "[1, 2, 3]", {"top level must be a JSON object", "found [1, 2, 3]"}},
        {"top_string", "\"facade\"", {"top level must be a JSON object", "found the string \"facade\""}},
        {"top_number", "42", {"top level must be a JSON object", "found 42"}},
        // Missing required fields.
        {"missing_color", manifest({{"color", kDrop}}), {"required field \"color\" is missing"}},
        {"missing_displacement", manifest({{"displacement", kDrop}}), {"required field \"displacement\" is missing"}},
        {"missing_range", manifest({{"displacement_range", kDrop}}), {"\"displacement_range\" is missing"}},
        {"missing_origin", manifest({{"origin", kDrop}}), {"required field \"origin\" is missing", "3 finite numbers"}},
        {"missing_a", manifest({{"a", kDrop}}), {"required field \"a\" is missing"}},
        {"missing_b", manifest({{"b", kDrop}}), {"required field \"b\" is missing"}},
        // Wrong types.
        {"color_number", manifest({{"color", "3"}}), {"field \"color\"", "non-empty string", "found 3"}},
        {"color_empty",
         manifest({{"color", "\"\""}}),
         {"field \"color\"", "non-empty string", "found the string \"\""}},
        {"color_null", manifest({{"color", "null"}}), {"field \"color\"", "found null"}},
        {"displacement_array",
         manifest({{"displacement", "[\"d.png\"]"}}),
         {"field \"displacement\"", "found [\"d.png\"]"}},
        {"displacement_object",
         manifest({{"displacement", "{\"file\": \"d.png\"}"}}),
         {"field \"displacement\"", "found an object with 1 fields"}},
        {"name_number", manifest({{"name", "5"}}), {"field \"name\" must be a string", "found 5"}},
        {"name_array", manifest({{"name", "[\"x\"]"}}), {"field \"name\" must be a string", "found [\"x\"]"}},
        // Vectors.
        {"origin_two", manifest({{"origin", "[1, 2]"}}), {"field \"origin\"", "3 finite numbers", "found [1, 2]"}},
        {"origin_four", manifest({{"origin", "[1, 2, 3, 4]"}}), {"field \"origin\"", "found [1, 2, 3, 4]"}},
        {"origin_string_elem", manifest({{"origin", "[1, \"2\", 3]"}}), {"field \"origin\"", "found [1, \"2\", 3]"}},
        {"origin_bool_elem", manifest({{"origin", "[1, true, 3]"}}), {"field \"origin\"", "found [1, true, 3]"}},
        {"origin_null_elem", manifest({{"origin", "[1, null, 3]"}}), {"field \"origin\"", "found [1, null, 3]"}},
        {"origin_infinite", manifest({{"origin", "[1e999, 0, 0]"}}), {"field \"origin\"", "finite", "found 1e999"}},
        {"origin_object",
         manifest({{"origin", "{\"x\": 1, \"y\": 2, \"z\": 3}"}}),
         {"field \"origin\"", "found an object with 3 fields"}},
        {"origin_string", manifest({{"origin", "\"0,0,0\""}}), {"field \"origin\"", "found the string \"0,0,0\""}},
        {"origin_empty", manifest({{"origin", "[]"}}), {"field \"origin\"", "found []"}},
        {"a_nested", manifest({{"a", "[[1], [0], [0]]"}}), {"field \"a\"", "found [[...], [...], [...]]"}},
        {"a_deep", manifest({{"a", deep}}), {"field \"a\"", "found [[...]]"}},
        {"a_long", manifest({{"a", "[1,2,3,4,5,6,7,8,9,10]"}}), {"field \"a\"", "found an array of 10 elements"}},
        {"a_negative_infinite", manifest({{"a", "[-1e999, 0, 0]"}}), {"field \"a\"", "finite", "found -1e999"}},
        {"key_with_newline_overflow", manifest({{"odd\\nkey", "1e999"}}), {"field \"odd\\nkey\"", "found 1e999"}},
        {"top_level_overflow", "-1e999", {"the manifest must hold finite numbers", "found -1e999"}},
        {"b_infinite", manifest({{"b", "[0, 1e400, 0]"}}), {"field \"b\"", "finite", "found 1e400"}},
        {"b_bool", manifest({{"b", "false"}}), {"field \"b\"", "found false"}},
        // Geometry.
        {"a_zero", manifest({{"a", "[0, 0, 0]"}}), {"field \"a\" has zero length", "found [0.0, 0.0, 0.0]"}},
        {"b_zero", manifest({{"b", "[0.0, -0.0, 0]"}}), {"field \"b\" has zero length"}},
        {"ab_parallel",
         manifest({{"a", "[0.01, 0, 0]"}, {"b", "[0.02, 0, 0]"}}),
         {"fields \"a\" and \"b\" are parallel", "a = [0.01, 0.0, 0.0]", "b = [0.02, 0.0, 0.0]"}},
        {"ab_antiparallel", manifest({{"a", "[1, 2, 3]"}, {"b", "[-2, -4, -6]"}}), {"\"a\" and \"b\" are parallel"}},
        {"ab_nearly_parallel",
         manifest({{"a", "[1, 0, 0]"}, {"b", "[1, 1e-13, 0]"}}),
         {"\"a\" and \"b\" are parallel"}},
        // Displacement range.
        {"range_one",
         manifest({{"displacement_range", "[0.5]"}}),
         {"field \"displacement_range\"", "2 finite numbers", "found [0.5]"}},
        {"range_three",
         manifest({{"displacement_range", "[0, 1, 2]"}}),
         {"field \"displacement_range\"", "found [0, 1, 2]"}},
        {"range_number", manifest({{"displacement_range", "0.25"}}), {"field \"displacement_range\"", "found 0.25"}},
        {"range_string_elem",
         manifest({{"displacement_range", "[0, \"1\"]"}}),
         {"field \"displacement_range\"", "found [0, \"1\"]"}},
        {"range_inverted",
         manifest({{"displacement_range", "[0.3, 0.1]"}}),
         {"field \"displacement_range\"", "min <= max", "found [0.3, 0.1]"}},
        {"range_infinite",
         manifest({{"displacement_range", "[-1e999, 0]"}}),
         {"field \"displacement_range\"", "finite", "found -1e999"}},
        // Optional discontinuity threshold.
        {"threshold_negative",
         manifest({{"discontinuity_threshold", "-1"}}),
         {"field \"discontinuity_threshold\"", ">= 0", "found -1"}},
        {"threshold_negative_small",
         manifest({{"discontinuity_threshold", "-1e-9"}}),
         {"field \"discontinuity_threshold\"", "found -1e-09"}},
        {"threshold_string",
         manifest({{"discontinuity_threshold", "\"abc\""}}),
         {"field \"discontinuity_threshold\"", "found the string \"abc\""}},
        {"threshold_null",
         manifest({{"discontinuity_threshold", "null"}}),
         {"field \"discontinuity_threshold\"", "found null"}},
        {"threshold_infinite",
         manifest({{"discontinuity_threshold", "1e999"}}),
         {"field \"discontinuity_threshold\"", "finite", "found 1e999"}},
        {"threshold_array",
         manifest({{"discontinuity_threshold", "[0.1]"}}),
         {"field \"discontinuity_threshold\"", "found [0.1]"}},
        // The coordinate limit (docs/DESIGN.md, "Input limits"): refused here, not later by a camera flag.
        {"origin_beyond_limit",
         manifest({{"origin", "[1e300, 0, 0]"}}),
         {"field \"origin\" [1e+300, 0.0, 0.0] has a coordinate beyond +-1e30"}},
        {"origin_just_beyond_limit",
         manifest({{"origin", "[0, -1.5e30, 0]"}}),
         {"field \"origin\" [0.0, -1.5e+30, 0.0] has a coordinate beyond +-1e30"}},
    };
}

class ReliefManifestTest : public ::testing::Test {
protected:
    void SetUp() override {
        write_rgba8(dir.file("c.png"), test_color(4, 3));
        write_gray(dir.file("d.png"), test_disp(4, 3));
    }
    TempDir dir;
};

TEST_F(ReliefManifestTest, ValidManifestParses) {
    const std::string path = dir.file("wall.relief.json");
    write_file(path, manifest());
    const ReliefManifest m = parse_relief_manifest(path);
    EXPECT_EQ(m.path, path);
    EXPECT_EQ(m.name, "wall");  // file stem without ".relief"
    EXPECT_EQ(fs::path(m.color_path), dir.path() / "c.png");
    EXPECT_EQ(fs::path(m.displacement_path), dir.path() / "d.png");
    EXPECT_EQ(m.range_min, 0.0);
    EXPECT_EQ(m.range_max, 0.25);
    EXPECT_EQ(m.geometry.origin, glm::dvec3(0.0));
    EXPECT_EQ(m.geometry.a, glm::dvec3(0.01, 0, 0));
    EXPECT_EQ(m.geometry.b, glm::dvec3(0, 0.01, 0));
    EXPECT_FALSE(m.discontinuity_threshold.has_value());
    const ReliefTexture t = load_relief(path);
    EXPECT_TRUE(t.breaks.empty());  // no threshold, no discontinuity marks
}

TEST_F(ReliefManifestTest, OptionalAndUnknownFields) {
    const std::string path = dir.file("x.relief.json");
    write_file(path, manifest({{"name", "\"brick wall\""},
                               {"discontinuity_threshold", "0"},
                               {"comment", "{\"anything\": [1, 2, {\"deep\": null}]}"},
                               {"version", "7"}}));
    const ReliefManifest m = parse_relief_manifest(path);
    EXPECT_EQ(m.name, "brick wall");
    ASSERT_TRUE(m.discontinuity_threshold.has_value());
    EXPECT_EQ(*m.discontinuity_threshold, 0.0);
}

TEST_F(ReliefManifestTest, EqualRangeAndTinyButIndependentVectorsAreValid) {
    // max == min is legal; the parallel test is relative, so texel steps of 1e-7 are fine.
    const std::string path = dir.file("tiny.relief.json");
    write_file(path, manifest({{"displacement_range", "[0.1, 0.1]"}, {"a", "[1e-7, 0, 0]"}, {"b", "[0, 1e-7, 0]"}}));
    ReliefManifest m;
    const ReliefTexture t = load_relief(path, &m);
    EXPECT_EQ(t.width, 4);
    EXPECT_EQ(t.height, 3);
    for (float d : t.displacement) EXPECT_EQ(d, 0.1f);
}

// A quad (4x3 texels here) whose corners lie beyond the coordinate limit, or whose sides are lost in rounding at
// its origin, is refused by load_relief (the rule needs the image's size), before any camera is made about it. The
// sides |a| * width and |b| * height must each be at least 1e-9 times the origin's largest |coordinate|.
TEST_F(ReliefManifestTest, QuadsBeyondTheLimitOrLostInRoundingAreRefused) {
    struct Case {
        std::string label, text;
        std::vector<std::string> parts;
    };
    const std::vector<Case> cases = {
        // The audit's case: a unit quad at 1e30, where every camera's eye equalled its look-at.
        {"unit_quad_at_1e30",
         manifest({{"origin", "[1e30, 0, 0]"}, {"a", "[0.25, 0, 0]"}, {"b", "[0, 0.5, 0]"}}),
         {"the quad's extent 1.0 is lost in rounding at origin [1e+30, 0.0, 0.0]", "|a| * width (1.0)",
          "|b| * height (1.5)", "1e-9", "1e+21"}},
        // Just past the rule: the shorter side 1 at a coordinate 1.01e9 (1e9 passes, below).
        {"just_lost",
         manifest({{"origin", "[0, 0, -1.01e9]"}, {"a", "[0.25, 0, 0]"}, {"b", "[0, 0.5, 0]"}}),
         {"the quad's extent 1.0 is lost in rounding at origin [0.0, 0.0, -1010000000.0]"}},
        // One side long enough is not enough.
        {"thin_side",
         manifest({{"origin", "[1e12, 0, 0]"}, {"a", "[0, 1e6, 0]"}, {"b", "[0, 0, 1e-4]"}}),
         {"the quad's extent 0.000", "is lost in rounding at origin [1000000000000.0, 0.0, 0.0]",
          "|a| * width (4000000.0)"}},
        {"corner_beyond_limit",
         manifest({{"a", "[1e30, 0, 0]"}, {"b", "[0, 1, 0]"}}),
         {"the quad's corner origin + width * a = [4e+30, 0.0, 0.0] has a coordinate beyond +-1e30",
          "the texture is 4x3"}},
        // Both sides' own corners within the limit, the corner across from the origin beyond it.
        {"far_corner_beyond_limit",
         manifest({{"a", "[1.5e29, 0, 0]"}, {"b", "[2e29, 2e29, 0]"}}),
         {"the quad's corner origin + width * a + height * b = [1.2", "beyond +-1e30"}},
        {"range_beyond_limit",
         manifest({{"displacement_range", "[-1e35, 0]"}}),
         {"field \"displacement_range\" [-1e+35, 0.0] reaches beyond the coordinate limit +-1e30"}},
    };
    for (const Case& c : cases) {
        const std::string path = dir.file(c.label + ".relief.json");
        write_file(path, c.text);
        EXPECT_NO_THROW(parse_relief_manifest(path)) << c.label << ": the manifest alone is well formed";
        expect_io_error([&] { load_relief(path); }, path, c.parts, c.label);
    }
    // At the rule's edge and at the limit itself, loaded.
    const std::vector<std::pair<std::string, std::string>> good = {
        {"at_rule", manifest({{"origin", "[0, 0, -1e9]"}, {"a", "[0.25, 0, 0]"}, {"b", "[0, 0.5, 0]"}})},
        {"at_limit", manifest({{"origin", "[1e30, -1e30, 0]"},
                               {"a", "[0, 2.5e29, 0]"},
                               {"b", "[0, 0, 1e29]"},
                               {"displacement_range", "[-1e30, 1e30]"}})},
    };
    for (const auto& [label, text] : good) {
        const std::string path = dir.file(label + ".relief.json");
        write_file(path, text);
        ReliefTexture t;
        EXPECT_NO_THROW(t = load_relief(path)) << label;
        EXPECT_EQ(t.width, 4) << label;
    }
}

TEST_F(ReliefManifestTest, PathsResolveAgainstTheManifestFolder) {
    fs::create_directories(dir.path() / "sub");
    fs::create_directories(dir.path() / "img");
    write_rgba8(dir.file("img/c2.png"), test_color(4, 3));
    const std::string path = dir.file("sub/m.relief.json");
    write_file(path, manifest({{"color", "\"../img/c2.png\""}, {"displacement", "\"../d.png\""}}));
    const ReliefTexture t = load_relief(path);
    EXPECT_EQ(t.width, 4);
}

TEST_F(ReliefManifestTest, BadManifestCorpus) {
    const std::vector<BadCase> corpus = bad_manifest_corpus();
    for (const BadCase& c : corpus) {
        const std::string path = dir.file(c.label + ".relief.json");
        write_file(path, c.text);
        expect_io_error([&] { parse_relief_manifest(path); }, path, c.must_contain, "parse " + c.label);
        expect_io_error([&] { load_relief(path); }, path, c.must_contain, "load " + c.label);
    }
}

TEST_F(ReliefManifestTest, MissingFileAndDirectory) {
    const std::string missing = dir.file("nope.relief.json");
    expect_io_error([&] { parse_relief_manifest(missing); }, missing, {"cannot open", "No such file"}, "missing");
    const std::string folder = dir.file("folder.relief.json");
    fs::create_directories(folder);
    expect_io_error([&] { load_relief(folder); }, folder, {"is a directory"}, "directory");
}

TEST_F(ReliefManifestTest, ImageErrorsNameTheManifestAndTheImage) {
    struct Case {
        std::string label, text;
        std::vector<std::string> parts;
    };
    write_gray(dir.file("d_small.png"), test_disp(2, 3));
    write_file(dir.file("garbage.png"), "this is not a PNG file at all");
    write_file(dir.file("nan.pfm"), pfm(4, 3, {0, 0, 0, 0, 0, NAN, 0, 0, 0, 0, 0, 0}));
    write_file(dir.file("inf.pfm"), pfm(4, 3, {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, -INFINITY}));
    write_file(dir.file("zero_size.png"), "");
    const std::vector<Case> cases = {
        {"color_missing", manifest({{"color", "\"nope.png\""}}), {"nope.png", "cannot open"}},
        {"displacement_missing", manifest({{"displacement", "\"gone.png\""}}), {"gone.png", "cannot open"}},
        {"color_folder", manifest({{"color", "\".\""}}), {"is a directory"}},
        {"displacement_garbage", manifest({{"displacement", "\"garbage.png\""}}), {"garbage.png"}},
        {"displacement_empty_file", manifest({{"displacement", "\"zero_size.png\""}}), {"zero_size.png", "empty"}},
        {"size_mismatch",
         manifest({{"displacement", "\"d_small.png\""}}),
         {"displacement image d_small.png is 2x3 but color c.png is 4x3"}},
        {"displacement_nan",
         manifest({{"displacement", "\"nan.pfm\""}}),
         {"displacement image nan.pfm", "non-finite", "nan"}},
        {"displacement_inf", manifest({{"displacement", "\"inf.pfm\""}}), {"displacement image inf.pfm", "-inf"}},
        {"range_beyond_float",
         manifest({{"displacement_range", "[-1e300, 1e300]"}}),
         {"\"displacement_range\"", "too large"}},
    };
    for (const Case& c : cases) {
        const std::string path = dir.file(c.label + ".relief.json");
        write_file(path, c.text);
        expect_io_error([&] { load_relief(path); }, path, c.parts, c.label);
    }
}

TEST_F(ReliefManifestTest, RoundTripReproducesSizesGeometryAndQuantizedTexels) {
    constexpr int w = 9, h = 5;
    ImageRGBA8 color = test_color(w, h);
    color.at(2, 1).a = 0;  // empty texels
    color.at(8, 4).a = 0;
    ImageF norm(w, h);
    for (int r = 0; r < h; ++r)
        for (int x = 0; x < w; ++x) norm.at(x, r) = float((x * 31 + r * 17) % 255) / 254.0f;  // exact 8-bit levels
    norm.at(0, 0) = 0.0f;
    norm.at(1, 0) = 1.0f;
    ReliefManifest m;
    m.name = "round trip";
    m.range_min = -0.1;
    m.range_max = 0.3;
    m.geometry.origin = {1.0, -2.5, 3.25};
    m.geometry.a = {0.01, 0.002, 0.0};
    m.geometry.b = {-0.001, 0.012, 0.003};
    m.discontinuity_threshold = 0.05;

    fs::create_directories(dir.path() / "out");
    const std::string path = dir.file("out/rt.relief.json");
    write_relief(path, m, color, norm);
    EXPECT_TRUE(fs::is_regular_file(dir.file("out/rt_color.png")));
    EXPECT_TRUE(fs::is_regular_file(dir.file("out/rt_disp.png")));
    // Nothing else (no temporary files) is left in the folder.
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path() / "out"), fs::directory_iterator{}), 3);
    const std::string text = read_file(path);
    EXPECT_NE(text.find("\"color\": \"rt_color.png\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"displacement\": \"rt_disp.png\""), std::string::npos) << text;

    ReliefManifest back;
    const ReliefTexture t = load_relief(path, &back);
    EXPECT_EQ(back.name, "round trip");
    ASSERT_TRUE(back.discontinuity_threshold.has_value());
    EXPECT_EQ(*back.discontinuity_threshold, 0.05);
    EXPECT_EQ(back.range_min, m.range_min);
    EXPECT_EQ(back.range_max, m.range_max);
    EXPECT_EQ(back.geometry.origin, m.geometry.origin);  // JSON numbers round-trip exactly
    EXPECT_EQ(back.geometry.a, m.geometry.a);
    EXPECT_EQ(back.geometry.b, m.geometry.b);
    ASSERT_EQ(t.width, w);
    ASSERT_EQ(t.height, h);
    EXPECT_EQ(t.geometry.a, m.geometry.a);

    // The same texture built directly from the unquantized data.
    ImageF world(w, h);
    for (size_t k = 0; k < world.pixels.size(); ++k)
        world.pixels[k] = float(m.range_min + double(norm.pixels[k]) * (m.range_max - m.range_min));
    const ReliefTexture direct = make_relief(color, world, m.range_min, m.range_max, m.geometry);
    for (int r = 0; r < h; ++r) {
        for (int x = 0; x < w; ++x) {
            SCOPED_TRACE("texel (" + std::to_string(x) + ", " + std::to_string(r) + ")");
            EXPECT_EQ(t.texel(x, r).q, direct.texel(x, r).q);
            if (!direct.empty_at(x, r)) {
                EXPECT_EQ(t.texel(x, r), direct.texel(x, r));
                // 16-bit storage: within half a 16-bit step of the range.
                EXPECT_NEAR(t.displ(x, r), direct.displ(x, r), 0.5 * 0.4 / 65535 + 1e-7);
            }
        }
    }
    EXPECT_TRUE(t.empty_at(2, 1));
    // The manifest's discontinuity threshold is applied.
    EXPECT_EQ(t.discontinuity_threshold, 0.05);
    EXPECT_EQ(t.breaks.size(), t.texels.size());
    EXPECT_EQ(t.quant.decode(t.texel(1, 0).q), 0.3);   // top level decodes to max exactly
    EXPECT_EQ(t.quant.decode(t.texel(0, 0).q), -0.1);  // bottom level to min

    // Writing again over existing files works and gives the same manifest.
    write_relief(path, m, color, norm);
    EXPECT_EQ(read_file(path), text);
}

TEST_F(ReliefManifestTest, WriteReliefRefusesWhatCannotBeLoaded) {
    const ImageRGBA8 color = test_color(4, 3);
    const ImageF disp = test_disp(4, 3);
    ReliefManifest good;
    good.range_min = 0.0;
    good.range_max = 0.1;
    good.geometry.a = {0.01, 0, 0};
    good.geometry.b = {0, 0.01, 0};
    const std::string path = dir.file("w.relief.json");

    expect_io_error([&] { write_relief(path, good, color, test_disp(3, 3)); }, path, {"is 3x3 but color is 4x3"},
                    "size");
    ImageF nan_disp = disp;
    nan_disp.at(1, 2) = NAN;
    expect_io_error([&] { write_relief(path, good, color, nan_disp); }, path, {"texel (1, 2)", "nan"}, "nan");
    ImageF big = disp;
    big.at(0, 0) = 1.5f;
    expect_io_error([&] { write_relief(path, good, color, big); }, path, {"texel (0, 0)", "1.5", "0..1"}, "range");
    ReliefManifest parallel = good;
    parallel.geometry.b = {0.02, 0, 0};
    expect_io_error([&] { write_relief(path, parallel, color, disp); }, path, {"parallel"}, "parallel");
    ReliefManifest inverted = good;
    inverted.range_min = 1.0;
    expect_io_error([&] { write_relief(path, inverted, color, disp); }, path, {"displacement_range", "[1.0, 0.1]"},
                    "inverted");
    ReliefManifest far = good;
    far.geometry.origin = {0, 0, 2e30};
    expect_io_error([&] { write_relief(path, far, color, disp); }, path,
                    {"field \"origin\" [0.0, 0.0, 2e+30] has a coordinate beyond +-1e30"}, "origin");
    ReliefManifest negative = good;
    negative.discontinuity_threshold = -0.5;
    expect_io_error([&] { write_relief(path, negative, color, disp); }, path, {"discontinuity_threshold", "-0.5"},
                    "threshold");
    EXPECT_FALSE(fs::exists(path)) << "a refused write left a manifest behind";
    EXPECT_EQ(std::distance(fs::directory_iterator(dir.path()), fs::directory_iterator{}), 2);  // c.png, d.png

    // The folder is created when missing; the name defaults to the file stem.
    const std::string nested = dir.file("new/folder/n.relief.json");
    write_relief(nested, good, color, disp);
    ReliefManifest back;
    load_relief(nested, &back);
    EXPECT_EQ(back.name, "n");
    EXPECT_TRUE(fs::is_regular_file(dir.file("new/folder/n_color.png")));
}

}  // namespace
}  // namespace rtm
