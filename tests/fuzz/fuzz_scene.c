/* fuzz_scene.c - fuzz target of the scene parser and the renderer behind it: any bytes must
 * either be rejected with a message or parse into a scene that renders a tiny image with
 * finite, non-negative pixels. libFuzzer entry point; tests/fuzz/fuzz_driver.c runs it
 * deterministically under CTest (also in the sanitizer build). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "fuzz_target.h"
#include "render.h"

/* Inputs that parsed and rendered (the driver reports it: coverage of the renderer). */
static unsigned long rendered;

/* A comment longer than any line buffer, and a word longer than the parser takes. */
#define LONG_TEXT_64 "0123456789abcdef0123456789abcdef0123456789abcdef0123456789abcdef"
#define LONG_WORD LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64 LONG_TEXT_64
#define LONG_COMMENT LONG_WORD " " LONG_WORD " " LONG_WORD " " LONG_WORD

const char *const fuzz_tokens[] = {
    "\n",
    " ",
    "=",
    ",",
    "#",
    "\r",
    "\t",
    "\0",
    "0",
    "-0",
    "1e308",
    "-1e308",
    "1e-320",
    "nan",
    "inf",
    "0x10",
    "999999999999",
    "1,2",
    "1,2,3,4",
    ",,,",
    "==",
    "sphere",
    "box",
    "capsule",
    "cylinder",
    "camera",
    "light",
    "point",
    "directional",
    "material",
    "ambient",
    "adaptive",
    "radius=",
    "height=",
    "size=",
    "scale=",
    "rotate=",
    "translate=",
    "tangent=",
    "material=",
    "model=",
    "diffuse=",
    "specular=",
    "kd=",
    "r=",
    "n=",
    "anisotropic=",
    "layer_count=",
    "position=",
    "look_at=",
    "up=",
    "fov=",
    "resolution=",
    "direction=",
    "intensity=",
    "color=",
    "disney_specular_aniso",
    "lambert",
    "f_2e",
    "marschner",
    "1e6",
    "-1e6",
    "179",
    "0,0,0",
    "\xff\xfe",
    "m",
    "mesh",
    "file=",
    "smooth=",
    "off",
    "uv",
    "x.obj",
    "measured=",
    "m.binary",
    "1e-310", /* subnormal: a finite number */
    "#" LONG_COMMENT,
    LONG_WORD,
};
const size_t fuzz_token_count = sizeof fuzz_tokens / sizeof fuzz_tokens[0];

void fuzz_report(FILE *f) { fprintf(f, "%lu parsed and rendered", rendered); }

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    scene s;
    char err[512];
    if (scene_parse_text("fuzz", (const char *)data, size, &s, err, sizeof err) != 0) {
        /* Rejected: the message must name the input (or a mesh file and the input's line
         * that asked for it) and be terminated. */
        if (memchr(err, '\0', sizeof err) == NULL) abort();
        if (strncmp(err, "fuzz:", 5) != 0 && !strstr(err, "(mesh at fuzz:")) abort();
        return 0;
    }
    /* With the effect plan, and without it (every effect everywhere). */
    for (int full = 0; full < 4; ++full) { /* and each precision */
        render_options opt = {3, 2, 1, 1, 1,   0, full >= 2 ? RENDER_DOUBLE : RENDER_FLOAT,
                              0, 0, 0, 0, NULL};
        render_scene rs;
        if (render_prepare(&s, &opt, &rs, err, sizeof err) == 0) {
            if ((full & 1) && render_plan_ignore(&rs) != 0) abort();
            float rgb[3 * 2 * 3];
            if (render_image(&rs, &opt, rgb, NULL) != 0) abort();
            for (size_t k = 0; k < sizeof rgb / sizeof rgb[0]; ++k)
                if (!(rgb[k] >= 0.0f) || isinf(rgb[k])) abort();
            render_release(&rs);
            rendered += full;
        }
    }
    scene_free(&s);
    return 0;
}
