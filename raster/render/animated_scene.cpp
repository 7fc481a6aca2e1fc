#include "raster/render/animated_scene.h"

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace tessera::render {

namespace {

// Uniform Catmull-Rom from b (t = 0) to c (t = 1), a and d their neighbours:
// 0.5 (2 b + (c - a) t + (2a - 5b + 4c - d) t^2 + (3b - a - 3c + d) t^3).
template <class T>
T catmull_rom(T a, T b, T c, T d, float t) {
    return 0.5f * (2.0f * b + (c - a) * t + (2.0f * a - 5.0f * b + 4.0f * c - d) * t * t +
                   (3.0f * b - a - 3.0f * c + d) * t * t * t);
}

}  // namespace

std::pair<float, float> fov_range(const std::vector<CameraKey>& keys, size_t segment) {
    const size_t i = segment;
    const float a = keys[i == 0 ? 0 : i - 1].fovy_deg, b = keys[i].fovy_deg, c = keys[i + 1].fovy_deg,
                d = keys[std::min(i + 2, keys.size() - 1)].fovy_deg;
    // The cubic's extremes on [0, 1]: its ends and the roots of its derivative,
    // 0.5 (p + 2 q t + 3 r t^2), that lie inside, each evaluated as camera_at does.
    const double p = double(c) - a, q = 2.0 * a - 5.0 * b + 4.0 * c - d, r = 3.0 * b - a - 3.0 * c + d;
    std::vector<double> ts{0.0, 1.0};
    if (r != 0.0) {
        const double discriminant = q * q - 3.0 * r * p;  // of 3r t^2 + 2q t + p, over 4
        if (discriminant >= 0.0) {
            ts.push_back((-q + std::sqrt(discriminant)) / (3.0 * r));
            ts.push_back((-q - std::sqrt(discriminant)) / (3.0 * r));
        }
    } else if (q != 0.0) {
        ts.push_back(-p / (2.0 * q));
    }
    float low = b, high = b;
    for (const double t : ts)
        if (t >= 0.0 && t <= 1.0) {
            const float v = catmull_rom(a, b, c, d, float(t));
            low = std::min(low, v), high = std::max(high, v);
        }
    return {low, high};
}

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
            c.eye = catmull_rom(p0.eye, p1.eye, p2.eye, p3.eye, t);
            c.lookat = catmull_rom(p0.lookat, p1.lookat, p2.lookat, p3.lookat, t);
            c.fovy_deg = catmull_rom(p0.fovy_deg, p1.fovy_deg, p2.fovy_deg, p3.fovy_deg, t);
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
