# The libraries sss uses, found through their CMake config or pkg-config files (never by a library
# file name, which carries versions: libOpenEXRCore-3_1). Included by the project, where every one is
# REQUIRED, and by the installed sssConfig.cmake for sss::sss_static, which sets
# sss_dependencies_quiet first: a missing one is then listed in sss_dependencies_missing.
if(sss_dependencies_quiet)
  set(sss_find_mode QUIET)
else()
  set(sss_find_mode REQUIRED)
endif()
set(sss_dependencies_missing "")

# Libraries with a CMake config file: package name and the imported target sss links.
find_package(OpenMP ${sss_find_mode} COMPONENTS C)
find_package(meshoptimizer ${sss_find_mode} CONFIG)
find_package(embree 3 ${sss_find_mode} CONFIG)
find_package(OpenEXR ${sss_find_mode} CONFIG)
find_package(draco ${sss_find_mode} CONFIG)  # KHR_draco_mesh_compression (src/scene/gltf_draco*.c*)
foreach(target OpenMP::OpenMP_C meshoptimizer::meshoptimizer embree OpenEXR::OpenEXRCore draco::draco)
  if(NOT TARGET ${target})
    list(APPEND sss_dependencies_missing ${target})
  endif()
endforeach()

# Libraries with a pkg-config file: PREFIX=module gives the imported target PkgConfig::PREFIX.
# sss.pc lists the same modules in Requires.private.
set(sss_pkg_config_modules CJSON=libcjson STB=stb JPEG=libjpeg LAPACKE=lapacke CAIRO=cairo EPOXY=epoxy EGL=egl
                           GLFW=glfw3 IMGUI=imgui)
find_package(PkgConfig ${sss_find_mode})
foreach(entry ${sss_pkg_config_modules})
  string(REPLACE "=" ";" entry "${entry}")
  list(GET entry 0 prefix)
  list(GET entry 1 module)
  if(PKG_CONFIG_FOUND)
    pkg_check_modules(${prefix} ${sss_find_mode} IMPORTED_TARGET ${module})
  endif()
  if(NOT TARGET PkgConfig::${prefix})
    list(APPEND sss_dependencies_missing ${module})
  endif()
endforeach()
