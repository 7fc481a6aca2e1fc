#include "raster/asset/model_import.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <utility>

#include "raster/core/error.h"
#include "raster/io/image_io.h"

namespace tessera::asset {

using scene::kNoTexture;
using scene::Material;
using texture::TexelEncoding;
using texture::Texture;

namespace {

// The Blinn-Phong exponent of a Beckmann lobe of roughness alpha (Walter et al. 2007,
// "Microfacet models for refraction", eq. 32 inverted): n = 2 / alpha^2 - 2.
float blinn_phong_exponent(float roughness) {
    const float alpha = std::max(roughness * roughness, 1e-3f);
    return std::clamp(2.0f / (alpha * alpha) - 2.0f, 1.0f, 1e4f);
}

// Loads each texture once per (source, encoding) and hands out its index.
class TextureLoader {
public:
    TextureLoader(const io::ModelFile& model, std::vector<Texture>& textures, std::vector<std::string>& warnings)
        : model_(model), textures_(textures), warnings_(warnings) {}

    // The texture's index, or kNoTexture (with a warning) when it cannot be had.
    int32_t load(const io::ModelTextureRef& ref, TexelEncoding encoding, const std::string& material,
                 const char* role) {
        const std::string key = (ref.embedded >= 0 ? "*" + std::to_string(ref.embedded) : ref.file.string()) +
                                (encoding == TexelEncoding::srgb ? "|srgb" : "|linear");
        if (const auto found = loaded_.find(key); found != loaded_.end()) return found->second;
        int32_t index = kNoTexture;
        try {
            textures_.push_back(Texture::from_image(image(ref), encoding));
            index = int32_t(textures_.size() - 1);
        } catch (const std::exception& e) {
            warnings_.push_back("'" + model_.path.string() + "': material '" + material + "': " + role + " texture '" +
                                ref.name + "' not loaded (" + e.what() + "); rendering without it");
        }
        loaded_.emplace(key, index);
        return index;
    }

private:
    io::FloatImage image(const io::ModelTextureRef& ref) const {
        if (ref.embedded < 0) return io::read_image(ref.file);
        if (size_t(ref.embedded) >= model_.images.size()) throw Error("no such embedded image");
        const io::ModelImage& stored = model_.images[size_t(ref.embedded)];
        if (!stored.encoded.empty())
            return io::read_image_memory(stored.encoded, "embedded image '" + ref.name + "'", stored.format);
        io::FloatImage out;
        out.width = stored.width;
        out.height = stored.height;
        out.channels = 4;
        out.pixels.resize(stored.rgba.size());
        std::transform(stored.rgba.begin(), stored.rgba.end(), out.pixels.begin(),
                       [](uint8_t v) { return float(v) / 255.0f; });
        return out;
    }

    const io::ModelFile& model_;
    std::vector<Texture>& textures_;
    std::vector<std::string>& warnings_;
    std::map<std::string, int32_t> loaded_;
};

// The mean of one channel over a texture's last (1x1) mip level: the texture's average.
float texture_mean(const Texture& texture, int channel) {
    return texture.level(texture.level_count() - 1).at(0, 0)[channel];
}

}  // namespace

Material map_material(const io::ModelMaterial& m) {
    Material out;
    out.model = scene::ShadingModel::phong;
    const glm::vec3 base(m.base_colour);
    if (m.workflow == io::ModelWorkflow::metallic_roughness) {
        out.kd = base * (1.0f - m.metallic);
        out.ks = glm::mix(glm::vec3(0.04f), base, m.metallic);
        out.shine = blinn_phong_exponent(m.roughness);
    } else {
        out.kd = base;
        out.ks = m.specular;
        out.shine = m.shininess;
    }
    out.ka = out.kd;
    out.textured_ambient = true;
    out.wrap = m.clamp ? texture::TextureWrap::clamp : texture::TextureWrap::repeat;
    if (m.nearest) out.filter = texture::TextureFilter::nearest;
    switch (m.alpha) {
        case io::ModelAlpha::opaque: break;
        case io::ModelAlpha::mask:
            out.alpha_cutoff = std::max(m.alpha_cutoff, 1e-6f);
            out.opacity = m.base_colour.a;
            break;
        case io::ModelAlpha::blend:
            out.blend = true;
            out.opacity = m.base_colour.a;
            break;
    }
    return out;
}

ImportedModel import_model(const std::filesystem::path& path) {
    io::ModelFile file = io::read_model(path);
    ImportedModel model;
    model.lower = file.lower;
    model.upper = file.upper;
    model.stats = file.stats;
    model.warnings = std::move(file.warnings);
    TextureLoader loader(file, model.textures, model.warnings);
    for (const io::ModelMaterial& m : file.materials) {
        // Averaged metallic and roughness, before the mapping reads them.
        io::ModelMaterial averaged = m;
        if (m.metallic_roughness_texture) {
            const int32_t t = loader.load(*m.metallic_roughness_texture, TexelEncoding::linear, m.name,
                                          "metallic-roughness");
            if (t != kNoTexture) {
                averaged.roughness *= texture_mean(model.textures[size_t(t)], 1);  // glTF: green
                averaged.metallic *= texture_mean(model.textures[size_t(t)], 2);   // glTF: blue
            }
        }
        Material material = map_material(averaged);
        if (m.base_colour_texture)
            material.diffuse_texture = loader.load(*m.base_colour_texture, TexelEncoding::srgb, m.name, "base colour");
        if (m.normal_texture)
            material.normal_texture = loader.load(*m.normal_texture, TexelEncoding::linear, m.name, "normal");
        model.materials.push_back(material);
    }
    for (io::ModelPart& part : file.parts) {
        scene::Object object;
        object.name = part.name;
        object.geometry = std::make_shared<const Mesh>(std::move(part.mesh));
        object.material = part.material;
        model.objects.push_back(std::move(object));
    }
    return model;
}

void add_to_scene(scene::Scene& scene, ImportedModel&& model, const scene::Transform& transform,
                  const std::string& prefix, std::optional<uint32_t> material) {
    const int32_t texture_base = int32_t(scene.textures.size());
    const uint32_t material_base = uint32_t(scene.materials.size());
    if (!material) {
        for (Texture& t : model.textures) scene.textures.push_back(std::move(t));
        for (Material m : model.materials) {
            if (m.diffuse_texture != kNoTexture) m.diffuse_texture += texture_base;
            if (m.normal_texture != kNoTexture) m.normal_texture += texture_base;
            scene.materials.push_back(m);
        }
    }
    for (scene::Object& o : model.objects) {
        o.name = prefix + "/" + o.name;
        o.transform = transform;
        o.material = material ? *material : material_base + o.material;
        scene.objects.push_back(std::move(o));
    }
}

}  // namespace tessera::asset
