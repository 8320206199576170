#include "cli/process_memory.hpp"

#include <malloc.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <fstream>

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
// its pages are then faulted in 2 MiB at a time, not 4 KiB. Three details decide whether the
// working set really gets huge pages (perf record -e page-faults -d on `fleetmerge pair`):
// - a 2 MiB page is only given to a range that has no 4 KiB page yet, so nothing in the range
//   may be written before the madvise. One block of `bytes` (served by brk, not mmap, while
//   M_MMAP_MAX is 0) writes a chunk header only at its end; growing the heap in 16 MiB steps
//   wrote one every 16 MiB, and each such range then took 512 small faults;
// - the block's first bytes up to a 2 MiB boundary cannot be a huge page, nor can the range the
//   heap already reached (written before main): the block is shrunk to them and kept, so that
//   nothing else is put there;
// - the heap below the block may hold free, never touched chunks when main runs (a library's
//   static initialiser that allocates and frees: OctoMap's free ~1.3 MB of ray buffers, though
//   OctoMap is now loaded with the commands module, after this runs): they are taken and kept
//   too, or the first maps loaded would land on them, 4 KiB at a time.
// What is kept is address space only: nothing writes to it but the allocator's headers.
constexpr int kMaxKeptBlocks = 64;
void* kept_blocks[kMaxKeptBlocks];  // reachable, so never reported as a leak
int kept_count = 0;

void ReserveHugePageHeap(std::size_t bytes) {
  const auto old_break = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_MMAP_MAX, 0);
  void* block = std::malloc(bytes);
  mallopt(M_MMAP_MAX, 65536);  // glibc's default
  if (block == nullptr) return;
  const auto start = reinterpret_cast<std::uintptr_t>(block);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  // Beyond the heap as it was, too: pages there may have been written already.
  const std::uintptr_t first =
      (std::max(start, old_break) + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t last = end & ~(kHugePageBytes - 1);
  // Without a brk heap (a sanitizer's malloc) the block is not below the program break.
  if (start >= end || end - start < bytes || last <= first + kHugePageBytes) {
    std::free(block);
    return;
  }
  // Without transparent huge pages this does nothing; the settings above still apply.
  madvise(reinterpret_cast<void*>(first), last - first, MADV_HUGEPAGE);
  // Shrunk in place to the unaligned head: the rest goes back to the heap's top.
  constexpr std::uintptr_t kChunkHeaderBytes = 2 * sizeof(std::size_t);
  kept_blocks[kept_count++] =
      std::realloc(block, std::max<std::uintptr_t>(first - start, 64) - kChunkHeaderBytes);
  // Free chunks below the block, largest first, for as long as malloc hands them out.
  for (std::size_t size = kHugePageBytes; size >= 4096 && kept_count < kMaxKeptBlocks;) {
    void* p = std::malloc(size);
    if (p == nullptr || reinterpret_cast<std::uintptr_t>(p) >= first) {
      std::free(p);
      size /= 2;
      continue;
    }
    kept_blocks[kept_count++] = p;
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
