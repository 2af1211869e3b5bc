# Re-runs tools/fit_fkub and requires its output to equal libabrdf/src/fkub_table.c byte for
# byte, so the committed table is the tool's output for the committed fit constants.
#   cmake -DFIT=<fit_fkub> -DTABLE=<fkub_table.c> -DOUT=<scratch file> -P check_fkub_table.cmake
execute_process(COMMAND ${FIT} ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fit_fkub failed (${rc})")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT} ${TABLE} RESULT_VARIABLE diff)
if(NOT diff EQUAL 0)
  message(FATAL_ERROR "${TABLE} differs from the output of fit_fkub: regenerate it with\n"
                      "  fit_fkub libabrdf/src/fkub_table.c")
endif()
