# abrdf_packages.cmake - what `cmake --install` puts beside the library and the command for a
# packager, under share/abrdf (the README's "Install"), and the source tarball:
#   share/abrdf/povray/    the POV-Ray includes (povray +L<dir>; docs/POVRAY.md)
#   share/abrdf/osl/       the OSL port (installed with the command, tools/export)
#   share/abrdf/python/    the Python package's source distribution, abrdf-VERSION.tar.gz
#                          (`pip install` builds it against its own copy of libabrdf's source)
#   share/abrdf/blender/   the Blender extension, abrdf-blender-VERSION.zip (Install from Disk)
# The sdist, the wheel the extension bundles and the extension are built with ABRDF_PYTHON, a
# Python 3.11 with pip and scikit-build-core: by default the project's .venv-python
# (scripts/setup_python.sh); without one they are not built (a status line says so), nor in
# the sanitizer build. `make package_source` (CPack) writes abrdf-VERSION.tar.gz, the source
# tree without what .gitignore ignores.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/povray_macros/ DESTINATION ${CMAKE_INSTALL_DATADIR}/abrdf/povray
        FILES_MATCHING PATTERN "*.inc")

set(ABRDF_PYTHON "" CACHE FILEPATH
    "Python 3.11 with pip and scikit-build-core for the sdist, wheel and Blender extension (default: .venv-python/bin/python)")
set(abrdf_python "${ABRDF_PYTHON}")
if(NOT abrdf_python AND EXISTS ${PROJECT_SOURCE_DIR}/.venv-python/bin/python)
  set(abrdf_python ${PROJECT_SOURCE_DIR}/.venv-python/bin/python)
endif()
set(ABRDF_PACKAGES OFF)
if(SKBUILD)
  # pip's own build of the module (pyproject.toml): no packages inside it.
elseif(ABRDF_SANITIZE)
  message(STATUS "abrdf: sanitizer build: the Python sdist/wheel and the Blender extension are not built")
elseif(abrdf_python)
  execute_process(COMMAND ${abrdf_python} -c "import scikit_build_core, pip" RESULT_VARIABLE rc
                  OUTPUT_QUIET ERROR_QUIET)
  if(rc EQUAL 0)
    set(ABRDF_PACKAGES ON)
  else()
    message(STATUS "abrdf: ${abrdf_python} lacks scikit-build-core or pip (scripts/setup_python.sh)")
  endif()
else()
  message(STATUS "abrdf: no .venv-python (scripts/setup_python.sh) and no ABRDF_PYTHON: the Python "
                 "sdist/wheel and the Blender extension are not built")
endif()

