// main() of the rostest gtest executables: gtest first (it takes its flags), then a ROS node named
// after the executable, kept alive by a NodeHandle for the whole run.
#include <gtest/gtest.h>
#include <ros/ros.h>

#include <string>

int main(int argc, char** argv) {
  testing::InitGoogleTest(&argc, argv);
  const std::string path = argv[0];
  ros::init(argc, argv, path.substr(path.find_last_of('/') + 1));
  ros::NodeHandle nh;
  return RUN_ALL_TESTS();
}
