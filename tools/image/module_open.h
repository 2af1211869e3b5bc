/* module_open.h - where the abrdf command finds a module it loads on first use (the image
 * I/O module, image_io_lazy.c; the texture module, tools/render/texture_lazy.c).
 *
 * PUBLIC FUNCTIONS
 *   module_open   dlopen a module by the tool's rules
 */
#ifndef ABRDF_MODULE_OPEN_H
#define ABRDF_MODULE_OPEN_H

/* dlopen (RTLD_NOW | RTLD_LOCAL) the module file `name`: the path in the environment
 * variable env_var if it is set and not empty; else next to the executable (the build tree);
 * else relative/name from the executable's directory (the installed tree: bin/ -> lib/abrdf/);
 * else through the loader's search path. NULL if none opens (dlerror() says why). */
void *module_open(const char *env_var, const char *name, const char *relative);

#endif
