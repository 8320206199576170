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

// Grows the heap by `bytes` of untouched address space in one brk call and marks it for
// transparent huge pages, as glibc's tunable glibc.malloc.hugetlb=1 does for each heap growth:
// its pages are then faulted in 2 MiB at a time, not 4 KiB. Two details decide whether the
// working set really gets huge pages (perf record -e page-faults -d on `fleetmerge pair`):
// - a 2 MiB page is only given to a range that has no 4 KiB page yet, so nothing in the range
//   may be written before the madvise. One block of `bytes` (served by brk, not mmap, while
//   M_MMAP_MAX is 0) writes a chunk header only at its end; growing the heap in 16 MiB steps
//   wrote one every 16 MiB, and each such range then took 512 small faults;
// - the heap's first bytes up to a 2 MiB boundary cannot be a huge page. Without a filler there,
//   the first allocations (the maps, their cell lists) landed on them: up to 512 small faults.
void* unaligned_heap_head = nullptr;  // the filler; reachable, so never reported as a leak

void ReserveHugePageHeap(std::size_t bytes) {
  mallopt(M_MMAP_MAX, 0);
  void* block = std::malloc(bytes);
  mallopt(M_MMAP_MAX, 65536);  // glibc's default
  if (block == nullptr) return;
  const auto start = reinterpret_cast<std::uintptr_t>(block);
  std::free(block);  // back into the heap's top (below the trim threshold: kept)
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  // Without a brk heap (a sanitizer's malloc) the block is not below the program break.
  if (start >= end || end - start < bytes) return;
  const std::uintptr_t first = (start + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t last = end & ~(kHugePageBytes - 1);
  if (last <= first) return;
  // Without transparent huge pages this does nothing; the settings above still apply.
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  constexpr std::uintptr_t kChunkHeaderBytes = 2 * sizeof(std::size_t);
  if (first - start > kChunkHeaderBytes) {
    unaligned_heap_head = std::malloc(first - start - kChunkHeaderBytes);
  }
}

}  // namespace

void KeepFreedMemoryForReuse() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's maximum (HEAP_MAX_SIZE / 2 on 64-bit)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  if (ReservationIsFree()) ReserveHugePageHeap(768 * kMiB);
}

void ShareTheHeapBetweenThreads() { mallopt(M_ARENA_MAX, 1); }

}  // namespace fleetmerge
