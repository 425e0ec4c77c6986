"""trap_ros: ROS 2 nodes and the ``process_bag`` command around :mod:`trap_core`."""
