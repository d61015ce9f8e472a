# ROTGEN_PYTHON (default ON): the Python module `rotgen` (python/) is built whenever pybind11
# (Debian: pybind11-dev, python3-pybind11) and NumPy (python3-numpy, with python3-dev) are found
# for Debian's interpreter /usr/bin/python3 (the `python3` on PATH may be another one, without
# NumPy); under ROTGEN_REQUIRE_ALL they are required. Decided before generator/ is read: the
# stages are then compiled position-independent, since the module links them into a shared object.
# Sets ROTGEN_PYTHON_MODULE (ON when python/ builds the module) and ROTGEN_PIC_FLAGS.
option(ROTGEN_PYTHON "Build the Python module when pybind11 and NumPy are found" ON)
set(ROTGEN_PYTHON_MODULE OFF)
if(ROTGEN_PYTHON)
  if(NOT Python3_EXECUTABLE)
    set(Python3_EXECUTABLE /usr/bin/python3 CACHE FILEPATH "The Python the module is built for")
  endif()
  find_package(Python3 COMPONENTS Interpreter Development.Module NumPy)
  set(_rotgen_have_pybind11 FALSE)
  if(Python3_FOUND AND Python3_NumPy_FOUND)
    set(PYBIND11_FINDPYTHON ON)
    find_package(pybind11 2.6 CONFIG QUIET)
    set(_rotgen_have_pybind11 ${pybind11_FOUND})
  endif()
  rotgen_optional(_rotgen_have_pybind11
    "pybind11 and NumPy for ${Python3_EXECUTABLE} (Debian: pybind11-dev python3-pybind11 python3-numpy python3-dev)")
  set(ROTGEN_PYTHON_MODULE ${_rotgen_have_pybind11})
endif()
# Position-independent stages (for the module) keep the calls between rotgen's own functions
# direct and inlinable, as in the executable: nothing interposes them.
set(ROTGEN_PIC_FLAGS)
if(ROTGEN_PYTHON_MODULE)
  include(CheckCXXCompilerFlag)
  check_cxx_compiler_flag(-fno-semantic-interposition ROTGEN_HAVE_NO_INTERPOSITION)
  if(ROTGEN_HAVE_NO_INTERPOSITION)
    set(ROTGEN_PIC_FLAGS -fno-semantic-interposition)
  endif()
endif()
