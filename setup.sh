#!/usr/bin/env bash
# One command from nothing to results: set up .venv, make the built-in example bag, run process_bag on it.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST ROS_DOMAIN_ID=${ROS_DOMAIN_ID:-42}
export ROS_HOME=${ROS_HOME:-$top/.ros} FASTRTPS_DEFAULT_PROFILES_FILE=$top/config/fastdds_profile.xml
"$top/scripts/setup_env.sh"
bin=$top/.venv/bin
example=$top/example
if [ ! -e "$example/anim2" ]; then
  mkdir -p "$example"
  "$bin/make_synthetic" "$example/anim2" --preset anim2
fi
"$bin/process_bag" "$example/anim2" --out "$top/results/anim2" --ros-args --params-file "$top/config/synthetic.yaml"
echo "results: $top/results/anim2"
