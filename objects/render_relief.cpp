#include "objects/render_relief.h"

#include <chrono>
#include <stdexcept>

#include "truth/micromesh.h"
#include "truth/raycast.h"
#include "warp/timing.h"

namespace rtm {

ImageRGBA8 render_relief_frame(ReliefQuad& quad, Renderer* renderer, const Camera& cam, const RenderSettings& s,
                               StageTimes& times, DrawReport* report) {
    const auto t0 = Clock::now();
    if (s.method == RenderMethod::raycast) {
        RaycastOptions ro;
        ro.threads = s.prewarp.threads;
        ro.progress = s.progress;
        ImageRGBA8 img = raycast_relief(quad.relief(), cam, ro);
        times.total_ms += ms_since(t0);
        return img;
    }
    if (!renderer) throw std::logic_error("render_relief_frame: " + to_string(s.method) + " needs a renderer");
    renderer->begin_frame(cam);
    if (s.method == RenderMethod::micromesh) {
        const MicroMesh& mesh = quad.micromesh();
        draw_mesh(*renderer, cam, mesh);
        renderer->finish();
        times.texture_map_ms += ms_since(t0);
    } else if (const auto pp = perpixel_method(s.method)) {
        quad.perpixel().draw(*renderer, cam, quad.relief(), *pp, s.perpixel);
        renderer->finish();
        times.texture_map_ms += ms_since(t0);
    } else {
        StageTimes st;
        quad.draw(*renderer, cam, s.method, s.prewarp, st, s.draw, report);
        times.prewarp_ms += st.prewarp_ms;
        times.upload_ms += st.upload_ms;
        times.texture_map_ms += st.texture_map_ms;
    }
    times.total_ms += ms_since(t0);
    return renderer->read_pixels(cam.width, cam.height);
}

}  // namespace rtm
