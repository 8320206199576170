"""ROS 2 nav_msgs/msg/OccupancyGrid <-> fleetmerge.Map, for rclpy nodes and bag scripts.

    from nav_msgs.msg import OccupancyGrid
    from ros2_occupancy_grid import map_from_msg, msg_from_map
    maps = [map_from_msg(msg, name) for name, msg in latest_maps.items()]
    result = fleetmerge.merge(maps)
    publisher.publish(msg_from_map(result.merged[0], OccupancyGrid(), frame_id="map"))

Only the message's fields are used (duck typing), so this module needs no rclpy to import.
"""

import math

import numpy as np

import fleetmerge


def yaw_from_quaternion(q):
    """Yaw of a planar rotation quaternion (x, y ~ 0)."""
    return math.atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z))


def map_from_msg(msg, name=""):
    """A fleetmerge.Map from an OccupancyGrid message: data is row-major, row 0 at the origin,
    exactly fleetmerge's convention, so the cells are only reshaped."""
    info = msg.info
    data = np.asarray(msg.data, dtype=np.int8).reshape(info.height, info.width)
    origin = (info.origin.position.x, info.origin.position.y,
              yaw_from_quaternion(info.origin.orientation))
    return fleetmerge.Map(data, info.resolution, origin, name=name)


def msg_from_map(map, msg, frame_id="map", stamp=None):
    """Fills `msg` (a new nav_msgs.msg.OccupancyGrid) from a fleetmerge.Map and returns it."""
    x, y, yaw = map.origin
    msg.header.frame_id = frame_id
    if stamp is not None:
        msg.header.stamp = stamp
    msg.info.resolution = float(map.resolution)
    msg.info.width = map.width
    msg.info.height = map.height
    msg.info.origin.position.x = float(x)
    msg.info.origin.position.y = float(y)
    msg.info.origin.position.z = 0.0
    msg.info.origin.orientation.x = 0.0
    msg.info.origin.orientation.y = 0.0
    msg.info.origin.orientation.z = math.sin(yaw / 2.0)
    msg.info.origin.orientation.w = math.cos(yaw / 2.0)
    msg.data = map.data.ravel().tolist()
    return msg
