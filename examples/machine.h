// What the machine and the build are, as `tessera info` prints them and `tessera compare`
// records them with its figures: a time means little without the CPU it was measured on.
#pragma once
#include <string>

namespace tessera::cli {

// /proc/cpuinfo's first "model name", or "unknown".
std::string cpu_model();

// The SIMD target this build was compiled for: "AVX-512 (16 float lanes)", "AVX2 (8 float
// lanes)" or "scalar fallback".
const char* simd_target();

}  // namespace tessera::cli
