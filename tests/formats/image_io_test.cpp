// Image files: exact round trips, channel handling, and every way a file can be wrong.
#include "formats/image_io.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <random>
#include <string>
#include <vector>

#include "common/io_error.h"
#include "common/scoped_env.h"
#include "texmap/test_util.h"

namespace rtm {
namespace {

using test::TempDir;

ImageRGBA8 random_rgba(int w, int h, uint32_t seed) {
    std::mt19937 rng(seed);
    ImageRGBA8 img(w, h);
    for (Rgba8& p : img.pixels) {
        uint32_t v = rng();
        p = {uint8_t(v), uint8_t(v >> 8), uint8_t(v >> 16), uint8_t(v >> 24)};
    }
    return img;
}

// One fragment, labelled by the file (tests/common/io_error.h).
void expect_io_error(const std::function<void()>& fn, const std::string& path, const std::string& fragment) {
    objects_testing::expect_io_error(fn, path, {fragment}, path);
}

TEST(ImageIo, PngRoundTripIsBitExact) {
    TempDir dir;
    // Odd sizes, every byte value, and alpha 0 texels with non-zero colour (alpha must stay unassociated).
    ImageRGBA8 img = random_rgba(37, 23, 1234);
    img.at(0, 0) = {200, 100, 50, 0};
    img.at(1, 0) = {1, 2, 3, 255};
    const std::string path = dir.file("round.png");
    write_rgba8(path, img);
    ImageRGBA8 back = read_rgba8(path);
    EXPECT_EQ(back.width, 37);
    EXPECT_EQ(back.height, 23);
    EXPECT_EQ(test::compare_images(img, back, 0), "");
    EXPECT_EQ(back.at(0, 0), (Rgba8{200, 100, 50, 0}));
}

TEST(ImageIo, RowZeroIsTheTopOfTheFile) {
    TempDir dir;
    // 1x2 RGB PNG written by hand: top row red, bottom row blue.
    const std::string path = dir.file("top.png");
    test::write_bytes(path, test::encode_png(1, 2, 3, 8, {255, 0, 0, 0, 0, 255}));
    ImageRGBA8 img = read_rgba8(path);
    ASSERT_EQ(img.height, 2);
    EXPECT_EQ(img.at(0, 0), (Rgba8{255, 0, 0, 255}));
    EXPECT_EQ(img.at(0, 1), (Rgba8{0, 0, 255, 255}));
}

TEST(ImageIo, RgbGetsOpaqueAlphaAndRgbaKeepsIt) {
    TempDir dir;
    const std::string rgb = dir.file("rgb.png"), rgba = dir.file("rgba.png");
    test::write_bytes(rgb, test::encode_png(2, 1, 3, 8, {10, 20, 30, 40, 50, 60}));
    test::write_bytes(rgba, test::encode_png(2, 1, 4, 8, {10, 20, 30, 0, 40, 50, 60, 128}));
    ImageRGBA8 a = read_rgba8(rgb);
    EXPECT_EQ(a.at(0, 0), (Rgba8{10, 20, 30, 255}));
    EXPECT_EQ(a.at(1, 0), (Rgba8{40, 50, 60, 255}));
    ImageRGBA8 b = read_rgba8(rgba);
    EXPECT_EQ(b.at(0, 0), (Rgba8{10, 20, 30, 0}));  // colour kept under alpha 0: not premultiplied
    EXPECT_EQ(b.at(1, 0), (Rgba8{40, 50, 60, 128}));
}

TEST(ImageIo, GreyIsReplicatedAndGreyAlphaKeepsAlpha) {
    TempDir dir;
    const std::string g = dir.file("g.png"), ga = dir.file("ga.png");
    test::write_bytes(g, test::encode_png(2, 1, 1, 8, {7, 250}));
    test::write_bytes(ga, test::encode_png(1, 1, 2, 8, {99, 0}));
    ImageRGBA8 a = read_rgba8(g);
    EXPECT_EQ(a.at(0, 0), (Rgba8{7, 7, 7, 255}));
    EXPECT_EQ(a.at(1, 0), (Rgba8{250, 250, 250, 255}));
    EXPECT_EQ(read_rgba8(ga).at(0, 0), (Rgba8{99, 99, 99, 0}));
}

TEST(ImageIo, ReadsPortablePixmap) {
    TempDir dir;
    const std::string path = dir.file("p.ppm");
    test::write_bytes(path, std::string("P6\n2 1\n255\n") + std::string("\x01\x02\x03\xfd\xfe\xff", 6));
    ImageRGBA8 img = read_rgba8(path);
    EXPECT_EQ(img.at(0, 0), (Rgba8{1, 2, 3, 255}));
    EXPECT_EQ(img.at(1, 0), (Rgba8{253, 254, 255, 255}));
}

TEST(ImageIo, ReadGrayNormalizes8And16Bit) {
    TempDir dir;
    const std::string g8 = dir.file("g8.png"), g16 = dir.file("g16.png"), rgb = dir.file("rgb.png");
    test::write_bytes(g8, test::encode_png(3, 1, 1, 8, {0, 51, 255}));
    test::write_bytes(g16, test::encode_png(3, 1, 1, 16, {0, 1000, 65535}));
    test::write_bytes(rgb, test::encode_png(1, 1, 3, 8, {102, 0, 255}));
    ImageF a = read_gray(g8);
    EXPECT_FLOAT_EQ(a.at(0, 0), 0.0f);
    EXPECT_NEAR(a.at(1, 0), 51.0 / 255.0, 1e-6);
    EXPECT_FLOAT_EQ(a.at(2, 0), 1.0f);
    ImageF b = read_gray(g16);
    EXPECT_NEAR(b.at(1, 0), 1000.0 / 65535.0, 1e-7);  // 16 bits survive: not squeezed through 8 bits
    EXPECT_FLOAT_EQ(b.at(2, 0), 1.0f);
    EXPECT_NEAR(read_gray(rgb).at(0, 0), 102.0 / 255.0, 1e-6);  // the first channel
}

TEST(ImageIo, GrayRoundTripKeeps16Bits) {
    TempDir dir;
    ImageF img(5, 3);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i * 4099 % 65536) / 65535.0f;
    img.at(0, 0) = -1.0f;  // clamped to 0
    img.at(1, 0) = 2.0f;   // clamped to 1
    img.at(2, 0) = NAN;    // written as 0
    const std::string path = dir.file("disp.png");
    write_gray(path, img);
    ImageF back = read_gray(path);
    ASSERT_EQ(back.width, 5);
    ASSERT_EQ(back.height, 3);
    EXPECT_EQ(back.at(0, 0), 0.0f);
    EXPECT_EQ(back.at(1, 0), 1.0f);
    EXPECT_EQ(back.at(2, 0), 0.0f);
    for (size_t i = 3; i < img.pixels.size(); ++i)
        EXPECT_NEAR(back.pixels[i], img.pixels[i], 0.5 / 65535.0 + 1e-7) << "pixel " << i;
    EXPECT_EQ(dir.list(), std::vector<std::string>{"disp.png"});
}

TEST(ImageIo, MissingFile) {
    TempDir dir;
    const std::string path = dir.file("nothing_here.png");
    expect_io_error([&] { read_rgba8(path); }, path, "cannot open: No such file");
    expect_io_error([&] { read_gray(path); }, path, "cannot open: No such file");
}

TEST(ImageIo, Directory) {
    TempDir dir;
    std::filesystem::create_directory(dir.file("folder.png"));
    expect_io_error([&] { read_rgba8(dir.file("folder.png")); }, dir.file("folder.png"), "is a directory");
}

TEST(ImageIo, EmptyFile) {
    TempDir dir;
    const std::string path = dir.file("empty.png");
    test::write_bytes(path, "");
    expect_io_error([&] { read_rgba8(path); }, path, "empty");
}

TEST(ImageIo, TextFileNamedPng) {
    TempDir dir;
    const std::string path = dir.file("notes.png");
    test::write_bytes(path, "These are notes, not an image.\nSecond line.\n");
    expect_io_error([&] { read_rgba8(path); }, path, "cannot read");
}

TEST(ImageIo, TruncatedPng) {
    TempDir dir;
    std::vector<uint16_t> samples(64 * 64 * 4);
    for (size_t i = 0; i < samples.size(); ++i) samples[i] = uint16_t(i * 31 % 256);
    std::string png = test::encode_png(64, 64, 4, 8, samples);
    // Cut in the middle of the pixel data: the header is intact, so the reader only notices when reading pixels.
    const std::string path = dir.file("cut.png");
    test::write_bytes(path, png.substr(0, png.size() / 2));
    // The failure is reported once, in the exception: libpng's own "libpng error: ..." line must not reach stderr
    // (the command line promises one line on stderr per failure and opts in to the quiet stderr).
    ASSERT_FALSE(quiet_image_library_stderr());  // off unless a program asks
    set_quiet_image_library_stderr(true);
    ::testing::internal::CaptureStderr();
    expect_io_error([&] { read_rgba8(path); }, path, "cannot read pixels");
    expect_io_error([&] { read_gray(path); }, path, "cannot read pixels");
    EXPECT_EQ(::testing::internal::GetCapturedStderr(), "");
    set_quiet_image_library_stderr(false);
}

TEST(ImageIo, ZeroSizedImage) {
    TempDir dir;
    const std::string path = dir.file("zero.ppm");
    test::write_bytes(path, "P6\n0 0\n255\n");
    expect_io_error([&] { read_rgba8(path); }, path, "");
}

// A header that claims a huge image must be rejected from the header alone. Checked in a child process whose
// address space is capped at its current size + 1 GiB: reading 100000 x 100000 RGBA (40 GB) would have to allocate
// and fail with std::bad_alloc (exit code 3, or the reader's own catch of it: exit code 2, another message) instead of
// the expected IoError naming the file and what is wrong (exit code 0).
void expect_rejected_without_allocating(
    const std::string& path,
    const std::string& want = "image claims 100000x100000 pixels, more than the limit of 16384x16384") {
    EXPECT_EXIT(
        {
            long pages = 0;
            if (FILE* f = std::fopen("/proc/self/statm", "r")) {
                if (std::fscanf(f, "%ld", &pages) != 1) pages = 0;
                std::fclose(f);
            }
            rlimit lim{};
            lim.rlim_cur = lim.rlim_max = rlim_t(pages) * rlim_t(sysconf(_SC_PAGESIZE)) + (rlim_t(1) << 30);
            setrlimit(RLIMIT_AS, &lim);
            try {
                read_rgba8(path);
                std::_Exit(1);
            } catch (const IoError& e) {
                std::string msg = e.what();
                bool ok = msg.rfind(path + ": ", 0) == 0 && msg.find(want) != std::string::npos;
                if (!ok) std::fprintf(stderr, "unexpected message: %s\n", msg.c_str());
                std::_Exit(ok ? 0 : 2);
            } catch (const std::bad_alloc&) {
                std::_Exit(3);
            } catch (...) {
                std::_Exit(4);
            }
        },
        ::testing::ExitedWithCode(0), "");
}

TEST(ImageIoDeathTest, HugePpmHeaderIsRejectedBeforeAllocating) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TempDir dir;
    const std::string path = dir.file("huge.ppm");
    test::write_bytes(path, "P6\n100000 100000\n255\n");
    expect_rejected_without_allocating(path);
}

