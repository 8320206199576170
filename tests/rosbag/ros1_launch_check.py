"""Checks a result set's transforms.launch (pipeline/launch_files.hpp) with ROS 1's own loader:
Debian's python3-roslaunch (roslaunch.xmlloader.XmlLoader) loads it into a ROSLaunchConfig, as
`roslaunch transforms.launch` does, and each node's package, type and args are compared with
report.json (one tf2_ros static_transform_publisher per map of a merged component: x y z yaw
pitch roll parent child, the map's pose in its component's frame).

    /usr/bin/python3 ros1_launch_check.py RESULT_FOLDER

Prints "ros1_launch_check: OK ..." and exits 0, or prints what differs and exits 1.
"""
import json
import math
import os
import sys

import roslaunch.config
import roslaunch.xmlloader


def main(folder):
    with open(os.path.join(folder, "report.json")) as f:
        report = json.load(f)
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(os.path.join(folder, "transforms.launch"), config,
                                         verbose=False)
    problems = []
    expected = [m for m in report["maps"] if "merged_map" in report["components"][m["component"]]]
    if len(config.nodes) != len(expected):
        problems.append("%d nodes, %d maps in merged components" % (len(config.nodes),
                                                                     len(expected)))
    by_child = {}
    for node in config.nodes:
        if (node.package, node.type) != ("tf2_ros", "static_transform_publisher"):
            problems.append("node %s: %s/%s" % (node.name, node.package, node.type))
        args = node.args.split()
        if len(args) != 8:
            problems.append("node %s: args '%s', expected 8" % (node.name, node.args))
            continue
        by_child[args[7]] = (node.name, args)
    for m in expected:
        if m["frame"] not in by_child:
            problems.append("no transform to %s" % m["frame"])
            continue
        name, args = by_child[m["frame"]]
        x, y, z, yaw, pitch, roll = (float(a) for a in args[:6])
        pose = m["pose"]
        parent = report["components"][m["component"]]["frame"]
        yaw_error = abs(math.atan2(math.sin(yaw - pose["yaw"]), math.cos(yaw - pose["yaw"])))
        # The file has 12 significant digits ("%.12g").
        def off(a, b):
            return abs(a - b) > 1e-10 * max(1.0, abs(b))
        if off(x, pose["x"]) or off(y, pose["y"]) or yaw_error > 1e-10:
            problems.append("node %s: x y yaw %s, report %s" % (name, args[:6], pose))
        if (z, pitch, roll) != (0.0, 0.0, 0.0) or args[6] != parent:
            problems.append("node %s: z pitch roll parent %s, expected 0 0 0 %s" %
                            (name, [args[2], args[4], args[5], args[6]], parent))
    if problems:
        print("ros1_launch_check: %s:\n  %s" % (folder, "\n  ".join(problems)))
        return 1
    print("ros1_launch_check: OK %s: %d nodes" % (folder, len(config.nodes)))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
