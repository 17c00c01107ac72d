# libsss.so.MAJOR (target sss) and libsss.a (target sss_static) from the objects of every module
# (sss_module in CMakeLists.txt records them in the global properties SSS_MODULES and
# SSS_EXTERNAL_LIBRARIES). Consumers see only include/sss: no public header includes a dependency's
# header, so every dependency is PRIVATE (for the static library CMake still passes them to the link).
include(GNUInstallDirs)
get_property(sss_modules GLOBAL PROPERTY SSS_MODULES)
get_property(sss_external_libraries GLOBAL PROPERTY SSS_EXTERNAL_LIBRARIES)
list(REMOVE_DUPLICATES sss_external_libraries)
set(sss_objects "")
foreach(module ${sss_modules})
  list(APPEND sss_objects $<TARGET_OBJECTS:${module}_objects>)
endforeach()

add_library(sss SHARED ${sss_objects})
add_library(sss_static STATIC ${sss_objects})
foreach(lib sss sss_static)
  target_include_directories(${lib} PUBLIC $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}/include>
                                           $<BUILD_INTERFACE:${sss_generated_include}>
                                           $<INSTALL_INTERFACE:${CMAKE_INSTALL_INCLUDEDIR}>)
  target_link_libraries(${lib} PRIVATE ${sss_external_libraries})
  # meshoptimizer is C++: link with the C++ driver so its runtime comes along.
  set_target_properties(${lib} PROPERTIES OUTPUT_NAME sss LINKER_LANGUAGE CXX)
endforeach()
# SOVERSION = MAJOR: docs/versioning.md says what a MAJOR bump means for the ABI.
set_target_properties(sss PROPERTIES VERSION ${PROJECT_VERSION} SOVERSION ${PROJECT_VERSION_MAJOR})
# Every symbol the library uses must come from a dependency it names (none left for the program to
# supply). Not in the fuzz build, whose objects call the fuzzer's runtime (and which has no use for
# the shared library).
if(NOT SSS_FUZZ)
  target_link_options(sss PRIVATE -Wl,--no-undefined)
endif()
target_link_options(sss PRIVATE -Wl,--version-script=${PROJECT_SOURCE_DIR}/cmake/libsss.map)
set_target_properties(sss PROPERTIES LINK_DEPENDS ${PROJECT_SOURCE_DIR}/cmake/libsss.map)
add_library(sss::sss ALIAS sss)
add_library(sss::sss_static ALIAS sss_static)
