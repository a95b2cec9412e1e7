// load_mesh: geometry, node transforms, materials, textures and what it refuses (mesh/triangle_mesh.h).
#include <gtest/gtest.h>

#include <cstdlib>

#include <sys/stat.h>
#include <initializer_list>
#include <string>
#include <utility>
#include <vector>

#include "common/scoped_env.h"
#include "common/temp_dir.h"
#include "formats/image_io.h"
#include "mesh/header_guard.h"
#include "mesh/mesh_test_util.h"
#include "mesh/triangle_mesh.h"

namespace rtm {
namespace {

using objects_testing::TempDir;
using objects_testing::write_file;

TEST(MeshLoader, BumpObjGeometryAndMaterialColours) {
    TempDir dir;
    const TriangleMesh m = load_mesh(mesh_testing::write_bump_obj(dir.path().string()));
    EXPECT_EQ(m.triangle_count(), 4u) << m.to_string();
    EXPECT_EQ(m.lo, glm::dvec3(0, 0, 0.25));
    EXPECT_EQ(m.hi, glm::dvec3(1, 1, 0.75));
    EXPECT_TRUE(m.warnings.empty());
    ASSERT_EQ(m.parts.size(), 2u);
    bool floor = false, bump = false;
    for (const MeshPart& p : m.parts) {
        const glm::vec4 c = m.materials[size_t(p.material)].base_color;
        floor = floor || c == glm::vec4(0.2f, 0.4f, 0.6f, 1.0f);
        bump = bump || c == glm::vec4(1.0f, 0.8f, 0.0f, 1.0f);
        EXPECT_FALSE(p.use_texture);
    }
    EXPECT_TRUE(floor && bump);
}

TEST(MeshLoader, NodeTransformsAreApplied) {
    // A Collada node translating its triangle by (10, 20, 30): the bounds move with it.
    TempDir dir;
    const std::string path = dir.file("moved.dae");
    write_file(path, R"(<?xml version="1.0"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
<asset><up_axis>Y_UP</up_axis></asset>
<library_geometries><geometry id="g"><mesh>
<source id="p"><float_array id="pa" count="9">0 0 0 1 0 0 0 1 0</float_array>
<technique_common><accessor source="#pa" count="3" stride="3"><param name="X" type="float"/>
<param name="Y" type="float"/><param name="Z" type="float"/></accessor></technique_common></source>
<vertices id="v"><input semantic="POSITION" source="#p"/></vertices>
<triangles count="1"><input semantic="VERTEX" source="#v" offset="0"/><p>0 1 2</p></triangles>
</mesh></geometry></library_geometries>
<library_visual_scenes><visual_scene id="s"><node id="n"><translate>10 20 30</translate>
<instance_geometry url="#g"/></node></visual_scene></library_visual_scenes>
<scene><instance_visual_scene url="#s"/></scene>
</COLLADA>
)");
    const TriangleMesh m = load_mesh(path);
    EXPECT_EQ(m.triangle_count(), 1u);
    EXPECT_EQ(m.lo, glm::dvec3(10, 20, 30)) << m.to_string();
    EXPECT_EQ(m.hi, glm::dvec3(11, 21, 30)) << m.to_string();
}

TEST(MeshLoader, TextureBesideTheModelOddlyNamed) {
    // The OBJ names "SUB\\Tex.PNG"; the file is tex.png beside the model: found by bare name, case-insensitively.
    TempDir dir;
    ImageRGBA8 tex(2, 2, Rgba8{10, 20, 30, 255});
    write_rgba8(dir.file("tex.png"), tex);
    write_file(dir.file("t.mtl"), "newmtl m\nKd 1 1 1\nmap_Kd SUB\\Tex.PNG\n");
    write_file(dir.file("t.obj"),
               "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
    const TriangleMesh m = load_mesh(dir.file("t.obj"));
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    ASSERT_EQ(m.parts.size(), 1u);
    EXPECT_TRUE(m.parts[0].use_texture);
    EXPECT_EQ(m.materials[size_t(m.parts[0].material)].texture, tex);
}

TEST(MeshLoader, MissingTextureWarnsAndKeepsTheMaterialColour) {
    TempDir dir;
    write_file(dir.file("t.mtl"), "newmtl m\nKd 0.5 0.25 1\nmap_Kd nowhere.png\n");
    write_file(dir.file("t.obj"),
               "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 0 1\nusemtl m\nf 1/1 2/2 3/3\n");
    const TriangleMesh m = load_mesh(dir.file("t.obj"));
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_NE(m.warnings[0].find("nowhere.png"), std::string::npos) << m.warnings[0];
    EXPECT_EQ(m.warnings[0].find('\n'), std::string::npos);
    EXPECT_FALSE(m.parts[0].use_texture);
    EXPECT_EQ(m.materials[size_t(m.parts[0].material)].base_color, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
}

TEST(MeshLoader, TextureWithoutUvsWarns) {
    TempDir dir;
    write_rgba8(dir.file("tex.png"), ImageRGBA8(2, 2, Rgba8{10, 20, 30, 255}));
    write_file(dir.file("t.mtl"), "newmtl m\nKd 1 0 0\nmap_Kd tex.png\n");
    write_file(dir.file("t.obj"), "mtllib t.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl m\nf 1 2 3\n");
    const TriangleMesh m = load_mesh(dir.file("t.obj"));
    ASSERT_EQ(m.warnings.size(), 1u);
    EXPECT_NE(m.warnings[0].find("no texture coordinates"), std::string::npos) << m.warnings[0];
    EXPECT_FALSE(m.parts[0].use_texture);
}

TEST(MeshLoader, VertexColoursOnlyPly) {
    TempDir dir;
    write_file(dir.file("c.ply"),
               "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
               "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
               "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
               "0 0 0 255 0 0\n1 0 0 0 255 0\n0 1 0 0 0 255\n3 0 1 2\n");
    const TriangleMesh m = load_mesh(dir.file("c.ply"));
    ASSERT_EQ(m.triangle_count(), 1u);
    EXPECT_TRUE(m.parts[0].use_vertex_color);
    EXPECT_EQ(m.vertices[m.indices[0]].color, glm::u8vec4(255, 0, 0, 255));
}

TEST(MeshLoader, DuckFromAssimpTestModels) {
    const std::string duck = mesh_testing::duck_path();
    if (duck.empty()) GTEST_SKIP() << "assimp-testmodels is not installed (scripts/setup.sh installs it)";
    const TriangleMesh m = load_mesh(duck);
    EXPECT_GT(m.triangle_count(), 4000u) << m.to_string();
    EXPECT_TRUE(m.warnings.empty()) << m.warnings.front();
    bool textured = false;
    for (const MeshPart& p : m.parts) textured = textured || p.use_texture;
    EXPECT_TRUE(textured) << "duck.dae's duckCM.tga should be found";
    for (int k = 0; k < 3; ++k) EXPECT_LT(m.lo[k], m.hi[k]);
}

TEST(MeshLoader, RefusesWithOneLineNamingTheFile) {
    TempDir dir;
    write_file(dir.file("garbage.obj"), std::string("\x00\x01\x02 not a mesh \xff", 17));
    write_file(dir.file("points.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\np 1 2 3\n");
    write_file(dir.file("empty.ply"), "");
    write_file(dir.file("nan.obj"), "v 0 0 0\nv nan 0 0\nv 0 1 0\nf 1 2 3\n");
    for (const char* name : {"garbage.obj", "points.obj", "empty.ply", "missing.obj", "nan.obj"}) {
        const std::string path = dir.file(name);
        try {
            (void)load_mesh(path);
            ADD_FAILURE() << name << " was accepted";
        } catch (const IoError& e) {
            const std::string msg = e.what();
            EXPECT_EQ(msg.rfind(path, 0), 0u) << msg;
            EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
        }
    }
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

TEST(MeshLoader, RefusesDeclaredCountsLargerThanTheFile) {
    // assimp's PLY and OFF readers reserve what the header declares (mesh/header_guard.h).
    objects_testing::TempDir dir;
    const std::string off = "OFF\n353535235358 6 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    const std::string ply =
        "ply\nformat ascii 1.0\nelement vertex 353535235358\nproperty float x\nproperty float y\n"
        "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"
        "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    objects_testing::write_file(dir.file("huge.off"), off);
    objects_testing::write_file(dir.file("huge.ply"), ply);
    for (const char* name : {"huge.off", "huge.ply"}) {
        try {
            (void)load_mesh(dir.file(name));
            ADD_FAILURE() << name << " was accepted";
        } catch (const IoError& e) {
            EXPECT_NE(std::string(e.what()).find("353535235358"), std::string::npos) << e.what();
        }
    }
    EXPECT_EQ(check_declared_counts(dir.file("huge.off"), 1000000000000ull), "");
    // Honest headers pass.
    objects_testing::write_file(dir.file("ok.off"), "OFF\n# a comment\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
    EXPECT_EQ(load_mesh(dir.file("ok.off")).triangle_count(), 1u);
}

}  // namespace
}  // namespace rtm

namespace rtm {
namespace {

// The file's own message: one line starting with the path and holding `want`.
void expect_refused(const std::string& path, const std::string& want) {
    try {
        (void)load_mesh(path);
        ADD_FAILURE() << path << " was accepted";
    } catch (const IoError& e) {
        const std::string msg = e.what();
        EXPECT_EQ(msg.rfind(path + ": cannot read mesh: ", 0), 0u) << msg;
        EXPECT_NE(msg.find(want), std::string::npos) << msg;
        EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
    }
}

using test::ScopedEnv;

// Files on which assimp 5.2 itself crashes or loops without end (found by changing its test models at random, then
// reduced): read in a child process (formats/isolated_call.h), each is one line naming the file and saying what
// happened, and this process goes on.
TEST(MeshLoader, ReaderCrashesAndEndlessLoopsEndTheChildOnly) {
    TempDir dir;
    // 52 bytes of a binary Caligari COB file whose one chunk claims 4864 bytes: the reader throws from where nothing
    // catches it, and the C++ runtime aborts (rtm aborted with it before meshes were read in a child).
    std::string cob(52, '\0');
    cob.replace(0, 9, "Caligari ");
    cob[16] = 'L';  // binary, little endian
    cob.replace(32, 4, "BitM");
    cob[49] = 0x13;  // the chunk's size, 0x1300
    write_file(dir.file("abort.cob"), cob);
    expect_refused(dir.file("abort.cob"),
                   "the mesh reader (assimp) crashed on it (signal 6, Aborted; it said \"  what():  End of file or "
                   "read limit was reached\")");
    // 15 bytes on which the SMD reader loops without end: stopped after the processor time it may use.
    write_file(dir.file("loop.smd"), "nodes\n0  1.0 0.");
    {
        const ScopedEnv env{{"RTM_MESH_READER_SECONDS", "1"}};
        expect_refused(dir.file("loop.smd"),
                       "the mesh reader (assimp) was stopped after the 1 s of processor time "
                       "it may use for a file of 15 bytes");
    }
    // The limits' variables must be whole numbers in range; the message names the variable and the value.
    {
        const ScopedEnv env{{"RTM_MESH_READER_SECONDS", "-5"}};
        expect_refused(dir.file("loop.smd"), "RTM_MESH_READER_SECONDS \"-5\" is not a whole number from 1 to");
    }
    {
        const ScopedEnv env{{"RTM_MESH_READER_MB", "12x"}};
        expect_refused(dir.file("loop.smd"), "RTM_MESH_READER_MB \"12x\" is not a whole number from 1 to");
    }
    // And this process still reads meshes.
    EXPECT_GT(load_mesh(mesh_testing::write_bump_obj(dir.path().string())).triangle_count(), 0u);
}

// A FIFO (or a device) is refused without being opened; a file that names one (an OBJ's material library) makes the
// reader wait, and it is stopped when its time is up.
TEST(MeshLoader, FifosAreRefusedOrTimedOut) {
    TempDir dir;
    ASSERT_EQ(::mkfifo(dir.file("fifo.obj").c_str(), 0600), 0);
    expect_refused(dir.file("fifo.obj"), "not a regular file");
    ASSERT_EQ(::mkfifo(dir.file("m.fifo").c_str(), 0600), 0);
    write_file(dir.file("waits.obj"), "mtllib m.fifo\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
    const ScopedEnv env{{"RTM_MESH_READER_SECONDS", "1"}};  // 1 s of processor time, 2 * 1 + 2 = 4 s in all
    expect_refused(dir.file("waits.obj"),
                   "the mesh reader (assimp) was stopped after the 4 s it may take for a file "
                   "of 46 bytes: it waited on something the file names");
}

// A PLY header cut short (a file cut short: the reader loops without end on it) is refused before assimp reads it.
TEST(MeshLoader, RefusesAPlyHeaderWithoutItsEnd) {
    TempDir dir;
    write_file(dir.file("cut.ply"), "ply\nformat binary_little_endian 1.0\ncomment VCGLIB generated\nelement vertex 8");
    expect_refused(dir.file("cut.ply"), "header has no \"end_header\" line: the file ends inside its header");
    std::string long_header = "ply\nformat ascii 1.0\n";
    while (long_header.size() < 70000) long_header += "comment a header longer than 64 KiB\n";
    write_file(dir.file("long.ply"), long_header + "end_header\n");
    expect_refused(dir.file("long.ply"), "header has no \"end_header\" line in its first 65536 bytes");
}

}  // namespace
}  // namespace rtm
