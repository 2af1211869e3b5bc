# install_consumer.cmake - installs the current build into a fresh temporary prefix and
# builds + runs examples/quickstart.c against that installed tree three ways:
#   1. pkg-config:   cc quickstart.c $(pkg-config --cflags --libs abrdf)
#                    (and a program that includes the selection header, abrdf_select.h)
#   2. find_package: abrdf::abrdf         (shared; its NEEDED entries must name libabrdf)
#   3. find_package: abrdf::abrdf_static  (static; must not need libabrdf.so at run time)
# and runs examples/hair_table.c (find_package, shared).
# Each build must print the line README.md quotes as the example's output.
#   cmake -DBUILD_DIR=.. -DEXAMPLES=.. -DWORK=.. -DCC=.. -DPKG_CONFIG=.. -DOBJDUMP=.. -DREADME=..
#         [-DEXTRA_FLAGS="-fsanitize=..."] -P install_consumer.cmake
foreach(var BUILD_DIR EXAMPLES WORK CC PKG_CONFIG README)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "install_consumer: -D${var}=... is required")
  endif()
endforeach()
separate_arguments(extra UNIX_COMMAND "${EXTRA_FLAGS}")
file(STRINGS "${README}" quoted REGEX "^#   abrdf [^:]+: disney_specular f_r = ")
list(LENGTH quoted quotes)
if(NOT quotes EQUAL 1)
  message(FATAL_ERROR "install_consumer: ${README} should quote the example's output once, as "
                      "'#   abrdf VERSION: disney_specular f_r = ...' (found ${quotes})")
endif()
string(REGEX REPLACE "^#   " "" expected "${quoted}")

function(step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "install_consumer: ${what} failed (${rc}):\n${ARGN}\n${out}\n${err}")
  endif()
  set(step_out "${out}" PARENT_SCOPE)
endfunction()

function(expect_output what)
  string(FIND "${step_out}" "${expected}" at)
  if(at EQUAL -1)
    message(FATAL_ERROR "install_consumer: ${what} printed '${step_out}', expected '${expected}'")
  endif()
  message(STATUS "install_consumer: ${what}: ${step_out}")
endfunction()

file(REMOVE_RECURSE "${WORK}")
set(prefix "${WORK}/prefix")
step("cmake --install" "${CMAKE_COMMAND}" --install "${BUILD_DIR}" --prefix "${prefix}")
file(GLOB_RECURSE pc_files "${prefix}/*/abrdf.pc")
file(GLOB_RECURSE config_files "${prefix}/*/abrdfConfig.cmake")
if(NOT pc_files OR NOT config_files OR NOT EXISTS "${prefix}/include/abrdf.h"
   OR NOT EXISTS "${prefix}/include/abrdf_select.h")
  message(FATAL_ERROR "install_consumer: the install lacks abrdf.pc, abrdfConfig.cmake, "
                      "abrdf.h or abrdf_select.h")
endif()
list(GET pc_files 0 pc)
get_filename_component(pc_dir "${pc}" DIRECTORY)
get_filename_component(libdir "${pc_dir}" DIRECTORY)

