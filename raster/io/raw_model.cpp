#include "raster/io/raw_model.h"

#include <cstring>
#include <optional>
#include <type_traits>

#include "raster/core/error.h"

namespace tessera::io {
namespace {

constexpr uint32_t kMagic = 0x4D525354;  // "TSRM"

class Writer {
public:
    template <class T>
    void pod(const T& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        const auto* p = reinterpret_cast<const uint8_t*>(&v);
        out.insert(out.end(), p, p + sizeof(T));
    }
    template <class T>
    void array(const std::vector<T>& v) {
        static_assert(std::is_trivially_copyable_v<T>);
        pod(uint64_t(v.size()));
        const auto* p = reinterpret_cast<const uint8_t*>(v.data());
        out.insert(out.end(), p, p + v.size() * sizeof(T));
    }
    void text(const std::string& s) { array(std::vector<char>(s.begin(), s.end())); }
    std::vector<uint8_t> out;
};

class Reader {
public:
    explicit Reader(const std::vector<uint8_t>& bytes) : bytes_(bytes) {}
    template <class T>
    T pod() {
        T v;
        take(&v, sizeof(T));
        return v;
    }
    template <class T>
    std::vector<T> array() {
        const uint64_t n = pod<uint64_t>();
        if (n > (bytes_.size() - at_) / sizeof(T)) throw Error("the importer's result is truncated");
        std::vector<T> v(static_cast<size_t>(n));
        take(v.data(), size_t(n) * sizeof(T));
        return v;
    }
    std::string text() {
        const std::vector<char> c = array<char>();
        return {c.begin(), c.end()};
    }
    size_t count(size_t min_bytes_each) {
        const uint64_t n = pod<uint64_t>();
        if (n > (bytes_.size() - at_) / min_bytes_each) throw Error("the importer's result is truncated");
        return size_t(n);
    }
    bool done() const { return at_ == bytes_.size(); }

private:
    void take(void* to, size_t n) {
        if (n > bytes_.size() - at_) throw Error("the importer's result is truncated");
        if (n) std::memcpy(to, bytes_.data() + at_, n);
        at_ += n;
    }
    const std::vector<uint8_t>& bytes_;
    size_t at_ = 0;
};

void put(Writer& w, const std::optional<ModelTextureRef>& ref) {
    w.pod(uint8_t(ref.has_value()));
    if (!ref) return;
    w.text(ref->name);
    w.text(ref->file.string());
    w.pod(int32_t(ref->embedded));
}

std::optional<ModelTextureRef> get_ref(Reader& r) {
    if (!r.pod<uint8_t>()) return std::nullopt;
    ModelTextureRef ref;
    ref.name = r.text();
    ref.file = r.text();
    ref.embedded = r.pod<int32_t>();
    return ref;
}

}  // namespace

std::vector<uint8_t> to_bytes(const RawModel& m) {
    Writer w;
    w.pod(kMagic);
    w.pod(uint64_t(m.nodes.size()));
    for (const RawNode& n : m.nodes) {
        w.text(n.name);
        w.pod(n.parent);
        w.pod(n.transform);
        w.array(n.meshes);
    }
    w.pod(uint64_t(m.meshes.size()));
    for (const RawMesh& s : m.meshes) {
        w.text(s.name);
        w.pod(s.material);
        w.array(s.positions);
        w.array(s.normals);
        w.array(s.tangents);
        w.array(s.bitangents);
        w.array(s.uvs);
        w.array(s.triangles);
        w.pod(s.points_and_lines);
    }
    w.pod(uint64_t(m.materials.size()));
    for (const ModelMaterial& a : m.materials) {
        w.text(a.name);
        w.pod(a.workflow);
        w.pod(a.base_colour);
        w.pod(a.specular);
        w.pod(a.shininess);
        w.pod(a.metallic);
        w.pod(a.roughness);
        w.pod(a.alpha);
        w.pod(a.alpha_cutoff);
        w.pod(uint8_t(a.clamp));
        w.pod(uint8_t(a.nearest));
        put(w, a.base_colour_texture);
        put(w, a.normal_texture);
        put(w, a.metallic_roughness_texture);
    }
    w.pod(uint64_t(m.images.size()));
    for (const ModelImage& i : m.images) {
        w.text(i.name);
        w.text(i.format);
        w.array(i.encoded);
        w.pod(int32_t(i.width));
        w.pod(int32_t(i.height));
        w.array(i.rgba);
    }
    w.pod(uint64_t(m.warnings.size()));
    for (const std::string& s : m.warnings) w.text(s);
    return std::move(w.out);
}

RawModel raw_model_from_bytes(const std::vector<uint8_t>& bytes) {
    Reader r(bytes);
    if (r.pod<uint32_t>() != kMagic) throw Error("the importer's result is corrupt");
    RawModel m;
    // Each record takes at least 8 bytes (a length), which bounds the counts by the input.
    m.nodes.resize(r.count(8));
    for (RawNode& n : m.nodes) {
        n.name = r.text();
        n.parent = r.pod<int32_t>();
        n.transform = r.pod<glm::mat4>();
        n.meshes = r.array<uint32_t>();
    }
    m.meshes.resize(r.count(8));
    for (RawMesh& s : m.meshes) {
        s.name = r.text();
        s.material = r.pod<uint32_t>();
        s.positions = r.array<glm::vec3>();
        s.normals = r.array<glm::vec3>();
        s.tangents = r.array<glm::vec3>();
        s.bitangents = r.array<glm::vec3>();
        s.uvs = r.array<glm::vec2>();
        s.triangles = r.array<uint32_t>();
        s.points_and_lines = r.pod<uint64_t>();
    }
    m.materials.resize(r.count(8));
    for (ModelMaterial& a : m.materials) {
        a.name = r.text();
        a.workflow = r.pod<ModelWorkflow>();
        a.base_colour = r.pod<glm::vec4>();
        a.specular = r.pod<glm::vec3>();
        a.shininess = r.pod<float>();
        a.metallic = r.pod<float>();
        a.roughness = r.pod<float>();
        a.alpha = r.pod<ModelAlpha>();
        a.alpha_cutoff = r.pod<float>();
        a.clamp = r.pod<uint8_t>() != 0;
        a.nearest = r.pod<uint8_t>() != 0;
        a.base_colour_texture = get_ref(r);
        a.normal_texture = get_ref(r);
        a.metallic_roughness_texture = get_ref(r);
    }
    m.images.resize(r.count(8));
    for (ModelImage& i : m.images) {
        i.name = r.text();
        i.format = r.text();
        i.encoded = r.array<uint8_t>();
        i.width = r.pod<int32_t>();
        i.height = r.pod<int32_t>();
        i.rgba = r.array<uint8_t>();
    }
    m.warnings.resize(r.count(8));
    for (std::string& s : m.warnings) s = r.text();
    if (!r.done()) throw Error("the importer's result is corrupt");
    return m;
}

}  // namespace tessera::io
