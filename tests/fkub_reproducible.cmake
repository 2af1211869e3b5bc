# fkub_reproducible.cmake - re-runs the least-squares fit of the cubic fkub and requires the
# output to equal the committed table libabrdf/src/fkub_table.c byte for byte.
#   cmake -DFIT=<fit_fkub> -DOUT=<new table> -DREF=<committed table> -P fkub_reproducible.cmake
foreach(var FIT OUT REF)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "fkub_reproducible: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE "${OUT}")
execute_process(COMMAND "${FIT}" "${OUT}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "fkub_reproducible: ${FIT} failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}" "${REF}" RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  # Show what changed (diff is part of every Debian system; the message stands without it).
  execute_process(COMMAND diff -u "${REF}" "${OUT}" OUTPUT_VARIABLE delta ERROR_QUIET)
  string(SUBSTRING "${delta}" 0 4000 delta)
  message(FATAL_ERROR "fkub_reproducible: regenerated ${OUT} differs from the committed ${REF}\n${delta}")
endif()
message(STATUS "fkub_reproducible: regenerated table is identical to ${REF}")
