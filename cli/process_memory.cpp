#include "cli/process_memory.hpp"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <fstream>
#include <vector>

namespace fleetmerge {
namespace {

constexpr std::size_t kMiB = std::size_t{1} << 20;
constexpr std::uintptr_t kHugePageBytes = 2 * kMiB;  // x86-64 and arm64 transparent huge pages

// Whether address space may be reserved without taking it from later allocations: the kernel
// overcommits (vm.overcommit_memory 0 or 1; under strict accounting a reservation counts against
// the commit limit) and neither the address space nor the data segment is limited (ulimit -v,
// -d: the reservation would use up the limit).
bool ReservationIsFree() {
  for (const int resource : {RLIMIT_AS, RLIMIT_DATA}) {
    rlimit limit{};
    if (getrlimit(resource, &limit) != 0 || limit.rlim_cur != RLIM_INFINITY) return false;
  }
  std::ifstream file("/proc/sys/vm/overcommit_memory");
  int mode = 2;
  return static_cast<bool>(file >> mode) && mode != 2;
}

// Grows the heap by about `bytes` of untouched address space (blocks below the mmap threshold
// come from the heap's top; freed, they stay there under the trim threshold) and marks it for
// transparent huge pages, as glibc's tunable glibc.malloc.hugetlb=1 does for each heap growth:
// the pages are then faulted in 2 MiB at a time, not 4 KiB.
void ReserveHugePageHeap(std::size_t bytes) {
  constexpr std::size_t kBlock = 16 * kMiB;  // below M_MMAP_THRESHOLD
  const auto start = reinterpret_cast<std::uintptr_t>(sbrk(0));
  std::vector<void*> blocks;
  blocks.reserve(bytes / kBlock);
  for (std::size_t reserved = 0; reserved + kBlock <= bytes; reserved += kBlock) {
    void* block = std::malloc(kBlock);
    if (block == nullptr) break;
    blocks.push_back(block);
  }
  for (void* block : blocks) std::free(block);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t first = (start + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t last = end & ~(kHugePageBytes - 1);
  // Without transparent huge pages (or with a malloc that does not use the heap, such as a
  // sanitizer's) this does nothing; the settings above still apply.
  if (last > first) madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
}

}  // namespace

void KeepFreedMemoryForReuse() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's maximum (HEAP_MAX_SIZE / 2 on 64-bit)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  if (ReservationIsFree()) ReserveHugePageHeap(768 * kMiB);
}

void ShareTheHeapBetweenThreads() { mallopt(M_ARENA_MAX, 1); }

}  // namespace fleetmerge
