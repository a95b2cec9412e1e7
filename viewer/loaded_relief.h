// A relief texture loaded in the viewer (NAME.relief.json): one relief quad.
#pragma once

#include <memory>
#include <string>

#include "objects/render_relief.h"
#include "viewer/loaded.h"

namespace rtm::viewer {

class LoadedRelief : public Loaded {
public:
    explicit LoadedRelief(const std::string& manifest);  // throws IoError naming the file
    std::string name() const override { return path_; }
    std::string kind() const override { return "relief"; }
    Bounds bounds() const override;
    void draw(Renderer& renderer, const Camera& cam, const ViewSettings& s, FrameReport& report) override;
    ImageRGBA8 raycast(const Camera& cam, const ViewSettings& s) override;
    void set_steep_texture(const ImageRGBA8& img) override;

private:
    std::unique_ptr<ImageRGBA8> steep_;  // set by set_steep_texture, given to every quad reload() makes
    std::string path_;
    double discontinuity_ = -1;  // the threshold the quad was made with (-1: the manifest's own)
    std::unique_ptr<ReliefQuad> quad_;
    void reload(double discontinuity);
};

// The settings as the relief renderer takes them (objects/render_relief.h).
RenderSettings render_settings(const ViewSettings& s);

}  // namespace rtm::viewer
