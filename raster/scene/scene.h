// The scene model (Scene, Object, Material, Texture, Geometry, Camera, Light),
// done the data-oriented way: objects refer to shared geometry and to materials by index, and
// each frame is baked into ONE world-space Mesh plus a material id per triangle. Everything
// downstream (the tile rasterizer, the Embree ray caster, shading) reads only that bake, so
// the two renderers see identical work and objects never disturb one another (the classic
// "render state passed by value").
#pragma once
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/mesh.h"
#include "raster/scene/light.h"
#include "raster/scene/material.h"
#include "raster/scene/transform.h"
#include "raster/scene/background.h"
#include "raster/texture/texture.h"

namespace tessera::scene {

struct Object {
    std::string name;
    std::shared_ptr<const Mesh> geometry;  // model space; shared between instances
    uint32_t material = 0;                 // index into Scene::materials
    Transform transform;
    // Animate(): called with the scene time (seconds) before a frame is baked; may
    // change the transform or replace the geometry (a waving flag, a writhing snake).
    std::function<void(Object&, float time)> animate;
};

struct Scene {
    Camera camera;
    std::vector<Object> objects;
    std::vector<Material> materials;
    std::vector<texture::Texture> textures;  // Material::diffuse_texture / normal_texture index these
    std::vector<Light> lights;
    Background background;

    // Runs every object's animate hook for time t (objects in parallel: hooks only touch
    // their own object).
    void animate(float time);
    // Throws std::invalid_argument naming the first object or material that refers to
    // something missing (no geometry, material or texture index out of range).
    void validate() const;
};

// One frame's geometry in world space.
struct BakedScene {
    Mesh mesh;                               // normals, uvs present whenever any object has them
    std::vector<uint32_t> triangle_material;  // one per triangle
    std::vector<uint32_t> vertex_material;    // one per vertex (Gouraud colours per vertex)
    std::vector<MeshPart> objects;            // where each object's vertices and triangles went
};

// Where each object's vertices and indices go in a bake (object i's from first_vertex[i] and
// first_index[i]), and which attributes the baked mesh has.
struct BakeLayout {
    std::vector<size_t> first_vertex, first_index;
    bool normals = false, uvs = false, tangents = false;

    bool operator==(const BakeLayout&) const = default;
};

// Applies each object's model matrix to its vertices (normals by the inverse transpose,
// renormalised), concatenating objects in order, so triangle ids follow the submission order
// of objects. Objects and big vertex ranges run in parallel; the result does not depend on
// the thread count. A mirroring transform (negative determinant) has its triangles' winding
// reversed so that front faces stay counter-clockwise. Objects without normals or uvs get
// zeros there (shading then uses the face normal). Calls validate() first.
BakedScene bake(const Scene& scene);

// bake() frame after frame, rewriting only what changed: an object whose geometry (the same
// Mesh), transform and material are those it had in the previous bake, in a scene whose
// objects' sizes and attributes are laid out as before, keeps its baked vertices and
// triangles (an animation's still objects: the ground, the buildings). The bake of an object
// is a function of those three alone, so the result equals bake(scene) bit for bit. The
// meshes of the previous bake are held, so that a new mesh cannot take an old one's address.
class SceneBaker {
public:
    // The bake of `scene`, valid until the next call. Throws as bake() does; a throw while
    // objects are being written leaves nothing of the previous bake to be kept.
    const BakedScene& bake(const Scene& scene);
    // How many objects the last bake() wrote (the others were kept).
    size_t objects_baked() const { return objects_baked_; }

private:
    struct Baked {
        std::shared_ptr<const Mesh> geometry;
        Transform transform;
        uint32_t material = 0;
    };
    BakedScene baked_;
    std::vector<Baked> baked_objects_;
    std::optional<BakeLayout> layout_;  // of baked_; none until a bake has succeeded
    size_t objects_baked_ = 0;
};

}  // namespace tessera::scene
