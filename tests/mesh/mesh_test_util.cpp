#include "mesh/mesh_test_util.h"

#include <filesystem>
#include <fstream>

namespace rtm::mesh_testing {

std::string write_bump_obj(const std::string& dir, const std::string& name) {
    const std::string obj = dir + "/" + name + ".obj";
    std::ofstream m(dir + "/" + name + ".mtl");
    m << "newmtl floor\nKd 0.2 0.4 0.6\nnewmtl bump\nKd 1 0.8 0\n";
    std::ofstream o(obj);
    o << "mtllib " << name << ".mtl\n"
      << "v 0 0 0.25\nv 1 0 0.25\nv 1 1 0.25\nv 0 1 0.25\n"
      << "v 0.25 0.25 0.75\nv 0.75 0.25 0.75\nv 0.75 0.75 0.75\nv 0.25 0.75 0.75\n"
      << "usemtl floor\nf 1 2 3\nf 1 3 4\nusemtl bump\nf 5 6 7\nf 5 7 8\n";
    return obj;
}

std::string duck_path() {
    const std::string p = "/usr/share/assimp/models/Collada/duck.dae";
    return std::filesystem::exists(p) ? p : std::string();
}

}  // namespace rtm::mesh_testing
