// Implicit fields for ray marching: a scalar f(p) over 3-D space with its analytic gradient.
// The surface is f = 0; f > 0 is inside the solid (the terrain
// f(p) = noise(p.xz) - p.y is positive below the ground), so the outward normal is
// -gradient / |gradient|.
//
// A marcher holds a `const ImplicitField&` and calls value() per step, sample() where it
// shades, or the batch forms for a packet of samples (structure of arrays, SIMD inside).
// The concrete classes are final, so a caller that knows the type gets inlined calls.
#pragma once
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

#include <array>
#include <cstddef>
#include <cstdint>

#include "procedural/dunes.h"
#include "procedural/fractal.h"
#include "procedural/simd_math.h"

namespace tessera::procedural {

struct FieldSample {
    float value;
    glm::vec3 gradient;
};

class ImplicitField {
public:
    virtual ~ImplicitField() = default;
    virtual float value(glm::vec3 p) const = 0;
    virtual FieldSample sample(glm::vec3 p) const = 0;
    glm::vec3 gradient(glm::vec3 p) const { return sample(p).gradient; }

    // n points (x[i], y[i], z[i]); writes value[i] (and the gradient), what value() and
    // sample() give at each point, bit for bit. The base versions loop over value() and
    // sample(); the fields below override them with vectorised loops.
    virtual void value_batch(size_t n, const float* x, const float* y, const float* z,
                             float* value) const;
    virtual void sample_batch(size_t n, const float* x, const float* y, const float* z,
                              float* value, float* gx, float* gy, float* gz) const;
};

// A 3-D noise of 16 sines with wave vectors from the
// 16-bit rotations of s = (7502, 22777, 4767),
//   f(r) = sum_i sin(dot(s_i - 32768, 40 r) / 65536) / 32 + 0.5 - r.y.
// Its gradient is sum_i cos(...) (s_i - 32768) 40 / 65536 / 32 - (0, 1, 0). (The GLSL original's
// fGrad omits the 1/32 of the noise term, which exaggerates the noise relative to the
// -(0,1,0) plane term; this is the exact gradient of f, checked by finite differences.)
class SineNoiseField final : public ImplicitField {
public:
    SineNoiseField();
    float value(glm::vec3 r) const override {
        float w = 0.0f;
        for (const glm::vec3& k : waves_) {
            float s, c;
            sincos_approx(k.x * r.x + k.y * r.y + k.z * r.z, s, c);
            w += s;
        }
        return w * (1.0f / 32.0f) + 0.5f - r.y;
    }
    FieldSample sample(glm::vec3 r) const override {
        float w = 0.0f;
        glm::vec3 g(0.0f);
        for (const glm::vec3& k : waves_) {
            float s, c;
            sincos_approx(k.x * r.x + k.y * r.y + k.z * r.z, s, c);
            w += s;
            g += c * k;
        }
        return {w * (1.0f / 32.0f) + 0.5f - r.y, g * (1.0f / 32.0f) - glm::vec3(0.0f, 1.0f, 0.0f)};
    }
    void value_batch(size_t n, const float* x, const float* y, const float* z,
                     float* value) const override;
    void sample_batch(size_t n, const float* x, const float* y, const float* z, float* value,
                      float* gx, float* gy, float* gz) const override;

    // The wave vectors (s_i - 32768) * 40 / 65536, i = 0..15.
    const std::array<glm::vec3, 16>& waves() const { return waves_; }

private:
    std::array<glm::vec3, 16> waves_;
};

// The relief h(x, z) of a terrain, with its gradient (dh/dx, dh/dz).
enum class Relief { fbm, ridged, warped, dunes };

struct TerrainParams {
    Relief relief = Relief::fbm;
    Fractal fractal{};
    float frequency = 0.01f;  // noise(p.xz * 0.01): gentle swells ~100 units wide
    float amplitude = 1.0f;   // height of the relief's [0, 1] range above `base`
    float base = 0.0f;
    float warp = 1.0f;        // domain-warp amount (Relief::warped)
    Dunes dunes{};            // Relief::dunes (its wavelength is in frequency-scaled units)
};

// Heightfield terrain as an implicit field: f(p) = h(p.x, p.z) - p.y.
// h lies within [base, base + amplitude] for fbm, ridged and warped relief (dunes may exceed
// by the ripple amplitude), which gives a marcher its entry and exit planes.
class TerrainField final : public ImplicitField {
public:
    explicit TerrainField(const TerrainParams& params);