TEST(ImageIoDeathTest, HugePngHeaderIsRejectedBeforeAllocating) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TempDir dir;
    const std::string path = dir.file("huge.png");
    test::write_bytes(path, test::png_claiming_size(100000, 100000));
    expect_rejected_without_allocating(path);
}

// Headers whose fields OpenImageIO 2.4's readers allocate and clear by at open, before rtm sees the image's size
// (formats/image_checks.cpp; each found by fuzz/fuzz_relief_loader): refused before the reader opens the file.
TEST(ImageIoDeathTest, SgiRowTablesAreCheckedBeforeAllocating) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TempDir dir;
    const std::string path = dir.file("tables.sgi");
    // Run-length encoded (storage 1), 1 x 16384 pixels of 16384 channels: two row tables of 1 GiB each.
    std::string sgi = {'\x01', '\xda', '\x01', '\x01', '\x00', '\x03', '\x00', '\x01', '\x40', '\x00', '\x40', '\x00'};
    sgi.resize(576, '\0');
    test::write_bytes(path, sgi);
    expect_rejected_without_allocating(path,
                                       "SGI run-length tables for \"16384 rows x 16384 channels\" at byte 512"
                                       " claims 2147483648 bytes, more than the 64 left in the file");
}

TEST(ImageIoDeathTest, GifScreenIsCheckedBeforeAllocating) {
    GTEST_FLAG_SET(death_test_style, "threadsafe");
    TempDir dir;
    // A 19789 x 19789 logical screen (a 1.5 GB canvas), behind "GIF89a" and behind a version giflib does not check.
    for (const char* version : {"89a", "a89"}) {
        const std::string path = dir.file(std::string("screen_") + version + ".gif");
        test::write_bytes(path, std::string("GIF") + version + std::string("\x4d\x4d\x4d\x4d\xf0\0\0", 7) +
                                    std::string(6, '\0') + ";");
        expect_rejected_without_allocating(path, "image claims 19789x19789 pixels, more than the limit of 16384x16384");
    }
}

