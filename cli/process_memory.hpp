// How the `fleetmerge` process asks glibc to keep freed memory: a batch process that allocates
// and frees the same large work buffers pair after pair should reuse them, not fault them in
// again. Called first thing in main; benchmarks of the commands' code call it too, so that they
// measure what the executable runs.
#pragma once

namespace fleetmerge {

// Every pair allocates and frees buffers of 0.2-2 MB (FFT work space inside OpenCV's dft,
// correlation surfaces, rotated point sets). By default glibc serves such blocks with mmap, or
// returns them to the kernel as soon as the top of the heap is free, so each one comes back as
// fresh pages: page faults were 17 % of a pair's hypothesis search (perf). This keeps blocks up
// to 32 MiB on the heap and trims it only beyond 1 GiB free. The price is a somewhat higher
// peak, as freed blocks stay resident for reuse (fleet_benchmark's 8-map job: 77 MB with these
// settings against 65 MB without, measured side by side; its current peak: docs/speed.md).
//
// It also reserves 768 MiB of untouched heap marked for transparent huge pages (madvise
// MADV_HUGEPAGE, as glibc's glibc.malloc.hugetlb=1 tunable does), so that the main thread's
// working set is faulted in 2 MiB pages: page faults had been a fifth of a `fleetmerge pair`
// process and a tenth of a fleet merge on a VM whose page faults are dear (docs/speed.md). Only
// address space is reserved (the process's VSZ grows, not its RSS), and only where that is free:
// not under ulimit -v / -d or strict overcommit accounting.
void KeepFreedMemoryForReuse();

// Puts every thread on the main heap (M_ARENA_MAX 1), and so on its huge pages; call it before
// any thread allocates. For one pair (`fleetmerge pair`, whose threads share one search): its
// process took 70 ms with per-thread heaps and 58 ms with this. A fleet's threads each search
// whole pairs and allocate more often; the shared heap's lock made the 33-robot ACES job 3-5 %
// slower, so `merge` keeps glibc's per-thread heaps.
void ShareTheHeapBetweenThreads();

}  // namespace fleetmerge
