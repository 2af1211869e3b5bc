# python_package.cmake - the Python route end to end: pip installs the wheel that `pip wheel .`
# made (the build's dist/wheel) into WORK/site, then pytest runs tests/python against it.
#   cmake -DPYTHON=<python> -DWHEELS=<dir> -DTESTS=<tests/python> -DWORK=<dir> -DABRDF=<abrdf>
#         -DSRC=<source tree> [-DSITE=<dir: test this package instead>] [-DPRELOAD=<libs>]
#         -P python_package.cmake
if(NOT EXISTS "${PYTHON}")
  message(FATAL_ERROR "python_package: ${PYTHON} is missing; run scripts/setup_python.sh")
endif()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
if(NOT SITE)
  file(GLOB wheel "${WHEELS}/abrdf-*.whl")
  list(LENGTH wheel n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "python_package: ${WHEELS} holds ${n} abrdf wheels, not one (the build "
                        "makes it with .venv-python: scripts/setup_python.sh, then re-run cmake)")
  endif()
  set(SITE "${WORK}/site")
  execute_process(COMMAND "${PYTHON}" -m pip install --quiet --disable-pip-version-check --no-deps
                          --no-index --target "${SITE}" ${wheel}
                  RESULT_VARIABLE rc)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "python_package: pip install ${wheel} failed (${rc})")
  endif()
endif()
set(ENV{PYTHONPATH} "${SITE}")
set(ENV{PYTHONDONTWRITEBYTECODE} 1)
set(ENV{ABRDF} "${ABRDF}")
set(ENV{ABRDF_SOURCE_DIR} "${SRC}")
set(ENV{ABRDF_TEST_WORK} "${WORK}")
set(ENV{MPLBACKEND} Agg)
if(PRELOAD)
  set(ENV{LD_PRELOAD} "${PRELOAD}")
  # CPython keeps its objects until exit; the leak report would be about them.
  set(ENV{ASAN_OPTIONS} "detect_leaks=0")
  # The suite runs a few long cases on fewer inputs there (test_py_fit.py).
  set(ENV{ABRDF_SANITIZE} 1)
endif()
# The package pip installed is imported, not the source tree's copy: run from WORK.
execute_process(COMMAND "${PYTHON}" -m pytest -q -p no:cacheprovider --rootdir "${TESTS}"
                        --basetemp "${WORK}/tmp" "${TESTS}"
                WORKING_DIRECTORY "${WORK}" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "python_package: pytest failed (${rc})")
endif()
