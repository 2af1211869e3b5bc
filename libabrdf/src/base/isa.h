/* isa.h - run-time instruction-set levels: the attributes that compile a loop once per level,
 * and the level this CPU runs (abrdf__isa_best, eval_float.c).
 *
 * Each hot loop is compiled once per level below, and every call runs the best level the CPU
 * supports, so the default (portable) build runs AVX2 or AVX-512 code where the machine has
 * it. The choice is a pure function of the CPU (abrdf__isa_best reads the compiler runtime's
 * CPU model, which it fills once at program start): no state of the library's own, no ifunc
 * (which needs the dynamic loader's cooperation that a static link does not have, and cannot
 * be forced to a level in tests). Where the compiler contracts a * b + c into an FMA (Clang
 * by default; GCC not in ISO C mode), levels 1 and 2 change the last bits of a result, nothing
 * more; huang's loops are compiled without contraction (libabrdf/CMakeLists.txt). */
#ifndef ABRDF_ISA_H
#define ABRDF_ISA_H

#if defined(__GNUC__)
#define ABRDF__NOINLINE __attribute__((noinline)) /* inlining would drop the restrict facts */
#else
#define ABRDF__NOINLINE
#endif

#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
#define ABRDF__ISA_X86 1
/* Levels: 0 the build's baseline, 1 AVX2 + FMA (x86-64-v3), 2 AVX-512 (x86-64-v4). */
#define ABRDF__ISA_ATTR_0
#define ABRDF__ISA_ATTR_1 __attribute__((target("avx2,fma")))
#define ABRDF__ISA_ATTR_2                                                                          \
    __attribute__((target("avx512f,avx512vl,avx512bw,avx512dq,avx2,fma,prefer-vector-width=512")))
#define ABRDF__ISA_LEVELS(X) X(0) X(1) X(2)
#else
#define ABRDF__ISA_X86 0
#define ABRDF__ISA_ATTR_0
#define ABRDF__ISA_LEVELS(X) X(0)
#endif

/* 0 the build's baseline, 1 AVX2 + FMA, 2 AVX-512 (x86-64 only; elsewhere only 0): the
 * highest level this CPU runs. */
int abrdf__isa_best(void);

/* The same, inlined where a call costs a visible share: the per-sample float call
 * (abrdf_eval_prepared_float: 12.55 -> 12.35 ns for disney_specular, docs/BENCHMARKS.md). */
static inline int abrdf__isa_best_inline(void)
{
#if ABRDF__ISA_X86
    if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl") &&
        __builtin_cpu_supports("avx512bw") && __builtin_cpu_supports("avx512dq"))
        return 2;
    if (__builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma")) return 1;
#endif
    return 0;
}

#endif /* ABRDF_ISA_H */
