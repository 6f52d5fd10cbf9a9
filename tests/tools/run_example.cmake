# Runs one example as a test (registered by tests/examples.cmake, one ctest per file):
#   cmake -DRAILWEAR=<binary> -DEXAMPLE=<file> -DKIND=contact|wear|calibration|fem
#         -DWORK_DIR=<scratch dir> -P run_example.cmake
# with small arguments, and checks the exit code and a key line of the output:
#   contact      `contact FILE --accuracy draft --json -`: exit 0, one JSON object, status
#                "converged" (a wheelset: both wheels)
#   wear         `wear FILE --db WORK_DIR/example.sqlite --steps 1`: exit 0, "run '...' in ...:
#                1 steps"
#   calibration  `calibrate FILE --out WORK_DIR/constants.toml --json -`: exit 0, JSON status
#                "converged", the constants file written
#   fem          `fem-reference FILE --report-only --out-dir D`, D the config's folder, then its
#                reference/ folder: the tables of the committed results (exit 0, "read from");
#                a config whose results are not committed is skipped with the reason (running
#                it needs gmsh + CalculiX for minutes)
# A skipped test prints "SKIPPED:" (the test's SKIP_REGULAR_EXPRESSION): FEM configs without
# committed results, and examples whose ../shared profile files are absent.
cmake_minimum_required(VERSION 3.22)
foreach(var RAILWEAR EXAMPLE KIND WORK_DIR)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "run_example.cmake: -D${var}=... is required")
  endif()
endforeach()
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}")

function(run)
  execute_process(COMMAND "${RAILWEAR}" ${ARGN} WORKING_DIRECTORY "${WORK_DIR}"
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err)
  set(code "${code}" PARENT_SCOPE)
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
  string(REPLACE ";" " " shown "${ARGN}")
  message("railwear ${shown}\n-> exit ${code}")
endfunction()

function(fail what)
  message(FATAL_ERROR "${EXAMPLE}: ${what}\n--- stdout ---\n${out}\n--- stderr ---\n${err}")
endfunction()

# JSON value at the given keys ("" when missing).
function(json_get result json)
  string(JSON value ERROR_VARIABLE json_error GET "${json}" ${ARGN})
  if(json_error)
    set(value "")
  endif()
  set(${result} "${value}" PARENT_SCOPE)
endfunction()

# Examples that read the real profile files of ../shared/data/profiles/ (never copied into the
# repository) are skipped with the reason when that folder is absent.
file(STRINGS "${EXAMPLE}" shared_refs REGEX "\"[^\"]*shared/data/profiles/[^\"]*\"")
get_filename_component(example_dir "${EXAMPLE}" DIRECTORY)
foreach(line IN LISTS shared_refs)
  string(REGEX MATCH "\"([^\"]*shared/data/profiles/[^\"]*)\"" _ "${line}")
  if(NOT EXISTS "${example_dir}/${CMAKE_MATCH_1}")
    message("SKIPPED: ${EXAMPLE} reads ${CMAKE_MATCH_1}, which is absent (../shared is not beside "
            "the repository)")
    return()
  endif()
endforeach()

if(KIND STREQUAL "contact")
  run(contact "${EXAMPLE}" --accuracy draft --json -)
  if(NOT code EQUAL 0)
    fail("exit ${code}, expected 0")
  endif()
  string(JSON type ERROR_VARIABLE json_error TYPE "${out}")
  if(json_error OR NOT type STREQUAL "OBJECT")
    fail("stdout is not one JSON object (${json_error})")
  endif()
  json_get(wheels "${out}" wheels)
  if(wheels)  # a wheelset: one object per wheel
    set(paths "wheels right status" "wheels left status")
  else()
    set(paths "status")
  endif()
  foreach(path IN LISTS paths)
    string(REPLACE " " ";" keys "${path}")
    json_get(status "${out}" ${keys})
    if(NOT status STREQUAL "converged")
      fail("JSON ${path} = '${status}', expected 'converged'")
    endif()
    message("${path}: ${status}")
  endforeach()
elseif(KIND STREQUAL "wear")
  run(wear "${EXAMPLE}" --db "${WORK_DIR}/example.sqlite" --steps 1)
  if(NOT code EQUAL 0)
    fail("exit ${code}, expected 0")
  endif()
  if(NOT out MATCHES "run '[^\n]*' in [^\n]*: 1 steps")
    fail("no line \"run '...' in ...: 1 steps\" on stdout")
  endif()
  message("${CMAKE_MATCH_0}")
elseif(KIND STREQUAL "calibration")
  run(calibrate "${EXAMPLE}" --out "${WORK_DIR}/constants.toml" --json -)
  if(NOT code EQUAL 0)
    fail("exit ${code}, expected 0")
  endif()
  json_get(status "${out}" status)
  if(NOT status STREQUAL "converged")
    fail("JSON status = '${status}', expected 'converged'")
  endif()
  if(NOT EXISTS "${WORK_DIR}/constants.toml")
    fail("no constants file written")
  endif()
  message("status: ${status}")
elseif(KIND STREQUAL "fem")
  # The committed results sit beside the config or in its reference/ folder, depending on the
  # experiment's output paths: try both.
  get_filename_component(config_dir "${EXAMPLE}" DIRECTORY)
  set(missing TRUE)
  set(errors "")
  foreach(dir "${config_dir}" "${config_dir}/reference")
    run(fem-reference "${EXAMPLE}" --report-only --out-dir "${dir}")
    if(code EQUAL 0)
      if(NOT out MATCHES "read from")
        fail("no \"read from\" line on stdout")
      endif()
      return()
    endif()
    string(APPEND errors "--out-dir ${dir}: ${err}")
    if(NOT err MATCHES "which does not exist; run that experiment first|cannot read the FEM contact result")
      set(missing FALSE)
    endif()
  endforeach()
  if(missing)
    message("SKIPPED: the FEM results of this config are not committed; running it needs gmsh + "
            "CalculiX for minutes: railwear fem-reference ${EXAMPLE}\n${errors}")
    return()
  endif()
  set(err "${errors}")
  fail("fem-reference --report-only failed with both output folders")
else()
  message(FATAL_ERROR "run_example.cmake: KIND '${KIND}': expected contact, wear, calibration or fem")
endif()
