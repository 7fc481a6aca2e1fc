// A ready-made ray-marched scene for one frame (terrain, noise surfaces, metaballs): the terrain,
// the 16-sine noise surface, the value-noise volume, the gradient-noise surface or animated
// metaballs, with the
// background and optional fog, as the tile passes the rasterizer runs. The `tessera march`
// command renders one; the render command can put its passes after the opaque shading of a
// triangle scene so both share one depth buffer.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "raster/core/camera.h"
#include "raster/march/fog.h"
#include "raster/march/march_settings.h"
#include "raster/march/metaball_kernel.h"
#include "raster/core/tile.h"
#include "raster/march/ray_generation.h"
#include "raster/march/surface_normal.h"
#include "raster/march/surface_shading.h"
#include "raster/scene/background.h"
#include "raster/pipeline/tile_pass.h"

namespace tessera::march {

enum class MarchSceneKind { terrain, sine_noise, noise_volume, gradient_noise, metaballs };

// "terrain", "sine-noise", "noise-volume", "gradient-noise", "metaballs"; throws
// std::invalid_argument otherwise.
MarchSceneKind parse_march_scene(const std::string& name);

struct MarchSceneSettings {
    MarchSceneKind kind = MarchSceneKind::metaballs;
    float time = 0.0f;  // seconds: moves the metaballs and the terrain camera
    MetaballKernel kernel = MetaballKernel::wyvill;
    int balls = 5;  // at least 3 (a blob needs company)
    MarchSettings march{};
    NormalSettings normals{};
    SurfaceMaterial material{};
    Fog fog{};
    scene::Background background = sky();

    static scene::Background sky() {
        scene::Background b;
        b.kind = scene::Background::Kind::sky;
        return b;
    }
};

class MarchScene {
public:
    // Throws std::invalid_argument for bad settings (fewer than 3 balls, zero steps, negative
    // fog density, NaN, ...) or a bad size.
    MarchScene(const MarchSceneSettings& settings, int width, int height);
    ~MarchScene();
    MarchScene(const MarchScene&) = delete;
    MarchScene& operator=(const MarchScene&) = delete;

    // The scene's own camera at the settings' time (the view each scene was designed for).
    const Camera& camera() const { return camera_; }

    // {background, marched surface, fog}; they borrow this object.
    std::vector<pipeline::TilePass> passes() const;

private:
    struct Fields;
    MarchSceneSettings settings_;
    Camera camera_;
    std::unique_ptr<RayGenerator> rays_;
    std::unique_ptr<Fields> fields_;
    std::function<void(const Tile&)> surface_;
    std::function<void(const Tile&)> background_;
    std::function<void(const Tile&)> fog_;
};

}  // namespace tessera::march
