# camdyn as a subproject: a tiny consumer that add_subdirectory()s the source tree.
#
#   -DCAMDYN_SOURCE_DIR=  the camdyn source tree
#   -DWORK_DIR=           scratch directory (emptied)
#   -DGENERATOR=          CMake generator (optional)
#   -DBUILD=ON            also build and run the consumer (compiles the library)
#
# Checks at configure time (in the consumer's CMakeLists.txt): camdyn::camdyn exists; the
# options CAMDYN_BUILD_TESTS/BENCH/CLI default OFF and no test, bench, CLI or Python
# target is defined; CMAKE_BUILD_TYPE is left as the consumer set it (empty here).
file(REMOVE_RECURSE ${WORK_DIR})
set(src ${WORK_DIR}/consumer)
file(WRITE ${src}/CMakeLists.txt "cmake_minimum_required(VERSION 3.25)
project(camdyn_consumer LANGUAGES C CXX)
add_subdirectory(\"${CAMDYN_SOURCE_DIR}\" camdyn)
if(NOT TARGET camdyn::camdyn)
  message(FATAL_ERROR \"no camdyn::camdyn\")
endif()
foreach(opt CAMDYN_BUILD_TESTS CAMDYN_BUILD_BENCH CAMDYN_BUILD_CLI CAMDYN_BUILD_PYTHON)
  if(\${opt})
    message(FATAL_ERROR \"\${opt} is ON in a subproject\")
  endif()
endforeach()
foreach(t camdyn_tests camdyn_cli camdyn_stability_tests _camdyn bench_cam bench_engines camdyn_library_example)
  if(TARGET \${t})
    message(FATAL_ERROR \"subproject defines target \${t}\")
  endif()
endforeach()
if(CMAKE_BUILD_TYPE)
  message(FATAL_ERROR \"camdyn set CMAKE_BUILD_TYPE=\${CMAKE_BUILD_TYPE} in a subproject\")
endif()
add_executable(consumer main.cpp)
target_link_libraries(consumer PRIVATE camdyn::camdyn)
")
file(WRITE ${src}/main.cpp "#include <cstdio>
#include <camdyn/batch.hpp>
int main() {
  camdyn::Scene s = camdyn::paper_case(\"A\");
  s.run.t_end = 0.01;
  const auto r = camdyn::run_batch({s, s}, 2);
  std::printf(\"%s\\n\", r[0].BriefReport().c_str());
  return r[0].finished && r[1].steps == r[0].steps ? 0 : 1;
}
")

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_out "${out}" PARENT_SCOPE)
endfunction()

set(gen)
if(GENERATOR)
  set(gen -G ${GENERATOR})
endif()
run("consumer configure" ${CMAKE_COMMAND} -S ${src} -B ${WORK_DIR}/build ${gen})
message(STATUS "add_subdirectory(camdyn): configured; options off, no extra targets, no build type")
if(BUILD)
  run("consumer build" ${CMAKE_COMMAND} --build ${WORK_DIR}/build -j2)
  run("consumer run" ${WORK_DIR}/build/consumer)
  message(STATUS "consumer: ${run_out}")
endif()
