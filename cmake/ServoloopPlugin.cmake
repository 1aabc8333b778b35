# servoloop_add_plugin(<target> SOURCES ... [LINK ...])
# Builds a servoloop plugin (controller or backend): a MODULE library that the
# plugin loader opens with dlopen. Used in tree and by out-of-tree projects.
function(servoloop_add_plugin target)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  add_library(${target} MODULE ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_LINK})
  set_target_properties(${target} PROPERTIES PREFIX "lib")
  if(DEFINED SERVOLOOP_PLUGIN_OUTPUT_DIR)
    set_target_properties(${target} PROPERTIES
      LIBRARY_OUTPUT_DIRECTORY ${SERVOLOOP_PLUGIN_OUTPUT_DIR})
  endif()
endfunction()
