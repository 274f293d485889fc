# Module declarations and one static library per module.
#
# patchwork_module(NAME DEPENDS ...) declares the module and the modules it may use; the graph
# must be acyclic (a module can only depend on modules declared before it).
# patchwork_add_library(NAME SOURCES ...) builds patchwork_NAME with alias patchwork::NAME and
# links the declared dependencies that have a library.

add_library(patchwork_warnings INTERFACE)
target_compile_options(patchwork_warnings INTERFACE -Wall -Wextra -Wpedantic
                       $<$<BOOL:${PATCHWORK_WERROR}>:-Werror>)

add_library(patchwork_build_flags INTERFACE)
target_compile_definitions(patchwork_build_flags INTERFACE
                           $<$<OR:$<CONFIG:Debug>,$<BOOL:${PATCHWORK_SANITIZE}>>:PATCHWORK_ENABLE_ASSERTS>)
if(PATCHWORK_SANITIZE)
  # Every library and program is instrumented, except targets that set the property
  # PATCHWORK_UNINSTRUMENTED (the test programs' own code, tests/CMakeLists.txt): they still link
  # the sanitizer runtimes, so every access the library code makes on their behalf is checked.
  set(instrumented "$<NOT:$<BOOL:$<TARGET_PROPERTY:PATCHWORK_UNINSTRUMENTED>>>")
  target_compile_options(patchwork_build_flags INTERFACE
                         "$<${instrumented}:-fsanitize=address,undefined;-fno-sanitize-recover=all>"
                         -fno-omit-frame-pointer)
  target_link_options(patchwork_build_flags INTERFACE -fsanitize=address,undefined)
  # Eigen picks its allocator by __SANITIZE_ADDRESS__; one choice for instrumented and plain
  # code alike, or a matrix allocated on one side would be freed by the other allocator.
  target_compile_definitions(patchwork_build_flags INTERFACE EIGEN_MALLOC_ALREADY_ALIGNED=0)
endif()
if(PATCHWORK_FUZZ)
  if(NOT PATCHWORK_SANITIZE OR NOT CMAKE_CXX_COMPILER_ID STREQUAL "Clang")
    message(FATAL_ERROR "PATCHWORK_FUZZ needs PATCHWORK_SANITIZE=ON and clang (-DCMAKE_CXX_COMPILER=clang++)")
  endif()
  # The fuzzer's coverage instrumentation in every instrumented target; the fuzz programs add
  # libFuzzer's main (tests/fuzz). Other programs of this build run as usual: the sanitizer
  # runtimes they link answer the coverage hooks.
  target_compile_options(patchwork_build_flags INTERFACE "$<${instrumented}:-fsanitize=fuzzer-no-link>")
endif()

set_property(GLOBAL PROPERTY PATCHWORK_MODULES "")

function(patchwork_module name)
  cmake_parse_arguments(ARG "" "" "DEPENDS" ${ARGN})
  get_property(modules GLOBAL PROPERTY PATCHWORK_MODULES)
  foreach(dep IN LISTS ARG_DEPENDS)
    if(NOT dep IN_LIST modules)
      message(FATAL_ERROR "patchwork_module(${name}): '${dep}' must be declared before it")
    endif()
  endforeach()
  set_property(GLOBAL APPEND PROPERTY PATCHWORK_MODULES ${name})
  set_property(GLOBAL PROPERTY PATCHWORK_MODULE_DEPENDS_${name} "${ARG_DEPENDS}")
endfunction()

function(patchwork_write_module_graph path)
  get_property(modules GLOBAL PROPERTY PATCHWORK_MODULES)
  set(text "# module: the modules it depends on directly (generated from CMakeLists.txt)\n")
  foreach(module IN LISTS modules)
    get_property(deps GLOBAL PROPERTY PATCHWORK_MODULE_DEPENDS_${module})
    string(REPLACE ";" " " deps "${deps}")
    string(APPEND text "${module}: ${deps}\n")
  endforeach()
  file(WRITE "${path}" "${text}")
endfunction()

function(patchwork_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PRIVATE_LIBRARIES" ${ARGN})
  get_property(declared GLOBAL PROPERTY PATCHWORK_MODULE_DEPENDS_${name} SET)
  if(NOT declared)
    message(FATAL_ERROR "patchwork_add_library(${name}): module not declared with patchwork_module")
  endif()
  get_property(deps GLOBAL PROPERTY PATCHWORK_MODULE_DEPENDS_${name})
  add_library(patchwork_${name} STATIC ${ARG_SOURCES})
  add_library(patchwork::${name} ALIAS patchwork_${name})
  set_target_properties(patchwork_${name} PROPERTIES UNITY_BUILD ${PATCHWORK_UNITY_BUILD})
  # The Python module links the static libraries into a shared extension: they are compiled as
  # position-independent code then (only they: the programs and the tests' precompiled header
  # keep their flags).
  # -fno-semantic-interposition: nothing interposes patchwork's functions, so GCC may inline and
  # bind calls within a file as it does without -fPIC.
  if(PATCHWORK_PYTHON_MODULE)
    set_target_properties(patchwork_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
    target_compile_options(patchwork_${name} PRIVATE -fno-semantic-interposition)
  endif()
  target_include_directories(patchwork_${name} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>)
  # The helper targets hold this build's own flags and stay out of the installed package (a
  # static library's private links are exported too); cmake/PatchworkInstall.cmake gives the
  # installed targets the include directory and patchwork::build_flags instead.
  target_link_libraries(patchwork_${name} PUBLIC $<BUILD_INTERFACE:patchwork_build_flags>
                        PRIVATE $<BUILD_INTERFACE:patchwork_warnings> ${ARG_PRIVATE_LIBRARIES})
  foreach(dep IN LISTS deps)
    if(TARGET patchwork_${dep})
      target_link_libraries(patchwork_${name} PUBLIC patchwork::${dep})
    endif()
  endforeach()
endfunction()
