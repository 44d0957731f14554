# Installation and the CMake package: `find_package(vcontact)` then link vcontact::geometry,
# vcontact::io, vcontact::volume, vcontact::dynamics, vcontact::validation, vcontact::formats
# or vcontact::report (STYLE.md §9); VCONTACT_LAYERS is set at the top level.
# Headers keep their layer folders, so an installed include reads as in the source tree:
# #include "volume/contact.hpp".
# GNUInstallDirs is included at the top level: geometry/ names the installed include folder.
include(CMakePackageConfigHelpers)

set(VCONTACT_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/vcontact)

foreach(layer IN LISTS VCONTACT_LAYERS)
  set_target_properties(vcontact_${layer} PROPERTIES EXPORT_NAME ${layer})
  install(DIRECTORY ${PROJECT_SOURCE_DIR}/${layer}
    DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/vcontact
    FILES_MATCHING PATTERN "*.hpp")
endforeach()
# The warning flags travel with the static libraries as a link-only dependency; exported
# under its own name so that a consumer's build does not inherit them as compile options.
set_target_properties(vcontact_warnings PROPERTIES EXPORT_NAME warnings)

list(TRANSFORM VCONTACT_LAYERS PREPEND vcontact_ OUTPUT_VARIABLE VCONTACT_LIBRARIES)
install(TARGETS ${VCONTACT_LIBRARIES} vcontact_warnings
  EXPORT vcontactTargets
  ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR})
install(EXPORT vcontactTargets
  NAMESPACE vcontact::
  DESTINATION ${VCONTACT_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/vcontactConfig.cmake.in
  ${PROJECT_BINARY_DIR}/vcontactConfig.cmake
  INSTALL_DESTINATION ${VCONTACT_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/vcontactConfigVersion.cmake
  COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/vcontactConfig.cmake
  ${PROJECT_BINARY_DIR}/vcontactConfigVersion.cmake
  DESTINATION ${VCONTACT_INSTALL_CMAKEDIR})
