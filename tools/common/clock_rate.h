/* clock_rate.h - the core's clock, measured, so that a cost in ns can be stated in cycles (the
 * paper's Table 4 unit): cycles = ns x GHz.
 *
 * How: the CPU's cycle counter (Linux perf_event, PERF_COUNT_HW_CPU_CYCLES, user space only)
 * counted over a fixed piece of work, divided by the thread's CPU time for it, where the
 * kernel exposes the counter; otherwise that work is a chain of dependent integer additions
 * and exclusive-ors, one per cycle on every out-of-order x86-64 and AArch64 core, so its count
 * over its CPU time is the clock. The median of several runs. */
#ifndef ABRDF_CLOCK_RATE_H
#define ABRDF_CLOCK_RATE_H
#include <stddef.h>

typedef enum clock_method { CLOCK_COUNTER, CLOCK_CHAIN } clock_method;

typedef struct clock_rate {
    double ghz;          /* cycles per ns */
    clock_method method; /* how it was measured */
} clock_rate;

/* Measure (about 0.1 s of CPU). Without GCC or Clang the chain is plain C, which an
 * optimiser may shorten: the clock is then overstated. */
void clock_rate_measure(clock_rate *out);
/* One phrase: "3.10 GHz, the CPU's cycle counter" or "... a chain of dependent additions
 * (the cycle counter is not readable here)". */
void clock_rate_text(const clock_rate *c, char *buf, size_t size);

#endif
