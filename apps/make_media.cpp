// rtm-make-media: writes the procedural relief textures (procedural/procedural_media.h) as NAME.relief.json plus
// NAME_color.png and NAME_disp.png, and the synthetic six-face objects (procedural/synthetic_object.h) as
// NAME.object.json plus twelve images each, the relief town and the registered room (procedural/town.h,
// procedural/room.h), for the shipped media/ folder and for tests.
//
//   rtm-make-media --out DIR [--size N] [--object-size N]
//
// Exit status: 0 success, 1 a runtime failure (one line on stderr naming the file), 2 a usage error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "procedural/procedural_media.h"
#include "formats/object_manifest.h"
#include "procedural/town.h"
#include "procedural/room.h"
#include "texmap/gl_context.h"
#include "formats/relief_manifest.h"
#include "procedural/synthetic_object.h"
#include "formats/image_io.h"

int main(int argc, char** argv) {
    CLI::App app{"Writes the procedural relief textures (" + rtm::procedural_names_list() +
                 ") as DIR/NAME.relief.json plus colour and displacement images, the six-face objects "
                 "DIR/NAME.object.json, the relief town DIR/town.scene.json and the registered room "
                 "DIR/room.scene.json (with its mesh DIR/room.ply)."};
    std::string out;
    int size = 256, object_size = 64;
    app.add_option("--out", out, "Output folder (created if missing)")->required();
    app.add_option("--size", size, "Texels per side (8..8192)")->check(CLI::Range(8, 8192));
    app.add_option("--object-size", object_size, "Texels per side of each object face (8..4096)")
        ->check(CLI::Range(8, 4096));
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        const int rc = app.exit(e);
        return rc == 0 ? 0 : 2;
    }

    try {
        std::error_code ec;
        std::filesystem::create_directories(out, ec);
        if (ec) throw rtm::IoError(out + ": cannot create folder: " + ec.message());
        for (const std::string& name : rtm::procedural_names()) {
            const rtm::ProceduralRelief p = rtm::make_procedural(name, size);
            rtm::ReliefManifest m;
            m.name = p.name;
            m.range_min = p.range_min;
            m.range_max = p.range_max;
            m.geometry = p.geometry;
            const std::string path = (std::filesystem::path(out) / (name + ".relief.json")).string();
            rtm::write_relief(path, m, p.color, p.displacement);
            std::printf("wrote %s (%dx%d)\n", path.c_str(), p.color.width, p.color.height);
        }
        for (const rtm::SyntheticShape shape :
             {rtm::SyntheticShape::sphere, rtm::SyntheticShape::cross_box, rtm::SyntheticShape::rounded_cube}) {
            const std::string name = rtm::to_string(shape);
            const auto faces = rtm::synthetic_faces(shape, object_size);
            std::array<rtm::ObjectFaceImages, rtm::kFaceCount> images;
            for (int f = 0; f < rtm::kFaceCount; ++f) {
                const double depth = rtm::kSyntheticBox.extent()[rtm::face_axis(f)];
                rtm::ObjectFaceImages& fi = images[size_t(f)];
                fi.color = faces[size_t(f)].color;
                fi.displacement_normalized = faces[size_t(f)].displacement;
                for (float& v : fi.displacement_normalized.pixels) v = float((v + depth) / depth);
                fi.range_min = -depth;
                fi.range_max = 0.0;
                fi.discontinuity = rtm::synthetic_discontinuity(object_size);
            }
            const std::string path = (std::filesystem::path(out) / (name + ".object.json")).string();
            rtm::write_object_manifest(path, name, rtm::kSyntheticBox, images);
            std::printf("wrote %s (6 faces of %dx%d)\n", path.c_str(), object_size, object_size);
        }
        // The relief town (procedural/town.h): seven relief quads a house, sharing seven textures.
        rtm::TownOptions town;
        town.texels = size;
        std::printf("wrote %s\n", rtm::write_town(out, town).c_str());
        // The registered room (procedural/room.h): a generated mesh baked onto four wall planes (needs GL).
        auto ctx = rtm::GlContext::create_offscreen(64, 64);
        std::printf("wrote %s\n", rtm::write_room(out).c_str());
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtm-make-media: %s\n", e.what());
        return 1;
    }
    return 0;
}
