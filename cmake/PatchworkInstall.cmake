# `cmake --install` and the package it installs (docs/guide.md, "Using the installed package"):
#
#   <prefix>/include/patchwork/<module>/*.h    the public headers, included as "core/errors.h"
#   <prefix>/<libdir>/libpatchwork_<module>.a  one static library per module
#   <prefix>/bin/patchwork                     the CLI
#   <prefix>/<libdir>/cmake/patchwork/         patchworkConfig.cmake, its version file, the
#                                              exported targets and the OpenSubdiv lookup
#   <prefix>/<libdir>/pkgconfig/patchwork.pc
#
# find_package(patchwork 0.1 CONFIG REQUIRED) gives patchwork::<module> for every module with a
# library (the names of the build tree's aliases) and patchwork::patchwork, all of them. Not
# installed: tools/ (the CLI's own code), meshes/interop (CGAL and OpenMesh, built only for the
# tests and benchmarks) and the internal headers listed below. Included from the end of the
# top-level CMakeLists.txt, when every target exists.

include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(patchwork_cmake_dir "${CMAKE_INSTALL_LIBDIR}/cmake/patchwork")
set(patchwork_include_dir "${CMAKE_INSTALL_INCLUDEDIR}/patchwork")
# Headers of installed modules that are not part of the installed API: osd_refiner.h is shared
# by subdivision's .cpp files and includes OpenSubdiv, which no public header may; the others
# are shared by their module's .cpp files only (the homogeneous form of rational curves, the
# tessellator's stages, the patch-edge helpers, what the two OBJ readers share, the free-form
# records' checks).
set(patchwork_internal_headers subdivision/osd_refiner.h curves/homogeneous.h surfaces/tessellator_stages.h
    surfaces/grid_bounds.h surfaces/patch_edge_geometry.h io/obj_syntax.h io/obj_freeform_checks.h)

# What code compiled against the installed libraries must share with them, in place of this
# build's patchwork_build_flags (assertions and instrumentation are the libraries' own business):
# C++20 for the headers, and from a sanitizer build the sanitizer runtimes the libraries call
# and Eigen's allocator choice (PatchworkModules.cmake). A sanitizer build's package thus makes
# every consumer link those runtimes; install a Release build for anything else.
add_library(patchwork_installed_flags INTERFACE)
set_target_properties(patchwork_installed_flags PROPERTIES EXPORT_NAME build_flags)
target_compile_features(patchwork_installed_flags INTERFACE cxx_std_20)
if(PATCHWORK_SANITIZE)
  target_compile_definitions(patchwork_installed_flags INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=0)
  target_link_options(patchwork_installed_flags INTERFACE -fsanitize=address,undefined)
endif()

# The module libraries in declaration order (each after the modules it uses) and their headers.
get_property(patchwork_all_modules GLOBAL PROPERTY PATCHWORK_MODULES)
set(patchwork_installed_modules "")
foreach(module IN LISTS patchwork_all_modules)
  if(NOT TARGET patchwork_${module})
    continue()  # tools: a program, installed below
  endif()
  list(APPEND patchwork_installed_modules ${module})
  set_target_properties(patchwork_${module} PROPERTIES EXPORT_NAME ${module})
  target_link_libraries(patchwork_${module} INTERFACE $<INSTALL_INTERFACE:patchwork_installed_flags>)
  # Only the module's own folder: subfolders (meshes/interop) are targets of their own.
  file(GLOB patchwork_headers CONFIGURE_DEPENDS RELATIVE "${PROJECT_SOURCE_DIR}" "${PROJECT_SOURCE_DIR}/${module}/*.h")
  list(REMOVE_ITEM patchwork_headers ${patchwork_internal_headers})
  install(FILES ${patchwork_headers} DESTINATION "${patchwork_include_dir}/${module}")
endforeach()
list(TRANSFORM patchwork_installed_modules PREPEND patchwork_ OUTPUT_VARIABLE patchwork_libraries)
list(JOIN patchwork_installed_modules " " patchwork_installed_modules_text)

# patchwork::patchwork, every module at once (the CLI owns the name patchwork in this build).
add_library(patchwork_all INTERFACE)
add_library(patchwork::patchwork ALIAS patchwork_all)
set_target_properties(patchwork_all PROPERTIES EXPORT_NAME patchwork)
target_link_libraries(patchwork_all INTERFACE ${patchwork_libraries})

install(TARGETS ${patchwork_libraries} patchwork_all patchwork_installed_flags EXPORT patchworkTargets
        ARCHIVE DESTINATION "${CMAKE_INSTALL_LIBDIR}"
        INCLUDES DESTINATION "${patchwork_include_dir}")
install(TARGETS patchwork RUNTIME DESTINATION "${CMAKE_INSTALL_BINDIR}")
install(EXPORT patchworkTargets NAMESPACE patchwork:: DESTINATION "${patchwork_cmake_dir}")

