// povray_scene.pov - a POV-Ray user's scene with abrdf materials (docs/POVRAY.md).
//   povray +Iexamples/povray_scene.pov +Opovray_scene.exr +FE +W320 +H240 -A +Lpovray_macros
// Coordinates are POV-Ray's own (left-handed, y up); every vector below is in them.
#version 3.7;
global_settings { assumed_gamma 1 ambient_light 0 }
#include "abrdf.inc"

#declare Eye = <0, 1.2, -6>;
camera { perspective location Eye look_at <0, 0.6, 0> right x * 4 / 3 angle 40 }

// One directional light, given twice: to the function pigments (kind 1 = directional,
// direction toward the light, irradiance E per channel) and as POV-Ray's light, which
// applies N.wi and casts the shadows (Lit = true below) and lights the native finish.
#declare Lights = array[1][7] { {1, -1, 1.5, -1, 1, 1, 1} }
light_source { <-1, 1.5, -1> * 1e5 color rgb 1 parallel point_at <0, 0, 0> }
#declare Ambient = <0.02, 0.02, 0.02>;  // ka * Ia

// Materials: one constructor per model, the registry's parameters in its order.
#declare Plastic = Abrdf_Combine(Abrdf_Lambert(<0.18, 0.30, 0.60>), Abrdf_Disney_Specular(1, 0.35, 0.04));
#declare Brushed = Abrdf_Combine(Abrdf_Lambert(0.05), Abrdf_Disney_Specular_Aniso(<0.9, 0.8, 0.6>, 0.3, 0.8, <0.9, 0.8, 0.6>));

// The selection flowchart picks models for a material (here: rough, isotropic).
#declare Choice = Abrdf_Select("photoreal", "general", -1, 0.2, 0, -1, -1);
#debug concat("Abrdf_Select(photoreal, r 0.2): ", Choice[0], " + ", Choice[1], "\n")

// Shaded in a function pigment: shape, its transform M (POV-Ray's scale/rotate/translate),
// the tangent rule (0: around the object's y axis) and the eye must be the object's own.
#declare M1 = Abrdf_Xform(1, <0, 0, 0>, <-1.2, 1, 0>);
object { Abrdf_Shape("sphere", 1)
  Abrdf_Shaded_Texture(Plastic, "sphere", 1, M1, array[4] {0, 0, 0, 0}, Eye, Lights, Ambient, true)
  Abrdf_Xform_Matrix(M1) }
#declare M2 = Abrdf_Xform(1, <0, 30, 0>, <1.3, 0.8, 0>);
object { Abrdf_Shape("capsule", <0.5, 0.6, 0>)
  Abrdf_Shaded_Texture(Brushed, "capsule", <0.5, 0.6, 0>, M2, array[4] {0, 0, 0, 0}, Eye, Lights, Ambient, true)
  Abrdf_Xform_Matrix(M2) }

// The fast path: POV-Ray's own finish where the model exists natively (lambert is exact).
#declare M3 = Abrdf_Xform(<8, 0.2, 8>, <0, 0, 0>, <0, -0.1, 0>);
object { Abrdf_Shape("box", 1) Abrdf_Native_Texture(Abrdf_Lambert(0.5), Ambient) Abrdf_Xform_Matrix(M3) }
