#include "cli/process_memory.hpp"

#include <malloc.h>

namespace fleetmerge {

void KeepFreedMemoryForReuse() {
  mallopt(M_MMAP_THRESHOLD, 32 << 20);  // glibc's maximum (HEAP_MAX_SIZE / 2 on 64-bit)
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
}

}  // namespace fleetmerge
