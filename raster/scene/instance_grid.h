// A grid of copies of a scene's objects, for measuring how a renderer's cost grows with the
// triangle count on the user's own content (`tessera compare --sweep`): N copies of every
// object laid side by side on the x-z plane (y is up), so the triangle count is exactly N
// times the scene's and every copy looks like the original. The copies share their geometry
// (Object::geometry is shared), so the grid costs memory only where the frame bakes it.
#pragma once
#include <glm/glm.hpp>

#include "raster/scene/scene.h"

namespace tessera::scene {

// Where copy i of `copies` goes: columns = ceil(sqrt(copies)) along +x, rows along +z, one
// cell per copy of `cell` size (x, z). The grid is centred on the origin's column and row
// zero so copy 0 stays near the original.
struct InstanceGrid {
    int copies = 1;
    int columns = 1;
    int rows = 1;
    glm::vec2 cell{0.0f};  // spacing along x and z

    // `copies` >= 1 objects' worth of cells for content whose bounding box is [lower, upper]:
    // the cell is the box's footprint plus a quarter of its largest side, so neighbours never
    // overlap and a flat or thin model still gets a gap. Throws std::invalid_argument for
    // copies < 1 or a non-finite box.
    InstanceGrid(int copies, glm::vec3 lower, glm::vec3 upper);

    glm::vec3 offset(int copy) const;
    // The box of all copies of content bounded by [lower, upper].
    std::pair<glm::vec3, glm::vec3> bounds(glm::vec3 lower, glm::vec3 upper) const;
};

// `scene` with every object repeated at each grid offset (copy after copy, so triangle ids
// of copy 0 are the original's). Camera, lights, materials and textures are kept. The copies'
// animate hooks are dropped: the grid is a still frame of the scene as it is now (animate it
// to the time wanted first), since a hook that sets the transform would undo the offset.
Scene instance_grid(const Scene& scene, const InstanceGrid& grid);

}  // namespace tessera::scene