// A run-length encoded SGI file (one 8-bit channel, 6 x 4, literal runs) reads; one whose length table puts a row
// past the end of the file, whose header claims 0 bytes per channel or no channel, or with a row of more values than
// the image is wide, is refused before OpenImageIO reads it (its reader allocated what a length claimed, read through
// a null pointer, and aborts the program on an assertion).
TEST(ImageIo, SgiRunLengthRowsMustLieInTheFile) {
    TempDir dir;
    auto be = [](std::string& s, uint32_t v, int bytes) {
        for (int i = bytes - 1; i >= 0; --i) s += char((v >> (8 * i)) & 0xff);
    };
    auto sgi = [&](uint32_t bad_length, char bpc, bool overlong = false) {
        std::string s = {'\x01', '\xda', '\x01', bpc};
        be(s, 2, 2), be(s, 6, 2), be(s, 4, 2), be(s, 1, 2);
        s.resize(512, '\0');
        std::string rows;
        std::vector<uint32_t> starts, lengths;
        for (int y = 0; y < 4; ++y) {
            starts.push_back(uint32_t(512 + 8 * 4 + rows.size()));
            const int count = y == 1 && overlong ? 127 : 6;  // 127 values for a row of 6: the decoder overruns
            rows += char(0x80 | count);
            for (int x = 0; x < count; ++x) rows += char(10 * y + x);
            rows += '\0';
            lengths.push_back(y == 2 && bad_length ? bad_length : uint32_t(count + 2));
        }
        for (uint32_t v : starts) be(s, v, 4);
        for (uint32_t v : lengths) be(s, v, 4);
        return s + rows;
    };
    const std::string path = dir.file("rle.sgi");
    test::write_bytes(path, sgi(0, 1));
    const ImageRGBA8 img = read_rgba8(path);
    ASSERT_EQ(img.width, 6);
    ASSERT_EQ(img.height, 4);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 6; ++x) {
            const uint8_t v = uint8_t(10 * (3 - y) + x);  // SGI's rows run bottom to top
            EXPECT_EQ(img.at(x, y), (Rgba8{v, v, v, 255})) << x << "," << y;
        }
    auto refused = [&](const std::string& bytes, const std::string& want) {
        test::write_bytes(path, bytes);
        try {
            read_rgba8(path);
            ADD_FAILURE() << "read " << want;
        } catch (const IoError& e) {
            EXPECT_EQ(std::string(e.what()), path + ": cannot read as an image: SGI " + want + " (corrupt)");
        }
    };
    refused(sgi(0x99e1cc62u, 1),
            "run-length row 2 of channel 0 claims 2581711970 bytes from byte 560, past the end of "
            "the 576-byte file");
    refused(sgi(0, 0), "header claims 0 bytes per channel, expected 1 or 2");
    refused(sgi(0, 1, true), "run-length row 1 of channel 0 (byte 552) has 127 values where 6 of its 6 remain");
    std::string no_channels = {'\x01', '\xda', '\x01', '\x01', '\x00', '\x02',
                               '\x00', '\x06', '\x00', '\xff', '\x00', '\x00'};
    no_channels.resize(576, '\0');
    refused(no_channels, "run-length file claims 255 rows x 0 channels");
}

