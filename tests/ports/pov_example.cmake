# pov_example.cmake - renders examples/povray_scene.pov (the scene docs/POVRAY.md shows) with
# povray and requires a finite, non-black image and the selection line it prints.
#   cmake -DPOVRAY=<povray> -DSCENE=<pov> -DINC=<povray_macros> -DOUT=<exr> -DOIIOTOOL=<oiiotool> -P pov_example.cmake
file(REMOVE "${OUT}")
execute_process(COMMAND "${POVRAY}" -D "+I${SCENE}" "+O${OUT}" +FE +W64 +H48 -A "+L${INC}"
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT EXISTS "${OUT}")
  message(FATAL_ERROR "pov_example: povray failed (${rc})\n${err}")
endif()
if(NOT "${out}${err}" MATCHES "Abrdf_Select\\(photoreal, r 0.2\\): disney_diffuse \\+ disney_specular")
  message(FATAL_ERROR "pov_example: the selection line is missing or differs\n${err}")
endif()
execute_process(COMMAND "${OIIOTOOL}" "${OUT}" --printstats OUTPUT_VARIABLE stats RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT stats MATCHES "NanCount: 0 0 0" OR NOT stats MATCHES "InfCount: 0 0 0"
   OR stats MATCHES "Stats Max: 0\\.000000 0\\.000000 0\\.000000")
  message(FATAL_ERROR "pov_example: image is black or not finite\n${stats}")
endif()
message(STATUS "pov_example: rendered, selection line present")
