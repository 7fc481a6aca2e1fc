#include "raster/render/animated_scene.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <utility>

namespace tessera::render {

Camera camera_at(const CameraSpec& spec, float time, float aspect) {
    Camera c = spec.camera;
    c.aspect = aspect;
    const auto& k = spec.keys;
    if (!k.empty()) {
        if (time <= k.front().time || k.size() == 1) {
            c.eye = k.front().eye, c.lookat = k.front().lookat, c.fovy_deg = k.front().fovy_deg;
        } else if (time >= k.back().time) {
            c.eye = k.back().eye, c.lookat = k.back().lookat, c.fovy_deg = k.back().fovy_deg;
        } else {
            size_t i = 0;
            while (time >= k[i + 1].time) ++i;
            const float t = (time - k[i].time) / (k[i + 1].time - k[i].time);
            const CameraKey& p0 = k[i == 0 ? 0 : i - 1];
            const CameraKey& p1 = k[i];
            const CameraKey& p2 = k[i + 1];
            const CameraKey& p3 = k[std::min(i + 2, k.size() - 1)];
            // Uniform Catmull-Rom: 0.5 (2 p1 + (p2 - p0) t + (2p0 - 5p1 + 4p2 - p3) t^2 + (3p1 - p0 - 3p2 + p3) t^3).
            const auto cr = [t](auto a, auto b, auto cc, auto d) {
                return 0.5f * (2.0f * b + (cc - a) * t + (2.0f * a - 5.0f * b + 4.0f * cc - d) * t * t +
                               (3.0f * b - a - 3.0f * cc + d) * t * t * t);
            };
            c.eye = cr(p0.eye, p1.eye, p2.eye, p3.eye);
            c.lookat = cr(p0.lookat, p1.lookat, p2.lookat, p3.lookat);
            c.fovy_deg = cr(p0.fovy_deg, p1.fovy_deg, p2.fovy_deg, p3.fovy_deg);
        }
    }
    if (spec.orbit != 0.0f) {
        const glm::quat q = glm::angleAxis(spec.orbit * time, glm::vec3(0.0f, 1.0f, 0.0f));
        c.eye = c.lookat + q * (c.eye - c.lookat);
    }
    return c;
}

void AnimatedScene::set_time(float time, float aspect) {
    scene.camera = camera_at(camera, time, aspect);
    scene.animate(time);
}

AnimatedScene still_scene(scene::Scene scene) {
    AnimatedScene out;
    out.camera.camera = scene.camera;
    out.scene = std::move(scene);
    return out;
}

}  // namespace tessera::render
