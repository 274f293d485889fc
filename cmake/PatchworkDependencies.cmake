# Every dependency comes from a Debian package (scripts/setup installs them). A missing one
# stops the configure step with the name of the package to install.

function(patchwork_missing what package)
  message(FATAL_ERROR "patchwork: ${what} not found. Install the Debian package '${package}' "
                      "(or run scripts/setup, which installs everything).")
endfunction()

find_package(Eigen3 3.4 CONFIG QUIET)
if(NOT TARGET Eigen3::Eigen)
  patchwork_missing("Eigen 3.4" libeigen3-dev)
endif()

# OpenSubdiv, found by hand (Debian 12's CMake config for it is broken); the installed package
# config repeats this lookup with the same file.
include(patchworkOpenSubdiv)
if(NOT TARGET patchwork_opensubdiv)
  patchwork_missing("OpenSubdiv (opensubdiv/far/topologyRefiner.h, libosdCPU)" libosd-dev)
endif()

# OpenMesh ships a config without a version file: no version in the request.
find_package(OpenMesh CONFIG QUIET)
if(NOT TARGET OpenMeshCore)
  patchwork_missing("OpenMesh" libopenmesh-dev)
endif()

find_package(CGAL CONFIG QUIET)
if(NOT CGAL_FOUND)
  patchwork_missing("CGAL" libcgal-dev)
endif()

# tinygltf is a shared library in Debian: never define TINYGLTF_IMPLEMENTATION.
find_package(TinyGLTF CONFIG QUIET)
if(NOT TARGET TinyGLTF::TinyGLTF)
  patchwork_missing("tinygltf" libtinygltf-dev)
endif()
find_package(nlohmann_json CONFIG QUIET)
if(NOT TARGET nlohmann_json::nlohmann_json)
  patchwork_missing("nlohmann-json" nlohmann-json3-dev)
endif()

find_package(CLI11 CONFIG QUIET)
if(NOT TARGET CLI11::CLI11)
  patchwork_missing("CLI11" libcli11-dev)
endif()
find_package(meshoptimizer CONFIG QUIET)
if(NOT TARGET meshoptimizer::meshoptimizer)
  patchwork_missing("meshoptimizer" libmeshoptimizer-dev)
endif()

if(PATCHWORK_BUILD_TESTS)
  find_package(GTest CONFIG QUIET)
  if(NOT TARGET GTest::gtest_main)
    patchwork_missing("GoogleTest" libgtest-dev)
  endif()
  find_package(rapidcheck CONFIG QUIET)
  if(NOT TARGET rapidcheck)
    patchwork_missing("RapidCheck" librapidcheck-dev)
  endif()
  # GMP's C++ rationals (mpq_class) are the exact reference of the numerical tests.
  find_path(PATCHWORK_GMPXX_INCLUDE gmpxx.h)
  find_library(PATCHWORK_GMPXX gmpxx)
  find_library(PATCHWORK_GMP gmp)
  if(NOT PATCHWORK_GMPXX_INCLUDE OR NOT PATCHWORK_GMPXX OR NOT PATCHWORK_GMP)
    patchwork_missing("GMP with C++ bindings (gmpxx.h, libgmpxx)" libgmp-dev)
  endif()
  if(NOT TARGET patchwork_gmp)
    add_library(patchwork_gmp INTERFACE IMPORTED GLOBAL)
    set_target_properties(patchwork_gmp PROPERTIES INTERFACE_INCLUDE_DIRECTORIES "${PATCHWORK_GMPXX_INCLUDE}"
                          INTERFACE_LINK_LIBRARIES "${PATCHWORK_GMPXX};${PATCHWORK_GMP}")
  endif()
endif()

if(PATCHWORK_BUILD_BENCH)
  find_package(benchmark CONFIG QUIET)
  if(NOT TARGET benchmark::benchmark)
    patchwork_missing("Google Benchmark" libbenchmark-dev)
  endif()
endif()

# The Python module (python/): Debian's pybind11 for Debian's python3 (/usr/bin/python3, where
# python3-numpy and pybind11 live; this machine image puts another Python first on PATH, so the
# interpreter is named, not searched). Optional: without pybind11 the rest builds as before and
# the configure log says why the module is left out. The sanitizer build leaves it out too: an
# instrumented extension needs the sanitizer runtime preloaded into the interpreter, which would
# test the interpreter's leaks rather than ours.
option(PATCHWORK_BUILD_PYTHON "Build the Python module when pybind11 and Debian's python3 are present" ON)
set(PATCHWORK_PYTHON "/usr/bin/python3" CACHE FILEPATH "The Python the module is built for and tested with")
set(PATCHWORK_PYTHON_MODULE OFF)
if(NOT PATCHWORK_BUILD_PYTHON)
  message(STATUS "patchwork: Python module off (PATCHWORK_BUILD_PYTHON=OFF)")
elseif(PATCHWORK_SANITIZE)
  message(STATUS "patchwork: Python module and its tests skipped in the sanitizer build (an instrumented "
                 "extension needs the sanitizer runtime preloaded into python3; the Release build tests it)")
elseif(NOT EXISTS "${PATCHWORK_PYTHON}")
  message(STATUS "patchwork: Python module skipped: ${PATCHWORK_PYTHON} not found (Debian package python3-dev)")
else()
  set(Python_EXECUTABLE "${PATCHWORK_PYTHON}")
  set(PYBIND11_FINDPYTHON ON)
  find_package(Python 3 QUIET COMPONENTS Interpreter Development.Module)
  find_package(pybind11 CONFIG QUIET)
  execute_process(COMMAND "${PATCHWORK_PYTHON}" -c "import numpy" RESULT_VARIABLE patchwork_numpy_missing
                  OUTPUT_QUIET ERROR_QUIET)
  if(NOT Python_FOUND OR NOT pybind11_FOUND)
    message(STATUS "patchwork: Python module skipped: pybind11 or the headers of ${PATCHWORK_PYTHON} not found "
                   "(Debian packages pybind11-dev python3-dev; scripts/setup installs them)")
  elseif(patchwork_numpy_missing)
    message(STATUS "patchwork: Python module skipped: ${PATCHWORK_PYTHON} has no numpy (Debian package python3-numpy)")
  else()
    set(PATCHWORK_PYTHON_MODULE ON)
    message(STATUS "patchwork: Python module for ${PATCHWORK_PYTHON} (Python ${Python_VERSION}, pybind11 ${pybind11_VERSION})")
  endif()
endif()
