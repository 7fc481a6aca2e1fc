// A model file as scene objects: the parts of io::read_model (model_file.h) with their materials
// mapped onto tessera's Material and their textures loaded, so that both renderers shade an
// imported model with the same kernel as every other object.
//
// The mapping (every imported material uses the per-pixel Blinn-Phong model):
// - Phong files (OBJ's MTL): kd = Kd, ks = Ks, shine = Ns, opacity = d;
// - metallic-roughness files (glTF 2.0): kd = base colour x (1 - metallic), ks = the specular
//   colour at normal incidence, 0.04 for dielectrics blended towards the base colour for
//   metals, and shine = 2 / alpha^2 - 2 with alpha = roughness^2 (the Blinn-Phong exponent that
//   matches a Beckmann lobe of roughness alpha, Walter et al. 2007), at least 1. A
//   metallic-roughness texture is averaged to one metallic and one roughness value per
//   material: tessera's materials have no per-pixel specular;
// - ka = kd, and the base colour texture modulates both: the rig's ambient light is reflected by
//   the albedo (MTL's Ka is ignored: exporters write anything there, Blender 1.0);
// - the base colour texture modulates kd (sRGB), the normal texture is a tangent-space normal
//   map (linear); the base colour texture's sampler applies to both: its wrap mode, and
//   nearest texels when it magnifies with NEAREST (else trilinear mip-mapping);
// - alpha: glTF OPAQUE ignores alpha; MASK keeps the fragments whose alpha (factor x texture)
//   reaches alpha_cutoff, as opaque surfaces; BLEND, and any other format's opacity below 1,
//   blends in submission order.
// Not mapped: emission, occlusion and clearcoat, vertex colours, texture transforms, uv sets
// other than the first (a warning), the normal map's scale.
//
// A texture that is missing or cannot be decoded is a warning naming the model, the material
// and the file; the material then renders with its factors alone.
#pragma once
#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "raster/io/model_file.h"
#include "raster/scene/scene.h"

namespace tessera::asset {

struct ImportedModel {
    std::vector<scene::Object> objects;      // one per part; material indices into `materials`
    std::vector<scene::Material> materials;  // texture indices into `textures`
    std::vector<texture::Texture> textures;
    glm::vec3 lower{0.0f}, upper{0.0f};
    io::ModelStats stats;
    std::vector<std::string> warnings;  // the reader's and the texture loader's
};

// Throws tessera::Error for a file that cannot be read (io::read_model).
ImportedModel import_model(const std::filesystem::path& path);

// The material `m` of a model as tessera shades it (textures not set).
scene::Material map_material(const io::ModelMaterial& m);

// Moves the model into `scene`: its textures and materials are appended (indices shifted),
// each object placed by `transform` after its node transform and named "<prefix>/<part>". With
// `material`, every object uses that scene material instead of its own.
void add_to_scene(scene::Scene& scene, ImportedModel&& model, const scene::Transform& transform, const std::string& prefix,
                  std::optional<uint32_t> material = std::nullopt);

}  // namespace tessera::asset
