# doc_tables.cmake - a document quotes measured numbers only as its tool prints them: runs
# TOOL (with the space-separated ARGS, if given) and requires every Markdown table row of its
# output to appear verbatim in DOC.
#   cmake -DTOOL=<program> [-DARGS="a b c"] -DDOC=<file.md> -P doc_tables.cmake
separate_arguments(args UNIX_COMMAND "${ARGS}")
execute_process(COMMAND "${TOOL}" ${args} RESULT_VARIABLE rc OUTPUT_VARIABLE out)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "doc_tables: ${TOOL} failed (${rc})")
endif()
file(READ "${DOC}" doc)
string(REPLACE "\n" ";" lines "${out}")
set(rows 0)
foreach(line IN LISTS lines)
  if(line MATCHES "^\\|")
    math(EXPR rows "${rows} + 1")
    string(FIND "${doc}" "${line}" at)
    if(at EQUAL -1)
      message(FATAL_ERROR "doc_tables: ${DOC} does not quote this measured row of ${TOOL}:\n${line}\n"
                          "(re-run the tool and paste its tables)")
    endif()
  endif()
endforeach()
if(rows EQUAL 0)
  message(FATAL_ERROR "doc_tables: ${TOOL} printed no table")
endif()
message(STATUS "doc_tables: all ${rows} rows of ${TOOL} appear in ${DOC}")
