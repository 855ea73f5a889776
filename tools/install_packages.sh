#!/usr/bin/env bash
# Installs the Debian packages given as arguments that are not installed yet (as root, or
# with sudo). Used by tools/setup.sh and tools/sanitizers.sh.
#   tools/install_packages.sh TAG PACKAGE...   # TAG prefixes the messages ("setup: ...")
set -euo pipefail
tag=$1
shift
missing=()
for p in "$@"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]} == 0)); then
  echo "$tag: all Debian packages present"
  exit 0
fi
echo "$tag: installing ${missing[*]}"
sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "$tag: run as root to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get update -q
"${sudo[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -q "${missing[@]}"
