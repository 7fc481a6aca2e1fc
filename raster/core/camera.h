// A pinhole camera: extrinsic eye / lookat / vup, intrinsic vertical field of
// view, aspect, front (near) and back (far) planes. View and projection are the classic
// matrices; GLM stores them column-major for column vectors (p' = P * V * p), which is the
// transpose of the row-vector form p * V * P and the same transform.
//
// Clip space is OpenGL's: visible points satisfy -w <= x, y, z <= w with w > 0; window depth is
// z_ndc * 0.5 + 0.5, and pixel rows run top to bottom (y_window = (1 - y_ndc) / 2 * height).
//
// A camera may show only part of its image plane (an off-axis window): a frame too large for
// one pass is rendered as regions, each through region() of the frame's camera, and every
// pixel of a region sees exactly the ray it would see in the whole frame. Everything that
// derives rays or clip coordinates from projection() follows the window unchanged.
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <tuple>
#include <utility>

namespace tessera {

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 3.0f};
    glm::vec3 lookat{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy_deg = 60.0f;
    float aspect = 16.0f / 9.0f;
    float near = 0.1f;  // fp/bp must not be tiny (z-fighting)
    float far = 100.0f;

    // The part of the image plane shown, in the whole frame's normalised device coordinates
    // (x to the right, y up): [x_low, x_high] x [y_low, y_high]; the default is all of it.
    struct Window {
        float x_low = -1.0f, x_high = 1.0f, y_low = -1.0f, y_high = 1.0f;
        bool whole() const { return x_low == -1.0f && x_high == 1.0f && y_low == -1.0f && y_high == 1.0f; }
        // The whole frame's NDC of a point at `ndc` in the window's own NDC.
        glm::vec2 frame_ndc(glm::vec2 ndc) const {
            return {x_low + (ndc.x + 1.0f) * 0.5f * (x_high - x_low), y_low + (ndc.y + 1.0f) * 0.5f * (y_high - y_low)};
        }
    } window;

    // w = normalize(eye - lookat), u = normalize(vup x w), v = w x u; rows u, v, w.
    glm::mat4 view() const { return glm::lookAtRH(eye, lookat, up); }

    // The perspective: sy = 1/tan(fov/2), sx = sy/asp,
    // z' = -(fp+bp)/(bp-fp) z - 2 fp bp/(bp-fp), w' = -z.
    // With a window, the window's NDC rectangle is then stretched over [-1, 1]^2 (a scale and
    // an offset in x and y: an off-axis frustum through the same eye).
    glm::mat4 projection() const {
        const glm::mat4 lens = lens_projection();
        if (window.whole()) return lens;
        const double sx = 2.0 / (double(window.x_high) - window.x_low);
        const double sy = 2.0 / (double(window.y_high) - window.y_low);
        glm::dmat4 crop(1.0);
        crop[0][0] = sx;
        crop[3][0] = -sx * 0.5 * (double(window.x_high) + window.x_low);
        crop[1][1] = sy;
        crop[3][1] = -sy * 0.5 * (double(window.y_high) + window.y_low);
        return glm::mat4(crop * glm::dmat4(lens));
    }
    // The projection of the whole frame, whatever the window.
    glm::mat4 lens_projection() const {
        return glm::perspectiveRH_NO(glm::radians(fovy_deg), aspect, near, far);
    }

    glm::mat4 view_projection() const { return projection() * view(); }

    // This camera showing only pixels [x0, x0 + w) x [y0, y0 + h) of its frame_width x
    // frame_height image (rows top to bottom), as a w x h image of its own.
    Camera region(int frame_width, int frame_height, int x0, int y0, int w, int h) const {
        const auto at = [](double pixel, double size) { return 2.0 * pixel / size - 1.0; };
        // Corners in this camera's NDC, then in its whole frame's (windows nest).
        const double x_low = at(x0, frame_width), x_high = at(x0 + w, frame_width);
        const double y_low = -at(y0 + h, frame_height), y_high = -at(y0, frame_height);
        const auto frame = [&](double low, double high, float w_low, float w_high) {
            const double scale = 0.5 * (double(w_high) - w_low);
            return std::pair<float, float>(float(w_low + (low + 1.0) * scale), float(w_low + (high + 1.0) * scale));
        };
        Camera c = *this;
        std::tie(c.window.x_low, c.window.x_high) = frame(x_low, x_high, window.x_low, window.x_high);
        std::tie(c.window.y_low, c.window.y_high) = frame(y_low, y_high, window.y_low, window.y_high);
        return c;
    }
};

}  // namespace tessera
