/* gen_teapot.c - the Utah teapot as a triangle mesh (Wavefront OBJ), tessellated from Martin
 * Newell's bicubic Bezier patches (1975). Writes scenes/teapot.obj; re-running it with the
 * same arguments reproduces that file byte for byte (tools/gen/gen_tables.py runs it; CTest
 * generated_files_current).
 *
 *   gen_teapot [--segments N] [-o OUT.obj]     (default: 8 segments, stdout)
 *
 * Data: the 32 patches and 306 control points of the teapot data set as distributed with
 * the teaset archive and reproduced in F. C. Crow, "The Origins of the Teapot", IEEE
 * Computer Graphics and Applications 7(1), 1987: 28 patches of Newell's teapot (rim, body,
 * handle, spout, lid) and the 4 bottom patches added later (Crow). Newell's proportions are
 * kept (no 1.3 vertical squash, no fitted lid). The data are z up; the mesh is written y up
 * (the scene format's axes: x_out = x, y_out = z, z_out = -y), spout toward +x, the base at
 * y = 0, height 3.15.
 *
 * Tessellation: every patch is sampled on an N x N grid of parameter steps; each grid cell
 * is two triangles (split along the diagonal from (i, j) to (i+1, j+1)). Vertices on shared
 * patch edges are evaluated from the same control points in the same order, so they are
 * bitwise equal and are welded; triangles that collapse to a point or a line (the lid's top
 * and the bottom's centre, where a patch edge is a single point) are dropped. Triangles:
 * 64 N^2 - 8 N (4032 for N = 8; 1 047 552 for N = 128).
 *
 * Normals are the surfaces' own: the unit cross product of the partial derivatives, oriented
 * outward, one per grid point and patch (so per face corner: where two patches meet at a
 * crease each keeps its own). Where a patch edge collapses to a point on the teapot's axis the
 * derivative cross product vanishes; the normal there is the axis direction, which every
 * rotationally symmetric patch meeting at that point shares. Texture coordinates are the
 * patch parameters: u along the second control index (around the teapot for rim, body and
 * lid), v = 1 - (first index) (along the profile, upward on the body), so a `tangent=uv` frame
 * follows the surface around the axis like the `u` rule does on a cylinder.
 *
 * Coordinates are rounded to float and written with 9 significant digits, which a float
 * reader recovers exactly. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define PATCHES 32
#define POINTS 306

/* Control point indices (1-based, as published) of each patch, row by row (4 rows of 4). */
static const short patch_index[PATCHES][16] = {
    /* rim */
    {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16},
    {4, 17, 18, 19, 8, 20, 21, 22, 12, 23, 24, 25, 16, 26, 27, 28},
    {19, 29, 30, 31, 22, 32, 33, 34, 25, 35, 36, 37, 28, 38, 39, 40},
    {31, 41, 42, 1, 34, 43, 44, 5, 37, 45, 46, 9, 40, 47, 48, 13},
    /* body */
    {13, 14, 15, 16, 49, 50, 51, 52, 53, 54, 55, 56, 57, 58, 59, 60},
    {16, 26, 27, 28, 52, 61, 62, 63, 56, 64, 65, 66, 60, 67, 68, 69},
    {28, 38, 39, 40, 63, 70, 71, 72, 66, 73, 74, 75, 69, 76, 77, 78},
    {40, 47, 48, 13, 72, 79, 80, 49, 75, 81, 82, 53, 78, 83, 84, 57},
    {57, 58, 59, 60, 85, 86, 87, 88, 89, 90, 91, 92, 93, 94, 95, 96},
    {60, 67, 68, 69, 88, 97, 98, 99, 92, 100, 101, 102, 96, 103, 104, 105},
    {69, 76, 77, 78, 99, 106, 107, 108, 102, 109, 110, 111, 105, 112, 113, 114},
    {78, 83, 84, 57, 108, 115, 116, 85, 111, 117, 118, 89, 114, 119, 120, 93},
    /* handle */
    {121, 122, 123, 124, 125, 126, 127, 128, 129, 130, 131, 132, 133, 134, 135, 136},
    {124, 137, 138, 121, 128, 139, 140, 125, 132, 141, 142, 129, 136, 143, 144, 133},
    {133, 134, 135, 136, 145, 146, 147, 148, 149, 150, 151, 152, 69, 153, 154, 155},
    {136, 143, 144, 133, 148, 156, 157, 145, 152, 158, 159, 149, 155, 160, 161, 69},
    /* spout */
    {162, 163, 164, 165, 166, 167, 168, 169, 170, 171, 172, 173, 174, 175, 176, 177},
    {165, 178, 179, 162, 169, 180, 181, 166, 173, 182, 183, 170, 177, 184, 185, 174},
    {174, 175, 176, 177, 186, 187, 188, 189, 190, 191, 192, 193, 194, 195, 196, 197},
    {177, 184, 185, 174, 189, 198, 199, 186, 193, 200, 201, 190, 197, 202, 203, 194},
    /* lid */
    {204, 204, 204, 204, 207, 208, 209, 210, 211, 211, 211, 211, 212, 213, 214, 215},
    {204, 204, 204, 204, 210, 217, 218, 219, 211, 211, 211, 211, 215, 220, 221, 222},
    {204, 204, 204, 204, 219, 224, 225, 226, 211, 211, 211, 211, 222, 227, 228, 229},
    {204, 204, 204, 204, 226, 230, 231, 207, 211, 211, 211, 211, 229, 232, 233, 212},
    {212, 213, 214, 215, 234, 235, 236, 237, 238, 239, 240, 241, 242, 243, 244, 245},
    {215, 220, 221, 222, 237, 246, 247, 248, 241, 249, 250, 251, 245, 252, 253, 254},
    {222, 227, 228, 229, 248, 255, 256, 257, 251, 258, 259, 260, 254, 261, 262, 263},
    {229, 232, 233, 212, 257, 264, 265, 234, 260, 266, 267, 238, 263, 268, 269, 242},
    /* bottom (Crow) */
    {270, 270, 270, 270, 279, 280, 281, 282, 275, 276, 277, 278, 271, 272, 273, 274},
    {270, 270, 270, 270, 282, 289, 290, 291, 278, 286, 287, 288, 274, 283, 284, 285},
    {270, 270, 270, 270, 291, 298, 299, 300, 288, 295, 296, 297, 285, 292, 293, 294},
    {270, 270, 270, 270, 300, 305, 306, 279, 297, 303, 304, 275, 294, 301, 302, 271},
};

