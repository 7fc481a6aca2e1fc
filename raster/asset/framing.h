// Framing: the camera for a model or scene given without one, chosen from its bounding box so
// that the whole box is in view and nothing of it is clipped.
//
// The view direction is fixed and documented, so the same model always gets the same picture:
// the eye looks at the box's centre from 30 degrees to the right of the +z axis and 20 degrees
// above the horizon, +y up. That is glTF 2.0's convention (+y up, a model's front facing +z);
// formats with other conventions (many STL and PLY scans are +z up) may want --up and --eye.
// The eye is as close as it can be with every corner of the box in view (and a 5% margin on
// each side), but never inside the box's bounding sphere; near and far sit just outside the
// nearest and farthest corners, so depth precision follows the model's own size.
#pragma once
#include <glm/glm.hpp>

#include <string>

#include "raster/core/camera.h"

namespace tessera::asset {

// Unit vector from the box's centre towards the eye.
glm::vec3 framing_direction();

// The camera that frames the box [lower, upper] at `aspect` (width / height) with a vertical
// field of view of `fovy_deg`. A box of zero size (one point) is framed as a tiny box around it. Throws std::invalid_argument for non-finite bounds or a field of view outside
// (0, 180).
Camera frame_box(glm::vec3 lower, glm::vec3 upper, float aspect, float fovy_deg = 45.0f);

// The camera as `tessera raster` flags ("--eye x,y,z --lookat x,y,z --up x,y,z --fov F --near N
// --far F"), every number printed so that it reads back to the same float.
std::string camera_flags(const Camera& camera);

}  // namespace tessera::asset
