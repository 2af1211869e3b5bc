# install_share.cmake - `cmake --install` puts the ports and the packages where a packager
# expects them, and each route works from the installed files (the README's "Install"):
#   share/abrdf/povray/  every povray_macros/*.inc; examples/povray_scene.pov renders with
#                        +L<that directory> (tests/ports/pov_example.cmake's checks)
#   share/abrdf/osl/     every osl/*.h and *.osl
#   share/abrdf/python/  abrdf-VERSION.tar.gz, from which pip builds a wheel that imports and
#                        selects (PACKAGES only: the build made it)
#   share/abrdf/web/     the browser explorer: every tools/web/static file and the WebAssembly
#                        module, a folder `abrdf explore` serves (ABRDF_WEB_DIR pointing there)
#   share/abrdf/blender/ abrdf-blender-VERSION.zip, the file the build made (PACKAGES only;
#                        tests/ports/test_blender_extension.py installs it in Blender)
#   cmake -DBUILD_DIR= -DSRC= -DWORK= -DVERSION= -DPACKAGES=ON|OFF -DPYTHON= -DPOVRAY=
#         -DOIIOTOOL= -P install_share.cmake
file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}"
                OUTPUT_QUIET RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install_share: cmake --install failed (${rc})")
endif()
set(share "${prefix}/share/abrdf")

function(expect_same_names what src_glob dest_dir)
  file(GLOB want RELATIVE "${SRC}" ${src_glob})
  list(TRANSFORM want REPLACE "^.*/" "")
  file(GLOB got RELATIVE "${dest_dir}" "${dest_dir}/*")
  list(SORT want)
  list(SORT got)
  if(NOT want STREQUAL got)
    message(FATAL_ERROR "install_share: ${what}: installed [${got}], expected [${want}]")
  endif()
  list(LENGTH got n)
  message(STATUS "install_share: ${what}: ${n} files in ${dest_dir}")
endfunction()
expect_same_names("POV-Ray includes" "${SRC}/povray_macros/*.inc" "${share}/povray")
file(GLOB osl_want RELATIVE "${SRC}/osl" "${SRC}/osl/*.h" "${SRC}/osl/*.osl")
foreach(f ${osl_want})
  if(NOT EXISTS "${share}/osl/${f}")
    message(FATAL_ERROR "install_share: ${share}/osl/${f} is missing")
  endif()
endforeach()

# The browser explorer: the page's files and the module, recognised by abrdf explore.
file(GLOB web_want RELATIVE "${SRC}/tools/web/static" "${SRC}/tools/web/static/*")
list(APPEND web_want abrdf_wasm.js abrdf_wasm.wasm)
foreach(f ${web_want})
  if(NOT EXISTS "${share}/web/${f}")
    message(FATAL_ERROR "install_share: ${share}/web/${f} is missing")
  endif()
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "ABRDF_WEB_DIR=${share}/web"
                        "${prefix}/bin/abrdf" explore --dir
                OUTPUT_VARIABLE web_dir RESULT_VARIABLE rc ERROR_VARIABLE web_err)
string(STRIP "${web_dir}" web_dir)
if(NOT rc EQUAL 0 OR NOT web_dir STREQUAL "${share}/web")
  message(FATAL_ERROR "install_share: abrdf explore --dir with the installed explorer: "
                      "'${web_dir}' (${rc}) ${web_err}")
endif()

# POV-Ray: the example scene with the installed includes only.
set(SCENE "${SRC}/examples/povray_scene.pov")
set(INC "${share}/povray")
set(OUT "${WORK}/povray_scene.exr")
include("${SRC}/tests/ports/pov_example.cmake")

if(NOT PACKAGES)
  message(FATAL_ERROR "install_share: the build made no Python sdist or Blender extension "
                      "(no .venv-python: run scripts/setup_python.sh, then cmake again)")
endif()
set(sdist "${share}/python/abrdf-${VERSION}.tar.gz")
set(zip "${share}/blender/abrdf-blender-${VERSION}.zip")
foreach(f "${sdist}" "${zip}")
  if(NOT EXISTS "${f}")
    message(FATAL_ERROR "install_share: ${f} is missing")
  endif()
endforeach()
execute_process(COMMAND "${CMAKE_COMMAND}" -E compare_files "${zip}"
                        "${BUILD_DIR}/dist/abrdf-blender-${VERSION}.zip" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install_share: the installed extension is not the one the build made")
endif()

# Python: a wheel from the installed sdist alone (no source tree), installed and used.
execute_process(COMMAND "${PYTHON}" -m pip wheel --quiet --disable-pip-version-check
                        --no-build-isolation --no-deps -w "${WORK}/wheel" "${sdist}"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install_share: pip could not build a wheel from ${sdist} (${rc})")
endif()
file(GLOB wheel "${WORK}/wheel/abrdf-${VERSION}-*.whl")
execute_process(COMMAND "${PYTHON}" -m pip install --quiet --disable-pip-version-check --no-deps
                        --no-index --target "${WORK}/site" ${wheel} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "install_share: pip install ${wheel} failed (${rc})")
endif()
set(ENV{PYTHONPATH} "${WORK}/site")
execute_process(COMMAND "${PYTHON}" -c
  "import abrdf; s = abrdf.select('gold', goal='performance'); print(abrdf.__file__, s.diffuse, s.specular)"
  WORKING_DIRECTORY "${WORK}" OUTPUT_VARIABLE out RESULT_VARIABLE rc)
if(NOT rc EQUAL 0 OR NOT out MATCHES "^${WORK}/site/abrdf/__init__.py lambert f8")
  message(FATAL_ERROR "install_share: the wheel built from the sdist does not work (${rc}): ${out}")
endif()
message(STATUS "install_share: the sdist builds a working wheel; the extension zip is installed")
