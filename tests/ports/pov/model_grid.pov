// model_grid.pov - one model of abrdf.inc evaluated on a grid of directions, one pixel per
// (direction, colour channel), for tests/ports/pov_grid_check.c. Declare on the command line:
//   Declare=ABRDF_GRID_MODEL=<id>  Declare=ABRDF_GRID_SET=<0|1|2>
// Grid (NA = NB = NC = 12, NM = 576 unless declared, below): theta_i = (a + 1/2) pi / (2 NA), theta_o = (b + 1/2) pi / (2 NB), phi = c 2 pi / NC;
// wi = (sin ti, 0, cos ti), wo = (sin to cos phi, sin to sin phi, cos to). Cell k = (a NB + b) NC + c
// is pixel row floor(k / COLS), columns 3 (k mod COLS) + channel. Then NM cells of the
// sweep wi = wo (N.H = cos t), which resolves narrow lobes in N.H: k = NA NB NC + j, wi = wo =
// (sin t, 0, cos t), t = (j + 1/2) pi / (2 NM).
// A pixel holds f_r of its channel split so that POV-Ray's half-float EXR keeps ~22 bits:
//   R = e + 512 (e = floor(log2 f)), G = hi = floor(f 2^(10-e)) / 1024, B = frac(f 2^(10-e)),
//   f = (G + B / 1024) 2^e; all zero for f < 2^-400 (read as 0).
#version 3.7;
global_settings { assumed_gamma 1 }
#include "abrdf.inc"

// A slow model may be checked on a coarser grid: Declare=ABRDF_GRID_N=<NA = NB = NC>
// Declare=ABRDF_GRID_NM=<NM> (pov_grid_check --grid); NA NB NC + NM must divide by COLS.
#ifndef(ABRDF_GRID_N) #declare ABRDF_GRID_N = 12; #end
#ifndef(ABRDF_GRID_NM) #declare ABRDF_GRID_NM = 576; #end
#declare NA = ABRDF_GRID_N; #declare NB = ABRDF_GRID_N; #declare NC = ABRDF_GRID_N; #declare NM = ABRDF_GRID_NM;
#declare COLS = 48;
#declare ROWS = (NA * NB * NC + NM) / COLS;

#declare D = Abrdf_Default(ABRDF_GRID_MODEL);
#switch (ABRDF_GRID_SET)
  #case (0) #break
  #case (1)
    #declare Kd = <0.2, 0.5, 0.8>; #declare Ks = <0.9, 0.6, 0.3>; #declare F0 = <0.95, 0.64, 0.54>;
    #declare Nexp = 20; #declare Rough = 0.15; #declare Sigma = 0.8; #declare Aniso = 0.8; #declare Gloss = 0.4;
    #declare Hair = array[7] {1.9, 0.8, 0.5, -5, 0.8, 4, 2};   // eta, melanin, redness, cuticle_tilt, aspect_ratio, entry_grid, internal_grid
  #break
  #case (2)
    #declare Kd = <0.7, 0.1, 0.4>; #declare Ks = <0.05, 1, 0.5>; #declare F0 = <0.02, 1, 0.3>;
    #declare Nexp = 3000; #declare Rough = 0.05; #declare Sigma = 1.5; #declare Aniso = 1; #declare Gloss = 0;
    #declare Hair = array[7] {1.2, 0.1, 0, 8, 0.75, 3, 4};
  #break
  #else #error "model_grid.pov: ABRDF_GRID_SET must be 0, 1 or 2\n"
