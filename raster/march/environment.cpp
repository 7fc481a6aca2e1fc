#include "raster/march/environment.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera::march {

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

const char* const kFaceNames[6] = {"+x", "-x", "+y", "-y", "+z", "-z"};

// IEC 61966-2-1 decode, for the 8/16-bit faces.
float srgb_decode(float e) {
    e = std::clamp(e, 0.0f, 1.0f);
    return e <= 0.04045f ? e / 12.92f : std::pow((e + 0.055f) / 1.055f, 2.4f);
}

bool stored_linear(const std::filesystem::path& path) {
    std::string ext = path.extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return ext == ".exr" || ext == ".hdr" || ext == ".pfm";
}

}  // namespace

Environment Environment::procedural(const Sky& sky) {
    if (!finite(sky.zenith) || !finite(sky.horizon) || !finite(sky.ground) || !finite(sky.sun_colour))
        throw std::invalid_argument("sky: colours must be finite");
    const float len = glm::length(sky.sun_direction);
    if (!(len > 0.0f) || !std::isfinite(len))
        throw std::invalid_argument("sky: the sun direction must be a finite non-zero vector");
    if (!(sky.sun_sharpness > 0.0f) || !std::isfinite(sky.sun_sharpness))
        throw std::invalid_argument("sky: sun sharpness must be positive and finite, got " +
                                    std::to_string(sky.sun_sharpness));
    Environment env;
    env.sky_ = sky;
    env.sun_ = sky.sun_direction / len;
    return env;
}

Environment Environment::cube_map(std::array<FloatImage, 6> faces) {
    const int size = faces[0].width;
    for (int f = 0; f < 6; ++f) {
        const FloatImage& face = faces[f];
        if (face.width <= 0 || face.width != face.height || face.width != size)
            throw std::invalid_argument(std::string("cube map: face ") + kFaceNames[f] + " is " +
                                        std::to_string(face.width) + "x" + std::to_string(face.height) +
                                        "; all six faces must be square and of one size (" +
                                        std::to_string(size) + ")");
        if (face.channels < 3 ||
            face.pixels.size() != size_t(face.width) * size_t(face.height) * size_t(face.channels))
            throw std::invalid_argument(std::string("cube map: face ") + kFaceNames[f] +
                                        " needs at least three channels");
    }
    Environment env;
    env.faces_ = std::move(faces);
    return env;
}

Environment Environment::load_cube_map(const std::array<std::filesystem::path, 6>& paths) {
    std::array<FloatImage, 6> faces;
    for (int f = 0; f < 6; ++f) {
        faces[f] = read_image(paths[f]);
        if (!stored_linear(paths[f]))
            for (size_t i = 0; i < faces[f].pixels.size(); ++i)
                if (faces[f].channels < 4 || i % size_t(faces[f].channels) != 3)  // alpha is linear
                    faces[f].pixels[i] = srgb_decode(faces[f].pixels[i]);
    }
    return cube_map(std::move(faces));
}

glm::vec3 Environment::radiance(glm::vec3 d) const {
    return is_cube_map() ? cube_radiance(d) : sky_radiance(d);
}

glm::vec3 Environment::sky_radiance(glm::vec3 d) const {
    d = glm::normalize(d);
    glm::vec3 base;
    if (d.y >= 0.0f) {
        // sqrt of the elevation keeps the horizon band bright and narrow.
        base = glm::mix(sky_.horizon, sky_.zenith, std::sqrt(d.y));
    } else {
        // A short blend below the horizon avoids a hard seam at d.y = 0.
        base = glm::mix(sky_.horizon, sky_.ground, std::min(1.0f, -d.y * 8.0f));
    }
    const float c = std::max(glm::dot(d, sun_), 0.0f);
    return base + sky_.sun_colour * std::pow(c, sky_.sun_sharpness);
}

glm::vec3 Environment::cube_radiance(glm::vec3 d) const {
    // OpenGL cube map selection: the major axis picks the face, (sc, tc) / |ma| the point on it.
    const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    int face;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        face = d.x >= 0.0f ? 0 : 1;
        sc = d.x >= 0.0f ? -d.z : d.z;
        tc = -d.y;
        ma = ax;
    } else if (ay >= az) {
        face = d.y >= 0.0f ? 2 : 3;
        sc = d.x;
        tc = d.y >= 0.0f ? d.z : -d.z;
        ma = ay;
    } else {
        face = d.z >= 0.0f ? 4 : 5;
        sc = d.z >= 0.0f ? d.x : -d.x;
        tc = -d.y;
        ma = az;
    }
    if (!(ma > 0.0f)) return glm::vec3(0.0f);  // zero or NaN direction
    const FloatImage& img = faces_[face];
    const int n = img.width;
    // Texel centres at (i + 0.5) / n; clamp to the face (no filtering across face seams).
    const float u = std::clamp((sc / ma * 0.5f + 0.5f) * float(n) - 0.5f, 0.0f, float(n - 1));
    const float v = std::clamp((tc / ma * 0.5f + 0.5f) * float(n) - 0.5f, 0.0f, float(n - 1));
    const int x0 = int(u), y0 = int(v);
    const int x1 = std::min(x0 + 1, n - 1), y1 = std::min(y0 + 1, n - 1);
    const float fx = u - float(x0), fy = v - float(y0);
    auto texel = [&img](int x, int y) { return glm::vec3(img.at(x, y, 0), img.at(x, y, 1), img.at(x, y, 2)); };
    return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), fx), glm::mix(texel(x0, y1), texel(x1, y1), fx), fy);
}

}  // namespace tessera::march
