# fragmpm_require(<Package> <debian-package> [find_package args...])
# Finds a dependency and, when it is missing, stops configure with the Debian package to install.
macro(fragmpm_require name debian_package)
  find_package(${name} ${ARGN} QUIET)
  if(NOT ${name}_FOUND)
    message(FATAL_ERROR "FragMPM needs ${name}: install the Debian package ${debian_package} "
                        "(sudo apt-get install ${debian_package})")
  endif()
endmacro()
