/* image_io.h - image files for the abrdf tool, through OpenImageIO (read/write EXR, PNG,
 * HDR, TIFF, JPEG, ...) and OpenColorIO (scene-linear <-> display for previews). Implemented
 * in C++ (image_io.cpp); this is its C interface. Pixels are linear float RGB, row-major, top
 * row first, 3 floats per pixel.
 *
 *   abrdf_image_write_linear    scene-linear float file (.exr, .hdr, .tif)
 *   abrdf_image_write_preview   8-bit display file (.png, .jpg) through an OpenColorIO view
 *   abrdf_image_write_heatmap   false-colour map of one value per pixel (.png)
 *   abrdf_image_read            any OpenImageIO format -> linear float RGB
 *   abrdf_image_free            release what abrdf_image_read allocated
 *   abrdf_image_is_display_format  true for 8-bit display formats (by extension)
 *
 * Every function returns 0, or -1 with a one-line message (naming the file) in err; none
 * throws or aborts. Thread-safe (no shared state). */
#ifndef ABRDF_IMAGE_IO_H
#define ABRDF_IMAGE_IO_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abrdf_image {
    int width, height;
    int channels;  /* channels in the file that was read (pixels always hold RGB) */
    float *pixels; /* width * height * 3 floats, malloc'd; free with abrdf_image_free */
} abrdf_image;

/* Write linear float RGB as a scene-linear file; the format follows the extension
 * (.exr and .tif as 32-bit float, .hdr as RGBE). Display formats (.png, .jpg) are refused:
 * use abrdf_image_write_preview. */
int abrdf_image_write_linear(const char *path, int width, int height, const float *rgb, char *err,
                             int err_size);
/* Write a display-referred 8-bit preview (.png, .jpg): the OpenColorIO display/view
 * transform from the scene_linear role of `config` (a .ocio file; NULL: the built-in config,
 * scene-linear Rec.709 -> display "sRGB", view "Standard" = piecewise sRGB encoding, no tone
 * mapping). NULL display/view: the config's defaults. Values above 1 clip. */
int abrdf_image_write_preview(const char *path, int width, int height, const float *rgb,
                              const char *config, const char *display, const char *view, char *err,
                              int err_size);
/* Write value[width*height] (one per pixel) as a false-colour 8-bit image: value/vmax clamped
 * to [0,1] (vmax <= 0: all zero) through OpenImageIO's colour map `map` ("inferno" if NULL;
 * also "viridis", "magma", "plasma", "turbo", "heat", ...). */
int abrdf_image_write_heatmap(const char *path, int width, int height, const float *value,
                              double vmax, const char *map, char *err, int err_size);
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
