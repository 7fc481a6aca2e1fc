#include "raster/march/march_scene.h"

#include <cmath>
#include <stdexcept>

#include "procedural/field.h"
#include "raster/march/background_pass.h"
#include "raster/march/fog_pass.h"
#include "raster/march/metaball_field.h"
#include "raster/march/metaball_orbits.h"
#include "raster/march/procedural_surfaces.h"
#include "raster/march/surface_pass.h"
#include "raster/march/tile_passes.h"

namespace tessera::march {

MarchSceneKind parse_march_scene(const std::string& name) {
    if (name == "terrain") return MarchSceneKind::terrain;
    if (name == "sine-noise") return MarchSceneKind::sine_noise;
    if (name == "noise-volume") return MarchSceneKind::noise_volume;
    if (name == "gradient-noise") return MarchSceneKind::gradient_noise;
    if (name == "metaballs") return MarchSceneKind::metaballs;
    throw std::invalid_argument("unknown march scene '" + name +
                                "' (expected terrain, sine-noise, noise-volume, gradient-noise or metaballs)");
}

// The fields live here so the passes can borrow them for the scene's lifetime.
struct MarchScene::Fields {
    std::unique_ptr<procedural::TerrainField> terrain;
    std::unique_ptr<procedural::SineNoiseField> sine_noise;
    std::unique_ptr<procedural::NoiseVolumeField> volume;
    GradientNoiseField gradient_noise;
    std::unique_ptr<MetaballField> metaballs;
};

namespace {

// The classic terrain is noise(p.xz * 0.01) - p.y between y = 0 and 1: gentle swells 100 units
// wide. The scene scales it up so the relief reads at a glance.
procedural::TerrainParams terrain_params() {
    procedural::TerrainParams p;
    p.frequency = 0.03f;
    p.amplitude = 8.0f;
    return p;
}

Camera scene_camera(MarchSceneKind kind, float t, float aspect) {
    Camera c;
    c.aspect = aspect;
    c.near = 0.05f;
    c.far = 50.0f;
    switch (kind) {
    case MarchSceneKind::terrain:
        // Hills ~30 units wide and up to 8 high (terrain_params), seen from above them.
        c.eye = {4.0f * t, 9.0f, 2.0f * t};
        c.lookat = c.eye + glm::vec3(60.0f, -12.0f, 40.0f);
        c.far = 400.0f;
        break;
    case MarchSceneKind::sine_noise:
        c.eye = {0.3f * t, 1.3f, 3.0f};
        c.lookat = {0.5f + 0.3f * t, 0.4f, 0.0f};
        break;
    case MarchSceneKind::noise_volume:
    case MarchSceneKind::gradient_noise:
        c.eye = {4.0f * std::sin(0.2f * t), 1.5f, 4.0f * std::cos(0.2f * t)};
        c.lookat = {0.0f, 0.3f, 0.0f};
        break;
    case MarchSceneKind::metaballs:
        c.eye = {4.5f * std::sin(0.3f * t), 1.2f, 4.5f * std::cos(0.3f * t)};
        c.lookat = {0.0f, 0.0f, 0.0f};
        break;
    }
    return c;
}

template <class Surface>
std::function<void(const Tile&)> surface_pass(Surface surface, const RayGenerator& rays,
                                                    const MarchSceneSettings& s) {
    const SurfaceLook look{s.material, SurfaceLook{}.lights, s.normals};
    auto pass = std::make_shared<SurfacePass<Surface>>(surface, rays, s.march, look, s.background);
    return [pass](const Tile& target) { pass->run(target); };
}

}  // namespace

MarchScene::MarchScene(const MarchSceneSettings& settings, int width, int height)
    : settings_(settings), fields_(std::make_unique<Fields>()) {
    if (!std::isfinite(settings.time))
        throw std::invalid_argument("march scene: time must be finite");
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("march scene: size must be positive");
    camera_ = scene_camera(settings.kind, settings.time, float(width) / float(height));
    rays_ = std::make_unique<RayGenerator>(camera_, width, height);
    const RayGenerator& rays = *rays_;
    switch (settings.kind) {
    case MarchSceneKind::terrain:
        fields_->terrain = std::make_unique<procedural::TerrainField>(terrain_params());
        surface_ = surface_pass(terrain_surface(*fields_->terrain), rays, settings_);
        break;
    case MarchSceneKind::sine_noise:
        fields_->sine_noise = std::make_unique<procedural::SineNoiseField>();
        surface_ = surface_pass(sine_noise_surface(*fields_->sine_noise), rays, settings_);
        break;
    case MarchSceneKind::noise_volume:
        fields_->volume = std::make_unique<procedural::NoiseVolumeField>(procedural::VolumeParams{});
        surface_ = surface_pass(noise_volume_surface(*fields_->volume), rays, settings_);
        break;
    case MarchSceneKind::gradient_noise:
        surface_ = surface_pass(gradient_noise_surface(fields_->gradient_noise), rays, settings_);
        break;
    case MarchSceneKind::metaballs:
        if (settings.balls < 3)
            throw std::invalid_argument("metaballs: at least 3 balls, got " + std::to_string(settings.balls));
        fields_->metaballs = std::make_unique<MetaballField>(
            orbiting_metaballs(settings.balls, settings.time), MetaballStyle{settings.kernel, 0.5f});
        surface_ = surface_pass(MetaballSurface{*fields_->metaballs}, rays, settings_);
        break;
    }
    auto background = std::make_shared<BackgroundPass>(rays, settings_.background);
    background_ = [background](const Tile& t) { background->run(t); };
    auto fog = std::make_shared<FogPass>(rays, settings_.fog);
    fog_ = [fog](const Tile& t) { fog->run(t); };
}

MarchScene::~MarchScene() = default;

std::vector<pipeline::TilePass> MarchScene::passes() const {
    std::vector<pipeline::TilePass> out;
    for (const auto* pass : {&background_, &surface_, &fog_})
        out.push_back([pass](const pipeline::TileContext& tile) { (*pass)(tile); });
    return out;
}

}  // namespace tessera::march
