# source_tarball.cmake - the CPack source tarball (make package_source) holds the source tree
# and nothing else: exactly the files git sees (tracked, or new and not ignored), so nothing
# generated or ignored (build trees, venvs, compiled shaders), and the unpacked tree
# configures. Without git (a tree from a tarball) the tree's own files, less the build
# trees and venvs, are the reference.
#   cmake -DBUILD_DIR= -DSRC= -DWORK= -DVERSION= -P source_tarball.cmake
cmake_minimum_required(VERSION 3.20)  # list() keeps empty elements (CMP0007)
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(COMMAND cpack --config "${BUILD_DIR}/CPackSourceConfig.cmake" -B "${WORK}"
                OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE rc)
set(tarball "${WORK}/abrdf-${VERSION}.tar.gz")
if(NOT rc EQUAL 0 OR NOT EXISTS "${tarball}")
  message(FATAL_ERROR "source_tarball: cpack failed (${rc})\n${out}\n${err}")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -E tar tf "${tarball}" OUTPUT_VARIABLE listing)
string(REPLACE "\n" ";" packed "${listing}")
list(FILTER packed EXCLUDE REGEX "/$|^$")
list(TRANSFORM packed REPLACE "^abrdf-${VERSION}/" "")

execute_process(COMMAND git -C "${SRC}" ls-files --cached --others --exclude-standard
                OUTPUT_VARIABLE listing RESULT_VARIABLE rc ERROR_QUIET)
if(rc EQUAL 0 AND listing)
  string(REPLACE "\n" ";" tree "${listing}")
  list(FILTER tree EXCLUDE REGEX "^$")
  # Files deleted in the work tree but still in the index are not in the tree.
  set(present "")
  foreach(f ${tree})
    if(EXISTS "${SRC}/${f}")
      list(APPEND present "${f}")
    endif()
  endforeach()
  set(tree ${present})
else()
  file(GLOB_RECURSE tree RELATIVE "${SRC}" "${SRC}/*")
  list(FILTER tree EXCLUDE REGEX "^(build[^/]*|\\.venv[^/]*|\\.git)/|(^|/)__pycache__/|\\.(o|oso|pyc)$")
endif()
list(SORT packed)
list(SORT tree)
set(extra ${packed})
list(REMOVE_ITEM extra ${tree})
set(missing ${tree})
list(REMOVE_ITEM missing ${packed})
if(extra OR missing)
  message(FATAL_ERROR "source_tarball: packed but not in the tree: [${extra}]\n"
                      "in the tree but not packed: [${missing}]")
endif()
list(LENGTH packed n)

# The unpacked tree configures (every CMake input is there).
execute_process(COMMAND "${CMAKE_COMMAND}" -E tar xf "${tarball}" WORKING_DIRECTORY "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${WORK}/abrdf-${VERSION}" -B "${WORK}/configure"
                        -DCMAKE_BUILD_TYPE=Release OUTPUT_QUIET ERROR_VARIABLE err RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "source_tarball: the unpacked tree does not configure (${rc})\n${err}")
endif()
message(STATUS "source_tarball: ${tarball}: ${n} files, the tree's; it configures")
