# ROS 1 bag support from Debian's packages (librosbag-storage-dev and the message headers), found
# by hand: they ship no CMake config. Debian's rosbag/bag.h includes ROS 2's pluginlib, so the one
# source that reads bags also needs pluginlib's include folders; they are set on that file alone and
# the libraries are private to scanloc. Without the packages, a stub says how to get the support.
option(SCANLOC_WITH_ROSBAG "Read ROS 1 bags (needs librosbag-storage-dev and the msgs headers)" ON)

set(SCANLOC_ROSBAG_FOUND OFF)
if(SCANLOC_WITH_ROSBAG)
  find_path(SCANLOC_ROSBAG_INCLUDE_DIR rosbag/bag.h)
  find_path(SCANLOC_SENSOR_MSGS_INCLUDE_DIR sensor_msgs/LaserScan.h)
  find_path(SCANLOC_NAV_MSGS_INCLUDE_DIR nav_msgs/Odometry.h)
  find_path(SCANLOC_TF2_MSGS_INCLUDE_DIR tf2_msgs/TFMessage.h)
  find_path(SCANLOC_PLUGINLIB_INCLUDE_DIR pluginlib/class_loader.hpp PATH_SUFFIXES pluginlib)
  set(scanloc_rosbag_libraries "")
  set(scanloc_rosbag_missing "")
  # bz2 and roslz4 also decompress chunks for the structure check (io/ros_bag_structure.cpp).
  foreach(library rosbag_storage roslz4 roscpp_serialization rostime cpp_common console_bridge
                  bz2)
    find_library(SCANLOC_LIB_${library} ${library})
    if(SCANLOC_LIB_${library})
      list(APPEND scanloc_rosbag_libraries ${SCANLOC_LIB_${library}})
    else()
      list(APPEND scanloc_rosbag_missing lib${library})
    endif()
  endforeach()
  foreach(header ROSBAG SENSOR_MSGS NAV_MSGS TF2_MSGS PLUGINLIB)
    if(NOT SCANLOC_${header}_INCLUDE_DIR)
      list(APPEND scanloc_rosbag_missing ${header})
    endif()
  endforeach()
  if(scanloc_rosbag_missing)
    message(STATUS "scanloc: no ROS bag support (missing: ${scanloc_rosbag_missing}); "
                   "scripts/install-deps.sh installs it")
  else()
    set(SCANLOC_ROSBAG_FOUND ON)
  endif()
endif()

# Picks the real reader or the stub among the sources, and wires the reader's private dependencies.
function(scanloc_add_rosbag target sources_var)
  set(reader ${CMAKE_CURRENT_SOURCE_DIR}/io/ros_bag_source.cpp)
  set(structure ${CMAKE_CURRENT_SOURCE_DIR}/io/ros_bag_structure.cpp)
  set(stub ${CMAKE_CURRENT_SOURCE_DIR}/io/ros_bag_unavailable.cpp)
  if(SCANLOC_ROSBAG_FOUND)
    list(REMOVE_ITEM ${sources_var} ${stub})
    set(include_dirs "")
    foreach(folder pluginlib class_loader rcpputils rcutils ament_index_cpp)
      list(APPEND include_dirs ${SCANLOC_ROSBAG_INCLUDE_DIR}/${folder})
    endforeach()
    set_source_files_properties(${reader} PROPERTIES INCLUDE_DIRECTORIES "${include_dirs}"
                                                     COMPILE_OPTIONS "-Wno-shadow;-Wno-pedantic")
  else()
    list(REMOVE_ITEM ${sources_var} ${reader} ${structure})
  endif()
  set(${sources_var} ${${sources_var}} PARENT_SCOPE)
endfunction()

function(scanloc_link_rosbag target)
  if(SCANLOC_ROSBAG_FOUND)
    target_link_libraries(${target} PRIVATE ${scanloc_rosbag_libraries})
  endif()
endfunction()
