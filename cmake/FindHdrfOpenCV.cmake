# Finds the four OpenCV modules the project uses (core, imgproc, imgcodecs, calib3d).
# Debian ships OpenCVConfig.cmake only in libopencv-dev, which drags in every module
# (highgui with Qt 5 among them); the per-module -dev packages are enough, so fall
# back to locating headers and libraries directly. Provides HdrfOpenCV::OpenCV.
find_package(OpenCV 4 QUIET COMPONENTS core imgproc imgcodecs calib3d)
if(OpenCV_FOUND)
  add_library(HdrfOpenCV::OpenCV INTERFACE IMPORTED)
  target_link_libraries(HdrfOpenCV::OpenCV INTERFACE opencv_core opencv_imgproc opencv_imgcodecs opencv_calib3d)
  set(HdrfOpenCV_FOUND TRUE)
  return()
endif()
find_path(HdrfOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_hdrf_cv_libs)
foreach(m core imgproc imgcodecs calib3d)
  find_library(HdrfOpenCV_${m}_LIBRARY opencv_${m})
  list(APPEND _hdrf_cv_libs ${HdrfOpenCV_${m}_LIBRARY})
endforeach()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(HdrfOpenCV REQUIRED_VARS HdrfOpenCV_INCLUDE_DIR
  HdrfOpenCV_core_LIBRARY HdrfOpenCV_imgproc_LIBRARY HdrfOpenCV_imgcodecs_LIBRARY HdrfOpenCV_calib3d_LIBRARY)
if(HdrfOpenCV_FOUND AND NOT TARGET HdrfOpenCV::OpenCV)
  add_library(HdrfOpenCV::OpenCV INTERFACE IMPORTED)
  target_include_directories(HdrfOpenCV::OpenCV INTERFACE ${HdrfOpenCV_INCLUDE_DIR})
  target_link_libraries(HdrfOpenCV::OpenCV INTERFACE ${_hdrf_cv_libs})
endif()