// An IPTC block claiming more bytes than its JPEG APP13 segment holds: OpenImageIO's decoder would read past the
// segment (AddressSanitizer's heap-buffer-overflow in the sanitizer suite); a legitimate block still reads.
TEST(ImageIo, JpegIptcBlockMustFitItsSegment) {
    TempDir dir;
    auto jpeg_with_app13 = [](const std::string& payload) {
        const size_t n = payload.size() + 2;
        return std::string("\xff\xd8\xff\xed", 4) + char(n >> 8) + char(n & 0xff) + payload + "\xff\xd9";
    };
    const std::string header = std::string(
        "Photoshop 3.0\0"
        "8BIM\x04\x04\0\0\0\0",
        24);
    const std::string path = dir.file("iptc.jpg");
    test::write_bytes(path, jpeg_with_app13(header + std::string("\0\x71", 2) + std::string(20, '\x1c')));
    try {
        read_rgba8(path);
        FAIL() << "read an IPTC block claiming 113 of 20 bytes";
    } catch (const IoError& e) {
        EXPECT_EQ(std::string(e.what()), path +
                                             ": cannot read as an image: JPEG APP13 segment at byte 2 has an IPTC "
                                             "block claiming 113 bytes, more than the 20 left in the segment "
                                             "(corrupt)");
    }
    // One cut inside the "Photoshop 3.0" signature: strcmp would read past it.
    test::write_bytes(path, jpeg_with_app13("Photo"));
    try {
        read_rgba8(path);
        FAIL() << "read an APP13 segment cut inside its signature";
    } catch (const IoError& e) {
        EXPECT_NE(std::string(e.what()).find("JPEG APP13 segment at byte 2 ends inside its \"Photoshop 3.0\" signature"
                                             " (5 bytes)"),
                  std::string::npos)
            << e.what();
    }
}

