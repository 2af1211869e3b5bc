/* clock_rate.c - the core's clock, measured (clock_rate.h). */
#define _GNU_SOURCE /* clock_gettime, syscall */
#include "clock_rate.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#ifdef __linux__
#include <linux/perf_event.h>
#include <sys/ioctl.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#define RUNS 7
#define ITERS 4000000u /* x 8 dependent operations: 32e6 cycles, ~10 ms at 3 GHz */

/* Keeps x in a register and the operation on it in place: the compiler may neither fold the
 * chain nor run it in parallel. */
#if defined(__GNUC__)
#define KEEP(x) __asm__ volatile("" : "+r"(x))
#else
#define KEEP(x) ((void)0)
#endif

static double thread_ns(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return 1e9 * (double)t.tv_sec + (double)t.tv_nsec;
}

/* 8 x ITERS dependent single-cycle operations on x. */
static uint64_t chain(uint64_t x)
{
    for (uint64_t i = 0; i < ITERS; ++i)
        for (int j = 0; j < 4; ++j) { /* unrolled by the compiler; KEEP orders every step */
            x += i;
            KEEP(x);
            x ^= i;
            KEEP(x);
        }
    return x;
}

static int by_value(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

#ifdef __linux__
static int counter_open(void)
{
    struct perf_event_attr a;
    memset(&a, 0, sizeof a);
    a.type = PERF_TYPE_HARDWARE;
    a.size = sizeof a;
    a.config = PERF_COUNT_HW_CPU_CYCLES;
    a.disabled = 1;
    a.exclude_kernel = 1;
    a.exclude_hv = 1;
    /* with the times enabled and running: a counter multiplexed with others (running <
     * enabled) undercounts, and is not used */
    a.read_format = PERF_FORMAT_TOTAL_TIME_ENABLED | PERF_FORMAT_TOTAL_TIME_RUNNING;
    return (int)syscall(SYS_perf_event_open, &a, 0, -1, -1, 0);
}
#endif

/* RUNS measurements into ghz, counted by the cycle counter fd (>= 0) or by the chain's own
 * length (fd < 0): 1, or 0 when a counter reading was not whole (the caller falls back). */
static int measure_runs(int fd, double ghz[RUNS])
{
    volatile uint64_t sink = 0;
    sink += chain(sink); /* warm up: the core at its working clock */
    for (int r = 0; r < RUNS; ++r) {
        uint64_t cycles = 8u * (uint64_t)ITERS;
#ifdef __linux__
        if (fd >= 0) {
            ioctl(fd, PERF_EVENT_IOC_RESET, 0);
            ioctl(fd, PERF_EVENT_IOC_ENABLE, 0);
        }
#endif
        double t0 = thread_ns();
        sink += chain(sink);
        double t1 = thread_ns();
#ifdef __linux__
        if (fd >= 0) {
            ioctl(fd, PERF_EVENT_IOC_DISABLE, 0);
            uint64_t v[3] = {0, 0, 0}; /* count, time enabled, time running */
            if (read(fd, v, sizeof v) != (ssize_t)sizeof v || v[0] == 0 || v[1] == 0 ||
                v[2] != v[1])
                return 0;
            cycles = v[0];
        }
#else
        (void)fd;
#endif
        ghz[r] = t1 > t0 ? (double)cycles / (t1 - t0) : 0.0;
    }
    return 1;
}

void clock_rate_measure(clock_rate *out)
{
    double ghz[RUNS];
    int fd = -1;
#ifdef __linux__
    fd = counter_open();
#endif
    out->method = CLOCK_COUNTER;
    if (fd < 0 || !measure_runs(fd, ghz)) { /* every run by one method */
        out->method = CLOCK_CHAIN;
        measure_runs(-1, ghz);
    }
#ifdef __linux__
    if (fd >= 0) close(fd);
#endif
    qsort(ghz, RUNS, sizeof ghz[0], by_value);
    out->ghz = ghz[RUNS / 2];
}

void clock_rate_text(const clock_rate *c, char *buf, size_t size)
{
    snprintf(buf, size, "%.2f GHz, %s", c->ghz,
             c->method == CLOCK_COUNTER
                 ? "the CPU's cycle counter (perf_event)"
                 : "a chain of dependent additions timed on the thread's CPU clock (the cycle "
                   "counter is not readable here)");
}
