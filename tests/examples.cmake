# Every example is a test: one ctest per scene or config found under examples/ (issue 13), run by
# tests/tools/run_example.cmake with small arguments. A file's kind comes from its tables:
#   [wear]         a wear scene          -> wear --steps 1 into a scratch database
#   [scene]        a contact scene       -> contact --accuracy draft --json -
#   [calibration]  a calibration config  -> calibrate --json -
#   [fem]          a FEM config          -> fem-reference --report-only (skipped with the reason
#                                           when its results are not committed)
#   [sweep]        a sweep plan          -> sweep --list (every line's scene read)
#   *_mbs.csv      an MBS time history   -> traffic import into a scratch collective, compared
#                                           with the committed <stem>_collective.toml beside it
# Other .toml files are data, not runnable (influence-constants files such as
# calibration/calibrated_paper.toml, FEM results in fem/reference/) and get no test.
# Test names: example.<path without .toml, '/' -> '.'>, e.g. example.calibration.synthetic.
file(GLOB_RECURSE RAILWEAR_EXAMPLES CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/examples
     ${PROJECT_SOURCE_DIR}/examples/*.toml)
list(SORT RAILWEAR_EXAMPLES)
foreach(example IN LISTS RAILWEAR_EXAMPLES)
  set(path ${PROJECT_SOURCE_DIR}/examples/${example})
  file(STRINGS ${path} tables REGEX "^\\[[a-z_]+\\]")
  if("[wear]" IN_LIST tables)
    set(kind wear)
  elseif("[scene]" IN_LIST tables)
    set(kind contact)
  elseif("[calibration]" IN_LIST tables)
    set(kind calibration)
  elseif("[fem]" IN_LIST tables)
    set(kind fem)
  elseif("[sweep]" IN_LIST tables)
    set(kind sweep)
  else()
    continue()
  endif()
  string(REGEX REPLACE "\\.toml$" "" name ${example})
  string(REPLACE "/" "." name ${name})
  add_test(NAME example.${name}
           COMMAND ${CMAKE_COMMAND} -DRAILWEAR=$<TARGET_FILE:railwear> -DEXAMPLE=${path}
                   -DKIND=${kind} -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/examples/${name}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/tools/run_example.cmake)
  set_tests_properties(example.${name} PROPERTIES LABELS "example;${kind}" TIMEOUT 300
                       SKIP_REGULAR_EXPRESSION "SKIPPED:")
endforeach()

# MBS time histories (examples/**/NAME_mbs.csv): `traffic import` must write the committed
# NAME_collective.toml beside it (below its comment header, the source path aside).
file(GLOB_RECURSE RAILWEAR_MBS_EXAMPLES CONFIGURE_DEPENDS RELATIVE ${PROJECT_SOURCE_DIR}/examples
     ${PROJECT_SOURCE_DIR}/examples/*_mbs.csv)
list(SORT RAILWEAR_MBS_EXAMPLES)
foreach(example IN LISTS RAILWEAR_MBS_EXAMPLES)
  string(REGEX REPLACE "\\.csv$" "" name ${example})
  string(REPLACE "/" "." name ${name})
  add_test(NAME example.${name}
           COMMAND ${CMAKE_COMMAND} -DRAILWEAR=$<TARGET_FILE:railwear>
                   -DEXAMPLE=${PROJECT_SOURCE_DIR}/examples/${example} -DKIND=mbs
                   -DWORK_DIR=${CMAKE_CURRENT_BINARY_DIR}/examples/${name}
                   -P ${CMAKE_CURRENT_SOURCE_DIR}/tools/run_example.cmake)
  set_tests_properties(example.${name} PROPERTIES LABELS "example;mbs" TIMEOUT 300)
endforeach()