/* Control points, z up. Points 205, 206, 216 and 223 are part of the data set but no patch
 * uses them. */
static const double point[POINTS][3] = {
    {1.4, 0.0, 2.4},
    {1.4, -0.784, 2.4},
    {0.784, -1.4, 2.4},
    {0.0, -1.4, 2.4},
    {1.3375, 0.0, 2.53125},
    {1.3375, -0.749, 2.53125},
    {0.749, -1.3375, 2.53125},
    {0.0, -1.3375, 2.53125},
    {1.4375, 0.0, 2.53125},
    {1.4375, -0.805, 2.53125},
    {0.805, -1.4375, 2.53125},
    {0.0, -1.4375, 2.53125},
    {1.5, 0.0, 2.4},
    {1.5, -0.84, 2.4},
    {0.84, -1.5, 2.4},
    {0.0, -1.5, 2.4},
    {-0.784, -1.4, 2.4},
    {-1.4, -0.784, 2.4},
    {-1.4, 0.0, 2.4},
    {-0.749, -1.3375, 2.53125},
    {-1.3375, -0.749, 2.53125},
    {-1.3375, 0.0, 2.53125},
    {-0.805, -1.4375, 2.53125},
    {-1.4375, -0.805, 2.53125},
    {-1.4375, 0.0, 2.53125},
    {-0.84, -1.5, 2.4},
    {-1.5, -0.84, 2.4},
    {-1.5, 0.0, 2.4},
    {-1.4, 0.784, 2.4},
    {-0.784, 1.4, 2.4},
    {0.0, 1.4, 2.4},
    {-1.3375, 0.749, 2.53125},
    {-0.749, 1.3375, 2.53125},
    {0.0, 1.3375, 2.53125},
    {-1.4375, 0.805, 2.53125},
    {-0.805, 1.4375, 2.53125},
    {0.0, 1.4375, 2.53125},
    {-1.5, 0.84, 2.4},
    {-0.84, 1.5, 2.4},
    {0.0, 1.5, 2.4},
    {0.784, 1.4, 2.4},
    {1.4, 0.784, 2.4},
    {0.749, 1.3375, 2.53125},
    {1.3375, 0.749, 2.53125},
    {0.805, 1.4375, 2.53125},
    {1.4375, 0.805, 2.53125},
    {0.84, 1.5, 2.4},
    {1.5, 0.84, 2.4},
    {1.75, 0.0, 1.875},
    {1.75, -0.98, 1.875},
    {0.98, -1.75, 1.875},
    {0.0, -1.75, 1.875},
    {2.0, 0.0, 1.35},
    {2.0, -1.12, 1.35},
    {1.12, -2.0, 1.35},
    {0.0, -2.0, 1.35},
    {2.0, 0.0, 0.9},
    {2.0, -1.12, 0.9},
    {1.12, -2.0, 0.9},
    {0.0, -2.0, 0.9},
    {-0.98, -1.75, 1.875},
    {-1.75, -0.98, 1.875},
    {-1.75, 0.0, 1.875},
    {-1.12, -2.0, 1.35},
    {-2.0, -1.12, 1.35},
    {-2.0, 0.0, 1.35},
    {-1.12, -2.0, 0.9},
    {-2.0, -1.12, 0.9},
    {-2.0, 0.0, 0.9},
    {-1.75, 0.98, 1.875},
    {-0.98, 1.75, 1.875},
    {0.0, 1.75, 1.875},
    {-2.0, 1.12, 1.35},
    {-1.12, 2.0, 1.35},
    {0.0, 2.0, 1.35},
    {-2.0, 1.12, 0.9},
    {-1.12, 2.0, 0.9},
    {0.0, 2.0, 0.9},
    {0.98, 1.75, 1.875},
    {1.75, 0.98, 1.875},
    {1.12, 2.0, 1.35},
    {2.0, 1.12, 1.35},
    {1.12, 2.0, 0.9},
    {2.0, 1.12, 0.9},
    {2.0, 0.0, 0.45},
    {2.0, -1.12, 0.45},
    {1.12, -2.0, 0.45},
    {0.0, -2.0, 0.45},
    {1.5, 0.0, 0.225},
    {1.5, -0.84, 0.225},
    {0.84, -1.5, 0.225},
    {0.0, -1.5, 0.225},
    {1.5, 0.0, 0.15},
    {1.5, -0.84, 0.15},
    {0.84, -1.5, 0.15},
    {0.0, -1.5, 0.15},
    {-1.12, -2.0, 0.45},
    {-2.0, -1.12, 0.45},
    {-2.0, 0.0, 0.45},
    {-0.84, -1.5, 0.225},
    {-1.5, -0.84, 0.225},
    {-1.5, 0.0, 0.225},
    {-0.84, -1.5, 0.15},
    {-1.5, -0.84, 0.15},
    {-1.5, 0.0, 0.15},
    {-2.0, 1.12, 0.45},
    {-1.12, 2.0, 0.45},
    {0.0, 2.0, 0.45},
    {-1.5, 0.84, 0.225},
    {-0.84, 1.5, 0.225},
    {0.0, 1.5, 0.225},
    {-1.5, 0.84, 0.15},
    {-0.84, 1.5, 0.15},
    {0.0, 1.5, 0.15},
    {1.12, 2.0, 0.45},
    {2.0, 1.12, 0.45},
    {0.84, 1.5, 0.225},
    {1.5, 0.84, 0.225},
    {0.84, 1.5, 0.15},
    {1.5, 0.84, 0.15},
    {-1.6, 0.0, 2.025},
    {-1.6, -0.3, 2.025},
    {-1.5, -0.3, 2.25},
    {-1.5, 0.0, 2.25},
    {-2.3, 0.0, 2.025},
    {-2.3, -0.3, 2.025},
    {-2.5, -0.3, 2.25},
    {-2.5, 0.0, 2.25},
    {-2.7, 0.0, 2.025},
    {-2.7, -0.3, 2.025},
    {-3.0, -0.3, 2.25},
    {-3.0, 0.0, 2.25},
    {-2.7, 0.0, 1.8},
    {-2.7, -0.3, 1.8},
    {-3.0, -0.3, 1.8},
    {-3.0, 0.0, 1.8},
    {-1.5, 0.3, 2.25},
    {-1.6, 0.3, 2.025},
    {-2.5, 0.3, 2.25},
    {-2.3, 0.3, 2.025},
    {-3.0, 0.3, 2.25},
    {-2.7, 0.3, 2.025},
    {-3.0, 0.3, 1.8},
    {-2.7, 0.3, 1.8},
    {-2.7, 0.0, 1.575},
    {-2.7, -0.3, 1.575},
    {-3.0, -0.3, 1.35},
    {-3.0, 0.0, 1.35},
    {-2.5, 0.0, 1.125},
    {-2.5, -0.3, 1.125},
    {-2.65, -0.3, 0.9375},
    {-2.65, 0.0, 0.9375},
    {-2.0, -0.3, 0.9},
    {-1.9, -0.3, 0.6},
    {-1.9, 0.0, 0.6},
    {-3.0, 0.3, 1.35},
    {-2.7, 0.3, 1.575},
    {-2.65, 0.3, 0.9375},
    {-2.5, 0.3, 1.125},
    {-1.9, 0.3, 0.6},
    {-2.0, 0.3, 0.9},
    {1.7, 0.0, 1.425},
    {1.7, -0.66, 1.425},
    {1.7, -0.66, 0.6},
    {1.7, 0.0, 0.6},
    {2.6, 0.0, 1.425},
    {2.6, -0.66, 1.425},
    {3.1, -0.66, 0.825},
    {3.1, 0.0, 0.825},
    {2.3, 0.0, 2.1},
    {2.3, -0.25, 2.1},
    {2.4, -0.25, 2.025},
    {2.4, 0.0, 2.025},
    {2.7, 0.0, 2.4},
    {2.7, -0.25, 2.4},
    {3.3, -0.25, 2.4},
    {3.3, 0.0, 2.4},
    {1.7, 0.66, 0.6},
    {1.7, 0.66, 1.425},
    {3.1, 0.66, 0.825},
    {2.6, 0.66, 1.425},
    {2.4, 0.25, 2.025},
    {2.3, 0.25, 2.1},
    {3.3, 0.25, 2.4},
    {2.7, 0.25, 2.4},
    {2.8, 0.0, 2.475},
    {2.8, -0.25, 2.475},
    {3.525, -0.25, 2.49375},
    {3.525, 0.0, 2.49375},
    {2.9, 0.0, 2.475},
    {2.9, -0.15, 2.475},
    {3.45, -0.15, 2.5125},
    {3.45, 0.0, 2.5125},
    {2.8, 0.0, 2.4},
    {2.8, -0.15, 2.4},
    {3.2, -0.15, 2.4},
    {3.2, 0.0, 2.4},
    {3.525, 0.25, 2.49375},
    {2.8, 0.25, 2.475},
    {3.45, 0.15, 2.5125},
    {2.9, 0.15, 2.475},
    {3.2, 0.15, 2.4},
    {2.8, 0.15, 2.4},
    {0.0, 0.0, 3.15},
    {0.0, -0.002, 3.15},
    {0.002, 0.0, 3.15},
    {0.8, 0.0, 3.15},
    {0.8, -0.45, 3.15},
    {0.45, -0.8, 3.15},
    {0.0, -0.8, 3.15},
    {0.0, 0.0, 2.85},
    {0.2, 0.0, 2.7},
    {0.2, -0.112, 2.7},
    {0.112, -0.2, 2.7},
    {0.0, -0.2, 2.7},
    {-0.002, 0.0, 3.15},
    {-0.45, -0.8, 3.15},
    {-0.8, -0.45, 3.15},
    {-0.8, 0.0, 3.15},
    {-0.112, -0.2, 2.7},
    {-0.2, -0.112, 2.7},
    {-0.2, 0.0, 2.7},
    {0.0, 0.002, 3.15},
    {-0.8, 0.45, 3.15},
    {-0.45, 0.8, 3.15},
    {0.0, 0.8, 3.15},
    {-0.2, 0.112, 2.7},
    {-0.112, 0.2, 2.7},
    {0.0, 0.2, 2.7},
    {0.45, 0.8, 3.15},
    {0.8, 0.45, 3.15},
    {0.112, 0.2, 2.7},
    {0.2, 0.112, 2.7},
    {0.4, 0.0, 2.55},
    {0.4, -0.224, 2.55},
    {0.224, -0.4, 2.55},
    {0.0, -0.4, 2.55},
    {1.3, 0.0, 2.55},
    {1.3, -0.728, 2.55},
    {0.728, -1.3, 2.55},
    {0.0, -1.3, 2.55},
    {1.3, 0.0, 2.4},
    {1.3, -0.728, 2.4},
    {0.728, -1.3, 2.4},
    {0.0, -1.3, 2.4},
    {-0.224, -0.4, 2.55},
    {-0.4, -0.224, 2.55},
    {-0.4, 0.0, 2.55},
    {-0.728, -1.3, 2.55},
    {-1.3, -0.728, 2.55},
    {-1.3, 0.0, 2.55},
    {-0.728, -1.3, 2.4},
    {-1.3, -0.728, 2.4},
    {-1.3, 0.0, 2.4},
    {-0.4, 0.224, 2.55},
    {-0.224, 0.4, 2.55},
    {0.0, 0.4, 2.55},
    {-1.3, 0.728, 2.55},
    {-0.728, 1.3, 2.55},
    {0.0, 1.3, 2.55},
    {-1.3, 0.728, 2.4},
    {-0.728, 1.3, 2.4},
    {0.0, 1.3, 2.4},
    {0.224, 0.4, 2.55},
    {0.4, 0.224, 2.55},
    {0.728, 1.3, 2.55},
    {1.3, 0.728, 2.55},
    {0.728, 1.3, 2.4},
    {1.3, 0.728, 2.4},
    {0.0, 0.0, 0.0},
    {1.5, 0.0, 0.15},
    {1.5, 0.84, 0.15},
    {0.84, 1.5, 0.15},
    {0.0, 1.5, 0.15},
    {1.5, 0.0, 0.075},
    {1.5, 0.84, 0.075},
    {0.84, 1.5, 0.075},
    {0.0, 1.5, 0.075},
    {1.425, 0.0, 0.0},
    {1.425, 0.798, 0.0},
    {0.798, 1.425, 0.0},
    {0.0, 1.425, 0.0},
    {-0.84, 1.5, 0.15},
    {-1.5, 0.84, 0.15},
    {-1.5, 0.0, 0.15},
    {-0.84, 1.5, 0.075},
    {-1.5, 0.84, 0.075},
    {-1.5, 0.0, 0.075},
    {-0.798, 1.425, 0.0},
    {-1.425, 0.798, 0.0},
    {-1.425, 0.0, 0.0},
    {-1.5, -0.84, 0.15},
    {-0.84, -1.5, 0.15},
    {0.0, -1.5, 0.15},
    {-1.5, -0.84, 0.075},
    {-0.84, -1.5, 0.075},
    {0.0, -1.5, 0.075},
    {-1.425, -0.798, 0.0},
    {-0.798, -1.425, 0.0},
    {0.0, -1.425, 0.0},
    {0.84, -1.5, 0.15},
    {1.5, -0.84, 0.15},
    {0.84, -1.5, 0.075},
    {1.5, -0.84, 0.075},
    {0.798, -1.425, 0.0},
    {1.425, -0.798, 0.0},
};

