// `--shade depth` as an image a person can read. Window depth z_ndc * 0.5 + 0.5 is hyperbolic
// in distance: with near = 0.1 every surface beyond a few units lies above 0.99, so grey =
// window depth is white wherever something is covered. This view turns each covered pixel's
// window depth back into its distance along the view axis, d = 2 n f / (f + n - z_ndc (f - n))
// (the inverse of the perspective's z row, camera.h), and maps the range of d over the
// covered pixels linearly onto grey: the nearest pixel white (255), the farthest kFarGrey,
// the background black, so it stays apart from the farthest surface.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/visibility.h"

namespace tessera::shade {

inline constexpr uint8_t kFarGrey = 40;

// Writes visibility.width x visibility.height RGB bytes (rows top to bottom) into `rgb8`
// (resized). A single depth (a plane facing the camera) is all white.
void depth_view(const VisibilityBuffer& visibility, const Camera& camera, std::vector<uint8_t>& rgb8);

}  // namespace tessera::shade
