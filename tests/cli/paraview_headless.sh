#!/usr/bin/env bash
# How tools/rdparaview.py renders without a display, checked without ParaView (tests/cli/
# paraview.sh renders for real where pvpython is installed): a stand-in vtkmodules package
# offers the render windows a ParaView build would have. EGL is chosen before OSMesa and set in
# VTK_DEFAULT_OPENGL_WINDOW (offscreen, no X server); a user's choice of window is kept; an X
# display is used when there is one; with neither a headless window nor xvfb-run, one error line
# and exit 2.
set -eu
T=${RD_TMP:-$(mktemp -d)}/pv_headless; mkdir -p "$T"
PY=/usr/bin/python3
fake() { # fake DIR CLASS... : a vtkmodules package whose vtkRenderingOpenGL2 has these classes
    mkdir -p "$1/vtkmodules"; : > "$1/vtkmodules/__init__.py"
    : > "$1/vtkmodules/vtkRenderingOpenGL2.py"
    local d=$1; shift
    for c in "$@"; do echo "class $c: pass" >> "$d/vtkmodules/vtkRenderingOpenGL2.py"; done
}
fake "$T/both" vtkXOpenGLRenderWindow vtkEGLRenderWindow vtkOSOpenGLRenderWindow
fake "$T/osmesa" vtkOSOpenGLRenderWindow
fake "$T/glx" vtkXOpenGLRenderWindow
mode() { # mode FAKEDIR [VAR=value...]: what rendering() picks, and VTK_DEFAULT_OPENGL_WINDOW
    local d=$1; shift
    env -u DISPLAY -u VTK_DEFAULT_OPENGL_WINDOW "$@" PYTHONPATH="$d:tools" PATH=/nonexistent $PY -c '
import os, rdparaview
print(rdparaview.rendering([]), "|", os.environ.get("VTK_DEFAULT_OPENGL_WINDOW"))'
}
fails=0
expect() { # expect WANTED GOT
    if [ "$1" = "$2" ]; then echo "CHECK rdparaview rendering: $1"
    else echo "FAIL rdparaview rendering: wanted '$1', got '$2'"; fails=$((fails + 1)); fi
}
expect "offscreen, vtkEGLRenderWindow | vtkEGLRenderWindow" "$(mode "$T/both")"
expect "offscreen, vtkOSOpenGLRenderWindow | vtkOSOpenGLRenderWindow" "$(mode "$T/osmesa")"
expect "offscreen, vtkOSOpenGLRenderWindow | vtkOSOpenGLRenderWindow" \
    "$(mode "$T/both" VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow)"
expect "X display | None" "$(mode "$T/glx" DISPLAY=:0)"
expect "None | None" "$(mode "$T/glx")"
# a GLX-only ParaView, no display, no xvfb-run: one line naming what to install, exit 2
: > "$T/run.h5"
set +e
out=$(env -u DISPLAY PYTHONPATH="$T/glx:tools" PATH=/nonexistent $PY tools/rdparaview.py \
    "$T/run.h5" 2>&1 >/dev/null); rc=$?
set -e
if [ "$rc" -eq 2 ] && [ "$(printf '%s\n' "$out" | wc -l)" -eq 1 ] && printf '%s' "$out" | grep -q "install xvfb"; then
    echo "CHECK rdparaview: no way to render: one line, exit 2"
else
    echo "FAIL rdparaview: no way to render: rc=$rc, stderr: $out"; fails=$((fails + 1))
fi
[ "$fails" -eq 0 ]
