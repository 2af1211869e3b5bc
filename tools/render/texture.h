/* texture.h - image textures of the built-in renderer through OpenImageIO's TextureSystem
 * (tiled, mip-mapped, cached image lookups: the texture engine OSL and many production
 * renderers use). Implemented in C++ (texture.cpp); this is its C interface.
 *
 * One texture system per render, shared by the threads: one cache whose tiles are bounded by
 * cache_mb (TEXTURE_CACHE_MB_DEFAULT unless the caller says; `abrdf render --texture-cache`);
 * each thread looks up through its own texture_thread. Files are resolved once (texture_open,
 * at render_prepare) into handles; lookups then name no file.
 *
 * Lookups are filtered: (s, t) with the derivatives of (s, t) along the two axes of a
 * sample's footprint choose the MIP level and the anisotropic filter (OpenImageIO's default
 * "aniso" MIP mode), bilinear within a level (so a lookup at a texel's centre returns that
 * texel exactly on the finest level). Wrap: periodic in s and t (glTF's default sampler,
 * REPEAT). Coordinates: (0, 0) is the top-left corner of the image, t downwards - glTF's UV
 * convention; the renderer converts an OBJ mesh's texture coordinates (v upwards) with
 * t = 1 - v and takes a glTF mesh's as they are (docs/GLTF.md, "Textures"). Values are the file's raw channel values in [0, 1]
 * for integer files (no colour conversion: sRGB decoding is the caller's).
 *
 * A file without MIP levels (a PNG, a scanline EXR) is read as it is and its levels are made
 * on demand (OpenImageIO's automip), tiled 64 x 64 in the cache (autotile), so the memory
 * bound holds for it too; `maketx` (openimageio-tools) makes tiled, mip-mapped files that
 * load only the tiles a render needs.
 *
 * In-memory images (a .glb file's embedded PNG or JPEG): texture_open with bytes != NULL
 * reads them through an OpenImageIO memory reader (IOProxy); `name` then only labels the
 * image in messages and statistics (e.g. "model.glb#image3"), and the bytes must outlive the
 * texture system. The formats that read from memory in OpenImageIO 2.4 include PNG, JPEG,
 * TIFF and OpenEXR; another one is refused at texture_open with one line.
 *
 * Every function that can fail returns 0, or -1 with one line "NAME: problem" in err; none
 * throws. The module (libabrdf_texture.so) is loaded on first use by texture_lazy.c, as the
 * image module is (tools/image/image_io_lazy.c): commands that never read a texture do not
 * load OpenImageIO.
 *
 * PUBLIC FUNCTIONS
 *   texture_system_new    a texture system with its cache bound
 *   texture_system_free   release it (its files, threads and tiles)
 *   texture_open          resolve a file (or bytes) into a handle; reads its header
 *   texture_thread_new    a thread's lookup state (one per thread)
 *   texture_thread_free   release it
 *   texture_lookup        filtered lookup of channels [first, first + n) at (s, t)
 *   texture_error         the first failed lookup's message, if any
 *   texture_stats_get     the system's statistics (memory, lookups, bytes read)
 *   texture_stats_print   OpenImageIO's own statistics report
 *   texture_channel_stats the histogram, minimum and maximum of one channel of a whole image
 */
#ifndef ABRDF_TEXTURE_H
#define ABRDF_TEXTURE_H

#include <stddef.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define TEXTURE_CACHE_MB_DEFAULT                                                                   \
    256.0                        /* OpenImageIO's own default: room for ~1000 64x64
                                          float RGBA tiles per 16 MB */
#define TEXTURE_CACHE_MB_MIN 1.0 /* below one MB the cache thrashes on any image */
#define TEXTURE_CACHE_MB_MAX 65536.0

typedef struct texture_system texture_system;
typedef struct texture_file texture_file; /* a resolved image, owned by its system */
typedef struct texture_thread texture_thread;

typedef struct texture_info {
    int width, height; /* of the finest level */
    int channels;      /* in the file */
    int levels;        /* MIP levels in the file (1: none; made on demand) */
    int tiled;         /* the file is tiled */
} texture_info;

typedef struct texture_stats {
    unsigned long long lookups;    /* filtered lookups (stat:texture_queries) */
    unsigned long long bytes_read; /* pixel bytes read from files (stat:bytes_read) */
    long long memory_used;         /* tile cache bytes now (stat:cache_memory_used) */
    double peak_memory_mb;         /* most tile cache memory at any time ("Peak cache memory"
                                      of OpenImageIO's report), MB; -1 if not reported */
    int tiles_peak;                /* most tiles held at any time (stat:tiles_peak) */
    int files;                     /* distinct files opened (stat:unique_files) */
} texture_stats;

/* NULL with the reason in err if OpenImageIO cannot be loaded or cache_mb is outside
 * [TEXTURE_CACHE_MB_MIN, TEXTURE_CACHE_MB_MAX]. */
texture_system *texture_system_new(double cache_mb, char *err, size_t err_size);
void texture_system_free(texture_system *ts);

/* Resolve name (a file path; with bytes, a label) into *out and read its header into info
 * (may be NULL): any image OpenImageIO reads, any channel count (a lookup reads up to 4).
 * Opening the same name twice gives the same handle. */
int texture_open(texture_system *ts, const char *name, const void *bytes, size_t size,
                 texture_file **out, texture_info *info, char *err, size_t err_size);

texture_thread *texture_thread_new(texture_system *ts);
void texture_thread_free(texture_system *ts, texture_thread *th);

/* Channels [first, first + n) (n <= 4, first + n <= the file's channels) at (s, t), with the
 * derivatives of s and t along the footprint's two axes x and y, into out[0..n-1]. 0, or -1
 * (out zeroed) if OpenImageIO fails (a file that breaks after texture_open). */
int texture_lookup(texture_system *ts, texture_thread *th, texture_file *f, int first, int n,
                   double s, double t, double dsdx, double dtdx, double dsdy, double dtdy,
                   float *out);

/* 0 if every lookup so far succeeded, else -1 with the first failure's "NAME: problem" (a
 * file whose header read but whose pixels do not: a truncated file). */
int texture_error(texture_system *ts, char *err, size_t err_size);

void texture_stats_get(texture_system *ts, texture_stats *out);
/* OpenImageIO's report (TextureSystem::getstats at `level`, 1 to 5) to f. */
void texture_stats_print(texture_system *ts, int level, FILE *f);

/* The values of one channel over the whole image at MIP level `level` (0: the finest; a
 * file without levels has only 0), read a row at a time through the cache (memory: the cache
 * bound plus one row). srgb: each value v is decoded first (the sRGB transfer function, IEC
 * 61966-2-1). hist[nbins] counts the values in nbins equal bins over [0, 1] (below 0 in the
 * first, 1 and above in the last); *min, *max the extremes (NaN values are not counted).
 * 0, or -1 with the message. */
int texture_channel_stats(texture_system *ts, texture_file *f, int level, int channel, int srgb,
                          int nbins, unsigned long long *hist, double *min, double *max, char *err,
                          size_t err_size);

/* The sRGB transfer function's inverse (encoded [0, 1] -> linear), IEC 61966-2-1. */
double texture_srgb_decode(double v);

#ifdef __cplusplus
}
#endif

#endif
