# Layering rule (DESIGN.md §2, §8): {app, api} -> {wear, calibration, profiles_db} -> core, never
# back. app and api (the two front ends) never include each other; wear, calibration and
# profiles_db never include each other; core includes none of them. The C API's public header
# include/railwear/railwear.h is plain C and includes nothing of ours; only api/ and the tests
# include it.
# Inside core: vehicle -> contact -> geometry -> profile -> numerics, never back.
# SQLite only in profiles_db/*.cpp; CLI11 only in app/; toml++ only in app/; Ceres and GSL never
# in headers; MPI only in app/sweep_mpi.cpp (linked into the railwear executable alone).
# Run as: cmake -DSOURCE_DIR=<repo> -P tests/layering_test.cmake
set(violations "")
function(check_dir dir pattern why)
  file(GLOB_RECURSE files "${SOURCE_DIR}/${dir}/*.h" "${SOURCE_DIR}/${dir}/*.cpp")
  foreach(f ${files})
    file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
    foreach(line ${lines})
      if(line MATCHES "${pattern}")
        file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
        set(violations "${violations}\n  ${rel}: ${line}   (${why})")
      endif()
    endforeach()
  endforeach()
  # Hand the list back once: a PARENT_SCOPE set inside the loop would not update the local copy
  # and this line would then overwrite it with the empty list (the rule never fired).
  set(violations "${violations}" PARENT_SCOPE)
endfunction()

check_dir(core "[\"<](app|api|wear|calibration|profiles_db|railwear)/"
          "core depends on nothing of ours")
check_dir(core "[\"<](sqlite3\\.h|CLI/|toml\\+\\+/)" "core uses no SQLite, CLI11 or toml++")
# Inside core, each folder includes only the folders below it.
check_dir(core/contact "[\"<]core/vehicle/" "core/contact never includes core/vehicle")
check_dir(core/geometry "[\"<]core/(vehicle|contact)/"
          "core/geometry never includes core/contact or core/vehicle")
check_dir(core/profile "[\"<]core/(vehicle|contact|geometry)/"
          "core/profile includes only core/numerics")
check_dir(core/numerics "[\"<]core/(vehicle|contact|geometry|profile)/"
          "core/numerics includes nothing else of core")
check_dir(wear "[\"<](app|api|railwear|calibration|profiles_db)/"
          "wear never includes app, calibration or profiles_db")
check_dir(wear "[\"<](sqlite3\\.h|CLI/|toml\\+\\+/)" "wear uses no SQLite, CLI11 or toml++")
check_dir(calibration "[\"<](app|api|railwear|wear|profiles_db)/"
          "calibration never includes app, wear or profiles_db")
check_dir(calibration "[\"<](sqlite3\\.h|CLI/|toml\\+\\+/)"
          "calibration uses no SQLite, CLI11 or toml++")
check_dir(profiles_db "[\"<](app|api|railwear|wear|calibration)/"
          "profiles_db never includes app, wear or calibration")
check_dir(profiles_db "[\"<](CLI/|toml\\+\\+/)" "profiles_db uses no CLI11 or toml++")
# The front ends: app (the CLI) and api (the C API) sit side by side over the same libraries.
check_dir(app "[\"<](api|railwear)/" "app never includes api or the C API's header")
check_dir(api "[\"<]app/" "api never includes app")
check_dir(api "[\"<](sqlite3\\.h|CLI/|toml\\+\\+/|mpi\\.h)"
          "api uses no SQLite, CLI11, toml++ or MPI (profiles_db, app)")
check_dir(include "[\"<](app|api|core|wear|calibration|profiles_db)/"
          "the public C header includes nothing of ours")

# Ceres and GSL only inside .cpp files; SQLite only in profiles_db/*.cpp.
file(GLOB_RECURSE headers "${SOURCE_DIR}/core/*.h" "${SOURCE_DIR}/wear/*.h"
     "${SOURCE_DIR}/calibration/*.h" "${SOURCE_DIR}/profiles_db/*.h" "${SOURCE_DIR}/app/*.h"
     "${SOURCE_DIR}/api/*.h" "${SOURCE_DIR}/include/*.h")
foreach(f ${headers})
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${lines})
    if(line MATCHES "[<\"](ceres/|gsl/|sqlite3\\.h)")
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
      set(violations "${violations}\n  ${rel}: ${line}   (Ceres, GSL and SQLite only in .cpp files)")
    endif()
  endforeach()
endforeach()
file(GLOB_RECURSE all_sources "${SOURCE_DIR}/app/*.cpp" "${SOURCE_DIR}/api/*.cpp" "${SOURCE_DIR}/core/*.cpp"
     "${SOURCE_DIR}/wear/*.cpp" "${SOURCE_DIR}/calibration/*.cpp")
foreach(f ${all_sources})
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${lines})
    if(line MATCHES "[<\"]sqlite3\\.h")
      file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
      set(violations "${violations}\n  ${rel}: ${line}   (SQLite only in profiles_db/*.cpp)")
    endif()
  endforeach()
endforeach()

# MPI only in app/sweep_mpi.cpp: the libraries and railwear_app (the test programs) never see it.
file(GLOB_RECURSE every_source "${SOURCE_DIR}/app/*.h" "${SOURCE_DIR}/app/*.cpp"
     "${SOURCE_DIR}/core/*.h" "${SOURCE_DIR}/core/*.cpp" "${SOURCE_DIR}/wear/*.h"
     "${SOURCE_DIR}/wear/*.cpp" "${SOURCE_DIR}/calibration/*.h" "${SOURCE_DIR}/calibration/*.cpp"
     "${SOURCE_DIR}/profiles_db/*.h" "${SOURCE_DIR}/profiles_db/*.cpp")
foreach(f ${every_source})
  file(RELATIVE_PATH rel "${SOURCE_DIR}" "${f}")
  if(rel STREQUAL "app/sweep_mpi.cpp")
    continue()
  endif()
  file(STRINGS "${f}" lines REGEX "^[ \t]*#[ \t]*include")
  foreach(line ${lines})
    if(line MATCHES "[<\"]mpi\\.h")
      set(violations "${violations}\n  ${rel}: ${line}   (MPI only in app/sweep_mpi.cpp)")
    endif()
  endforeach()
endforeach()

if(violations)
  message(FATAL_ERROR
          "Forbidden include edges ({app, api} -> {wear, calibration, profiles_db} -> core):${violations}")
endif()
message(STATUS "layering: no forbidden include edge")
