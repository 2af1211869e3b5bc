# venv_common.sh - what setup_bpy.sh and setup_python.sh share (sourced, not run):
#   apt_missing TAG PACKAGE...   installs the Debian packages not yet installed (root or sudo)
#   python311 TAG WHY            prints a Python 3.11 interpreter's name, or fails naming WHY

apt_missing() {
  local tag=$1 p sudo=""
  shift
  command -v dpkg-query >/dev/null || return 0
  local missing=()
  for p in "$@"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
  done
  ((${#missing[@]})) || return 0
  echo "$tag: installing ${missing[*]}"
  if [ "$(id -u)" -ne 0 ]; then
    command -v sudo >/dev/null || { echo "$tag: need root or sudo to install ${missing[*]}" >&2; exit 1; }
    sudo=sudo
  fi
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
}

python311() {
  local c
  for c in python3.11 python3; do
    if command -v "$c" >/dev/null && "$c" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
      echo "$c"
      return 0
    fi
  done
  echo "$1: $2 needs Python 3.11 (python3.11 not found)" >&2
  exit 1
}
