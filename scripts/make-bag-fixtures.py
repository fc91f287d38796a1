#!/usr/bin/python3
"""Writes the small ROS 1 bags tests/ros_bag_source_test.cpp reads (committed in tests/data/).

tf_odometry.bag: three LaserScans on /scan (frame "laser", stamps 1, 2, 3 s) with a negative
angle_increment and one beam of each kind of no-echo; odometry only on /tf (odom → base_link) at
0.5, 1.5, 2.5, 3.5 s, so that each scan's odometry is interpolated halfway; the mounting as a chain
on /tf_static: base_link → base_laser (0.1, 0, 0), base_laser → laser (0.05, 0.02, π/2).

zero_increment.bag: one LaserScan on /scan whose angle_increment is 0 (no layout scanloc can use).

Run with /usr/bin/python3 (Debian's python3-rosbag and the message packages).
"""
import math
import os

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage


def transform(t, parent, child, x, y, yaw):
    m = TransformStamped()
    m.header.stamp, m.header.frame_id, m.child_frame_id = rospy.Time.from_sec(t), parent, child
    m.transform.translation.x, m.transform.translation.y = x, y
    m.transform.rotation.z, m.transform.rotation.w = math.sin(yaw / 2), math.cos(yaw / 2)
    return m


def tf_odometry(path):
    with rosbag.Bag(path, "w") as bag:
        start = rospy.Time.from_sec(0.1)
        bag.write("/tf_static", TFMessage([transform(0.1, "base_link", "base_laser", 0.1, 0, 0),
                                           transform(0.1, "base_laser", "laser", 0.05, 0.02,
                                                     math.pi / 2)]), start)
        odometry = {0.5: (0, 0, 0), 1.5: (1, 0, 0.2), 2.5: (2, 1, 0.4), 3.5: (3, 1, 0.4)}
        events = [(t, "odom") for t in odometry] + [(t, "scan") for t in (1.0, 2.0, 3.0)]
        for t, kind in sorted(events):
            stamp = rospy.Time.from_sec(t)
            if kind == "odom":
                # a frame with a leading slash, as older ROS 1 drivers wrote it
                bag.write("/tf", TFMessage([transform(t, "/odom", "base_link", *odometry[t])]),
                          stamp)
                continue
            s = LaserScan()
            s.header.stamp, s.header.frame_id = stamp, "laser"
            s.angle_min, s.angle_increment = 0.5, -0.25
            s.angle_max = 0.5 - 0.25 * 5
            s.range_min, s.range_max = 0.1, 20.0
            s.ranges = [1.25, math.inf, math.nan, 30.0, 0.05, 3.45]
            s.intensities = [10, 20, 30, 40, 50, 60]
            bag.write("/scan", s, stamp)


def zero_increment(path):
    with rosbag.Bag(path, "w") as bag:
        s = LaserScan()
        s.header.stamp, s.header.frame_id = rospy.Time.from_sec(1.0), "laser"
        s.angle_min, s.angle_increment, s.range_max = -1.0, 0.0, 10.0
        s.ranges = [1.0, 2.0, 3.0]
        bag.write("/scan", s, s.header.stamp)


if __name__ == "__main__":
    here = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "tests", "data")
    tf_odometry(os.path.join(here, "tf_odometry.bag"))
    zero_increment(os.path.join(here, "zero_increment.bag"))
