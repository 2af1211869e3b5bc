/* cmd_export.c - `abrdf export --pov SCENE -o OUT.pov`: the scene for POV-Ray 3.7. */
#include <stdlib.h>
#include <string.h>

#include "cli.h"
#include "export_pov.h"

static int usage(void)
{
    printf("usage: abrdf export --pov SCENE -o OUT.pov [--model NAME [--set NAME=VALUE ...]]\n"
           "                    [--width W] [--height H] [--no-shadows | --native]\n\n"
           "Writes SCENE (docs/SCENES.md) as POV-Ray 3.7 SDL that shades every object with the\n"
           "library's models (povray_macros/abrdf.inc, docs/POVRAY.md): same camera, lights,\n"
           "primitives and materials. Render it with +L<abrdf>/povray_macros, linear HDR (+FE).\n\n"
           "  --model/--set      as abrdf render: every material becomes this model\n"
           "  --width/--height   the resolution written in the header comment (aspect ratio\n"
           "                     of the camera); default the scene's\n"
           "  --no-shadows       emissive mode even with one light (no shadows); with several\n"
           "                     lights this is the only mode\n"
           "  --native           POV-Ray's own finishes instead of function pigments (fast path):\n"
           "                     lambert, phong, blinn_phong only; directional lights only;\n"
           "                     phong/blinn_phong then lack the factor N.wi (docs/POVRAY.md)\n");
    return 0;
}

int cmd_export(int argc, char **argv)
{
    const char *cmd = "export", *path = NULL, *out = NULL, *model_name = NULL;
    const char *sets[64];
    int nsets = 0, pov = 0, no_shadows = 0, native = 0;
    render_options opt;
    memset(&opt, 0, sizeof opt);
    opt.spp = 1;
    opt.threads = 1;
    for (int i = 1; i < argc; ++i) {
        const char *a = argv[i], *val = i + 1 < argc ? argv[i + 1] : NULL;
        if (cli_is_help(a)) return usage();
        if (!strcmp(a, "--pov")) pov = 1;
        else if (!strcmp(a, "--no-shadows")) no_shadows = 1;
        else if (!strcmp(a, "--native")) native = 1;
        else if (!strcmp(a, "-o") || !strcmp(a, "--model") || !strcmp(a, "--set")) {
            if (!val) return cli_fail(cmd, "%s needs a value", a);
            ++i;
            if (!strcmp(a, "-o")) out = val;
            else if (!strcmp(a, "--model")) model_name = val;
            else if (nsets == 64) return cli_fail(cmd, "too many --set options (64 at most)");
            else sets[nsets++] = val;
        } else if (!strcmp(a, "--width") || !strcmp(a, "--height")) {
            long v;
            if (!cli_parse_int(val, 1, SCENE_MAX_RESOLUTION, &v))
                return cli_fail(cmd, "%s needs a whole number in [1, %d]", a, SCENE_MAX_RESOLUTION);
            ++i;
            if (!strcmp(a, "--width")) opt.width = (int)v;
            else opt.height = (int)v;
        } else if (a[0] == '-') {
            return cli_fail(cmd, "unknown option '%s' (abrdf export --help)", a);
        } else if (!path) {
            path = a;
        } else {
            return cli_fail(cmd, "more than one SCENE ('%s' and '%s')", path, a);
        }
    }
    if (!pov) return cli_fail(cmd, "choose the format: --pov (the only exporter of this build)");
    if (!path) return cli_fail(cmd, "missing SCENE (abrdf export --help)");
    if (!out) return cli_fail(cmd, "missing -o OUT.pov");
    if (nsets && !model_name) return cli_fail(cmd, "--set needs --model");
    if (native && no_shadows) return cli_fail(cmd, "--native uses POV-Ray's lights (with shadows); drop --no-shadows");

    scene s;
    char err[512];
    if (scene_parse_file(path, &s, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        return 1;
    }
    int rc = 1, prepared = 0;
    render_scene rs;
    FILE *f = NULL;
    if (model_name) {
        abrdf_model m;
        if (cli_model(cmd, model_name, &m)) {
            rc = CLI_EXIT_USAGE;
            goto done;
        }
        if (render_set_model(&s, m, err, sizeof err)) {
            fprintf(stderr, "abrdf export: %s\n", err);
            goto done;
        }
        for (int i = 0; i < nsets; ++i)
            for (int j = 0; j < s.material_count; ++j)
                if (cli_set_param(cmd, m, &s.materials[j].params, sets[i])) {
                    rc = CLI_EXIT_USAGE;
                    goto done;
                }
    }
    if (render_prepare(&s, &opt, &rs, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s\n", err);
        goto done;
    }
    prepared = 1;
    export_pov_options eo = {!native && !no_shadows && rs.light_count == 1, native, path};
    if (!(f = fopen(out, "w"))) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        goto done;
    }
    if (export_pov_write(&rs, &eo, f, err, sizeof err)) {
        fprintf(stderr, "abrdf export: %s: %s\n", out, err);
        goto done;
    }
    rc = 0;
done:
    if (f && fclose(f) && rc == 0) {
        fprintf(stderr, "abrdf export: cannot write %s\n", out);
        rc = 1;
    }
    if (prepared) render_release(&rs);
    scene_free(&s);
    return rc;
}
