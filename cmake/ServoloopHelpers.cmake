include(${CMAKE_CURRENT_LIST_DIR}/ServoloopPlugin.cmake)

# servoloop_install_headers(<folder> <header>...)
# Installs include/<folder>/<header> (a path that may name a subfolder) of the
# current source folder as <includedir>/<folder>/<header>: the API plugin
# authors include. scripts/check_install.sh checks that what is installed is
# exactly what the headers authors start from need.
function(servoloop_install_headers folder)
  foreach(header IN LISTS ARGN)
    get_filename_component(subfolder ${header} DIRECTORY)
    install(FILES ${CMAKE_CURRENT_SOURCE_DIR}/include/${folder}/${header}
      DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/${folder}/${subfolder})
  endforeach()
endfunction()

# servoloop_add_library(<module> SOURCES ... [PUBLIC_LINK ...] [PRIVATE_LINK ...]
#                       [INSTALL_HEADERS <header>...])
# One shared library per module folder, with headers under
# <module>/include/servoloop/<module>/, exported as servoloop::<module>. Only
# the INSTALL_HEADERS (paths under include/servoloop/<module>/) are installed;
# the other headers are the module's and its tests' own.
function(servoloop_add_library module)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_LINK;PRIVATE_LINK;INSTALL_HEADERS" ${ARGN})
  add_library(${module} SHARED ${ARG_SOURCES})
  add_library(servoloop::${module} ALIAS ${module})
  set_target_properties(${module} PROPERTIES OUTPUT_NAME servoloop_${module}
    VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR}.${PROJECT_VERSION_MINOR}
    EXPORT_NAME ${module})
  target_include_directories(${module} PUBLIC
    $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
    $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_compile_features(${module} PUBLIC cxx_std_20)
  target_link_libraries(${module} PUBLIC ${ARG_PUBLIC_LINK} PRIVATE ${ARG_PRIVATE_LINK})
  install(TARGETS ${module} EXPORT servoloopTargets
    LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
    ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
    RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
  servoloop_install_headers(servoloop/${module} ${ARG_INSTALL_HEADERS})
endfunction()

# servoloop_add_test(<name> SOURCES ... LINK ... [LABELS ...])
# A gtest executable registered with CTest under its own name.
function(servoloop_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  target_link_libraries(${name} PRIVATE ${ARG_LINK} servoloop_test_support GTest::gtest GTest::gtest_main)
  # The test code itself unoptimised: it compiles in half the time, and what
  # it tests (the libraries, plugins and the command) keeps its own -O2.
  # Physics tests stay optimised: they compile engine code and integrate
  # reference solutions themselves (tens of times slower at -O0).
  if(SERVOLOOP_UNOPTIMISED_TESTS AND NOT "physics" IN_LIST ARG_LABELS)
    target_compile_options(${name} PRIVATE -O0)
  endif()
  target_compile_definitions(${name} PRIVATE
    SERVOLOOP_SOURCE_DIR="${PROJECT_SOURCE_DIR}"
    SERVOLOOP_SEED_DIR="${PROJECT_SOURCE_DIR}/robots/one_dof")
  add_test(NAME ${name} COMMAND ${name})
  if(ARG_LABELS)
    set_tests_properties(${name} PROPERTIES LABELS "${ARG_LABELS}")
  endif()
endfunction()
