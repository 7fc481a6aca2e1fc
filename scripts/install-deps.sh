#!/usr/bin/env bash
# Installs the Debian packages listed in scripts/packages.txt that are not installed yet, and
# those of scripts/packages-<group>.txt for each group named (`install-deps.sh demo`).
# Idempotent: does nothing (and needs no network) when everything is present. Uses sudo when
# not run as root. The package lists are refreshed first, since a fresh machine's are stale.
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)

lists=("$here/packages.txt")
for group in "$@"; do
  [[ -f $here/packages-$group.txt ]] || { echo "install-deps: no package list $here/packages-$group.txt" >&2; exit 2; }
  lists+=("$here/packages-$group.txt")
done
mapfile -t wanted < <(cat "${lists[@]}" | grep -v '^\s*#' | awk 'NF {print $1}')
missing=()
for pkg in "${wanted[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done

if ((${#missing[@]} == 0)); then
  echo "install-deps: all ${#wanted[@]} packages present"
  exit 0
fi

sudo=()
if [[ $(id -u) -ne 0 ]]; then
  command -v sudo >/dev/null || { echo "install-deps: need root or sudo to install: ${missing[*]}" >&2; exit 1; }
  sudo=(sudo)
fi
echo "install-deps: installing ${missing[*]}"
"${sudo[@]}" apt-get update -qq
DEBIAN_FRONTEND=noninteractive "${sudo[@]}" apt-get install -y -qq --no-install-recommends "${missing[@]}"
