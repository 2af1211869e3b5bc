/* isa.c - the instruction-set level this CPU runs (isa.h). */
#include "isa.h"

int abrdf__isa_best(void)
{
#if ABRDF__ISA_X86
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq"))
        return 2;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return 1;
#endif
    return 0;
}
