/* fuzz_driver.c - deterministic driver for a fuzz target (fuzz_scene.c, fuzz_mesh.c,
 * fuzz_image.c, fuzz_costs.c, fuzz_materials.c, fuzz_merl.c, fuzz_rgl.c, fuzz_cli.c) under CTest:
 * every seed file given on the command line, then
 * ITERATIONS inputs mutated from them by a fixed-seed generator (byte flips, inserted tokens
 * of the target's format and hostile numbers, deleted and duplicated spans, splices of two
 * seeds). A crash, sanitizer report or abort() fails it. Each target defines fuzz_tokens[]
 * (what its format is made of) and fuzz_report() (what it saw, printed at the end).
 * usage: fuzz_X_driver [--iterations N] SEED...  */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_target.h"

#define MAX_SEEDS 64
#define MAX_INPUT (1u << 16)

static uint64_t rng_state = 0x243f6a8885a308d3ull;

static uint32_t rnd(uint32_t n)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return n ? (uint32_t)(rng_state % n) : 0;
}

static size_t mutate(uint8_t *buf, size_t len, const uint8_t *other, size_t olen)
{
    int edits = rnd(2) ? 1 : 1 + (int)rnd(8); /* single edits keep many inputs valid */
    for (int e = 0; e < edits; ++e) {
        size_t at = len ? rnd((uint32_t)len + 1) : 0;
        switch (rnd(5)) {
        case 0: /* flip a byte */
            if (len) buf[rnd((uint32_t)len)] ^= (uint8_t)(1u << rnd(8));
            break;
        case 1: { /* insert a token (the "\0" token inserts one NUL byte) */
            const char *t = fuzz_tokens[rnd((uint32_t)fuzz_token_count)];
            size_t tl = *t ? strlen(t) : 1;
            if (len + tl >= MAX_INPUT) break;
            memmove(buf + at + tl, buf + at, len - at);
            memcpy(buf + at, t, tl);
            len += tl;
            break;
        }
        case 2: { /* delete a span */
            size_t n = rnd(64);
            if (at + n > len) n = len - at;
            memmove(buf + at, buf + at + n, len - at - n);
            len -= n;
            break;
        }
        case 3: { /* duplicate a span */
            if (!len) break;
            size_t from = rnd((uint32_t)len), n = rnd(200);
            if (from + n > len) n = len - from;
            if (len + n >= MAX_INPUT) break;
            memmove(buf + at + n, buf + at, len - at);
            memmove(buf + at, buf + (from < at ? from : from + n), n);
            len += n;
            break;
        }
        default: { /* splice: tail of the other seed */
            if (!olen) break;
            size_t from = rnd((uint32_t)olen), n = olen - from;
            if (at + n >= MAX_INPUT) n = MAX_INPUT - at - 1;
            memcpy(buf + at, other + from, n);
            len = at + n;
            break;
        }
        }
    }
    return len;
}

int main(int argc, char **argv)
{
    long iterations = 3000;
    static uint8_t seeds[MAX_SEEDS][MAX_INPUT], buf[MAX_INPUT];
    size_t lens[MAX_SEEDS];
    int count = 0;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--iterations") && i + 1 < argc) {
            iterations = strtol(argv[++i], NULL, 10);
            continue;
        }
        if (count == MAX_SEEDS) break;
        FILE *f = fopen(argv[i], "rb");
        if (!f) {
            fprintf(stderr, "fuzz_driver: cannot open %s\n", argv[i]);
            return 1;
        }
        lens[count] = fread(seeds[count], 1, MAX_INPUT - 1, f);
        fclose(f);
        LLVMFuzzerTestOneInput(seeds[count], lens[count]);
        ++count;
    }
    if (!count) {
        fprintf(stderr, "usage: fuzz_driver [--iterations N] SEED...\n");
        return 1;
    }
    for (long it = 0; it < iterations; ++it) {
        int a = (int)rnd((uint32_t)count), b = (int)rnd((uint32_t)count);
        size_t len = lens[a];
        memcpy(buf, seeds[a], len);
        len = mutate(buf, len, seeds[b], lens[b]);
        /* An exact-size heap copy lets AddressSanitizer see any read past the end. */
        uint8_t *in = malloc(len ? len : 1);
        if (!in) return 1;
        memcpy(in, buf, len);
        LLVMFuzzerTestOneInput(in, len);
        free(in);
    }
    printf("fuzz_driver: %d seeds, %ld mutated inputs, no failure (", count, iterations);
    fuzz_report(stdout);
    printf(")\n");
    return 0;
}
