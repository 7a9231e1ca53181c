// What a fresh page costs on this machine: maps 256 MiB and touches every
// 4 KiB page, as a subdivision level's first write does, then overwrites it
// warm. Mode 0: plain 4 KiB pages; 1: MADV_HUGEPAGE; 2: MAP_POPULATE (the
// kernel faults everything in the mmap call). docs/performance.md and
// src/mem.rs quote its figures.
//   gcc -O2 scripts/page-cost.c -o /tmp/page-cost && /tmp/page-cost 0
// Run mode 1 right after another run and again after a few idle seconds to
// see the cost of host-reclaimed memory (free page reporting) on a VM.
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <time.h>

static double now_ms(void) {
  struct timespec t;
  clock_gettime(CLOCK_MONOTONIC, &t);
  return t.tv_sec * 1e3 + t.tv_nsec / 1e6;
}

int main(int argc, char **argv) {
  size_t n = (size_t)256 << 20;
  int mode = argc > 1 ? atoi(argv[1]) : 0;
  double t0 = now_ms();
  char *p = mmap(0, n, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS | (mode == 2 ? MAP_POPULATE : 0), -1, 0);
  if (p == MAP_FAILED) {
    perror("mmap");
    return 1;
  }
  if (mode == 1) madvise(p, n, MADV_HUGEPAGE);
  double t1 = now_ms();
  for (size_t i = 0; i < n; i += 4096) p[i] = 1;
  double t2 = now_ms();
  memset(p, 2, n);
  double t3 = now_ms();
  printf("mode %d: map %.1f ms, first touch %.1f ms, warm memset %.1f ms (256 MiB)\n", mode, t1 - t0, t2 - t1, t3 - t2);
  return 0;
}
