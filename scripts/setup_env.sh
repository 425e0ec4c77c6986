#!/usr/bin/env bash
# Set up (or refresh) the project venv: pinned wheels, vision_msgs, trap_ros itself.
# Idempotent: a second run only checks, so it takes a few seconds.
set -euo pipefail
unset _ROS_WHEELS_BOOTSTRAP_COMPLETE   # a leaked guard breaks `import rclpy` in another venv
top=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
venv=${TRAP_VENV:-$top/.venv}
py=$venv/bin/python
say() { printf '[setup] %s\n' "$*"; }
# Run a noisy install step; show its output only if it fails.
quiet() { local log; log=$(mktemp); if ! "$@" >"$log" 2>&1; then cat "$log"; rm -f "$log"; return 1; fi; rm -f "$log"; }

if [ ! -x "$py" ]; then
  # Inside a sourced ROS 2 Jazzy installation, reuse its rclpy and messages.
  if [ "${ROS_DISTRO:-}" = jazzy ] && python3 -c 'import rclpy' 2>/dev/null; then
    say "creating $venv on top of ROS 2 $ROS_DISTRO"
    python3 -m venv --system-site-packages "$venv"
  else
    say "creating $venv"
    python3 -m venv "$venv"
  fi
  "$py" -m pip install -q --upgrade pip
fi

stamp=$venv/.trap-requirements
want=$(cat "$top/requirements.txt" | sha256sum | cut -c1-64)
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  say "installing pinned requirements (about a minute the first time)"
  if [ "${ROS_DISTRO:-}" = jazzy ] && "$py" -c 'import rclpy' 2>/dev/null; then
    grep -v '^ros-jazzy-' "$top/requirements.txt" | "$py" -m pip install -q -r /dev/stdin
  else
    quiet "$py" -m pip install -r "$top/requirements.txt"
  fi
  echo "$want" > "$stamp"
fi

# py-motmetrics only for its TUD-Campus reference data (its numpy-2 code is not imported).
if ! "$py" -c 'import importlib.util as u; assert u.find_spec("motmetrics")' 2>/dev/null; then
  quiet "$py" -m pip install --no-deps motmetrics==1.4.0
fi

if ! "$py" -c 'import vision_msgs.msg' 2>/dev/null; then
  say "building vision_msgs into $venv"
  quiet "$py" -m pip install -r "$top/requirements-msgbuild.txt"
  "$py" "$top/scripts/build_interfaces.py" --venv "$venv" --package "$top/interfaces/vision_msgs"
fi

if ! "$py" -c 'import trap_core, trap_ros' 2>/dev/null || [ ! -x "$venv/bin/process_bag" ]; then
  say "installing trap_ros (editable)"
  quiet "$py" -m pip install --no-deps --no-build-isolation -e "$top"
fi
say "ready: $venv"