TEST(ImageIo, LimitIsOnPixelsNotOnOneSide) {
    TempDir dir;
    // 20000 x 1 is wide but small: accepted (only the header check matters here, the file has the data).
    const std::string path = dir.file("wide.pgm");
    test::write_bytes(path, "P5\n20000 1\n255\n" + std::string(20000, '\x10'));
    ImageRGBA8 img = read_rgba8(path);
    EXPECT_EQ(img.width, 20000);
    EXPECT_EQ(img.at(19999, 0), (Rgba8{16, 16, 16, 255}));
}

TEST(ImageIo, WriteReplacesAnExistingFileAndLeavesNoTemporary) {
    TempDir dir;
    const std::string path = dir.file("out.png");
    write_rgba8(path, ImageRGBA8(3, 3, Rgba8{1, 2, 3, 255}));
    write_rgba8(path, ImageRGBA8(2, 2, Rgba8{9, 8, 7, 255}));
    ImageRGBA8 back = read_rgba8(path);
    EXPECT_EQ(back.width, 2);
    EXPECT_EQ(back.at(1, 1), (Rgba8{9, 8, 7, 255}));
    EXPECT_EQ(dir.list(), std::vector<std::string>{"out.png"});
}

TEST(ImageIo, WriteErrorsNameThePathAndLeaveNothing) {
    TempDir dir;
    ImageRGBA8 img(2, 2, Rgba8{1, 2, 3, 4});
    const std::string missing_folder = dir.file("no/such/folder/out.png");
    expect_io_error([&] { write_rgba8(missing_folder, img); }, missing_folder, "does not exist");

    std::filesystem::create_directory(dir.file("taken.png"));
    expect_io_error([&] { write_rgba8(dir.file("taken.png"), img); }, dir.file("taken.png"), "is a directory");

    const std::string unknown = dir.file("out.unknownformat");
    expect_io_error([&] { write_rgba8(unknown, img); }, unknown, "cannot write");

    const std::string empty = dir.file("empty.png");
    expect_io_error([&] { write_rgba8(empty, ImageRGBA8()); }, empty, "empty image");
    expect_io_error([&] { write_gray(empty, ImageF()); }, empty, "empty image");

    EXPECT_EQ(dir.list(), std::vector<std::string>{"taken.png"});  // no partial or temporary files
}

TEST(ImageIo, WriteFailureKeepsThePreviousFile) {
    TempDir dir;
    const std::string path = dir.file("keep.png");
    write_rgba8(path, ImageRGBA8(2, 2, Rgba8{5, 6, 7, 255}));
    const std::string before = test::read_bytes(path);
    ImageRGBA8 broken(4, 4);
    broken.pixels.resize(3);  // inconsistent: must be refused before anything is written
    expect_io_error([&] { write_rgba8(path, broken); }, path, "holds 3 pixels");
    EXPECT_EQ(test::read_bytes(path), before);
    EXPECT_EQ(dir.list(), std::vector<std::string>{"keep.png"});
}

TEST(ImageIo, FormatWithoutAlphaDropsIt) {
    TempDir dir;
    const std::string path = dir.file("out.ppm");
    write_rgba8(path, ImageRGBA8(2, 1, Rgba8{10, 20, 30, 0}));
    ImageRGBA8 back = read_rgba8(path);
    EXPECT_EQ(back.at(1, 0), (Rgba8{10, 20, 30, 255}));
}

using test::ScopedEnv;

// `bytes` with the big-endian number `value` of `width` bytes written at `at`.
std::string patched(std::string bytes, size_t at, uint32_t value, int width) {
    for (int i = 0; i < width; ++i) bytes.at(at + size_t(i)) = char(value >> (8 * (width - 1 - i)));
    return bytes;
}