/* Cubic Bernstein basis and its derivative at t. */
static void bernstein(double t, double b[4], double db[4])
{
    double s = 1.0 - t;
    b[0] = s * s * s;
    b[1] = 3.0 * s * s * t;
    b[2] = 3.0 * s * t * t;
    b[3] = t * t * t;
    db[0] = -3.0 * s * s;
    db[1] = 3.0 * s * s - 6.0 * s * t;
    db[2] = 6.0 * s * t - 3.0 * t * t;
    db[3] = 3.0 * t * t;
}

/* Point and partial derivatives of patch k at (s, t): s along the first control index
 * (rows), t along the second; y-up output axes. Sums run in a fixed order, so two patches
 * that share a boundary row or column give bitwise equal points along it. */
static void patch_eval(int k, double s, double t, double p[3], double ds[3], double dt[3])
{
    double bs[4], dbs[4], bt[4], dbt[4];
    bernstein(s, bs, dbs);
    bernstein(t, bt, dbt);
    double q[3] = {0, 0, 0}, qs[3] = {0, 0, 0}, qt[3] = {0, 0, 0};
    for (int i = 0; i < 4; ++i) {
        double row[3] = {0, 0, 0}, row_t[3] = {0, 0, 0};
        for (int j = 0; j < 4; ++j) {
            const double *c = point[patch_index[k][4 * i + j] - 1];
            for (int a = 0; a < 3; ++a) {
                row[a] += bt[j] * c[a];
                row_t[a] += dbt[j] * c[a];
            }
        }
        for (int a = 0; a < 3; ++a) {
            q[a] += bs[i] * row[a];
            qs[a] += dbs[i] * row[a];
            qt[a] += bs[i] * row_t[a];
        }
    }
    /* z up -> y up: (x, y, z) -> (x, z, -y) */
    p[0] = q[0], p[1] = q[2], p[2] = -q[1];
    ds[0] = qs[0], ds[1] = qs[2], ds[2] = -qs[1];
    dt[0] = qt[0], dt[1] = qt[2], dt[2] = -qt[1];
}

