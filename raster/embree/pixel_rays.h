// Rays through pixel centres for a view-projection matrix, and the window depth of a world
// point under it: the ray-cast renderer's camera model, matched to the rasterizer's.
//
// The rasterizer samples pixel (x, y) at its centre (x + 0.5, y + 0.5), rows top to bottom,
// and keeps what lies between the near and far planes (-w <= z <= w). The ray for a pixel
// therefore starts on the near plane and ends on the far plane: origin = unproject(ndc, -1),
// direction = unproject(ndc, +1) - origin, so t in [0, 1] spans exactly the clip volume.
// Unprojection runs in double: the inverse of a perspective matrix with near/far = 1e-3
// loses most float digits, and the ray's cost dwarfs the arithmetic.
#pragma once
#include <glm/glm.hpp>

namespace tessera::rt {

class PixelRays {
public:
    PixelRays(const glm::mat4& view_projection, int width, int height);

    // The ray through the centre of pixel (x, y): t = 0 on the near plane, t = 1 on the far.
    void ray(float x_centre, float y_centre, glm::vec3& origin, glm::vec3& direction) const;
    void pixel_ray(int x, int y, glm::vec3& origin, glm::vec3& direction) const {
        ray(float(x) + 0.5f, float(y) + 0.5f, origin, direction);
    }

    // Window depth z_ndc * 0.5 + 0.5 of a world point, as the rasterizer stores it.
    float window_depth(const glm::vec3& world) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    glm::dmat4 view_projection_;
    glm::dmat4 inverse_;
    int width_;
    int height_;
};

}  // namespace tessera::rt
