/* texture_module.h - the table of functions the texture module (texture.cpp, built as
 * libabrdf_texture.so) hands texture_lazy.c, which implements texture.h over it. */
#ifndef ABRDF_TEXTURE_MODULE_H
#define ABRDF_TEXTURE_MODULE_H

#include "texture.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TEXTURE_MODULE_VERSION 1 /* raised when the table changes */

typedef struct texture_module_api {
    int version;
    texture_system *(*system_new)(double, char *, size_t);
    void (*system_free)(texture_system *);
    int (*open)(texture_system *, const char *, const void *, size_t, texture_file **,
                texture_info *, char *, size_t);
    texture_thread *(*thread_new)(texture_system *);
    void (*thread_free)(texture_system *, texture_thread *);
    int (*lookup)(texture_system *, texture_thread *, texture_file *, int, int, double, double,
                  double, double, double, double, float *);
    void (*stats_get)(texture_system *, texture_stats *);
    void (*stats_print)(texture_system *, int, FILE *);
    int (*channel_stats)(texture_system *, texture_file *, int, int, int, int, unsigned long long *,
                         double *, double *, char *, size_t);
    int (*error)(texture_system *, char *, size_t);
} texture_module_api;

/* The module's one exported symbol. */
typedef const texture_module_api *(*texture_module_fn)(void);

#ifdef __cplusplus
}
#endif

#endif
