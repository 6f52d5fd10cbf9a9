# The installed package (issue 20 point 3): `cmake --install` of the build tree's library
# component into a scratch prefix, then the downstream projects examples/embedding/c and
# examples/embedding/cpp configured with find_package(railwear), built and run against it, and
# the C one compiled once more by hand with the flags pkg-config gives from railwear.pc.
# With -DPYTHON=<interpreter> (the Python module was built) the python component is installed
# too and `import railwear` must work from the installed tree.
# Run as: cmake -DBUILD_DIR=<build> -DSOURCE_DIR=<repo> -DWORK_DIR=<scratch> [-DPYTHON=<python3>]
#         -P package_test.cmake
file(REMOVE_RECURSE ${WORK_DIR})
set(prefix ${WORK_DIR}/prefix)

function(run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif()
  set(run_output "${out}" PARENT_SCOPE)
endfunction()

run("cmake --install" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
    --component library)
file(GLOB_RECURSE installed RELATIVE ${prefix} ${prefix}/*)
foreach(expected include/railwear/railwear.h cmake/railwear/railwearConfig.cmake
                 cmake/railwear/railwearConfigVersion.cmake cmake/railwear/railwearTargets.cmake
                 pkgconfig/railwear.pc librailwear.so)
  set(found FALSE)
  foreach(f ${installed})
    if(f MATCHES "${expected}$")
      set(found TRUE)
    endif()
  endforeach()
  if(NOT found)
    message(FATAL_ERROR "cmake --install did not install ${expected}; installed:\n${installed}")
  endif()
endforeach()

foreach(project c cpp)
  run("configure examples/embedding/${project}" ${CMAKE_COMMAND}
      -S ${SOURCE_DIR}/examples/embedding/${project} -B ${WORK_DIR}/${project}
      -DCMAKE_PREFIX_PATH=${prefix} -DCMAKE_BUILD_TYPE=Release)
  run("build examples/embedding/${project}" ${CMAKE_COMMAND} --build ${WORK_DIR}/${project})
endforeach()
run("examples/embedding/c" ${WORK_DIR}/c/gauge_corner)
if(NOT run_output MATCHES "patch 0: .*MPa")
  message(FATAL_ERROR "gauge_corner printed no patch:\n${run_output}")
endif()
message(STATUS "C:\n${run_output}")
run("examples/embedding/cpp" ${WORK_DIR}/cpp/wheelset_sweep)
if(NOT run_output MATCHES "y_ws 8.0 mm: [0-9]+ patches.*right wheel")
  message(FATAL_ERROR "wheelset_sweep did not print its steps:\n${run_output}")
endif()
message(STATUS "C++:\n${run_output}")

# The Python module from the installed tree: PYTHONPATH to its dist-packages, librailwear found
# through the module's RPATH.
if(PYTHON)
  run("cmake --install (python)" ${CMAKE_COMMAND} --install ${BUILD_DIR} --prefix ${prefix}
      --component python)
  file(GLOB_RECURSE module ${prefix}/railwear.*.so)
  if(NOT module)
    message(FATAL_ERROR "cmake --install did not install the Python module")
  endif()
  get_filename_component(module_dir ${module} DIRECTORY)
  set(ENV{PYTHONPATH} ${module_dir})
  file(WRITE ${WORK_DIR}/import_railwear.py [=[
import railwear
p = railwear.Problem()
p.set_profile_file(railwear.BODY_WHEEL, "circle:300")
p.set_profile_file(railwear.BODY_RAIL, "circle:300")
p.set_model(kind=railwear.MODEL_HERTZ)
p.set_state(vertical_force_N=5e4)
assert p.calculate() == railwear.OK
print(railwear.__file__, "p_max", p.get_patch(0)["p_max_Pa"], "Pa")
]=])
  run("import railwear from the installed tree" ${PYTHON} ${WORK_DIR}/import_railwear.py)
  if(NOT run_output MATCHES "dist-packages/railwear.* p_max [0-9.e+]+ Pa")
    message(FATAL_ERROR "the installed module did not solve:\n${run_output}")
  endif()
  message(STATUS "Python: ${run_output}")
endif()

# pkg-config: the flags of the installed railwear.pc compile and link the C program.
find_program(PKG_CONFIG pkg-config)
find_program(CC NAMES cc gcc)
if(PKG_CONFIG AND CC)
  file(GLOB_RECURSE pc ${prefix}/*/railwear.pc)
  get_filename_component(pc_dir ${pc} DIRECTORY)
  set(ENV{PKG_CONFIG_PATH} ${pc_dir})
  run("pkg-config --modversion" ${PKG_CONFIG} --modversion railwear)
  message(STATUS "pkg-config: railwear ${run_output}")
  run("pkg-config --variable=libdir" ${PKG_CONFIG} --variable=libdir railwear)
  string(STRIP "${run_output}" libdir)
  run("pkg-config --cflags --libs" ${PKG_CONFIG} --cflags --libs railwear)
  string(STRIP "${run_output}" all_flags)
  separate_arguments(all_flags UNIX_COMMAND "${all_flags}")
  run("cc with pkg-config's flags" ${CC} -std=c99 ${SOURCE_DIR}/examples/embedding/c/gauge_corner.c
      ${all_flags} -Wl,-rpath,${libdir} -o ${WORK_DIR}/gauge_corner_pc)
  run("the pkg-config build" ${WORK_DIR}/gauge_corner_pc)
  message(STATUS "pkg-config build ran")
else()
  message(STATUS "pkg-config or cc not found: the pkg-config build is skipped")
endif()
file(REMOVE_RECURSE ${WORK_DIR})
