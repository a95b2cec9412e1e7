// Opens a file in the viewer by its kind: NAME.relief.json, NAME.object.json, NAME.scene.json, or a mesh (any
// other extension assimp reads, baked into an object when prepared). Throws IoError naming the file.
#pragma once

#include <memory>
#include <string>

#include "viewer/loaded.h"

namespace rtm::viewer {

std::unique_ptr<Loaded> open_file(const std::string& path);

}  // namespace rtm::viewer
