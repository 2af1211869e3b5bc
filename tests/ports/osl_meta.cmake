# osl_meta.cmake - the committed OSL data headers are what tools/gen/gen_osl_meta.py generates
# from the C library now (models, ranges, defaults, selection rules, fkub table, Belcour's
# FGD and TIR tables, hair tables).
#   cmake -DPYTHON=<python3> -DABRDF=<abrdf> -DSRC=<source dir> -DOUT=<scratch dir> -P osl_meta.cmake
file(REMOVE_RECURSE "${OUT}")
execute_process(COMMAND "${PYTHON}" "${SRC}/tools/gen/gen_osl_meta.py" "${ABRDF}" "${SRC}" "${OUT}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "osl_meta: gen_osl_meta.py failed (${rc})")
endif()
foreach(h abrdf_meta.h abrdf_fkub.h abrdf_belcour_tables.h abrdf_hair_tables.h)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files "${OUT}/${h}" "${SRC}/osl/${h}"
                  RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "osl_meta: osl/${h} is out of date; run tools/gen/gen_osl_meta.py build/bin/abrdf .")
  endif()
endforeach()
message(STATUS "osl_meta: osl/abrdf_meta.h, abrdf_fkub.h, abrdf_belcour_tables.h and abrdf_hair_tables.h are up to date")
