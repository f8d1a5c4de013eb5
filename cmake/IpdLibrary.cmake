# ipd_add_library(NAME SOURCES ... [PUBLIC deps...] [PRIVATE deps...]): one folder's static library. Headers
# are included from the project root ("core/geometry/geometry.h"), so an include names the folder it lives in.
function(ipd_add_library name)
  cmake_parse_arguments(L "" "" "SOURCES;PUBLIC;PRIVATE" ${ARGN})
  add_library(${name} STATIC ${L_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR})
  target_link_libraries(${name} PUBLIC ${L_PUBLIC} PRIVATE ${L_PRIVATE})
endfunction()
