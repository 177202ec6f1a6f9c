#!/usr/bin/env bash
# Installs the independent test peers: socat (pty pairs), chromium and tmux (the plots and the
# terminal scope), mosquitto (an MQTT broker and its clients) and a Python venv at the workspace
# root with pinned pymodbus / pyserial / canopen / python-can / pyModbusTCP / cantools / asyncua
# (the OPC UA client of drivegen-cli/tests/gateway_opcua.rs; it brings cryptography).
# Idempotent; a no-op when already done.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
venv="$root/.venv"
pins=(pymodbus==3.16.1 pyserial==3.5 canopen==2.4.1 python-can==4.6.1 pyModbusTCP==0.3.1 cantools==45.1.0 asyncua==2.1.0)
stamp="$venv/.drivegen-peers"

# socat: pty pairs; chromium: opens the HTML plots headless (drivegen-cli/tests/plot.rs); tmux:
# runs the terminal scope `watch --tui` (drivegen-cli/tests/tui.rs); mosquitto and its clients:
# the gateway's broker (drivegen-cli/tests/gateway.rs; Debian puts the broker in /usr/sbin).
missing=()
for tool in socat chromium tmux mosquitto_sub; do
    command -v "$tool" >/dev/null 2>&1 || missing+=("$tool")
done
missing=("${missing[@]/mosquitto_sub/mosquitto-clients}")
command -v mosquitto >/dev/null 2>&1 || [ -x /usr/sbin/mosquitto ] || missing+=(mosquitto)
if [ "${#missing[@]}" -gt 0 ]; then
    sudo_cmd=()
    if [ "$(id -u)" -ne 0 ]; then sudo_cmd=(sudo); fi
    "${sudo_cmd[@]}" apt-get update -qq
    DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# The stamp records the exact pins, so changing a pin reinstalls and an unchanged venv is skipped.
if [ -x "$venv/bin/python" ] && [ -f "$stamp" ] && [ "$(cat "$stamp")" = "${pins[*]}" ]; then
    exit 0
fi

python="${DRIVEGEN_BOOTSTRAP_PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    "$python" -m venv "$venv"
fi
"$venv/bin/python" -m pip install --quiet --disable-pip-version-check "${pins[@]}"
printf '%s' "${pins[*]}" >"$stamp"
echo "peers ready: $(socat -V | sed -n 2p | tr -s ' '); $("$venv/bin/python" -c 'import pymodbus; print("pymodbus", pymodbus.__version__)')"
