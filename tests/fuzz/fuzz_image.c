/* fuzz_image.c - fuzz target of the image reader (tools/image/image_io.cpp, OpenImageIO
 * behind it), which reads environment maps and the images `abrdf compare` compares: any bytes
 * must either be refused with a message naming the file, or read into an image whose size
 * keeps the reader's cap (width x height x the channels used, as floats, at most 1 GiB).
 * A header may declare any size: the reader reads in strips, so a mutated header over a few
 * bytes fails at its first missing rows instead of allocating what it declares. The input
 * goes through a file (OpenImageIO reads files), named with the extension of its magic
 * number. libFuzzer entry point; tests/fuzz/fuzz_driver.c runs it deterministically. */
#define _POSIX_C_SOURCE 200809L /* mkstemps is a BSD/GNU extension: declared below */
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "fuzz_target.h"
#include "image_io.h"

int mkstemps(char *template_name, int suffix_len);

#define FUZZ_REQUIRE(cond)                                                                         \
    do {                                                                                           \
        if (!(cond)) {                                                                             \
            fprintf(stderr, "fuzz_image: %s does not hold (%s)\n", #cond, err);                    \
            abort();                                                                               \
        }                                                                                          \
    } while (0)

static unsigned long read_ok, refused;

/* Parts of EXR, PNG and Radiance headers, and sizes a hostile header would declare. */
const char *const fuzz_tokens[] = {
    "channels",
    "chlist",
    "dataWindow",
    "displayWindow",
    "box2i",
    "compression",
    "tiles",
    "tiledesc",
    "lineOrder",
    "\0",
    "\xff\xff\xff\x7f",
    "\x00\x20\x00\x00",
    "\x00\x00\x01\x00",
    "\x01",
    "\x0c",
    "IHDR",
    "IDAT",
    "IEND",
    "#?RADIANCE\n",
    "-Y 8192 +X 8192\n",
    "FORMAT=32-bit_rle_rgbe\n",
    "\x76\x2f\x31\x01",
    "\x89PNG\r\n\x1a\n",
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu read, %lu refused", read_ok, refused); }

static const char *extension(const uint8_t *d, size_t n)
{
    if (n >= 4 && !memcmp(d, "\x76\x2f\x31\x01", 4)) return ".exr";
    if (n >= 4 && !memcmp(d, "\x89PNG", 4)) return ".png";
    if (n >= 2 && !memcmp(d, "#?", 2)) return ".hdr";
    return ".exr";
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    char path[64], err[1024] = "";
    const char *ext = extension(data, size);
    snprintf(path, sizeof path, "/tmp/abrdf_fuzz_image_XXXXXX%s", ext);
    int fd = mkstemps(path, (int)strlen(ext));
    FUZZ_REQUIRE(fd >= 0);
    FUZZ_REQUIRE(write(fd, data, size) == (ssize_t)size);
    close(fd);
    abrdf_image img;
    int rc = abrdf_image_read(path, &img, err, (int)sizeof err);
    unlink(path);
    if (rc != 0) {
        FUZZ_REQUIRE(memchr(err, '\0', sizeof err) && !strncmp(err, path, strlen(path)));
        FUZZ_REQUIRE(!img.pixels);
        ++refused;
        return 0;
    }
    FUZZ_REQUIRE(img.width > 0 && img.height > 0 && img.channels > 0 && img.pixels);
    FUZZ_REQUIRE((long long)img.width * img.height * 3 * (long long)sizeof(float) <= 3LL << 30);
    /* every pixel was written (an unread row would be uninitialised memory under MSan) */
    volatile float sink = 0;
    for (size_t k = 0; k < (size_t)img.width * img.height * 3; ++k) sink += img.pixels[k];
    (void)sink;
    abrdf_image_free(&img);
    ++read_ok;
    return 0;
}
