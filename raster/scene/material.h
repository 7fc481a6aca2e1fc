// Materials: which shading model a surface uses (flat, Gouraud, Phong, NPR toon)
// and the parameters of the Blinn-Phong formula
//     L = ka*La + (kd*cos(theta) + ks*cos(delta)^shine) * Le,
// plus optional textures (a diffuse colour texture modulating kd, a tangent-space normal map
// sampled in the surface's tangent frame), an opacity for alpha blending and an alpha cutoff for alpha testing.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "raster/texture/sampler.h"

namespace tessera::scene {

enum class ShadingModel : uint8_t {
    flat,     // one colour per triangle: the face normal, lit at the triangle's centroid
    gouraud,  // Blinn-Phong per vertex, the colour interpolated (per-vertex shading)
    phong,    // Blinn-Phong per pixel with N, V, L interpolated and renormalised
    toon,     // two diffuse levels, black silhouette, ink outline (NPR shading; shade/outline.h)
};

inline constexpr int32_t kNoTexture = -1;

struct Material {
    ShadingModel model = ShadingModel::phong;
    glm::vec3 ka{0.1f};
    glm::vec3 kd{0.7f};
    glm::vec3 ks{0.3f};
    float shine = 32.0f;
    float opacity = 1.0f;  // < 1: drawn after the opaque pass, blended in submission order
    // Blended even at opacity 1: the diffuse texture's alpha varies over the surface (glTF 2.0
    // alphaMode BLEND).
    bool blend = false;
    // Alpha testing (glTF 2.0 alphaMode MASK) when > 0: where opacity x diffuse texture alpha is
    // below the cutoff the surface is absent, elsewhere it is opaque (nearest one wins).
    float alpha_cutoff = 0.0f;
    int32_t diffuse_texture = kNoTexture;  // index into the scene's textures; modulates kd
    bool textured_ambient = false;         // the diffuse texture modulates ka too (an albedo map)
    int32_t normal_texture = kNoTexture;   // tangent-space normal map (per-pixel models only)
    texture::TextureFilter filter = texture::TextureFilter::trilinear;
    texture::TextureWrap wrap = texture::TextureWrap::repeat;
    glm::vec2 uv_scale{1.0f};  // texture coordinates are multiplied by this before sampling

    bool masked() const { return alpha_cutoff > 0.0f; }
    bool transparent() const { return !masked() && (blend || opacity < 1.0f); }
};

const char* to_string(ShadingModel model);
// Throws std::invalid_argument naming the accepted values.
ShadingModel parse_shading_model(std::string_view name);
texture::TextureFilter parse_texture_filter(std::string_view name);
texture::TextureWrap parse_texture_wrap(std::string_view name);

// A parameter as a scene description gives it: numbers ("kd": [0.8, 0.2, 0.1]) or a word
// ("model": "toon").
struct MaterialParameter {
    std::string name;
    std::vector<float> numbers;
    std::string word;
};

// Sets the named parameters on `material` (model first, whatever the order, so the checks
// below see the final model). Bad values (wrong count, negative shine, opacity outside [0, 1],
// unknown model name) throw std::invalid_argument. Unknown names and parameters that the
// material's model does not use are not errors (a warning, not an error): one
// line per such parameter is returned for the caller to print.
std::vector<std::string> set_material_parameters(Material& material,
                                                 std::span<const MaterialParameter> parameters);

}  // namespace tessera::scene
