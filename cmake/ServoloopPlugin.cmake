# servoloop_add_plugin(<target> SOURCES ... [LINK ...] [NO_INSTALL]
#                      [NO_PRECOMPILED_HEADERS])
# Builds a servoloop plugin (controller or backend): a MODULE library that the
# plugin loader opens with dlopen. Used in tree and by out-of-tree projects.
# Out of tree, servoloop's common plugin headers (ServoloopPluginPrecompiled.hpp,
# beside this file) are precompiled once for the target, so that rebuilding
# after an edit to a source parses none of them again; NO_PRECOMPILED_HEADERS
# turns that off.
set(SERVOLOOP_PLUGIN_PRECOMPILED_HEADER ${CMAKE_CURRENT_LIST_DIR}/ServoloopPluginPrecompiled.hpp)
function(servoloop_add_plugin target)
  cmake_parse_arguments(ARG "NO_INSTALL;NO_PRECOMPILED_HEADERS" "" "SOURCES;LINK" ${ARGN})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LINK})
  set_target_properties(${target} PROPERTIES PREFIX "lib")
  # A plugin runs on the real-time cycle: with no build type chosen (CMake's
  # default adds no optimisation flags), build it optimised anyway.
  if(NOT CMAKE_BUILD_TYPE AND NOT CMAKE_CONFIGURATION_TYPES)
    target_compile_options(${target} PRIVATE -O2)
    target_compile_definitions(${target} PRIVATE NDEBUG)
  endif()
  if(DEFINED SERVOLOOP_PLUGIN_OUTPUT_DIR)
    # In the servoloop tree: build next to the other plugins and install with them.
    # Out-of-tree projects install to ${SERVOLOOP_PLUGIN_DIR} (or any folder on
    # SERVOLOOP_PLUGIN_PATH) themselves.
    set_target_properties(${target} PROPERTIES
      LIBRARY_OUTPUT_DIRECTORY ${SERVOLOOP_PLUGIN_OUTPUT_DIR})
    if(NOT ARG_NO_INSTALL)
      install(TARGETS ${target} LIBRARY DESTINATION ${SERVOLOOP_PLUGIN_SUBDIR})
      # Part of what `servoloop` runs with (the servoloop_runtime target).
      set_property(GLOBAL APPEND PROPERTY SERVOLOOP_RUNTIME_PLUGINS ${target})
    endif()
  else()
    # Out of tree: keep the path to the servoloop libraries it links in the
    # installed plugin, so it loads from any prefix (servoloop itself does not
    # load sim_common or transmissions for a plugin).
    set_target_properties(${target} PROPERTIES INSTALL_RPATH_USE_LINK_PATH TRUE)
    # In tree the plugins are many and each built once, so a header compiled
    # for each would cost more than it saves.
    if(NOT ARG_NO_PRECOMPILED_HEADERS)
      target_precompile_headers(${target} PRIVATE ${SERVOLOOP_PLUGIN_PRECOMPILED_HEADER})
    endif()
  endif()
endfunction()
