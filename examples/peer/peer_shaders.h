// The peer's GLSL, written to compute exactly what tessera's shading computes (issue 3's
// `--shade` definitions), so that the two renderers do the same work per pixel.
#pragma once

namespace tessera::peer {

// Positions are world space (the mesh has no model transform); GLSL's default `smooth`
// interpolation is perspective-correct, as tessera's barycentrics are.
inline constexpr const char* kVertexShader = R"(
layout(location = 0) in vec3 position;
layout(location = 1) in vec3 normal;
layout(location = 2) in vec2 uv;
uniform mat4 view_projection;
out vec3 world_position;
out vec3 world_normal;
out vec2 texcoord;
void main() {
    world_position = position;
    world_normal = normal;
    texcoord = uv;
    gl_Position = view_projection * vec4(position, 1.0);
}
)";

// One body for every --shade mode; the mode and whether the triangle-id target exists are
// #defines prepended at compile time, so llvmpipe JIT-compiles only the work asked for.
inline constexpr const char* kFragmentShader = R"(
in vec3 world_position;
in vec3 world_normal;
in vec2 texcoord;
uniform vec3 eye;
uniform vec3 light_position;
layout(location = 0) out vec4 colour;
#ifdef WRITE_ID
layout(location = 1) out uint triangle_id;  // gl_PrimitiveID + 1; 0 is "nothing covers"
#endif

// procedural/hash.h in GLSL (uint arithmetic wraps modulo 2^32 as in C++): lowbias32 mixes.
uint mix32(uint x) {
    x ^= x >> 16; x *= 0x7feb352du; x ^= x >> 15; x *= 0x846ca68bu; x ^= x >> 16;
    return x;
}
uint hash(uint seed, uint x) {
    uint h = mix32(seed ^ 0x9e3779b9u);
    h = mix32(h ^ x);
    h = mix32(h ^ 0u);  // y = 0
    return mix32(h ^ 0u);  // z = 0
}

// issue 3, --shade phong: two-sided Blinn-Phong with a checker albedo, no sRGB encoding.
vec3 phong() {
    vec3 N = normalize(world_normal);
    vec3 V = normalize(eye - world_position);
    if (dot(N, V) < 0.0) N = -N;
    vec3 L = normalize(light_position - world_position);
    vec3 H = normalize(L + V);
    float checker = mod(floor(texcoord.x * 16.0) + floor(texcoord.y * 8.0), 2.0);
    vec3 albedo = mix(vec3(0.80, 0.35, 0.20), vec3(0.90, 0.85, 0.70), checker);
    return albedo * (0.08 + 0.92 * max(dot(N, L), 0.0)) + 0.5 * pow(max(dot(N, H), 0.0), 48.0);
}

void main() {
#if defined(SHADE_PHONG)
    colour = vec4(clamp(phong(), 0.0, 1.0), 1.0);
#elif defined(SHADE_NORMAL)
    colour = vec4(normalize(world_normal) * 0.5 + 0.5, 1.0);
#elif defined(SHADE_DEPTH)
    colour = vec4(vec3(gl_FragCoord.z), 1.0);
#else
    // SHADE_ID: procedural::hash(0x7e55e7a, id) as tessera colours ids (procedural/hash.h).
    uint h = hash(0x7e55e7au, uint(gl_PrimitiveID));
    colour = vec4(float(h & 255u), float((h >> 8) & 255u), float((h >> 16) & 255u), 255.0) / 255.0;
#endif
#ifdef WRITE_ID
    triangle_id = uint(gl_PrimitiveID) + 1u;
#endif
}
)";

// Multisampled frames: one sample of the id target copied into a single-sample target, so
// that glReadPixels (which takes no multisample buffer) reads every sample, one pass each. The
// vertices are a triangle that covers the viewport, made from gl_VertexID alone.
inline constexpr const char* kCopySampleVertexShader = R"(
void main() {
    vec2 corner = vec2((gl_VertexID << 1) & 2, gl_VertexID & 2);  // (0,0) (2,0) (0,2)
    gl_Position = vec4(corner * 2.0 - 1.0, 0.0, 1.0);
}
)";

inline constexpr const char* kCopySampleFragmentShader = R"(
uniform usampler2DMS ids;
uniform int sample_index;
layout(location = 0) out uint id;
void main() {
    id = texelFetch(ids, ivec2(gl_FragCoord.xy), sample_index).r;
}
)";

}  // namespace tessera::peer
