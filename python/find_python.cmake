# Finds pybind11 and a Python 3 interpreter that can import numpy (the module's tests and
# users need it), and sets MESHSAL_PYTHON_FOUND. Python_EXECUTABLE, when given (setup.py
# passes the interpreter that runs pip), is used as it is; otherwise `python3` on the PATH,
# then the system's /usr/bin/python3 (Debian's python3-numpy and pybind11-dev are
# installed for it; a python3 earlier on the PATH, e.g. pyenv's, may lack numpy).
set(MESHSAL_PYTHON_FOUND OFF)
if(NOT Python_EXECUTABLE)
  find_program(MESHSAL_PATH_PYTHON NAMES python3)
  foreach(candidate ${MESHSAL_PATH_PYTHON} /usr/bin/python3)
    if(EXISTS "${candidate}")
      execute_process(COMMAND "${candidate}" -c "import numpy"
                      RESULT_VARIABLE numpy_status OUTPUT_QUIET ERROR_QUIET)
      if(numpy_status EQUAL 0)
        set(Python_EXECUTABLE "${candidate}" CACHE FILEPATH "Python interpreter of the meshsal module")
        break()
      endif()
    endif()
  endforeach()
endif()
if(Python_EXECUTABLE)
  set(PYBIND11_FINDPYTHON ON)
  find_package(Python COMPONENTS Interpreter Development.Module QUIET)
  if(Python_FOUND)
    find_package(pybind11 CONFIG QUIET)
    if(pybind11_FOUND)
      set(MESHSAL_PYTHON_FOUND ON)
    endif()
  endif()
endif()
if(MESHSAL_PYTHON_FOUND)
  message(STATUS "meshsal: Python module for ${Python_EXECUTABLE} (pybind11 ${pybind11_VERSION})")
else()
  message(STATUS "meshsal: no Python module (needs pybind11-dev and an interpreter with numpy)")
endif()
