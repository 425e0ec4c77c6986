#!/usr/bin/env bash
# Run the whole test suite (sets up .venv first if needed). Extra arguments go to pytest.
set -euo pipefail
top=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
"$top/scripts/setup_env.sh"
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST ROS_DOMAIN_ID=${ROS_DOMAIN_ID:-$((RANDOM % 80 + 10))}
export ROS_HOME=$(mktemp -d) FASTRTPS_DEFAULT_PROFILES_FILE=$top/config/fastdds_profile.xml
cd "$top"
exec "$top/.venv/bin/python" -m pytest -q "$top/test" "$@"