# 1. pkg-config, seeing only the temporary prefix.
set(ENV{PKG_CONFIG_LIBDIR} "${pc_dir}")
unset(ENV{PKG_CONFIG_PATH})
step("pkg-config" "${PKG_CONFIG}" --cflags --libs abrdf)
string(STRIP "${step_out}" pc_flags)
separate_arguments(pc_flags UNIX_COMMAND "${pc_flags}")
step("cc via pkg-config" "${CC}" "${EXAMPLES}/quickstart.c" ${pc_flags} ${extra} -o "${WORK}/quickstart_pc")
set(ENV{LD_LIBRARY_PATH} "${libdir}")
step("quickstart (pkg-config)" "${WORK}/quickstart_pc")
expect_output("pkg-config build")
# The selection header is installed beside abrdf.h and includes it.
file(WRITE "${WORK}/select.c" [=[
#include <stdio.h>
#include <abrdf_select.h>
int main(void)
{
    abrdf_material m;
    abrdf_selection s;
    abrdf_material_init(&m);
    abrdf_selection_init(&s);
    m.r = 0.2;
    if (abrdf_select(&m, ABRDF_GOAL_PHOTOREAL, NULL, NULL, &s, NULL, NULL, NULL) != ABRDF_OK) return 1;
    printf("%s + %s\n", abrdf_model_get(s.diffuse)->name, abrdf_model_get(s.specular)->name);
    return 0;
}
]=])
step("cc select.c via pkg-config" "${CC}" "${WORK}/select.c" ${pc_flags} ${extra} -o "${WORK}/select_pc")
step("select (pkg-config)" "${WORK}/select_pc")
if(NOT step_out MATCHES "disney_diffuse \\+ disney_specular")
  message(FATAL_ERROR "install_consumer: select.c printed '${step_out}'")
endif()
message(STATUS "install_consumer: abrdf_select.h: ${step_out}")
unset(ENV{LD_LIBRARY_PATH})

# 2 + 3. find_package from a separate CMake project (no package registry, only the prefix).
step("configure examples" "${CMAKE_COMMAND}" -S "${EXAMPLES}" -B "${WORK}/consumer"
     "-DCMAKE_C_COMPILER=${CC}" "-DCMAKE_C_FLAGS=${EXTRA_FLAGS}" -DCMAKE_BUILD_TYPE=Release
     "-DCMAKE_PREFIX_PATH=${prefix}" -DCMAKE_FIND_USE_PACKAGE_REGISTRY=OFF)
file(STRINGS "${WORK}/consumer/CMakeCache.txt" found REGEX "^abrdf_DIR:")
string(FIND "${found}" "${prefix}/" at)
if(NOT at GREATER -1)
  message(FATAL_ERROR "install_consumer: find_package found '${found}', not the temporary prefix")
endif()
step("build examples" "${CMAKE_COMMAND}" --build "${WORK}/consumer")
step("quickstart (find_package, shared)" "${WORK}/consumer/quickstart")
expect_output("find_package abrdf::abrdf")
step("quickstart (find_package, static)" "${WORK}/consumer/quickstart_static")
expect_output("find_package abrdf::abrdf_static")
# examples/hair_table.c: a huang table built, prepared on and read (abrdf.h, "huang
# tabulated"), beside the quadrature, and the budget mode against it (abrdf_fit.h,
# abrdf_budget.reference: the table itself wins, error 0)
step("hair_table (find_package, shared)" "${WORK}/consumer/hair_table")
if(NOT step_out MATCHES "huang f_r, tabulated \\([0-9]+ values\\): [0-9.]+ [0-9.]+ [0-9.]+\n"
   OR NOT step_out MATCHES "huang f_r, integrated per call: +[0-9.]+ [0-9.]+ [0-9.]+\n"
   OR NOT step_out MATCHES "budget slight against the table: huang, predicted NMSE 0\n")
  message(FATAL_ERROR "install_consumer: hair_table printed '${step_out}'")
endif()
message(STATUS "install_consumer: hair_table: ${step_out}")

# Shared really links the shared library; static really does not.
if(OBJDUMP)
  step("objdump" "${OBJDUMP}" -p "${WORK}/consumer/quickstart")
  if(NOT step_out MATCHES "NEEDED +libabrdf\\.so")
    message(FATAL_ERROR "install_consumer: quickstart does not link libabrdf.so")
  endif()
  step("objdump" "${OBJDUMP}" -p "${WORK}/consumer/quickstart_static")
  if(step_out MATCHES "libabrdf\\.so")
    message(FATAL_ERROR "install_consumer: quickstart_static depends on libabrdf.so")
  endif()
  message(STATUS "install_consumer: shared/static linkage confirmed by objdump -p")
endif()
