"""trap_core: TRAP (Unsupervised Tracking From Clustered Graph Patterns) without ROS.

Subpackages, each with its own ``__all__`` and error class:

- :mod:`trap_core.bagio` -- stream RGB frames out of ROS 1 / ROS 2 bags.
- :mod:`trap_core.synthetic` -- benchmark videos with ground truth (Anim1/Anim2 analogues).
"""

__version__ = "0.1.0"
