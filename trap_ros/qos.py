"""QoS of trap_ros topics.

Offline processing must not drop frames: every pipeline topic is reliable and keeps all
samples, and the bag reader's credit window (flow control) bounds what is in flight.
Results (tracks, end of bag) are transient-local so a late subscriber still gets them.
"""
from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile, ReliabilityPolicy

PIPELINE = QoSProfile(history=HistoryPolicy.KEEP_ALL, reliability=ReliabilityPolicy.RELIABLE,
                      durability=DurabilityPolicy.VOLATILE)
LATCHED = QoSProfile(history=HistoryPolicy.KEEP_LAST, depth=1000, reliability=ReliabilityPolicy.RELIABLE,
                     durability=DurabilityPolicy.TRANSIENT_LOCAL)