// Files on which OpenImageIO 2.4 itself crashes or loops without end (found by changing images it writes at random,
// then reduced to one field of an image written here): read in a child process (formats/image_io.cpp), each is one
// line naming the file and saying what happened, and this process goes on.
TEST(ImageIo, ReaderCrashesAndEndlessLoopsEndTheChildOnly) {
    TempDir dir;
    const ImageRGBA8 img = random_rgba(16, 12, 77);
    // A Maya IFF file whose first tile's chunk (the "RGBA" after "TBMP") claims 8 bytes, its coordinates alone: the
    // reader takes the tile as compressed and decodes it from the empty buffer's null pointer.
    const std::string iff = dir.file("empty_tile.iff");
    write_rgba8(iff, img);
    EXPECT_EQ(read_rgba8(iff), img);  // as written, it reads
    std::string bytes = test::read_bytes(iff);
    const size_t tbmp = bytes.find("TBMPRGBA");
    ASSERT_NE(tbmp, std::string::npos);
    test::write_bytes(iff, patched(bytes, tbmp + 8, 8, 4));
#if defined(__SANITIZE_ADDRESS__)
    // AddressSanitizer reports the read through a null pointer and ends the child itself (exit status 1, or SIGABRT
    // with abort_on_error).
    expect_io_error([&] { read_rgba8(iff); }, iff, "the image reader (OpenImageIO) ");
#else
    expect_io_error([&] { read_rgba8(iff); }, iff,
                    "cannot read as an image: the image reader (OpenImageIO) crashed on it (signal 11, ");
#endif
    // A Wavefront RLA file whose matte channel claims 0 bits: the reader's bit-depth conversion loops without end.
    const std::string rla = dir.file("no_matte_bits.rla");
    write_rgba8(rla, img);
    EXPECT_EQ(read_rgba8(rla), img);
    bytes = test::read_bytes(rla);
    ASSERT_GE(bytes.size(), 740u);                              // the header
    ASSERT_EQ(bytes.substr(662, 2), std::string("\0\x08", 2));  // NumOfMatteBits, big-endian
    test::write_bytes(rla, patched(bytes, 662, 0, 2));
    {
        const ScopedEnv env{{"RTM_IMAGE_READER_SECONDS", "1"}};
        expect_io_error([&] { read_rgba8(rla); }, rla,
                        "the image reader (OpenImageIO) was stopped after the 1 s of processor time it may use for a "
                        "file of " +
                            std::to_string(bytes.size()) + " bytes");
        expect_io_error([&] { read_gray(rla); }, rla, "was stopped after the 1 s of processor time");
    }
    // The limits' variables must be whole numbers in range; the message names the variable and the value.
    {
        const ScopedEnv env{{"RTM_IMAGE_READER_SECONDS", "0"}};
        expect_io_error([&] { read_rgba8(rla); }, rla,
                        "RTM_IMAGE_READER_SECONDS \"0\" is not a whole number from 1 to");
    }
    {
        const ScopedEnv env{{"RTM_IMAGE_READER_MB", "lots"}};
        expect_io_error([&] { read_rgba8(rla); }, rla, "RTM_IMAGE_READER_MB \"lots\" is not a whole number from 1 to");
    }
    // And this process still reads and writes images.
    const std::string tif = dir.file("after.tif");
    write_rgba8(tif, img);
    EXPECT_EQ(read_rgba8(tif), img);
}

// OpenEXR compresses and decompresses with a pool of threads unless told not to; a child forked after this process
// wrote an OpenEXR file would have that pool without its threads and wait for them forever. The image module keeps
// the pool from starting (image_io_oiio.cpp): a large file (many chunks, which OpenEXR hands to its pool) written
// here reads back in the child.
TEST(ImageIo, ReadsBackAfterWritingOpenExr) {
    TempDir dir;
    const std::string path = dir.file("many_chunks.exr");
    ImageF img(512, 384);
    for (size_t i = 0; i < img.pixels.size(); ++i) img.pixels[i] = float(i % 65536) / 65535.0f;
    write_gray(path, img);
    const ScopedEnv env{{"RTM_IMAGE_READER_SECONDS", "5"}};  // a child that waits is stopped after 12 s
    const ImageF back = read_gray(path);
    ASSERT_EQ(back.width, 512);
    ASSERT_EQ(back.height, 384);
    for (size_t i = 0; i < img.pixels.size(); i += 997)
        EXPECT_NEAR(back.pixels[i], img.pixels[i], 1.0f / 2048);  // stored as half: 11 bits
}

}  // namespace
}  // namespace rtm
