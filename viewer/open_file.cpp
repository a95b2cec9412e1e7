#include "viewer/open_file.h"

#include "formats/image_io.h"
#include "viewer/loaded_object.h"
#include "viewer/loaded_relief.h"
#include "viewer/loaded_scene.h"

namespace rtm::viewer {

std::unique_ptr<Loaded> open_file(const std::string& path) {
    auto ends_with = [&](const std::string& suffix) {
        return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
    };
    if (ends_with(".relief.json")) return std::make_unique<LoadedRelief>(path);
    if (ends_with(".object.json")) return LoadedObject::from_manifest(path);
    if (ends_with(".scene.json")) return std::make_unique<LoadedScene>(path);
    if (ends_with(".json"))
        throw IoError(path + ": unknown kind of file; expected NAME.relief.json, NAME.object.json or NAME.scene.json");
    return LoadedObject::from_mesh(path);  // load_mesh names the file when assimp cannot read it
}

}  // namespace rtm::viewer
