# Re-runs the generator of Belcour's tables and requires the committed data file to be
# reproduced byte for byte. Variables: GEN (generator), REF (committed file), OUT (scratch).
execute_process(COMMAND ${GEN} ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "gen_belcour_tables failed: ${rc}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${REF} ${OUT} RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "${REF} is not what tools/gen_belcour_tables.c produces (see ${OUT})")
endif()