    // h and (dh/dx, dh/dz) at ground position (x, z).
    Noise2 height(float x, float z) const {
        const glm::vec2 q = glm::vec2(x, z) * p_.frequency;
        Noise2 r;
        switch (p_.relief) {
            case Relief::fbm: r = fbm(q, p_.fractal); break;
            case Relief::ridged: r = ridged(q, p_.fractal); break;
            case Relief::warped: r = domain_warp(q, p_.fractal, p_.warp); break;
            case Relief::dunes: r = dunes(q, p_.dunes); break;
        }
        return height_of_relief(r);
    }
    float value(glm::vec3 p) const override { return height(p.x, p.z).value - p.y; }
    FieldSample sample(glm::vec3 p) const override {
        const Noise2 h = height(p.x, p.z);
        return {h.value - p.y, {h.gradient.x, -1.0f, h.gradient.y}};
    }
    void value_batch(size_t n, const float* x, const float* y, const float* z,
                     float* value) const override;
    void sample_batch(size_t n, const float* x, const float* y, const float* z, float* value,
                      float* gx, float* gy, float* gz) const override;

    const TerrainParams& params() const { return p_; }

private:
    // h from the relief r at q = (x, z) * frequency (fbm and warped relief map [-1, 1] to
    // [0, 1]): height() and the batch forms both finish with it.
    TESSERA_NOISE_INLINE Noise2 height_of_relief(Noise2 r) const {
        if (p_.relief == Relief::fbm || p_.relief == Relief::warped) {
            r.value = 0.5f * r.value + 0.5f;
            r.gradient *= 0.5f;
        }
        return {p_.base + p_.amplitude * r.value, (p_.amplitude * p_.frequency) * r.gradient};
    }
    // The relief over n points q, through the batch form of fractal_batch.h or
    // dunes.h; dq/dx and dq/dz null: values only.
    void relief_batch(size_t n, const float* qx, const float* qz, float* r, float* dqx, float* dqz) const;
    template <bool kGradient>
    void heights(size_t n, const float* x, const float* y, const float* z, float* value, float* gx, float* gz) const;

    TerrainParams p_;
};

// 3-D noise volume: f(p) = base + amplitude * fbm3(p * frequency) - p.y, ground with
// overhangs, arches and floating pieces (3-D value noise instead of sines).
struct VolumeParams {
    Fractal fractal{};
    float frequency = 1.0f;
    float amplitude = 0.5f;
    float base = 0.5f;
};

class NoiseVolumeField final : public ImplicitField {
public:
    explicit NoiseVolumeField(const VolumeParams& params);
    float value(glm::vec3 p) const override { return sample(p).value; }
    FieldSample sample(glm::vec3 p) const override { return sample_of(p, fbm(p * p_.frequency, p_.fractal)); }
    void value_batch(size_t n, const float* x, const float* y, const float* z,
                     float* value) const override;
    void sample_batch(size_t n, const float* x, const float* y, const float* z, float* value,
                      float* gx, float* gy, float* gz) const override;

    const VolumeParams& params() const { return p_; }

private:
    // f and its gradient at p from n = fbm(p * frequency): sample() and the batch forms both
    // finish with it.
    TESSERA_NOISE_INLINE FieldSample sample_of(glm::vec3 p, Noise3 n) const {
        return {p_.base + p_.amplitude * n.value - p.y,
                (p_.amplitude * p_.frequency) * n.gradient - glm::vec3(0.0f, 1.0f, 0.0f)};
    }
    template <bool kGradient>
    void samples(size_t n, const float* x, const float* y, const float* z, float* value, float* gx, float* gy,
                 float* gz) const;

    VolumeParams p_;
};

}  // namespace tessera::procedural
