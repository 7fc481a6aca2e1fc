#include "raster/io/mesh_weld.h"

#include <bit>
#include <cstdint>
#include <cstring>
#include <vector>

namespace tessera::io {
namespace {

// The attribute streams a vertex is made of, hashed and compared in place (no key copies: a
// face-indexed 1M-triangle mesh has 3M vertices).
struct Streams {
    const Mesh& mesh;
    bool normals, uvs, tangents;

    static uint64_t mix(uint64_t h, const void* data, size_t bytes) {
        // The multiply-xorshift step of splitmix64, per 32-bit word.
        for (size_t i = 0; i < bytes; i += 4) {
            uint32_t w;
            std::memcpy(&w, static_cast<const char*>(data) + i, 4);
            h ^= w;
            h *= 0xBF58476D1CE4E5B9ull;
            h ^= h >> 31;
        }
        return h;
    }
    uint64_t hash(size_t v) const {
        uint64_t h = mix(0x9E3779B97F4A7C15ull, &mesh.positions[v], sizeof(glm::vec3));
        if (normals) h = mix(h, &mesh.normals[v], sizeof(glm::vec3));
        if (uvs) h = mix(h, &mesh.uvs[v], sizeof(glm::vec2));
        if (tangents) h = mix(h, &mesh.tangents[v], sizeof(glm::vec4));
        return h;
    }
    bool same(size_t a, size_t b) const {
        return std::memcmp(&mesh.positions[a], &mesh.positions[b], sizeof(glm::vec3)) == 0 &&
               (!normals || std::memcmp(&mesh.normals[a], &mesh.normals[b], sizeof(glm::vec3)) == 0) &&
               (!uvs || std::memcmp(&mesh.uvs[a], &mesh.uvs[b], sizeof(glm::vec2)) == 0) &&
               (!tangents || std::memcmp(&mesh.tangents[a], &mesh.tangents[b], sizeof(glm::vec4)) == 0);
    }
};

}  // namespace

size_t weld_vertices(Mesh& mesh) {
    const size_t n = mesh.positions.size();
    if (n < 2) return 0;
    const Streams streams{mesh, mesh.normals.size() == n, mesh.uvs.size() == n, mesh.tangents.size() == n};

    // Open addressing, linear probing, at most half full; a slot holds an old index + 1 (the
    // first vertex of its kind).
    const size_t slots = std::bit_ceil(2 * n);
    std::vector<uint32_t> table(slots, 0);
    std::vector<uint32_t> remap(n);
    std::vector<uint32_t> kept;  // old index of each new vertex
    kept.reserve(n);
    for (size_t v = 0; v < n; ++v) {
        size_t slot = size_t(streams.hash(v)) & (slots - 1);
        while (true) {
            const uint32_t entry = table[slot];
            if (entry == 0) {
                table[slot] = uint32_t(v) + 1;
                remap[v] = uint32_t(kept.size());
                kept.push_back(uint32_t(v));
                break;
            }
            if (streams.same(entry - 1, v)) {
                remap[v] = remap[entry - 1];
                break;
            }
            slot = (slot + 1) & (slots - 1);
        }
    }
    const size_t merged = n - kept.size();
    if (merged == 0) return 0;
    for (uint32_t& i : mesh.indices) i = remap[i];
    // kept[i] >= i: each stream compacts in place, front to back.
    const auto compact = [&](auto& stream) {
        if (stream.size() != n) return;
        for (size_t i = 0; i < kept.size(); ++i) stream[i] = stream[kept[i]];
        stream.resize(kept.size());
        stream.shrink_to_fit();
    };
    compact(mesh.positions);
    compact(mesh.normals);
    compact(mesh.uvs);
    compact(mesh.tangents);
    return merged;
}

}  // namespace tessera::io
