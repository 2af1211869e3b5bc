/* fuzz_target.h - what a fuzz target gives the deterministic driver (fuzz_driver.c): the
 * libFuzzer entry point, the tokens its format is made of (the mutator inserts them; "\0"
 * inserts one NUL byte), and a report of what it saw. */
#ifndef ABRDF_FUZZ_TARGET_H
#define ABRDF_FUZZ_TARGET_H

#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);
extern const char *const fuzz_tokens[];
extern const size_t fuzz_token_count;
/* One line fragment, e.g. "123 parsed and rendered". */
void fuzz_report(FILE *f);

#endif
