/* bench.h - `abrdf bench`: what accuracy costs in time (docs/BENCHMARKS.md).
 *
 *   bench_robot_parse    the built-in robot scene (scenes/robot.scene)
 *   bench_robot_lobes    render the robot with every material replaced by given lobes
 *   bench_render_report  `abrdf bench --render`: full Disney vs adaptive photoreal and
 *                        performance on the robot: time ratios and NMSE per material
 *   bench_lobe_report    per-lobe render cost vs per-eval cost on the 16-light robot
 *   bench_lights_report  MIS vs light-only vs BRDF-only noise on the sampled lights, at equal
 *                        samples and equal time, per model (bench_lights.c)
 */
#ifndef ABRDF_BENCH_H
#define ABRDF_BENCH_H
#include <stdio.h>
#include "abrdf.h"
#include "bench_scene.h"
#include "scene.h"

/* Returns 0, or -1 with a message in err. */
int bench_robot_parse(scene *s, char *err, size_t err_size);

/* Every material of s becomes `diffuse` (ABRDF_MODEL_NONE: none) + `specular`
 * (ABRDF_MODEL_NONE: none) with parameters p, no ambient term; rendered at size x size,
 * 1 sample per pixel (pixel centres), into rgb (size*size*3 floats). *seconds (may be NULL)
 * receives the wall time of render_image. Returns 0, or -1 with a message in err. */
int bench_robot_lobes(scene *s, int size, int threads, abrdf_model diffuse, abrdf_model specular,
                      const abrdf_params *p, float *rgb, double *seconds, char *err,
                      size_t err_size);

/* `abrdf bench --render`: writes a table (json 0) or a JSON object (json 1) to out.
 * size: image size (0 = the scene's); reps: timed renders per variant (median). Ends with
 * bench_lobe_report at lobe_size (JSON: its object under "lobe_costs"). */
int bench_render_report(FILE *out, int json, int size, int reps, int threads, int lobe_size,
                        int quick);

/* What each specular lobe costs in a one-thread render of scenes/robot16.scene at size x size
 * (time with lambert + X minus lambert alone) beside its batch per-eval cost, both relative
 * to disney_specular, and the BRDFs' share of the render time (bench_lobes.c). */
int bench_lobe_report(FILE *out, int json, int size, int reps, int quick);

/* The noise of the three estimators of the sampled lights (render_estimator) against a
 * high-sample MIS reference, and their render times, on scenes/area.scene and under a sky
 * map, for a few models (bench_lights.c). A table (json 0) or a JSON object (json 1). */
int bench_lights_report(FILE *out, int json, int reps, int threads, int quick);

#endif
