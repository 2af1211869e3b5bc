/* image_io.h - image files for the abrdf tool, through OpenImageIO (read/write EXR, PNG,
 * HDR, ...) and OpenColorIO (scene-linear -> display for previews). Implemented in C++
 * (image_io.cpp); this is its C interface. Pixels are linear float RGB, row-major, top row
 * first, 3 floats per pixel. */
#ifndef ABRDF_IMAGE_IO_H
#define ABRDF_IMAGE_IO_H

#ifdef __cplusplus
extern "C" {
#endif

typedef struct abrdf_image {
    int width, height;
    int channels;   /* channels in the file that was read (pixels always hold RGB) */
    float *pixels;  /* width * height * 3 floats, malloc'd; free with abrdf_image_free */
} abrdf_image;

/* Write linear float RGB as a scene-linear file; the format follows the extension
 * (.exr half/float, .hdr, .tif, ...). Returns 0 or -1 with a message in err. */
int abrdf_image_write_linear(const char *path, int width, int height, const float *rgb,
                             char *err, int err_size);
/* Write a display-referred 8-bit preview (.png, .jpg): OpenColorIO transform from
 * scene-linear to `display`/`view` of `config` (NULL: the built-in sRGB transform of
 * OpenColorIO's default config). Returns 0 or -1 with a message in err. */
int abrdf_image_write_preview(const char *path, int width, int height, const float *rgb,
                              const char *config, const char *display, const char *view,
                              char *err, int err_size);
/* Read any format OpenImageIO reads into linear float RGB (grey replicated, alpha dropped;
 * 8-bit sRGB files are linearised by OpenImageIO's colour handling). */
int abrdf_image_read(const char *path, abrdf_image *img, char *err, int err_size);
void abrdf_image_free(abrdf_image *img);

#ifdef __cplusplus
}
#endif
#endif