if(ABRDF_PACKAGES)
  set(ABRDF_DIST ${PROJECT_BINARY_DIR}/dist)
  set(ABRDF_SDIST ${ABRDF_DIST}/abrdf-${PROJECT_VERSION}.tar.gz)
  set(ABRDF_WHEEL_DIR ${ABRDF_DIST}/wheel)
  set(ABRDF_BLENDER_ZIP ${ABRDF_DIST}/abrdf-blender-${PROJECT_VERSION}.zip)
  # What pip builds from (pyproject.toml's sdist.include): a change rebuilds the packages.
  file(GLOB_RECURSE python_inputs CONFIGURE_DEPENDS
       ${PROJECT_SOURCE_DIR}/libabrdf/include/*.h ${PROJECT_SOURCE_DIR}/libabrdf/src/*
       ${PROJECT_SOURCE_DIR}/tools/common/* ${PROJECT_SOURCE_DIR}/tools/measured/*
       ${PROJECT_SOURCE_DIR}/tools/image/metrics.*
       ${PROJECT_SOURCE_DIR}/python/abrdf/* ${PROJECT_SOURCE_DIR}/python/src/*)
  list(APPEND python_inputs ${PROJECT_SOURCE_DIR}/pyproject.toml ${PROJECT_SOURCE_DIR}/CMakeLists.txt
       ${PROJECT_SOURCE_DIR}/python/CMakeLists.txt ${PROJECT_SOURCE_DIR}/data/materials.csv
       ${PROJECT_SOURCE_DIR}/docs/PYTHON.md)
  list(FILTER python_inputs EXCLUDE REGEX "__pycache__|\\.pyc$")
  add_custom_command(OUTPUT ${ABRDF_SDIST}
    COMMAND ${abrdf_python} -c "import sys; from scikit_build_core.build import build_sdist; build_sdist(sys.argv[1])" ${ABRDF_DIST}
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR} DEPENDS ${python_inputs}
    COMMENT "Python sdist ${ABRDF_SDIST}" VERBATIM)
  # The wheel's CMake build tree is kept (dist/wheel_build), so a rebuild is incremental.
  add_custom_command(OUTPUT ${ABRDF_WHEEL_DIR}/stamp
    COMMAND ${CMAKE_COMMAND} -E rm -rf ${ABRDF_WHEEL_DIR}
    COMMAND ${abrdf_python} -m pip wheel --quiet --disable-pip-version-check --no-build-isolation
            --no-deps --config-settings=build-dir=${ABRDF_DIST}/wheel_build -w ${ABRDF_WHEEL_DIR}
            ${PROJECT_SOURCE_DIR}
    COMMAND ${CMAKE_COMMAND} -E touch ${ABRDF_WHEEL_DIR}/stamp
    DEPENDS ${python_inputs} COMMENT "Python wheel (pip wheel .) in ${ABRDF_WHEEL_DIR}" VERBATIM)
  file(GLOB blender_inputs CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/blender/*
       ${PROJECT_SOURCE_DIR}/osl/*.h ${PROJECT_SOURCE_DIR}/osl/*.osl ${PROJECT_SOURCE_DIR}/osl/*.py)
  list(FILTER blender_inputs EXCLUDE REGEX "__pycache__|\\.pyc$|\\.oso$")
  add_custom_command(OUTPUT ${ABRDF_BLENDER_ZIP}
    COMMAND ${abrdf_python} ${PROJECT_SOURCE_DIR}/blender/build_extension.py --wheel ${ABRDF_WHEEL_DIR}
            -o ${ABRDF_BLENDER_ZIP}
    DEPENDS ${ABRDF_WHEEL_DIR}/stamp ${blender_inputs} COMMENT "Blender extension ${ABRDF_BLENDER_ZIP}"
    VERBATIM)
  add_custom_target(abrdf_python_sdist ALL DEPENDS ${ABRDF_SDIST})
  # The wheel (dist/wheel, also the Python tests' input) is built on the way to the zip.
  add_custom_target(abrdf_blender_extension ALL DEPENDS ${ABRDF_BLENDER_ZIP})
  install(FILES ${ABRDF_SDIST} DESTINATION ${CMAKE_INSTALL_DATADIR}/abrdf/python)
  install(FILES ${ABRDF_BLENDER_ZIP} DESTINATION ${CMAKE_INSTALL_DATADIR}/abrdf/blender)
endif()

# The source tarball: every file of the tree but what .gitignore ignores (the same
# patterns; the test source_tarball compares the tarball with `git ls-files`).
string(REGEX REPLACE "([][+.*()^$?|\\\\])" "\\\\\\1" src_re "${PROJECT_SOURCE_DIR}")
set(CPACK_SOURCE_GENERATOR TGZ)
set(CPACK_SOURCE_PACKAGE_FILE_NAME abrdf-${PROJECT_VERSION})
set(CPACK_SOURCE_IGNORE_FILES "^${src_re}/\\.git(/|$)" "^${src_re}/build[^/]*/" "^${src_re}/\\.venv"
    "/__pycache__/" "\\.o$" "\\.oso$" "\\.pyc$")
set(CPACK_PACKAGE_NAME abrdf)
set(CPACK_PACKAGE_VENDOR "abrdf")
set(CPACK_GENERATOR TGZ)
include(CPack)
