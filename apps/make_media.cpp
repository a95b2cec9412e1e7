// rtm-make-media: writes the procedural relief textures (procedural/procedural_media.h) as NAME.relief.json plus
// NAME_color.png and NAME_disp.png, for the shipped media/ folder and for tests.
//
//   rtm-make-media --out DIR [--size N]
//
// Exit status: 0 success, 1 a runtime failure (one line on stderr naming the file), 2 a usage error.
#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

#include "procedural/procedural_media.h"
#include "formats/relief_manifest.h"
#include "formats/image_io.h"

int main(int argc, char** argv) {
    CLI::App app{"Writes the procedural relief textures (" + rtm::procedural_names_list() +
                 ") as DIR/NAME.relief.json plus colour and displacement images."};
    std::string out;
    int size = 256;
    app.add_option("--out", out, "Output folder (created if missing)")->required();
    app.add_option("--size", size, "Texels per side (8..8192)")->check(CLI::Range(8, 8192));
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
    } catch (const std::exception& e) {
        std::fprintf(stderr, "rtm-make-media: %s\n", e.what());
        return 1;
    }
    return 0;
}
