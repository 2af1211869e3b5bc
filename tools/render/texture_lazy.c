/* texture_lazy.c - texture.h for the renderer, loading the OpenImageIO implementation
 * (texture.cpp, the module libabrdf_texture.so) on first use, for the reason and by the rules
 * of tools/image/image_io_lazy.c: next to the executable (the build tree), else
 * ABRDF_TEXTURE_RELATIVE from the executable's directory (the installed tree); the
 * environment variable ABRDF_TEXTURE_MODULE overrides both. texture_system_new loads it
 * (the tool's main thread, before any worker starts). */
#define _GNU_SOURCE
#include <dlfcn.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "module_open.h"
#include "texture_module.h"

#define TEXTURE_MODULE_NAME "libabrdf_texture.so"

static const texture_module_api *api;
static char load_error[512];

static int load(char *err, size_t err_size)
{
    static int tried;
    if (!tried) {
        tried = 1;
        const char *env = getenv("ABRDF_TEXTURE_MODULE");
        void *h = module_open("ABRDF_TEXTURE_MODULE", TEXTURE_MODULE_NAME, ABRDF_TEXTURE_RELATIVE);
        texture_module_fn get = NULL;
        if (h) *(void **)&get = dlsym(h, "abrdf_texture_module"); /* POSIX's idiom */
        if (!h) {
            const char *e = dlerror();
            snprintf(load_error, sizeof load_error, "cannot load the texture module %s: %s",
                     env && *env ? env : TEXTURE_MODULE_NAME, e ? e : "not found");
        } else if (!get || !get() || get()->version != TEXTURE_MODULE_VERSION) {
            snprintf(load_error, sizeof load_error,
                     "the texture module %s is not this build's (entry point or version)",
                     env && *env ? env : TEXTURE_MODULE_NAME);
        } else {
            api = get();
        }
    }
    if (api) return 0;
    if (err && err_size) snprintf(err, err_size, "%s", load_error);
    return -1;
}

texture_system *texture_system_new(double cache_mb, char *err, size_t err_size)
{
    return load(err, err_size) ? NULL : api->system_new(cache_mb, err, err_size);
}

/* The functions below take a system, which only exists once the module is loaded. */
void texture_system_free(texture_system *ts)
{
    if (ts) api->system_free(ts);
}

int texture_open(texture_system *ts, const char *name, const void *bytes, size_t size,
                 texture_file **out, texture_info *info, char *err, size_t err_size)
{
    return api->open(ts, name, bytes, size, out, info, err, err_size);
}

texture_thread *texture_thread_new(texture_system *ts) { return api->thread_new(ts); }

void texture_thread_free(texture_system *ts, texture_thread *th)
{
    if (ts && th) api->thread_free(ts, th);
}

int texture_lookup(texture_system *ts, texture_thread *th, texture_file *f, int first, int n,
                   double s, double t, double dsdx, double dtdx, double dsdy, double dtdy,
                   float *out)
{
    return api->lookup(ts, th, f, first, n, s, t, dsdx, dtdx, dsdy, dtdy, out);
}

int texture_error(texture_system *ts, char *err, size_t err_size)
{
    return api->error(ts, err, err_size);
}

void texture_stats_get(texture_system *ts, texture_stats *out) { api->stats_get(ts, out); }

void texture_stats_print(texture_system *ts, int level, FILE *f) { api->stats_print(ts, level, f); }

int texture_channel_stats(texture_system *ts, texture_file *f, int level, int channel, int srgb,
                          int nbins, unsigned long long *hist, double *min, double *max, char *err,
                          size_t err_size)
{
    return api->channel_stats(ts, f, level, channel, srgb, nbins, hist, min, max, err, err_size);
}

double texture_srgb_decode(double v)
{
    return v <= 0.04045 ? v / 12.92 : pow((v + 0.055) / 1.055, 2.4); /* IEC 61966-2-1 */
}
