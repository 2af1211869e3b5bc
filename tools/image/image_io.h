/* image_io.h - image files for the abrdf tool, through OpenImageIO (read/write EXR, PNG,
 * HDR, TIFF, JPEG, ...) and OpenColorIO (scene-linear <-> display for previews). Implemented
 * in C++ (image_io.cpp); this is its C interface. Pixels are linear float RGB, row-major, top
 * row first, 3 floats per pixel.
 *
 *   abrdf_image_encode_linear   scene-linear float file (.exr, .hdr, .tif), in memory
 *   abrdf_image_encode_linear_half  the same as an EXR of half floats
 *   abrdf_image_encode_preview  8-bit display file (.png, .jpg) through an OpenColorIO view
 *   abrdf_image_encode_heatmap  false-colour map of one value per pixel (.png)
 *   abrdf_bytes_free            release what an encoder allocated
 *   abrdf_image_check_output    can a file of this name be encoded (before the work)?
 *   abrdf_image_check_preview   can this preview transform be built (before the work)?
 *   abrdf_image_read            any OpenImageIO format -> linear float RGB
 *   abrdf_image_free            release what abrdf_image_read allocated
 *   abrdf_image_is_display_format  true for 8-bit display formats (by extension)
 *
 * Nothing here writes a file: the encoders return the file's bytes, which the caller writes
 * through out_file.h (whole or not at all, every write checked; OpenImageIO's own file
 * writers do not report every failed write). The format follows the name's extension.
 * Every function returns 0, or -1 with a one-line message (naming the file) in err; none
 * throws or aborts. Thread-safe (no shared state). */
#ifndef ABRDF_IMAGE_IO_H
#define ABRDF_IMAGE_IO_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abrdf_image {
    int width, height;
    int channels;  /* channels in the file that was read (pixels always hold RGB) */
    float *pixels; /* width * height * 3 floats, malloc'd; free with abrdf_image_free */
} abrdf_image;

/* A file's bytes, malloc'd; release with abrdf_bytes_free. */
typedef struct abrdf_bytes {
    unsigned char *data;
    size_t size;
} abrdf_bytes;

/* Encode linear float RGB as a scene-linear file named `name` (the extension picks the
 * format: .exr and .tif as 32-bit float, .hdr as RGBE). Display formats (.png, .jpg) are
 * refused: use abrdf_image_encode_preview. */
int abrdf_image_encode_linear(const char *name, int width, int height, const float *rgb,
                              abrdf_bytes *out, char *err, int err_size);
/* The same as an EXR of half floats (`name` must end in .exr): each value rounded to the
 * nearest half, so exact for values that are halves already (abrdf export --pov's huang
 * tables, about half the size of float32); beyond half's range (65504) a value becomes
 * infinite. */
int abrdf_image_encode_linear_half(const char *name, int width, int height, const float *rgb,
                                   abrdf_bytes *out, char *err, int err_size);
/* Encode a display-referred 8-bit preview (.png, .jpg): the OpenColorIO display/view
 * transform from the scene_linear role of `config` (a .ocio file; NULL: the built-in config,
 * scene-linear Rec.709 -> display "sRGB", view "Standard" = piecewise sRGB encoding, no tone
 * mapping). NULL display/view: the config's defaults. Values above 1 clip. */
int abrdf_image_encode_preview(const char *name, int width, int height, const float *rgb,
                               const char *config, const char *display, const char *view,
                               abrdf_bytes *out, char *err, int err_size);
/* Encode value[width*height] (one per pixel) as a false-colour 8-bit image: value/vmax
 * clamped to [0,1] (vmax <= 0: all zero) through OpenImageIO's colour map `map` ("inferno"
 * if NULL; also "viridis", "magma", "plasma", "turbo", "heat", ...). */
int abrdf_image_encode_heatmap(const char *name, int width, int height, const float *value,
                               double vmax, const char *map, abrdf_bytes *out, char *err,
                               int err_size);
void abrdf_bytes_free(abrdf_bytes *b);
/* 0 if a file named `name` can be encoded here: OpenImageIO knows the extension and encodes
 * it in memory, and it is scene-linear (linear = 1: not a display format) or a display
 * format (linear = 0). Else -1 with "NAME: reason". */
int abrdf_image_check_output(const char *name, int linear, char *err, int err_size);
/* 0 if the preview transform of abrdf_image_encode_preview can be built from these
 * arguments (config readable, display and view defined), else -1 with the reason. */
int abrdf_image_check_preview(const char *config, const char *display, const char *view, char *err,
                              int err_size);
/* Read any format OpenImageIO reads into linear float RGB (grey replicated, alpha and extra
 * channels dropped). Display-referred files - tagged sRGB, or untagged integer pixels
 * (8/16-bit PNG, JPEG, TIFF) - are decoded with the inverse of the built-in sRGB display
 * transform; float files (EXR, HDR, float TIFF) are taken as scene-linear. */
int abrdf_image_read(const char *path, abrdf_image *img, char *err, int err_size);
void abrdf_image_free(abrdf_image *img);
/* 1 if the extension names an 8-bit display format (png, jpg, jpeg, bmp, gif, webp, ppm). */
int abrdf_image_is_display_format(const char *path);

#ifdef __cplusplus
}
#endif
#endif
