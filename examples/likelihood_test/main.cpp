// The Likelihood Test of one scan against a line map from one posture, through the installed
// scanloc package. Usage: likelihood_test_example MAP.lines SCAN.scan X Y THETA [LASER_OFFSET]
#include <cstdlib>
#include <iostream>

#include <scanloc/io/scan_file.hpp>
#include <scanloc/likelihood/likelihood_test.hpp>
#include <scanloc/maps/line_map.hpp>
#include <scanloc/simulation/simulated_scan.hpp>

int main(int argc, char** argv) {
  if (argc < 6) {
    std::cerr << "usage: " << argv[0] << " MAP.lines SCAN.scan X Y THETA [LASER_OFFSET]\n";
    return 2;
  }
  const scanloc::LineMap map = scanloc::ReadLineMap(argv[1]);
  const scanloc::LaserScan scan = scanloc::ReadScanFile(argv[2]);
  const scanloc::Pose2D T_world_robot(std::atof(argv[3]), std::atof(argv[4]), std::atof(argv[5]));
  scanloc::LaserMounting mounting;
  mounting.T_robot_laser.x_m = argc > 6 ? std::atof(argv[6]) : 0.0;
  const scanloc::SimulatedScan simulated =
      scanloc::SimulateFromLines(map, scan.layout, mounting.LaserPose(T_world_robot));
  const scanloc::LikelihoodTestResult test = scanloc::RunLikelihoodTest(scan, simulated);
  std::cout << "MP " << test.match_pairs << " NVP " << test.valid_pairs << " MP/NVP "
            << test.MatchRatio() << " EV " << test.expect_value_m << " m\n";
  return test.valid_pairs > 0 ? 0 : 1;
}
