"""ament_python package trap_ros: the pure-Python/numba core (trap_core) and the ROS 2 nodes (trap_ros)."""
from glob import glob

from setuptools import find_packages, setup

PACKAGE = "trap_ros"

setup(
    name=PACKAGE,
    version="0.1.0",
    packages=find_packages(include=["trap_core", "trap_core.*", "trap_ros", "trap_ros.*"]),
    data_files=[
        ("share/ament_index/resource_index/packages", [f"resource/{PACKAGE}"]),
        (f"share/{PACKAGE}", ["package.xml"]),
        (f"share/{PACKAGE}/config", glob("config/*")),
    ],
    install_requires=["setuptools"],
    zip_safe=False,
    maintainer="trap_ros developers",
    maintainer_email="trap_ros@example.invalid",
    description="Unsupervised tracking from clustered graph patterns (TRAP) for ROS 2 bags",
    license="Apache-2.0",
    tests_require=["pytest"],
    entry_points={
        "console_scripts": [
            "process_bag = trap_ros.process_bag:main",
            "bag_reader_node = trap_ros.bag_reader_node:main",
            "segmentation_node = trap_ros.segmentation_node:main",
            "mining_node = trap_ros.mining_node:main",
            "make_synthetic = trap_core.synthetic.cli:main",
            "evaluate = trap_core.evaluation.report:main",
        ],
    },
)