static void cross(const double a[3], const double b[3], double o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* Outward unit normal of patch k at grid point (s, t). In this data set ds x dt points
 * inward on every patch (the rows run from top to bottom, the columns counter-clockwise
 * seen from above), hence dt x ds. */
static void patch_normal(int k, double s, double t, const double p[3], double n[3])
{
    double q[3], ds[3], dt[3];
    patch_eval(k, s, t, q, ds, dt);
    cross(dt, ds, n);
    double l = sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    /* 1e-9: the cross product of two derivatives of size ~1 vanishes only where an edge of
     * the patch collapses to a point (lid top, bottom centre), both on the axis. */
    if (l < 1e-9) {
        double s2 = s < 0.5 ? s + 1e-3 : s - 1e-3;
        patch_eval(k, s2, t, q, ds, dt);
        cross(dt, ds, n);
        double side = n[1] > 0 ? 1.0 : -1.0;
        if (fabs(p[0]) > 1e-12 || fabs(p[2]) > 1e-12) {
            fprintf(stderr, "gen_teapot: degenerate normal off the axis (patch %d)\n", k + 1);
            exit(1);
        }
        n[0] = 0, n[1] = side, n[2] = 0;
        return;
    }
    for (int a = 0; a < 3; ++a) n[a] /= l;
}

/* ---- a small open-addressing table that welds equal float triples ------------------ */

typedef struct table {
    float *v; /* dim floats per entry */
    int dim, count, cap;
    int *slot; /* 2 * cap slots, -1 empty */
} table;

static unsigned hash_floats(const float *x, int dim)
{
    unsigned h = 2166136261u;
    for (int a = 0; a < dim; ++a) {
        unsigned u;
        memcpy(&u, &x[a], sizeof u);
        h = (h ^ u) * 16777619u;
        h ^= h >> 15;
    }
    return h;
}

static void table_init(table *t, int dim, int cap)
{
    t->dim = dim, t->count = 0, t->cap = cap;
    t->v = malloc((size_t)cap * (size_t)dim * sizeof *t->v);
    t->slot = malloc(2 * (size_t)cap * sizeof *t->slot);
    if (!t->v || !t->slot) {
        fprintf(stderr, "gen_teapot: out of memory\n");
        exit(1);
    }
    for (int i = 0; i < 2 * cap; ++i) t->slot[i] = -1;
}

/* Index of x (1-based, as OBJ counts), adding it if new. */
static int table_add(table *t, const float *x)
{
    unsigned m = 2u * (unsigned)t->cap;
    for (unsigned h = hash_floats(x, t->dim) % m;; h = (h + 1) % m) {
        int e = t->slot[h];
        if (e < 0) {
            if (t->count == t->cap) {
                fprintf(stderr, "gen_teapot: table full\n");
                exit(1);
            }
            memcpy(t->v + (size_t)t->count * t->dim, x, (size_t)t->dim * sizeof *x);
            t->slot[h] = t->count;
            return ++t->count;
        }
        if (!memcmp(t->v + (size_t)e * t->dim, x, (size_t)t->dim * sizeof *x)) return e + 1;
    }
}

int main(int argc, char **argv)
{
    int n = 8;
    const char *out = NULL;
    for (int i = 1; i < argc; ++i) {
        if (!strcmp(argv[i], "--segments") && i + 1 < argc) {
            char *end;
            long v = strtol(argv[++i], &end, 10);
            if (*end || v < 1 || v > 1024) {
                fprintf(stderr, "gen_teapot: --segments needs a whole number in [1, 1024]\n");
                return 2;
            }
            n = (int)v;
        } else if (!strcmp(argv[i], "-o") && i + 1 < argc) {
            out = argv[++i];
        } else {
            fprintf(stderr, "usage: gen_teapot [--segments N] [-o OUT.obj]\n");
            return 2;
        }
    }
    int grid = (n + 1) * (n + 1), cap = PATCHES * grid;
    table pos, nrm, uv;
    table_init(&pos, 3, cap);
    table_init(&nrm, 3, cap);
    table_init(&uv, 2, grid);
    /* per patch and grid point: the OBJ indices of position, uv, normal */
    int *ip = malloc((size_t)cap * 3 * sizeof *ip);
    if (!ip) return 1;
    for (int k = 0; k < PATCHES; ++k)
        for (int i = 0; i <= n; ++i)
            for (int j = 0; j <= n; ++j) {
                double s = (double)i / n, t = (double)j / n, p[3], ds[3], dt[3], nv[3];
                patch_eval(k, s, t, p, ds, dt);
                patch_normal(k, s, t, p, nv);
                float pf[3] = {(float)p[0], (float)p[1], (float)p[2]};
                float nf[3] = {(float)nv[0], (float)nv[1], (float)nv[2]};
                float tf[2] = {(float)t, (float)(1.0 - s)};
                int *e = ip + 3 * ((size_t)k * grid + (size_t)i * (n + 1) + j);
                e[0] = table_add(&pos, pf);
                e[1] = table_add(&uv, tf);
                e[2] = table_add(&nrm, nf);
            }
    FILE *f = out ? fopen(out, "w") : stdout;
    if (!f) {
        fprintf(stderr, "gen_teapot: cannot write %s\n", out);
        return 1;
    }
    fprintf(
        f,
        "# The Utah teapot: Newell's 32 bicubic Bezier patches (28 of 1975 and Crow's 4 bottom\n"
        "# patches) tessellated by gen_teapot --segments %d (tools/gen/gen_teapot.c); y up,\n"
        "# spout toward +x, base at y = 0. Normals are the patches' own, texture coordinates\n"
        "# their parameters.\n"
        "o teapot\n",
        n);
    for (int i = 0; i < pos.count; ++i)
        fprintf(f, "v %.9g %.9g %.9g\n", pos.v[3 * i], pos.v[3 * i + 1], pos.v[3 * i + 2]);
    for (int i = 0; i < uv.count; ++i) fprintf(f, "vt %.9g %.9g\n", uv.v[2 * i], uv.v[2 * i + 1]);
    for (int i = 0; i < nrm.count; ++i)
        fprintf(f, "vn %.9g %.9g %.9g\n", nrm.v[3 * i], nrm.v[3 * i + 1], nrm.v[3 * i + 2]);
    long triangles = 0;
    for (int k = 0; k < PATCHES; ++k)
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < n; ++j) {
                const int *c[4];
                int at[4][2] = {{i, j}, {i + 1, j}, {i + 1, j + 1}, {i, j + 1}};
                for (int q = 0; q < 4; ++q)
                    c[q] = ip + 3 * ((size_t)k * grid + (size_t)at[q][0] * (n + 1) + at[q][1]);
                /* (i,j), (i+1,j+1), (i+1,j) and (i,j), (i,j+1), (i+1,j+1): counter-clockwise
                 * seen from outside (face normal dt x ds, the side the normals point to). */
                static const int tri[2][3] = {{0, 2, 1}, {0, 3, 2}};
                for (int h = 0; h < 2; ++h) {
                    const int *a = c[tri[h][0]], *b = c[tri[h][1]], *d = c[tri[h][2]];
                    if (a[0] == b[0] || b[0] == d[0] || a[0] == d[0]) continue; /* collapsed */
                    fprintf(f, "f %d/%d/%d %d/%d/%d %d/%d/%d\n", a[0], a[1], a[2], b[0], b[1], b[2],
                            d[0], d[1], d[2]);
                    ++triangles;
                }
            }
    int bad = ferror(f);
    if (out && fclose(f)) bad = 1;
    if (bad) {
        fprintf(stderr, "gen_teapot: write error\n");
        return 1;
    }
    fprintf(stderr, "gen_teapot: %d segments, %d vertices, %ld triangles\n", n, pos.count,
            triangles);
    free(ip);
    free(pos.v), free(pos.slot), free(nrm.v), free(nrm.slot), free(uv.v), free(uv.slot);
    return 0;
}
