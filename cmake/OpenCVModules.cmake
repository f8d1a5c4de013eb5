# Finds the OpenCV modules IPD Studio uses from Debian's per-module -dev packages. OpenCV's own CMake
# config ships only in the libopencv-dev meta-package, which drags in VTK and ~1 GB of unrelated modules.
function(ipd_find_opencv_modules)
  find_path(IPD_OPENCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4 REQUIRED)
  foreach(module IN LISTS ARGN)
    find_library(IPD_OPENCV_${module}_LIBRARY NAMES opencv_${module} REQUIRED)
    if(NOT TARGET opencv_${module})
      add_library(opencv_${module} UNKNOWN IMPORTED GLOBAL)
      set_target_properties(opencv_${module} PROPERTIES
        IMPORTED_LOCATION "${IPD_OPENCV_${module}_LIBRARY}"
        INTERFACE_INCLUDE_DIRECTORIES "${IPD_OPENCV_INCLUDE_DIR}")
    endif()
  endforeach()
  message(STATUS "OpenCV modules: ${ARGN} (headers in ${IPD_OPENCV_INCLUDE_DIR})")
endfunction()
