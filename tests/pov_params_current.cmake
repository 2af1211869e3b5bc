# pov_params_current.cmake - regenerates povray_macros/abrdf_params.inc from the C registry
# (tools/gen_pov_params.py) and requires it to equal the committed include byte for byte.
#   cmake -DPYTHON=<python3> -DGEN=<gen_pov_params.py> -DABRDF=<abrdf> -DFKUB=<fkub_table.c>
#         -DMODELS_INC=<abrdf_models.inc>
#         -DOUT=<new include> -DREF=<committed include> -P pov_params_current.cmake
foreach(var PYTHON GEN ABRDF FKUB MODELS_INC OUT REF)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "pov_params_current: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE "${OUT}")
execute_process(COMMAND "${PYTHON}" "${GEN}" "${ABRDF}" "${FKUB}" "${MODELS_INC}" "${OUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "pov_params_current: ${GEN} failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}" "${REF}" RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  execute_process(COMMAND diff -u "${REF}" "${OUT}" OUTPUT_VARIABLE delta ERROR_QUIET)
  string(SUBSTRING "${delta}" 0 4000 delta)
  message(FATAL_ERROR "pov_params_current: ${REF} is out of date; run tools/gen_pov_params.py\n${delta}")
endif()
message(STATUS "pov_params_current: ${REF} matches the registry")
