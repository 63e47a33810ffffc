# Installs camdyn into a fresh prefix, then configures, builds and runs the downstream
# examples (examples/downstream, examples/library: find_package(camdyn 0.1 REQUIRED))
# against that installation only, and builds examples/library once more with pkg-config.
#
#   -DCAMDYN_BINARY_DIR=  the build to install (static: the main build)
#   -DCAMDYN_VERSION=     the project version: the examples must ask for its MAJOR.MINOR,
#                         find_package(camdyn <it> REQUIRED) must succeed and
#                         find_package(camdyn <major+1>.0 REQUIRED) must fail
#   -DSHARED=ON           instead: build the library alone with BUILD_SHARED_LIBS=ON from
#                         CAMDYN_SOURCE_DIR into WORK_DIR/camdyn-build (generator GENERATOR)
#                         and install that; the consumers must then link libcamdyn.so (ldd)
#   static: the consumers must not depend on libcamdyn.so.
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

if(SHARED)
  set(gen)
  if(GENERATOR)
    set(gen -G ${GENERATOR})
  endif()
  run("shared configure" ${CMAKE_COMMAND} -S ${CAMDYN_SOURCE_DIR} -B ${WORK_DIR}/camdyn-build ${gen}
      -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON -DCAMDYN_BUILD_TESTS=OFF
      -DCAMDYN_BUILD_BENCH=OFF -DCAMDYN_BUILD_CLI=OFF -DCAMDYN_BUILD_PYTHON=OFF)
  run("shared build" ${CMAKE_COMMAND} --build ${WORK_DIR}/camdyn-build -j2)
  set(CAMDYN_BINARY_DIR ${WORK_DIR}/camdyn-build)
endif()

run("install" ${CMAKE_COMMAND} --install ${CAMDYN_BINARY_DIR} --prefix ${prefix})

foreach(example downstream library)
  set(exe ${example})
  if(example STREQUAL "library")
    set(exe library_example)
  endif()
  run("${example} configure" ${CMAKE_COMMAND} -S ${CAMDYN_SOURCE_DIR}/examples/${example}
      -B ${WORK_DIR}/${example} -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
  run("${example} build" ${CMAKE_COMMAND} --build ${WORK_DIR}/${example})
  run("${example} run" ${WORK_DIR}/${example}/${exe})
  message(STATUS "${example}: ${run_out}")
  run("ldd ${example}" ldd ${WORK_DIR}/${example}/${exe})
  if(SHARED AND NOT run_out MATCHES "libcamdyn\\.so\\.[0-9]+ => ${prefix}/")
    message(FATAL_ERROR "${example} does not link the installed libcamdyn.so:\n${run_out}")
  elseif(NOT SHARED AND run_out MATCHES "libcamdyn\\.so")
    message(FATAL_ERROR "static build, yet ${example} needs libcamdyn.so:\n${run_out}")
  endif()
  if(SHARED)
    message(STATUS "ldd ${example}: libcamdyn from the prefix:\n${run_out}")
    # private dependencies stay private: the consumer itself needs only libcamdyn
    find_program(READELF readelf)
    if(READELF)
      run("readelf ${example}" ${READELF} -d ${WORK_DIR}/${example}/${exe})
      if(run_out MATCHES "NEEDED[^\n]*(sundials|klu|tomlplusplus)")
        message(FATAL_ERROR "${example} links camdyn's private dependencies directly:\n${run_out}")
      endif()
    endif()
  endif()
endforeach()

# Versioned find_package: the examples ask for this project's MAJOR.MINOR; asking for the
# exact installed version works, a later major version fails (SameMajorVersion).
if(CAMDYN_VERSION)
  string(REGEX MATCH "^[0-9]+\\.[0-9]+" major_minor "${CAMDYN_VERSION}")
  foreach(example downstream library)
    file(READ ${CAMDYN_SOURCE_DIR}/examples/${example}/CMakeLists.txt text)
    if(NOT text MATCHES "find_package\\(camdyn ${major_minor} REQUIRED\\)")
      message(FATAL_ERROR "examples/${example}/CMakeLists.txt does not ask for camdyn ${major_minor} "
                          "(the project version is ${CAMDYN_VERSION})")
    endif()
  endforeach()
  string(REGEX MATCH "^[0-9]+" major "${CAMDYN_VERSION}")
  math(EXPR next_major "${major} + 1")
  foreach(want ${CAMDYN_VERSION} ${next_major}.0)
    set(dir ${WORK_DIR}/version_${want})
    file(WRITE ${dir}/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(camdyn_version_check LANGUAGES C CXX)
find_package(camdyn ${want} REQUIRED)
message(STATUS \"found camdyn \${camdyn_VERSION}\")
")
    execute_process(COMMAND ${CMAKE_COMMAND} -S ${dir} -B ${dir}/build -DCMAKE_PREFIX_PATH=${prefix}
                    RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
    if(want STREQUAL CAMDYN_VERSION AND rc)
      message(FATAL_ERROR "find_package(camdyn ${want} REQUIRED) failed:\n${out}\n${err}")
    elseif(NOT want STREQUAL CAMDYN_VERSION AND NOT rc)
      message(FATAL_ERROR "find_package(camdyn ${want} REQUIRED) accepted version ${CAMDYN_VERSION}")
    endif()
    message(STATUS "find_package(camdyn ${want} REQUIRED): ${rc}")
  endforeach()
endif()

# pkg-config (camdyn.pc): the library example once more, compiled and linked by hand.
find_program(PKG_CONFIG pkg-config)
find_program(CXX_COMPILER NAMES c++ g++)
if(PKG_CONFIG AND CXX_COMPILER)
  file(GLOB_RECURSE pc ${prefix}/*/camdyn.pc)
  if(NOT pc)
    message(FATAL_ERROR "camdyn.pc not installed under ${prefix}")
  endif()
  get_filename_component(pcdir ${pc} DIRECTORY)
  get_filename_component(libdir ${pcdir} DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} ${pcdir})
  run("pkg-config version" ${PKG_CONFIG} --print-errors "camdyn >= 0.1")
  set(static)
  if(NOT SHARED)
    set(static --static)
  endif()
  run("pkg-config flags" ${PKG_CONFIG} ${static} --cflags --libs camdyn)
  string(STRIP "${run_out}" flags)
  separate_arguments(flags UNIX_COMMAND "${flags}")
  run("pkg-config build" ${CXX_COMPILER} -O1 ${CAMDYN_SOURCE_DIR}/examples/library/main.cpp
      ${flags} -Wl,-rpath,${libdir} -o ${WORK_DIR}/library_pc)
  run("pkg-config program run" ${WORK_DIR}/library_pc)
  message(STATUS "pkg-config build (${static} ${flags}) runs")
else()
  message(STATUS "pkg-config or c++ not found: camdyn.pc not checked")
endif()
