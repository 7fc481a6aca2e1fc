#include "raster/scene/material.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tessera::scene {
namespace {

[[noreturn]] void bad(const std::string& what) {
    throw std::invalid_argument("material parameter " + what);
}

glm::vec3 colour(const MaterialParameter& p) {
    for (float x : p.numbers)
        if (!std::isfinite(x) || x < 0.0f) bad("'" + p.name + "' must be non-negative numbers");
    if (p.numbers.size() == 1) return glm::vec3(p.numbers[0]);
    if (p.numbers.size() == 3) return {p.numbers[0], p.numbers[1], p.numbers[2]};
    bad("'" + p.name + "' takes 1 or 3 numbers, got " + std::to_string(p.numbers.size()));
}

float scalar(const MaterialParameter& p) {
    if (p.numbers.size() != 1 || !std::isfinite(p.numbers[0]))
        bad("'" + p.name + "' takes one finite number");
    return p.numbers[0];
}

// Which parameters each model reads; the others are legal but pointless, hence a warning.
bool model_uses(ShadingModel model, std::string_view name) {
    switch (model) {
        case ShadingModel::toon: return name != "ka" && name != "ks" && name != "shine";
        case ShadingModel::gouraud:
            // Per-vertex colour: textures would need per-pixel lighting to be meaningful.
            return name != "filter" && name != "wrap" && name != "uv_scale";
        case ShadingModel::flat:
        case ShadingModel::phong: return true;
    }
    return true;
}

}  // namespace

const char* to_string(ShadingModel model) {
    switch (model) {
        case ShadingModel::flat: return "flat";
        case ShadingModel::gouraud: return "gouraud";
        case ShadingModel::phong: return "phong";
        case ShadingModel::toon: return "toon";
    }
    return "?";
}

ShadingModel parse_shading_model(std::string_view name) {
    for (ShadingModel m : {ShadingModel::flat, ShadingModel::gouraud, ShadingModel::phong,
                           ShadingModel::toon})
        if (name == to_string(m)) return m;
    bad("'model': unknown shading model '" + std::string(name) +
        "' (expected flat, gouraud, phong or toon)");
}

texture::TextureFilter parse_texture_filter(std::string_view name) {
    if (name == "nearest") return texture::TextureFilter::nearest;
    if (name == "bilinear") return texture::TextureFilter::bilinear;
    if (name == "mipmap") return texture::TextureFilter::mipmap;
    if (name == "trilinear") return texture::TextureFilter::trilinear;
    bad("'filter': unknown filter '" + std::string(name) +
        "' (expected nearest, bilinear, mipmap or trilinear)");
}

texture::TextureWrap parse_texture_wrap(std::string_view name) {
    if (name == "repeat") return texture::TextureWrap::repeat;
    if (name == "clamp") return texture::TextureWrap::clamp;
    bad("'wrap': unknown wrap mode '" + std::string(name) + "' (expected repeat or clamp)");
}

std::vector<std::string> set_material_parameters(Material& material,
                                                 std::span<const MaterialParameter> parameters) {
    auto model = std::find_if(parameters.begin(), parameters.end(),
                              [](const MaterialParameter& p) { return p.name == "model"; });
    if (model != parameters.end()) material.model = parse_shading_model(model->word);

    std::vector<std::string> warnings;
    for (const MaterialParameter& p : parameters) {
        if (p.name == "model") continue;
        if (p.name == "ka") material.ka = colour(p);
        else if (p.name == "kd") material.kd = colour(p);
        else if (p.name == "ks") material.ks = colour(p);
        else if (p.name == "shine") {
            material.shine = scalar(p);
            if (material.shine < 0.0f) bad("'shine' must be >= 0");
        } else if (p.name == "opacity") {
            material.opacity = scalar(p);
            if (material.opacity < 0.0f || material.opacity > 1.0f)
                bad("'opacity' must lie in [0, 1]");
        } else if (p.name == "filter") material.filter = parse_texture_filter(p.word);
        else if (p.name == "wrap") material.wrap = parse_texture_wrap(p.word);
        else if (p.name == "uv_scale") {
            if (p.numbers.size() != 2 || !std::isfinite(p.numbers[0]) ||
                !std::isfinite(p.numbers[1]))
                bad("'uv_scale' takes two finite numbers");
            material.uv_scale = {p.numbers[0], p.numbers[1]};
        } else {
            warnings.push_back("material parameter '" + p.name + "' is unknown; ignored");
            continue;
        }
        if (!model_uses(material.model, p.name))
            warnings.push_back("material parameter '" + p.name + "' is not used by the " +
                               to_string(material.model) + " model; ignored");
    }
    return warnings;
}

}  // namespace tessera::scene
