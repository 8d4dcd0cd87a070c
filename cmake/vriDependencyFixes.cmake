# What finding vri's dependencies needs beyond find_package, on Debian and elsewhere: shared by the build
# (CMakeLists.txt) and the installed package (vriConfig.cmake), which must find them the same way.

# OpenVDB has no CMake config file, only its FindOpenVDB.cmake, which Debian ships under the multiarch
# library folder rather than on CMake's module path: appends the folder holding it to CMAKE_MODULE_PATH.
function(vri_add_openvdb_module_path)
  find_path(VRI_OPENVDB_MODULE_DIR FindOpenVDB.cmake
            PATHS ${CMAKE_PREFIX_PATH} ${CMAKE_INSTALL_PREFIX} /usr/local /usr
            PATH_SUFFIXES lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/OpenVDB lib64/cmake/OpenVDB lib/cmake/OpenVDB
            DOC "the folder holding OpenVDB's FindOpenVDB.cmake")
  if(VRI_OPENVDB_MODULE_DIR)
    set(CMAKE_MODULE_PATH ${CMAKE_MODULE_PATH} ${VRI_OPENVDB_MODULE_DIR} PARENT_SCOPE)
  endif()
endfunction()

# Debian's OpenImageIO export names /usr/include/opencv4 among its include folders, which need not exist
# (CMake then refuses every target that uses it): drops it from the imported target.
function(vri_drop_opencv_include_dirs)
  foreach(prop INTERFACE_INCLUDE_DIRECTORIES INTERFACE_SYSTEM_INCLUDE_DIRECTORIES)
    get_target_property(dirs OpenImageIO::OpenImageIO ${prop})
    if(dirs)
      list(FILTER dirs EXCLUDE REGEX "opencv4")
      set_target_properties(OpenImageIO::OpenImageIO PROPERTIES ${prop} "${dirs}")
    endif()
  endforeach()
endfunction()