#end
#if (ABRDF_GRID_SET > 0)
  #declare D[ABRDF_SLOT_KD] = Kd.x; #declare D[ABRDF_SLOT_KD + 1] = Kd.y; #declare D[ABRDF_SLOT_KD + 2] = Kd.z;
  #declare D[ABRDF_SLOT_KS] = Ks.x; #declare D[ABRDF_SLOT_KS + 1] = Ks.y; #declare D[ABRDF_SLOT_KS + 2] = Ks.z;
  #declare D[ABRDF_SLOT_F0] = F0.x; #declare D[ABRDF_SLOT_F0 + 1] = F0.y; #declare D[ABRDF_SLOT_F0 + 2] = F0.z;
  #declare D[ABRDF_SLOT_N] = Nexp; #declare D[ABRDF_SLOT_R] = Rough; #declare D[ABRDF_SLOT_SIGMA] = Sigma;
  #declare D[ABRDF_SLOT_ANISOTROPIC] = Aniso; #declare D[ABRDF_SLOT_CLEARCOAT_GLOSS] = Gloss;
  #declare D[ABRDF_SLOT_ETA] = Hair[0]; #declare D[ABRDF_SLOT_MELANIN] = Hair[1]; #declare D[ABRDF_SLOT_REDNESS] = Hair[2];
  #declare D[ABRDF_SLOT_CUTICLE_TILT] = Hair[3]; #declare D[ABRDF_SLOT_ASPECT_RATIO] = Hair[4];
  #declare D[ABRDF_SLOT_ENTRY_GRID] = Hair[5]; #declare D[ABRDF_SLOT_INTERNAL_GRID] = Hair[6];
  // layer stacks (layered models): set 1 a coat with absorption over a dielectric over a
  // rough conductor; set 2 a denser coat over a less dense layer (total internal reflection)
  #if (ABRDF_GRID_SET = 1)
    #declare Layers = array[4][7] {
      {1.5, 0, 0.1, 0.5, 1, 2, 0.3}, {1.2, 0, 0.3, 0, 0, 0, 0}, {0.3, 3, 0.25, 0, 0, 0, 0}, {1.5, 0, 0.1, 0, 0, 0, 0}}
    #declare D[ABRDF_SLOT_LAYER_COUNT] = 3;
  #else
    #declare Layers = array[4][7] {
      {1.5, 0, 0.05, 0, 0, 0, 0}, {0.7, 0, 0.4, 0.1, 0.1, 0.1, 1}, {1.5, 0, 0.1, 0, 0, 0, 0}, {1.5, 0, 0.1, 0, 0, 0, 0}}
    #declare D[ABRDF_SLOT_LAYER_COUNT] = 2;
  #end
  #declare Slots = array[4] {ABRDF_SLOT_LAYER0_ETA, ABRDF_SLOT_LAYER1_ETA, ABRDF_SLOT_LAYER2_ETA, ABRDF_SLOT_LAYER3_ETA}
  #declare Lk = 0;
  #while (Lk < 4)
    // slot order of a layer: eta, kappa, r, sigma_a (3), depth
    #declare Lj = 0;
    #while (Lj < 7) #declare D[Slots[Lk] + Lj] = Layers[Lk][Lj]; #declare Lj = Lj + 1; #end
    #declare Lk = Lk + 1;
  #end
  Abrdf__Check(D, "model_grid.pov")
#end

#declare F0c = Abrdf_Fn(D, 0); #declare F1c = Abrdf_Fn(D, 1); #declare F2c = Abrdf_Fn(D, 2);
// f of channel ch at angles (ti, to, ph)
#declare Fch = function(ch, ti, to, ph) {
  select(ch - 0.5, F0c(sin(ti), 0, cos(ti), sin(to) * cos(ph), sin(to) * sin(ph), cos(to)),
    select(ch - 1.5, F1c(sin(ti), 0, cos(ti), sin(to) * cos(ph), sin(to) * sin(ph), cos(to)),
                     F2c(sin(ti), 0, cos(ti), sin(to) * cos(ph), sin(to) * sin(ph), cos(to))))
}
#declare Fgrid = function(k, ch) {
  Fch(ch, (floor(k / (NB * NC)) + 0.5) * pi / (2 * NA), (mod(floor(k / NC), NB) + 0.5) * pi / (2 * NB),
      mod(k, NC) * 2 * pi / NC)
}
#declare Fmirror = function(j, ch) { Fch(ch, (j + 0.5) * pi / (2 * NM), (j + 0.5) * pi / (2 * NM), 0) }
#declare Fcell = function(k, ch) { select(k - NA * NB * NC, Fgrid(k, ch), Fmirror(k - NA * NB * NC, ch)) }
// pixel (px, py) -> f; x = px + 1/2, y = -(py + 1/2) on the plane z = 0
#declare Fpix = function(x, y) { Fcell(floor(-y) * COLS + floor(floor(x) / 3), mod(floor(x), 3)) }
#declare Tiny = pow(2, -400);
#declare Ex = function(f) { floor(ln(f) / ln(2)) }
#declare EncR = function(f) { select(f - Tiny, 0, (Ex(f) + 512) / 1024) }
#declare EncG2 = function(f, e) { floor(f * pow(2, 10 - e)) / 4096 }
#declare EncB2 = function(f, e) { f * pow(2, 10 - e) - floor(f * pow(2, 10 - e)) }
#declare EncG = function(f) { select(f - Tiny, 0, EncG2(f, Ex(f))) }
#declare EncB = function(f) { select(f - Tiny, 0, EncB2(f, Ex(f))) }

camera { orthographic location <COLS * 3 / 2, -ROWS / 2, -1> direction z right COLS * 3 * x up ROWS * y }
plane { z, 0
  texture {
    pigment { average pigment_map {
      [1 function { EncR(Fpix(x, y)) } color_map { [0 rgb 0] [1 rgb <3072, 0, 0>] }]
      [1 function { EncG(Fpix(x, y)) } color_map { [0 rgb 0] [1 rgb <0, 12, 0>] }]
      [1 function { EncB(Fpix(x, y)) } color_map { [0 rgb 0] [1 rgb <0, 0, 3>] }]
    } }
    finish { ambient 0 diffuse 0 specular 0 phong 0 emission 1 }
  }
}
