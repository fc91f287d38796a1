#!/usr/bin/python3
"""Writes a ROS 1 bag from a CARMEN log (.clf, plain or gzip) or a scanloc sequence (.seq.jsonl).

The bag holds what a robot running ROS would have recorded: sensor_msgs/LaserScan on /scan (frame
"laser"), the odometry of each scan at the scan's stamp as nav_msgs/Odometry on /odom (odom →
base_link), or with --odometry tf as /tf transforms, and the laser's mounting on /tf_static
(base_link → laser). CARMEN FLASER scans span 180° from -90° (step π/n for even n, π/(n-1) for odd
n, as scanloc's CARMEN reader); their odometry is the message's own odom fields. Ranges that carry
no echo (-1 or null in a sequence) are written as +inf.

Needs Debian's python3-rosbag, python3-sensor-msgs, python3-nav-msgs, python3-tf2-msgs (run it
with /usr/bin/python3). Example:
    /usr/bin/python3 scripts/make-bag.py datasets/classroom/classroom.seq.jsonl classroom.bag
"""
import argparse
import gzip
import json
import math
import sys

import rosbag
import rospy
from geometry_msgs.msg import TransformStamped
from nav_msgs.msg import Odometry
from sensor_msgs.msg import LaserScan
from tf2_msgs.msg import TFMessage

ODOM_FRAME, BASE_FRAME, LASER_FRAME = "odom", "base_link", "laser"
# rosbag refuses to index a record at time 0: records stamped 0 are written 1 ns later (the
# messages' header stamps stay as they are).
EARLIEST_RECORD_TIME = rospy.Time(0, 1)


def quaternion(yaw):
    return (0.0, 0.0, math.sin(yaw / 2.0), math.cos(yaw / 2.0))


def set_pose(target, x, y, yaw):
    """Fills a geometry_msgs Pose or Transform with a planar pose."""
    position = target.position if hasattr(target, "position") else target.translation
    orientation = target.orientation if hasattr(target, "orientation") else target.rotation
    position.x, position.y, position.z = x, y, 0.0
    orientation.x, orientation.y, orientation.z, orientation.w = quaternion(yaw)


def transform(stamp, parent, child, pose):
    t = TransformStamped()
    t.header.stamp, t.header.frame_id, t.child_frame_id = stamp, parent, child
    set_pose(t.transform, *pose)
    return t


class BagWriter:
    def __init__(self, path, odometry, compression):
        self.bag = rosbag.Bag(path, "w", compression=compression)
        self.odometry = odometry
        self.mounting_written = False
        self.seq = 0

    def write(self, topic, message, stamp):
        self.bag.write(topic, message, max(stamp, EARLIEST_RECORD_TIME))

    def mounting(self, stamp, pose):
        if not self.mounting_written:
            self.write("/tf_static", TFMessage([transform(stamp, BASE_FRAME, LASER_FRAME, pose)]),
                       stamp)
            self.mounting_written = True

    def scan(self, t, angle_min, increment, range_min, range_max, ranges, odom):
        stamp = rospy.Time.from_sec(t)
        self.mounting(stamp, (0.0, 0.0, 0.0))
        if odom is not None:
            self.write_odometry(stamp, odom)
        s = LaserScan()
        s.header.seq, s.header.stamp, s.header.frame_id = self.seq, stamp, LASER_FRAME
        s.angle_min, s.angle_increment = angle_min, increment
        s.angle_max = angle_min + increment * (len(ranges) - 1)
        s.range_min, s.range_max = range_min, range_max
        s.ranges = [math.inf if r is None or r < 0 else r for r in ranges]
        self.write("/scan", s, stamp)
        self.seq += 1

    def write_odometry(self, stamp, pose):
        if self.odometry == "tf":
            self.write("/tf", TFMessage([transform(stamp, ODOM_FRAME, BASE_FRAME, pose)]), stamp)
            return
        o = Odometry()
        o.header.stamp, o.header.frame_id, o.child_frame_id = stamp, ODOM_FRAME, BASE_FRAME
        set_pose(o.pose.pose, *pose)
        self.write("/odom", o, stamp)

    def close(self):
        self.bag.close()


def open_text(path):
    with open(path, "rb") as f:
        magic = f.read(2)
    return gzip.open(path, "rt") if magic == b"\x1f\x8b" else open(path, "rt")


def carmen(path, writer, max_scans, max_range):
    count = 0
    with open_text(path) as lines:
        for line in lines:
            f = line.split()
            if not f or f[0].startswith("#"):
                continue
            if f[0] == "PARAM" and len(f) >= 3 and f[1] == "robot_frontlaser_offset":
                writer.pending_offset = float(f[2])
            elif f[0] == "FLASER":
                n = int(f[1])
                ranges = [float(r) for r in f[2:2 + n]]
                odom = tuple(float(v) for v in f[2 + n + 3:2 + n + 6])
                t = float(f[2 + n + 6])
                writer.mounting(rospy.Time.from_sec(t), (getattr(writer, "pending_offset", 0.0), 0, 0))
                step = math.pi / n if n % 2 == 0 else math.pi / (n - 1)
                writer.scan(t, -math.pi / 2, step, 0.0, max_range, ranges, odom)
                count += 1
                if max_scans and count >= max_scans:
                    break
    return count


def sequence(path, writer, max_scans):
    count = 0
    with open(path) as lines:
        header = json.loads(lines.readline())
        mounting = header.get("mounting", [0.0, 0.0, 0.0])
        for line in lines:
            if not line.strip():
                continue
            record = json.loads(line)
            t = record.get("timestamp_s", 0.0)
            writer.mounting(rospy.Time.from_sec(t), tuple(mounting))
            s = record["scan"]
            odom = tuple(record["odometry"]) if "odometry" in record else None
            writer.scan(t, s["angle_min_rad"], s["angle_increment_rad"], s.get("range_min_m", 0.0),
                        s.get("range_max_m", 20.0), s["ranges"], odom)
            count += 1
            if max_scans and count >= max_scans:
                break
    return count


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("input", help="CARMEN log (.clf[.gz]) or scanloc sequence (.seq.jsonl)")
    parser.add_argument("output", help="bag to write")
    parser.add_argument("--max-scans", type=int, default=0, help="stop after N scans (0: all)")
    parser.add_argument("--max-range", type=float, default=50.0,
                        help="CARMEN FLASER's no-return range, as scanloc's reader (default 50)")
    parser.add_argument("--odometry", choices=["topic", "tf"], default="topic",
                        help="odometry as nav_msgs/Odometry on /odom (default) or on /tf")
    parser.add_argument("--compression", choices=["none", "lz4", "bz2"], default="none")
    args = parser.parse_args()
    writer = BagWriter(args.output, args.odometry, args.compression)
    with open_text(args.input) as probe:
        is_sequence = probe.read(64).lstrip().startswith("{")
    if is_sequence:
        count = sequence(args.input, writer, args.max_scans)
    else:
        count = carmen(args.input, writer, args.max_scans, args.max_range)
    writer.close()
    print(f"make-bag: {count} scans from {args.input} to {args.output}", file=sys.stderr)


if __name__ == "__main__":
    main()
