# OpenSubdiv as the imported target patchwork_opensubdiv, one lookup for this build
# (cmake/PatchworkDependencies.cmake) and for the installed package (patchworkConfig.cmake, where
# the static patchwork_subdivision still needs it at link time). Debian 12's CMake config for
# OpenSubdiv names static libraries that are not installed, so the header and the shared osdCPU
# library are found by hand. Leaves the target undefined when either is missing.

find_path(PATCHWORK_OSD_INCLUDE opensubdiv/far/topologyRefiner.h)
find_library(PATCHWORK_OSD_CPU osdCPU)
if(PATCHWORK_OSD_INCLUDE AND PATCHWORK_OSD_CPU AND NOT TARGET patchwork_opensubdiv)
  add_library(patchwork_opensubdiv SHARED IMPORTED GLOBAL)
  set_target_properties(patchwork_opensubdiv PROPERTIES IMPORTED_LOCATION "${PATCHWORK_OSD_CPU}"
                        INTERFACE_INCLUDE_DIRECTORIES "${PATCHWORK_OSD_INCLUDE}")
endif()
