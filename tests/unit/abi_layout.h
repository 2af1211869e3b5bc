/* abi_layout.h - the public layout as one set of headers defines it: the size of every
 * struct of the 0.2.0 ABI, the offset and size of each of its fields, and the value of each
 * enum constant and frozen macro. abi_layout.c is compiled once per set of headers
 * (tests/unit/CMakeLists.txt), and test_abi.c compares the tables. */
#ifndef ABRDF_ABI_LAYOUT_H
#define ABRDF_ABI_LAYOUT_H

#include <stddef.h>

typedef enum abi_kind {
    ABI_STRUCT, /* name = the struct; size = sizeof */
    ABI_FIELD,  /* name = the struct, field = the member; offset and size */
    ABI_VALUE   /* name = the enum constant or macro; offset = its value + ABI_VALUE_BIAS */
} abi_kind;

/* Values are stored biased so that ABRDF_MODEL_NONE (-1) and the negative status codes fit. */
#define ABI_VALUE_BIAS 1000

typedef struct abi_entry {
    abi_kind kind;
    const char *name;  /* struct or constant */
    const char *field; /* member (ABI_FIELD), else NULL */
    size_t offset;     /* member offset, or the biased value */
    size_t size;       /* sizeof the struct or the member */
} abi_entry;

/* Terminated by an entry with name NULL. */
extern const abi_entry abi_layout_0_2_0[];  /* tests/data/abi: the headers of the 0.2.0 release */
extern const abi_entry abi_layout_now[];    /* libabrdf/include: this source tree */
extern const abi_entry abi_layout_counts[]; /* this tree with every *_COUNT one higher */

#endif