# The config finds every dependency the exported targets name, the private links of the static
# libraries included (patchwork_opensubdiv through the same file as this build).
configure_package_config_file(cmake/patchworkConfig.cmake.in "${PROJECT_BINARY_DIR}/patchworkConfig.cmake"
                              INSTALL_DESTINATION "${patchwork_cmake_dir}")
# Before 1.0 a minor version may break the API, so a request for 0.1 accepts 0.1.x only.
write_basic_package_version_file("${PROJECT_BINARY_DIR}/patchworkConfigVersion.cmake"
                                 COMPATIBILITY SameMinorVersion)
install(FILES "${PROJECT_BINARY_DIR}/patchworkConfig.cmake" "${PROJECT_BINARY_DIR}/patchworkConfigVersion.cmake"
              cmake/patchworkOpenSubdiv.cmake
        DESTINATION "${patchwork_cmake_dir}")

# pkg-config: the libraries are static, so Libs lists them (each before the ones it uses) and
# then what they link privately; Eigen's flags come through Requires. The prefix is found from
# the file's own place (pcfiledir), so the file is right for `cmake --install --prefix DIR` too.
block()
  set(libraries ${patchwork_libraries})
  list(REVERSE libraries)
  list(TRANSFORM libraries PREPEND -l)
  list(JOIN libraries " " libs)
  set(directories "")
  set(names "")
  foreach(dependency IN ITEMS patchwork_opensubdiv meshoptimizer::meshoptimizer TinyGLTF::TinyGLTF)
    get_target_property(location ${dependency} LOCATION)
    get_filename_component(file "${location}" NAME)
    if(NOT file MATCHES "^lib([^.]+)\\.")
      message(FATAL_ERROR "patchwork.pc: cannot name ${dependency}'s library ${location} as -l")
    endif()
    list(APPEND names "-l${CMAKE_MATCH_1}")
    get_filename_component(directory "${location}" DIRECTORY)
    list(APPEND directories "-L${directory}")
  endforeach()
  list(REMOVE_DUPLICATES directories)
  list(JOIN directories " " directories)
  list(JOIN names " " names)
  string(APPEND libs " ${directories} ${names} -pthread")
  # And what patchwork::build_flags asks of consumers besides C++20 (a sanitizer build's flags).
  set(cflags "")
  get_target_property(definitions patchwork_installed_flags INTERFACE_COMPILE_DEFINITIONS)
  if(definitions)
    list(TRANSFORM definitions PREPEND " -D")
    string(JOIN "" cflags ${definitions})
  endif()
  get_target_property(link_options patchwork_installed_flags INTERFACE_LINK_OPTIONS)
  if(link_options)
    list(JOIN link_options " " link_options)
    string(APPEND libs " ${link_options}")
  endif()
  file(RELATIVE_PATH prefix "${CMAKE_INSTALL_FULL_LIBDIR}/pkgconfig" "${CMAKE_INSTALL_PREFIX}")
  string(REGEX REPLACE "/$" "" prefix "${prefix}")
  configure_file(cmake/patchwork.pc.in "${PROJECT_BINARY_DIR}/patchwork.pc" @ONLY)
endblock()
install(FILES "${PROJECT_BINARY_DIR}/patchwork.pc" DESTINATION "${CMAKE_INSTALL_LIBDIR}/pkgconfig")

if(PATCHWORK_BUILD_TESTS)
  # The guide's code samples are the example files, byte for byte.
  add_test(NAME install_guide_examples
           COMMAND "${PROJECT_SOURCE_DIR}/tests/install/guide_examples_test.sh" "${PROJECT_SOURCE_DIR}")
endif()
if(PATCHWORK_BUILD_TESTS)
  # Every build type installs the same modules, the table of docs/guide.md.
  add_test(NAME install_modules
           COMMAND "${PROJECT_SOURCE_DIR}/tests/install/installed_modules_test.sh" "${PROJECT_SOURCE_DIR}"
                   "${PROJECT_BINARY_DIR}" $<CONFIG> "${CMAKE_COMMAND}")
  set_tests_properties(install_modules PROPERTIES TIMEOUT 120)
endif()
if(PATCHWORK_BUILD_TESTS AND NOT PATCHWORK_SANITIZE)
  # Installs this build into a temporary prefix and builds and runs examples/ against it, with
  # CMake and with pkg-config. It needs the whole build, which ctest runs after.
  add_test(NAME install_package
           COMMAND "${PROJECT_SOURCE_DIR}/tests/install/install_test.sh" "${PROJECT_SOURCE_DIR}" "${PROJECT_BINARY_DIR}"
                   $<CONFIG> "${CMAKE_COMMAND}" "${CMAKE_GENERATOR}" "${CMAKE_MAKE_PROGRAM}" "${CMAKE_CXX_COMPILER}")
  set_tests_properties(install_package PROPERTIES SKIP_RETURN_CODE 77 TIMEOUT 300)
endif()
