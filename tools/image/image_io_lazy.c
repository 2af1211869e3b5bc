/* image_io_lazy.c - image_io.h for the abrdf command, loading the OpenImageIO/OpenColorIO
 * implementation (image_io.cpp, built as the module libabrdf_image_io.so) on first use.
 *
 * Why: linking OpenImageIO pulls about 260 shared libraries whose loading and relocation
 * cost 0.1-1 s at every start (docs/BENCHMARKS.md, "Start-up"), paid by commands that never
 * touch an image (models, eval, advise, bench, ...). With the module only the commands that
 * read or write an image pay it, once.
 *
 * Where: next to the executable (the build tree), else ABRDF_IMAGE_IO_RELATIVE from the
 * executable's directory (the installed tree: bin/ -> lib/abrdf/); $ABRDF_IMAGE_IO_MODULE
 * overrides both. On failure every function returns -1 with the loader's message in err. */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "image_io.h"
#include "module_open.h"

#define MODULE_NAME "libabrdf_image_io.so"

typedef int (*encode_linear_fn)(const char *, int, int, const float *, abrdf_bytes *, char *, int);
typedef int (*encode_preview_fn)(const char *, int, int, const float *, const char *, const char *,
                                 const char *, abrdf_bytes *, char *, int);
typedef int (*encode_heatmap_fn)(const char *, int, int, const float *, double, const char *,
                                 abrdf_bytes *, char *, int);
typedef void (*bytes_free_fn)(abrdf_bytes *);
typedef int (*check_output_fn)(const char *, int, char *, int);
typedef int (*check_preview_fn)(const char *, const char *, const char *, char *, int);
typedef int (*read_fn)(const char *, abrdf_image *, char *, int);
typedef void (*free_fn)(abrdf_image *);
typedef int (*is_display_fn)(const char *);

/* The module's entry points; filled once by load() (the tool calls image I/O from its main
 * thread only). */
static struct {
    int tried;
    char error[512];
    encode_linear_fn encode_linear, encode_linear_half;
    encode_preview_fn encode_preview;
    encode_heatmap_fn encode_heatmap;
    bytes_free_fn bytes_free;
    check_output_fn check_output;
    check_preview_fn check_preview;
    read_fn read;
    free_fn free_image;
    is_display_fn is_display;
} mod;

static int load(char *err, int err_size)
{
    if (!mod.tried) {
        mod.tried = 1;
        const char *env = getenv("ABRDF_IMAGE_IO_MODULE");
        void *h = module_open("ABRDF_IMAGE_IO_MODULE", MODULE_NAME, ABRDF_IMAGE_IO_RELATIVE);
        if (!h) {
            const char *e = dlerror();
            snprintf(mod.error, sizeof mod.error, "cannot load the image I/O module %s: %s",
                     env && *env ? env : MODULE_NAME, e ? e : "not found");
        } else {
            /* POSIX: dlsym's void * converts to a function pointer through this idiom. */
            const struct {
                const char *name;
                void **fn;
            } entry[] = {
                {"abrdf_image_encode_linear", (void **)&mod.encode_linear},
                {"abrdf_image_encode_linear_half", (void **)&mod.encode_linear_half},
                {"abrdf_image_encode_preview", (void **)&mod.encode_preview},
                {"abrdf_image_encode_heatmap", (void **)&mod.encode_heatmap},
                {"abrdf_bytes_free", (void **)&mod.bytes_free},
                {"abrdf_image_check_output", (void **)&mod.check_output},
                {"abrdf_image_check_preview", (void **)&mod.check_preview},
                {"abrdf_image_free", (void **)&mod.free_image},
                {"abrdf_image_is_display_format", (void **)&mod.is_display},
                {"abrdf_image_read", (void **)&mod.read}, /* last: set means loaded */
            };
            for (size_t i = 0; i < sizeof entry / sizeof entry[0]; ++i)
                if (!(*entry[i].fn = dlsym(h, entry[i].name))) {
                    snprintf(mod.error, sizeof mod.error,
                             "the image I/O module %s lacks %s (a module of another abrdf "
                             "build: build or install the two together)",
                             env && *env ? env : MODULE_NAME, entry[i].name);
                    mod.read = NULL;
                    break;
                }
        }
    }
    if (mod.read) return 0;
    if (err && err_size > 0) snprintf(err, (size_t)err_size, "%s", mod.error);
    return -1;
}

static void no_bytes(abrdf_bytes *out)
{
    if (out) out->data = NULL, out->size = 0;
}

int abrdf_image_encode_linear(const char *name, int width, int height, const float *rgb,
                              abrdf_bytes *out, char *err, int err_size)
{
    no_bytes(out);
    if (load(err, err_size)) return -1;
    return mod.encode_linear(name, width, height, rgb, out, err, err_size);
}

int abrdf_image_encode_linear_half(const char *name, int width, int height, const float *rgb,
                                   abrdf_bytes *out, char *err, int err_size)
{
    no_bytes(out);
    if (load(err, err_size)) return -1;
    return mod.encode_linear_half(name, width, height, rgb, out, err, err_size);
}

int abrdf_image_encode_preview(const char *name, int width, int height, const float *rgb,
                               const char *config, const char *display, const char *view,
                               abrdf_bytes *out, char *err, int err_size)
{
    no_bytes(out);
    if (load(err, err_size)) return -1;
    return mod.encode_preview(name, width, height, rgb, config, display, view, out, err, err_size);
}

int abrdf_image_encode_heatmap(const char *name, int width, int height, const float *value,
                               double vmax, const char *map, abrdf_bytes *out, char *err,
                               int err_size)
{
    no_bytes(out);
    if (load(err, err_size)) return -1;
    return mod.encode_heatmap(name, width, height, value, vmax, map, out, err, err_size);
}

void abrdf_bytes_free(abrdf_bytes *b)
{
    if (!b) return;
    if (load(NULL, 0) == 0) {
        mod.bytes_free(b);
    } else { /* nothing was encoded through the module */
        free(b->data);
        b->data = NULL;
        b->size = 0;
    }
}

int abrdf_image_check_output(const char *name, int linear, char *err, int err_size)
{
    if (load(err, err_size)) return -1;
    return mod.check_output(name, linear, err, err_size);
}

int abrdf_image_check_preview(const char *config, const char *display, const char *view, char *err,
                              int err_size)
{
    if (load(err, err_size)) return -1;
    return mod.check_preview(config, display, view, err, err_size);
}

int abrdf_image_read(const char *path, abrdf_image *img, char *err, int err_size)
{
    if (load(err, err_size)) {
        if (img) img->width = img->height = img->channels = 0, img->pixels = NULL;
        return -1;
    }
    return mod.read(path, img, err, err_size);
}

void abrdf_image_free(abrdf_image *img)
{
    if (!img) return;
    if (load(NULL, 0) == 0) {
        mod.free_image(img);
    } else { /* nothing was read through the module; release as image_io.cpp would */
        free(img->pixels);
        img->pixels = NULL;
    }
}

int abrdf_image_is_display_format(const char *path)
{
    return load(NULL, 0) == 0 ? mod.is_display(path) : 0;
}
