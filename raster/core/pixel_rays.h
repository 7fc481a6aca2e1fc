// Rays through pixel centres for a view-projection matrix, and the window depth of a world
// point under it: the ray-cast renderer's camera model, matched to the rasterizer's.
//
// The rasterizer samples pixel (x, y) at its centre (x + 0.5, y + 0.5), rows top to bottom,
// and keeps what lies between the near and far planes (-w <= z <= w). The ray for a pixel
// therefore starts on the near plane and ends on the far plane: origin = unproject(ndc, -1),
// direction = unproject(ndc, +1) - origin, so t in [0, 1] spans exactly the clip volume.
// The unprojected points are affine in the window position, so a ray costs two 4-vector
// evaluations and two divisions. Both run in double: the far point's w is 1/far, the
// difference of two terms near 1/near, so float would lose about log2(far/near) bits of it.
#pragma once
#include <glm/glm.hpp>

#include <cstddef>

namespace tessera {

class PixelRays {
public:
    PixelRays(const glm::mat4& view_projection, int width, int height);

    // The ray through the centre of pixel (x, y): t = 0 on the near plane, t = 1 on the far.
    void ray(float x_centre, float y_centre, glm::vec3& origin, glm::vec3& direction) const;
    void pixel_ray(int x, int y, glm::vec3& origin, glm::vec3& direction) const {
        ray(float(x) + 0.5f, float(y) + 0.5f, origin, direction);
    }
    // ray() for n window positions at once, structure of arrays: the same double arithmetic
    // in the same order, written as one loop over independent elements so that the compiler
    // runs it in vector lanes (the library builds with -ffp-contract=off: no fused
    // multiply-adds, so every element equals ray()'s).
    struct RayArrays {
        float *ox, *oy, *oz, *dx, *dy, *dz;
    };
    void rays(size_t n, const float* x_centre, const float* y_centre, const RayArrays& out) const;

    // Window depth z_ndc * 0.5 + 0.5 of a world point, as the rasterizer stores it.
    float window_depth(const glm::vec3& world) const;

    // The window depth of the plane through a, b, c as a function of the window position:
    // the rasterizer's depth plane Z(X, Y) = aX + bY + c, which a plane
    // keeps under any projective map. Evaluating it at a pixel centre gives the depth of the
    // ray's hit to double precision, where the hit distance Embree returns loses digits on
    // triangles seen nearly edge-on.
    struct DepthPlane {
        double per_x = 0, per_y = 0, at_zero = 0;
        bool valid = false;  // false for a plane through the eye (seen edge-on)
        float at(double x, double y) const { return float(per_x * x + per_y * y + at_zero); }
    };
    DepthPlane depth_plane(const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) const;

    int width() const { return width_; }
    int height() const { return height_; }

private:
    // A homogeneous point affine in the window position: origin + x * per_x + y * per_y.
    struct Affine {
        glm::dvec4 origin, per_x, per_y;
        glm::dvec4 at(double x, double y) const { return origin + x * per_x + y * per_y; }
    };

    glm::dmat4 view_projection_;
    glm::dmat4 inverse_;
    Affine near_, far_;  // unprojections onto the near (z_ndc = -1) and far (+1) planes
    int width_;
    int height_;
};

}  // namespace tessera
