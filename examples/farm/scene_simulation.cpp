#include "examples/farm/scene_simulation.h"

#include <cstring>
#include <stdexcept>
#include <string>

#include "procedural/rd_presets.h"
#include "raster/core/error.h"
#include "raster/scene_file/rd_texture.h"

namespace tessera::farm {

namespace {

constexpr char kMagic[8] = {'T', 'S', 'S', 'I', 'M', '0', '0', '1'};

// FNV-1a, 64 bit: a checksum for damage, not an adversary.
struct Fnv {
    uint64_t h = 0xcbf29ce484222325ull;
    void bytes(const void* p, size_t n) {
        const auto* b = static_cast<const unsigned char*>(p);
        for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 0x100000001b3ull;
    }
    template <class T> void value(const T& v) { bytes(&v, sizeof v); }
};

template <class T> void put(std::vector<std::byte>& out, const T& v) {
    const auto* p = reinterpret_cast<const std::byte*>(&v);
    out.insert(out.end(), p, p + sizeof v);
}

struct Reader {
    std::span<const std::byte> in;
    size_t at = 0;
    const std::string& what;
    void get(void* dst, size_t n) {
        if (in.size() - at < n) throw Error("checkpoint '" + what + "' is truncated");
        std::memcpy(dst, in.data() + at, n);
        at += n;
    }
    template <class T> T get() {
        T v;
        get(&v, sizeof v);
        return v;
    }
};

}  // namespace

SceneSimulation::SceneSimulation(std::span<const scene_file::TextureSpec> textures) {
    Fnv f;
    f.bytes(kMagic, sizeof kMagic);
    for (size_t i = 0; i < textures.size(); ++i) {
        const scene_file::TextureSpec& t = textures[i];
        if (t.kind != scene_file::TextureSpec::Kind::reaction_diffusion || t.grow_per_frame == 0) continue;
        skins_.push_back(Skin{i, t, scene_file::rd_simulation(t), 0});
        const procedural::RdPreset* preset = procedural::find_rd_preset(t.preset);
        f.value(uint64_t(i));
        f.value(preset->feed);
        f.value(preset->kill);
        f.value(t.size);
        f.value(t.seed);
        f.value(t.steps);
        f.value(t.grow_per_frame);
        f.value(t.anisotropy);
    }
    fingerprint_ = f.h;
}

void SceneSimulation::advance_to(int frame) {
    if (frame < 0) throw std::invalid_argument("simulated frames start at 0, got " + std::to_string(frame));
    if (frame_ && frame < *frame_) {
        for (Skin& s : skins_) {
            s.rd = scene_file::rd_simulation(s.spec);
            s.steps = 0;
        }
    }
    for (Skin& s : skins_) {
        const int64_t target = s.steps_for(frame);
        // ReactionDiffusion::step takes an int: run long gaps in int-sized pieces.
        while (s.steps < target) {
            const int n = int(std::min<int64_t>(target - s.steps, 1 << 30));
            s.rd.step(n);
            s.steps += n;
        }
    }
    frame_ = frame;
}

void SceneSimulation::apply(render::AnimatedScene& scene) const {
    for (const Skin& s : skins_) scene.scene.textures[s.texture] = scene_file::rd_texture(s.rd.state(), s.spec);
}

size_t SceneSimulation::checkpoint_size() const {
    size_t n = sizeof kMagic + 8 + 8 + 8 + 8;
    for (const Skin& s : skins_) n += 8 + 8 + 2 * s.rd.state().a.size() * sizeof(float);
    return n;
}

std::vector<std::byte> SceneSimulation::checkpoint() const {
    if (!frame_) throw std::logic_error("checkpoint of a simulation that holds no frame");
    std::vector<std::byte> out;
    out.reserve(checkpoint_size());
    for (char c : kMagic) put(out, c);
    put(out, fingerprint_);
    put(out, int64_t(*frame_));
    put(out, uint64_t(skins_.size()));
    for (const Skin& s : skins_) {
        const procedural::RdState& st = s.rd.state();
        put(out, s.steps);
        put(out, int32_t(st.a.width));
        put(out, int32_t(st.a.height));
        const auto* a = reinterpret_cast<const std::byte*>(st.a.values.data());
        const auto* b = reinterpret_cast<const std::byte*>(st.b.values.data());
        out.insert(out.end(), a, a + st.a.size() * sizeof(float));
        out.insert(out.end(), b, b + st.b.size() * sizeof(float));
    }
    Fnv sum;
    sum.bytes(out.data(), out.size());
    put(out, sum.h);
    return out;
}

void SceneSimulation::restore(std::span<const std::byte> bytes, const std::string& what) {
    if (bytes.size() < sizeof kMagic + 8) throw Error("checkpoint '" + what + "' is truncated");
    Fnv sum;
    sum.bytes(bytes.data(), bytes.size() - 8);
    uint64_t stored;
    std::memcpy(&stored, bytes.data() + bytes.size() - 8, 8);
    if (stored != sum.h) throw Error("checkpoint '" + what + "' is damaged (checksum mismatch)");
    Reader r{bytes.first(bytes.size() - 8), 0, what};
    char magic[8];
    r.get(magic, 8);
    if (std::memcmp(magic, kMagic, 8) != 0) throw Error("'" + what + "' is not a tessera simulation checkpoint");
    if (r.get<uint64_t>() != fingerprint_)
        throw Error("checkpoint '" + what + "' was made by a scene with other simulation parameters");
    const int64_t frame = r.get<int64_t>();
    if (r.get<uint64_t>() != skins_.size()) throw Error("checkpoint '" + what + "' holds another number of skins");
    std::vector<procedural::RdState> states;
    std::vector<int64_t> steps;
    for (const Skin& s : skins_) {
        steps.push_back(r.get<int64_t>());
        const int w = r.get<int32_t>(), h = r.get<int32_t>();
        if (w != s.spec.size || h != s.spec.size || steps.back() != s.steps_for(int(frame)))
            throw Error("checkpoint '" + what + "' does not match the scene's skins");
        procedural::RdState st{procedural::Grid(w, h), procedural::Grid(w, h)};
        r.get(st.a.values.data(), st.a.size() * sizeof(float));
        r.get(st.b.values.data(), st.b.size() * sizeof(float));
        states.push_back(std::move(st));
    }
    if (r.at != r.in.size()) throw Error("checkpoint '" + what + "' has trailing bytes");
    for (size_t i = 0; i < skins_.size(); ++i) {
        skins_[i].rd = procedural::ReactionDiffusion(skins_[i].rd.params(), std::move(states[i]));
        skins_[i].steps = steps[i];
    }
    frame_ = int(frame);
}

}  // namespace tessera::farm
