#!/usr/bin/env bash
# Installs Intel Open Image Denoise, the peer `bmfr peer oidn` and the demo run beside the
# filters: PyPI's pyoidn (pinned), whose wheel carries OIDN's libraries, into .venv/ (Debian's
# Python refuses system-wide pip installs). bmfr loads the library at run time; configure again
# after this (scripts/build.sh does) so that bmfr finds it without BMFR_OIDN_LIBRARY.
# Needs python3-venv (scripts/install-deps.sh installs it, then calls this).
set -euo pipefail
cd "$(dirname "$0")/.."
pyoidn=2.5.1.0 # OIDN 2.5.1
numpy=2.2.6    # what pyoidn's Python side imports; the one the FLIP check pins too
venv=.venv
installed=$(ls -d "$venv"/lib/python3*/site-packages/pyoidn-"$pyoidn".dist-info 2>/dev/null || true)
if [ -n "$installed" ] && [ -x "$venv/bin/pip" ]; then
    exit 0
fi
echo "installing Intel Open Image Denoise (pyoidn $pyoidn from PyPI) into $venv/"
# Debian's python3 where there is one, as scripts/build.sh builds the module with it.
python=python3
[ -x /usr/bin/python3 ] && python=/usr/bin/python3
# A venv left half-made (python3-venv missing when it was made) is made again.
[ -x "$venv/bin/pip" ] || "$python" -m venv --clear "$venv"
"$venv/bin/python" -m pip install --disable-pip-version-check -q "pyoidn==$pyoidn" "numpy==$numpy"
ls "$venv"/lib/python3*/site-packages/pyoidn/oidn/lib/libOpenImageDenoise.so.2 > /dev/null
