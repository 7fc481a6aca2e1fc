// A pinhole camera as in seeds/000: extrinsic eye / lookat / vup, intrinsic vertical field of
// view, aspect, front (near) and back (far) planes. View and projection are the seed's
// matrices; GLM stores them column-major for column vectors (p' = P * V * p), which is the
// transpose of the seed's row-vector form p * V * P and the same transform.
//
// Clip space is OpenGL's: visible points satisfy -w <= x, y, z <= w with w > 0; window depth is
// z_ndc * 0.5 + 0.5, and pixel rows run top to bottom (y_window = (1 - y_ndc) / 2 * height).
#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace tessera {

struct Camera {
    glm::vec3 eye{0.0f, 0.0f, 3.0f};
    glm::vec3 lookat{0.0f, 0.0f, 0.0f};
    glm::vec3 up{0.0f, 1.0f, 0.0f};
    float fovy_deg = 60.0f;
    float aspect = 16.0f / 9.0f;
    float near = 0.1f;  // the seed warns: fp/bp must not be tiny (z-fighting)
    float far = 100.0f;

    // w = normalize(eye - lookat), u = normalize(vup x w), v = w x u; rows u, v, w.
    glm::mat4 view() const { return glm::lookAtRH(eye, lookat, up); }

    // The seed's perspective: sy = 1/tan(fov/2), sx = sy/asp,
    // z' = -(fp+bp)/(bp-fp) z - 2 fp bp/(bp-fp), w' = -z.
    glm::mat4 projection() const {
        return glm::perspectiveRH_NO(glm::radians(fovy_deg), aspect, near, far);
    }

    glm::mat4 view_projection() const { return projection() * view(); }
};

}  // namespace tessera
