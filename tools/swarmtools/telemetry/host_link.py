"""The host's end of the link to e-pucks: frames that carry the overhead
tracker's pose and messages (a planner's route) to robots.

The frames are the robots' own (frames.py, firmware/telemetry/telemetry_frame.h)
on the channels of frames.HOST_CHANNEL_IDS; the payloads are those of
firmware/telemetry/telemetry_host.h:

    POSE      x_mm int32, y_mm int32, heading_mrad int16, big-endian: 10 bytes
    HOST_MSG  1..HOST_MSG_MAX opaque bytes, the controller's (hal_host_receive)

The robot id addresses one robot, or every robot (frames.BROADCAST_ID).
Rates, costs and the robot's side: docs/host_link.md.

    link = HostLink()
    os.write(fd, link.pose(7, x_mm=1234, y_mm=-5678, heading_mrad=-1571))
"""
import struct

from swarmtools.telemetry.frames import BROADCAST_ID, HOST_CHANNEL_IDS, encode_frame

CH_POSE = next(k for k, v in HOST_CHANNEL_IDS.items() if v == "POSE")
CH_HOST_MSG = next(k for k, v in HOST_CHANNEL_IDS.items() if v == "HOST_MSG")
POSE_PAYLOAD = 10
#: Longest message a robot takes (hal.h: HAL_HOST_MSG_MAX).
HOST_MSG_MAX = 64
_POSE = struct.Struct(">iih")

__all__ = ["BROADCAST_ID", "CH_HOST_MSG", "CH_POSE", "HOST_MSG_MAX", "HostLink", "decode_pose",
           "encode_host_msg", "encode_pose", "pose_payload"]


def pose_payload(x_mm, y_mm, heading_mrad):
    """The 10-byte POSE payload; raises ValueError for values out of their fields' range
    (the heading is a whole number of mrad in int16; the robot wraps it to (-3142, 3142])."""
    try:
        return _POSE.pack(int(x_mm), int(y_mm), int(heading_mrad))
    except struct.error as e:
        raise ValueError(f"pose ({x_mm}, {y_mm}, {heading_mrad}) does not fit int32, int32, int16") from e


def decode_pose(payload):
    """(x_mm, y_mm, heading_mrad) of a POSE payload."""
    if len(payload) != POSE_PAYLOAD:
        raise ValueError(f"a POSE payload is {POSE_PAYLOAD} bytes, not {len(payload)}")
    return _POSE.unpack(bytes(payload))


def encode_pose(robot_id, seq, x_mm, y_mm, heading_mrad):
    """A whole POSE frame on the wire (21 bytes)."""
    return encode_frame(CH_POSE, robot_id, seq & 0xFFFF, pose_payload(x_mm, y_mm, heading_mrad))


def encode_host_msg(robot_id, seq, data):
    """A whole HOST_MSG frame on the wire (12 + len(data) bytes)."""
    data = bytes(data)
    if not 1 <= len(data) <= HOST_MSG_MAX:
        raise ValueError(f"a message to a robot is 1..{HOST_MSG_MAX} bytes, not {len(data)}")
    return encode_frame(CH_HOST_MSG, robot_id, seq & 0xFFFF, data)


class HostLink:
    """Numbers the frames sent on one link (one sequence per link, as a
    robot numbers its telemetry): returns the bytes to write."""

    def __init__(self):
        self.seq = 0

    def _next(self):
        s = self.seq
        self.seq = (self.seq + 1) & 0xFFFF
        return s

    def pose(self, robot_id, x_mm, y_mm, heading_mrad):
        return encode_pose(robot_id, self._next(), x_mm, y_mm, heading_mrad)

    def message(self, robot_id, data):
        return encode_host_msg(robot_id, self._next(), data)
