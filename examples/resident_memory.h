// The process's memory, as `render --stats` prints it after every frame (so a leak shows as
// growth from frame to frame) and at the end:
//   resident: what Linux counts in /proc/self/status (VmRSS, VmHWM for the peak): every page
//       the process touches, malloc'ed or mapped. Under AddressSanitizer this also counts the
//       sanitizer's shadow memory and allocator regions, which it does not give back, so there
//       it measures the sanitizer rather than tessera.
//   heap: the bytes of live allocations, as the allocator itself counts them: glibc's
//       mallinfo2() (in use in every arena, plus chunks mapped on their own), or, in a
//       sanitizer build, the sanitizer allocator's count of bytes allocated and not yet freed,
//       which excludes its quarantine. The same meaning in every build.
#pragma once

namespace tessera::cli {

// VmRSS and VmHWM (the peak) in MiB; 0 where /proc is not available.
double resident_mib();
double peak_resident_mib();

// Starts a new peak: VmHWM drops to the current VmRSS (Linux's /proc/self/clear_refs "5"), so
// that peak_resident_mib() afterwards is the peak of what follows. False where the kernel does
// not allow it: the peak then stays the process's since it started.
bool reset_peak_resident();

// Live heap allocations in MiB.
double heap_mib();

// The sanitizer whose allocator this build uses ("AddressSanitizer", "ThreadSanitizer"), or
// nullptr; `tessera info` says it, so that a test knows what resident memory means here.
const char* sanitizer_allocator();

}  // namespace tessera::cli
