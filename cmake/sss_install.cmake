# cmake --install: the public headers (with the generated version.h), libsss.so.MAJOR and libsss.a,
# the sss tool, the CMake package (find_package(sss CONFIG): sss::sss shared, sss::sss_static), the
# pkg-config file sss.pc, and docs/ and examples/ (with LICENSE, when the repository has one) in
# share/doc/sss.
include(CMakePackageConfigHelpers)
set(sss_cmake_dir ${CMAKE_INSTALL_LIBDIR}/cmake/sss)
set(sss_pkgconfig_dir ${CMAKE_INSTALL_LIBDIR}/pkgconfig)

install(DIRECTORY include/sss ${sss_generated_include}/sss DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILES_MATCHING PATTERN "*.h")
install(TARGETS sss EXPORT sssTargets LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS sss_static EXPORT sssStaticTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(TARGETS sss_cli RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})

install(EXPORT sssTargets NAMESPACE sss:: DESTINATION ${sss_cmake_dir})
install(EXPORT sssStaticTargets NAMESPACE sss:: DESTINATION ${sss_cmake_dir})
configure_package_config_file(cmake/sssConfig.cmake.in ${CMAKE_CURRENT_BINARY_DIR}/sssConfig.cmake
                              INSTALL_DESTINATION ${sss_cmake_dir})
# While 0.x, a MINOR bump may break the ABI (docs/versioning.md): 0.1 does not satisfy a request for 0.2.
if(PROJECT_VERSION_MAJOR EQUAL 0)
  set(sss_compatibility SameMinorVersion)
else()
  set(sss_compatibility SameMajorVersion)
endif()
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/sssConfigVersion.cmake
                                 COMPATIBILITY ${sss_compatibility})
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sssConfig.cmake ${CMAKE_CURRENT_BINARY_DIR}/sssConfigVersion.cmake
              cmake/sss_dependencies.cmake
        DESTINATION ${sss_cmake_dir})

# sss.pc. Static linking needs the dependencies: those with a pkg-config file go to Requires.private,
# the others (CMake config only) to Libs.private as -l flags taken from their imported targets.
function(sss_pc_link_flags out)
  set(flags "")
  foreach(lib ${ARGN})
    if(lib MATCHES "^PkgConfig::")
      continue()  # in Requires.private
    elseif(lib MATCHES "^OpenMP::")
      list(APPEND flags ${OpenMP_C_FLAGS})
    elseif(NOT TARGET ${lib})
      list(APPEND flags -l${lib})  # a system library such as m
    else()
      get_target_property(configs ${lib} IMPORTED_CONFIGURATIONS)
      get_target_property(location ${lib} IMPORTED_LOCATION)
      foreach(config ${configs})
        if(NOT location)
          get_target_property(location ${lib} IMPORTED_LOCATION_${config})
        endif()
      endforeach()
      if(NOT location)
        message(FATAL_ERROR "sss.pc: no library file for ${lib}")
      endif()
      get_filename_component(dir ${location} DIRECTORY)
      get_filename_component(name ${location} NAME)
      string(REGEX REPLACE "^lib(.+)\\.(so|a)(\\.[0-9.]+)?$" "\\1" name ${name})
      if(NOT dir IN_LIST CMAKE_C_IMPLICIT_LINK_DIRECTORIES)
        list(APPEND flags -L${dir})
      endif()
      list(APPEND flags -l${name})
    endif()
  endforeach()
  list(JOIN flags " " flags)
  set(${out} "${flags}" PARENT_SCOPE)
endfunction()
sss_pc_link_flags(sss_pc_libs_private ${sss_external_libraries})
set(sss_pc_requires_private "")
foreach(entry ${sss_pkg_config_modules})
  string(REGEX REPLACE "^[^=]*=" "" module ${entry})
  list(APPEND sss_pc_requires_private ${module})
endforeach()
list(JOIN sss_pc_requires_private " " sss_pc_requires_private)
file(RELATIVE_PATH sss_pc_prefix_from_pcfiledir ${CMAKE_INSTALL_PREFIX}/${sss_pkgconfig_dir}
     ${CMAKE_INSTALL_PREFIX})
string(REGEX REPLACE "/$" "" sss_pc_prefix_from_pcfiledir ${sss_pc_prefix_from_pcfiledir})
configure_file(cmake/sss.pc.in ${CMAKE_CURRENT_BINARY_DIR}/sss.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/sss.pc DESTINATION ${sss_pkgconfig_dir})

install(DIRECTORY docs/ DESTINATION ${CMAKE_INSTALL_DOCDIR})
install(DIRECTORY examples DESTINATION ${CMAKE_INSTALL_DOCDIR})  # sources to copy, and their CMakeLists.txt
if(EXISTS ${PROJECT_SOURCE_DIR}/LICENSE)
  install(FILES LICENSE DESTINATION ${CMAKE_INSTALL_DOCDIR})
endif()
