/* map_range.c - a material's maps for the selection (map_range.h). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "map_range.h"

int map_open(texture_system *ts, const scene_map *mp, texture_file **out, texture_info *info,
             char *err, size_t err_size)
{
    char named[1200];
    const char *name = mp->path;
    if (mp->blob) {
        const unsigned char *b = mp->blob;
        int png = !strcmp(mp->mime, "image/png") ||
                  (!mp->mime[0] && mp->blob_size >= 4 && b[0] == 0x89 && b[1] == 'P');
        int jpg = !strcmp(mp->mime, "image/jpeg") ||
                  (!mp->mime[0] && mp->blob_size >= 2 && b[0] == 0xff && b[1] == 0xd8);
        snprintf(named, sizeof named, "%s%s", mp->path, png ? ".png" : jpg ? ".jpg" : "");
        name = named;
    }
    return texture_open(ts, name, mp->blob, mp->blob_size, out, info, err, err_size);
}

int map_range_read(void *user, const scene_material *sm, pbr_range *out, char *err, size_t err_size)
{
    (void)user;
    const scene_map *mp = &sm->maps[SCENE_MAP_ROUGHNESS];
    memset(out, 0, sizeof *out);
    if (!mp->path) {
        snprintf(err, err_size, "material '%s' has no roughness map", sm->name);
        return -1;
    }
    texture_system *ts = texture_system_new(TEXTURE_CACHE_MB_DEFAULT, err, err_size);
    if (!ts) return -1;
    texture_file *f;
    texture_info info;
    unsigned long long hist[MAP_RANGE_BINS];
    double lo, hi;
    int rc = map_open(ts, mp, &f, &info, err, err_size);
    if (!rc && mp->channel >= info.channels) {
        snprintf(err, err_size, "%s: no channel %d (it has %d) for the roughness of material '%s'",
                 mp->path, mp->channel, info.channels, sm->name);
        rc = -1;
    }
    if (!rc)
        rc = texture_channel_stats(ts, f, 0, mp->channel, 0, MAP_RANGE_BINS, hist, &lo, &hi, err,
                                   err_size);
    texture_system_free(ts);
    if (rc) return -1;
    unsigned long long total = 0;
    for (int b = 0; b < MAP_RANGE_BINS; ++b) total += hist[b];
    if (!total) {
        snprintf(err, err_size, "%s: the roughness channel holds no value", mp->path);
        return -1;
    }
    double factor = sm->pbr_in.roughness;
    for (int b = 0; b < MAP_RANGE_BINS; ++b) {
        if (!hist[b]) continue;
        /* the bin's centre, kept within the values it holds */
        double v = fmin(fmax((b + 0.5) / MAP_RANGE_BINS, lo), hi);
        out->r[out->count] = fmin(fmax(factor * v, 0.0), 1.0);
        out->share[out->count++] = (double)hist[b] / (double)total;
    }
    out->r[out->count] = fmin(fmax(factor * lo, 0.0), 1.0), out->share[out->count++] = 0;
    out->r[out->count] = fmin(fmax(factor * hi, 0.0), 1.0), out->share[out->count++] = 0;
    out->what = mp->path;
    return 0;
}
