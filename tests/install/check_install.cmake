# Installs the build into a fresh prefix, builds tests/install/consumer
# against it with find_package(raycast), runs it and compares its PPMs with
# the command line's for the same scene (byte for byte); with REPORT_PYTHON,
# runs the installed bench report. Run by CTest:
#   cmake -DBUILD=... -DSOURCE=... -DWORK=... -DRAYCAST=... [-DREPORT_PYTHON=...] -P check_install.cmake
foreach(v BUILD SOURCE WORK RAYCAST)
  if(NOT DEFINED ${v})
    message(FATAL_ERROR "${v} is not set")
  endif()
endforeach()
file(REMOVE_RECURSE ${WORK})
set(prefix ${WORK}/prefix)
function(run)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE out)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${ARGN}\n${out}")
  endif()
endfunction()
run(${CMAKE_COMMAND} --install ${BUILD} --prefix ${prefix})
foreach(f include/raycast/raycast.h lib/cmake/raycast/raycastConfig.cmake lib/cmake/raycast/raycastConfigVersion.cmake
          bin/raycast)
  if(NOT EXISTS ${prefix}/${f})
    message(FATAL_ERROR "not installed: ${f}")
  endif()
endforeach()
run(${CMAKE_COMMAND} -S ${SOURCE}/tests/install/consumer -B ${WORK}/consumer -G Ninja
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH=${prefix})
run(${CMAKE_COMMAND} --build ${WORK}/consumer)
run(${WORK}/consumer/consumer ${WORK}/api.ppm ${WORK}/arrays.ppm)
run(${prefix}/bin/raycast --scene world --width 96 --samples 4 -q -o ${WORK}/cli.ppm)
foreach(f api.ppm arrays.ppm)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK}/cli.ppm ${WORK}/${f} RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "${f} differs from the command line's cli.ppm")
  endif()
endforeach()
# raycast-bench's report, installed as bench-report.py beside its parts: it
# must find them wherever it is run from (a run with no rows prints nothing).
if(REPORT_PYTHON)
  file(WRITE ${WORK}/empty-run.json "{\"benchmarks\": []}\n")
  run(${REPORT_PYTHON} ${prefix}/share/raycast/bench-report.py ${WORK}/empty-run.json)
endif()
file(REMOVE_RECURSE ${WORK})
