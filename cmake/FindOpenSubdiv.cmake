# Debian's exported OpenSubdiv targets name static libraries the package does not ship,
# so find the headers and the two shared libraries by hand.
find_path(OpenSubdiv_INCLUDE_DIR opensubdiv/version.h)
find_library(OpenSubdiv_CPU_LIBRARY osdCPU)
find_library(OpenSubdiv_GPU_LIBRARY osdGPU)

include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(OpenSubdiv
  REQUIRED_VARS OpenSubdiv_INCLUDE_DIR OpenSubdiv_CPU_LIBRARY OpenSubdiv_GPU_LIBRARY)

if(OpenSubdiv_FOUND AND NOT TARGET OpenSubdiv::osdCPU)
  add_library(OpenSubdiv::osdCPU SHARED IMPORTED)
  set_target_properties(OpenSubdiv::osdCPU PROPERTIES
    IMPORTED_LOCATION "${OpenSubdiv_CPU_LIBRARY}"
    INTERFACE_INCLUDE_DIRECTORIES "${OpenSubdiv_INCLUDE_DIR}")
  # Only the GLSL source strings are used from osdGPU (GLSLPatchShaderSource); its GL
  # classes load libGL themselves and do not work under OSMesa.
  add_library(OpenSubdiv::osdGPU SHARED IMPORTED)
  set_target_properties(OpenSubdiv::osdGPU PROPERTIES
    IMPORTED_LOCATION "${OpenSubdiv_GPU_LIBRARY}"
    INTERFACE_LINK_LIBRARIES OpenSubdiv::osdCPU)
endif()
mark_as_advanced(OpenSubdiv_INCLUDE_DIR OpenSubdiv_CPU_LIBRARY OpenSubdiv_GPU_LIBRARY)
