# reproduces.cmake - a generated file in the tree is exactly what its generator writes now:
# runs the command after `--` (it writes OUT) and requires OUT to equal REF byte for byte.
#   cmake -DNAME=<test> -DOUT=<scratch file> -DREF=<committed file> -DHINT=<how to update>
#         -P reproduces.cmake -- <generator> [args...]
foreach(var NAME OUT REF HINT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "reproduces: -D${var}=... is required")
  endif()
endforeach()
include("${CMAKE_CURRENT_LIST_DIR}/args_after_dashes.cmake")
if(NOT cmd)
  message(FATAL_ERROR "${NAME}: no generator command after --")
endif()
file(REMOVE "${OUT}")
execute_process(COMMAND ${cmd} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  list(GET cmd 0 gen)
  message(FATAL_ERROR "${NAME}: ${gen} failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${OUT}" "${REF}" RESULT_VARIABLE same)
if(NOT same EQUAL 0)
  # Show what changed (diff is part of every Debian system; the message stands without it).
  execute_process(COMMAND diff -u "${REF}" "${OUT}" OUTPUT_VARIABLE delta ERROR_QUIET)
  string(SUBSTRING "${delta}" 0 4000 delta)
  message(FATAL_ERROR "${NAME}: ${REF} differs from what its generator writes now (${OUT}); ${HINT}\n${delta}")
endif()
message(STATUS "${NAME}: regenerated ${OUT} is identical to ${REF}")
