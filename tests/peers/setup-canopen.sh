#!/usr/bin/env bash
# Creates (or reuses) the workspace-root .venv holding the pinned CANopen/Modbus peers.
# Idempotent: re-running only installs what is missing or at the wrong version.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="$root/.venv"
pins=(pymodbus==3.16.1 pyserial==3.5 canopen==2.4.1 python-can==4.6.1)

if [ ! -x "$venv/bin/python" ]; then
    python3 -m venv "$venv"
fi
# pip skips pins that are already satisfied, so a second run is a quick no-op.
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${pins[@]}"
"$venv/bin/python" -c 'import can, canopen; print("python-can", can.__version__, "canopen", canopen.__version__)'
