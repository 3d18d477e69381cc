#!/usr/bin/env pvpython
"""rdparaview — open a rockdem run in ParaView ready to play: the free bodies coloured by tilt
ratio (tilt / alpha; 1 = the static tipping angle), the fixed bodies (pedestals) in grey, a
ground plane, the camera on the scene and the animation snapped to the written steps.

    pvpython tools/rdparaview.py RUN.h5 --state RUN.pvsm   then   paraview --state=RUN.pvsm
    paraview --script=tools/rdparaview.py                  (RDPARAVIEW_RUN=RUN.h5 in the env)
    pvpython tools/rdparaview.py RUN.h5 --screenshot last.png --time end

Given RUN.h5 it writes the XDMF sidecar first (tools/rdxdmf.py: RUN.xmf + RUN.vis.h5, every
k-th step with --every k) unless an up-to-date RUN.xmf is there; given RUN.xmf it opens that.
The .xmf is opened by its absolute path: ParaView 5.11's Xdmf3 readers join a bare file name
("run.xmf") and the HDF5 path inside it wrongly.

Headless (no $DISPLAY), in this order:
  1. offscreen: when this ParaView's VTK has an EGL or OSMesa render window (vtkEGLRenderWindow,
     vtkOSOpenGLRenderWindow: ParaView's own egl/osmesa builds, and every build on VTK 9.4 or
     later, which picks its window at run time), VTK_DEFAULT_OPENGL_WINDOW selects it (EGL
     first) and the view renders offscreen, no X server involved;
  2. Xvfb: Debian's ParaView (5.11, VTK 9.1) has neither, and --force-offscreen-rendering still
     opens an X window (without a display pvpython dies with SIGSEGV in XSync, exit 139), so the
     script runs itself again under xvfb-run (a virtual X display, Debian's xvfb);
  3. otherwise it says in one line what to install.
A VTK_DEFAULT_OPENGL_WINDOW set by the user is kept."""
import argparse
import os
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)


XVFB_SCREEN = "-screen 0 1280x1024x24 +extension GLX"  # room for the 1200 x 800 picture


# VTK's headless render windows, preferred first: EGL (GPU or Mesa's EGL), then OSMesa (CPU)
HEADLESS_WINDOWS = ("vtkEGLRenderWindow", "vtkOSOpenGLRenderWindow")


def headless_window():
    """The name of a render window of this VTK that needs no X display, or None."""
    if os.environ.get("VTK_DEFAULT_OPENGL_WINDOW") in HEADLESS_WINDOWS:
        return os.environ["VTK_DEFAULT_OPENGL_WINDOW"]
    try:
        from vtkmodules import vtkRenderingOpenGL2 as gl
    except ImportError:
        return None
    return next((w for w in HEADLESS_WINDOWS if hasattr(gl, w)), None)


def rendering(argv):
    """How this run renders: "X display", "Xvfb" or "offscreen, <window>" (VTK_DEFAULT_OPENGL_WINDOW
    then names it); without any, re-run this script under xvfb-run (never returns) or None."""
    if os.environ.get("DISPLAY"):
        return "Xvfb" if os.environ.get("RDPARAVIEW_XVFB") else "X display"
    window = headless_window()
    if window:
        os.environ["VTK_DEFAULT_OPENGL_WINDOW"] = window
        return "offscreen, " + window
    import shutil
    xvfb, pvpython = shutil.which("xvfb-run"), shutil.which("pvpython")
    if not xvfb or not pvpython or os.environ.get("RDPARAVIEW_XVFB"):
        return None
    env = dict(os.environ, RDPARAVIEW_XVFB="1")
    # pvpython's sys.executable names its embedded interpreter, not a program to run
    cmd = [xvfb, "-a", "-s", XVFB_SCREEN, pvpython, os.path.abspath(__file__)] + list(argv)
    os.execve(xvfb, cmd, env)


NO_RENDERING = ("rdparaview: error: no X display ($DISPLAY unset), no EGL or OSMesa render window "
                "in this ParaView and no xvfb-run: install xvfb (apt-get install xvfb), use an egl "
                "or osmesa build of ParaView, or set DISPLAY")


def sidecar(path, every, frame):
    """The .xmf to open for path (a run file or an .xmf), made or refreshed when needed."""
    if path.endswith(".xmf"):
        return os.path.abspath(path)
    from rdtools.xdmf import write_sidecar
    xmf = os.path.splitext(path)[0] + ".xmf"
    vis = os.path.splitext(path)[0] + ".vis.h5"
    fresh = all(os.path.exists(p) and os.path.getmtime(p) >= os.path.getmtime(path) for p in (xmf, vis))
    if not fresh or every != 1:
        write_sidecar(path, xmf, every, frame)
    return os.path.abspath(xmf)


def scene(xmf, ratio_max=1.5):
    """Build the pipeline and view; returns (view, reader)."""
    from paraview import simple as pv
    reader = pv.XDMFReader(registrationName=os.path.basename(xmf), FileNames=[xmf])
    reader.UpdatePipeline(reader.TimestepValues[0] if reader.TimestepValues else 0.0)
    view = pv.GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 1
    d = pv.Show(reader, view)
    pv.ColorBy(d, ("CELLS", "tilt_ratio"))
    lut = pv.GetColorTransferFunction("tilt_ratio")
    lut.ApplyPreset("Cool to Warm", True)
    lut.RescaleTransferFunction(0.0, ratio_max)
    lut.AutomaticRescaleRangeMode = "Never"
    bar = pv.GetScalarBar(lut, view)
    bar.Title = "tilt / alpha"
    bar.ComponentTitle = ""
    bar.TitleFontSize = 14
    bar.LabelFontSize = 12
    bar.RangeLabelFormat = "%-#.2g"
    bar.ScalarBarLength = 0.4
    d.SetScalarBarVisibility(view, True)
    lut.NanColor = [0.62, 0.6, 0.57]  # fixed bodies: no tilt (NaN), drawn grey
    # the ground: a plane under everything, three times the scene's horizontal extent
    b = reader.GetDataInformation().GetBounds()
    cx, cy, w = 0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 1.5 * max(b[1] - b[0], b[3] - b[2], 1e-3)
    plane = pv.Plane(registrationName="ground", Origin=[cx - w, cy - w, b[4]],
                     Point1=[cx + w, cy - w, b[4]], Point2=[cx - w, cy + w, b[4]])
    g = pv.Show(plane, view)
    g.DiffuseColor = [0.78, 0.74, 0.66]
    scene_ = pv.GetAnimationScene()
    scene_.UpdateAnimationUsingDataTimeSteps()
    scene_.PlayMode = "Snap To TimeSteps"
    view.CameraFocalPoint = [cx, cy, 0.5 * (b[4] + b[5])]
    view.CameraPosition = [cx + 1.2 * w, cy - 2.0 * w, b[5] + 0.9 * w]
    view.CameraViewUp = [0, 0, 1]
    view.CameraParallelScale = w
    pv.ResetCamera(view)  # fits everything, keeps the direction set above
    view.CenterOfRotation = view.CameraFocalPoint
    pv.SetActiveSource(reader)
    return view, reader


def main(argv):
    ap = argparse.ArgumentParser(prog="rdparaview", description=__doc__.split("\n\n")[0]
                                 .split(" — ", 1)[1].replace("\n", " "))
    ap.add_argument("run", nargs="?", default=os.environ.get("RDPARAVIEW_RUN"),
                    metavar="RUN.h5|RUN.xmf", help="run file (or its .xmf); default $RDPARAVIEW_RUN")
    ap.add_argument("--every", type=int, default=1, metavar="K",
                    help="write every K-th output step to the sidecar (default 1; the last is kept)")
    ap.add_argument("--frame", choices=("ground", "absolute"), default="ground",
                    help="ground: the pedestal frame (default); absolute: moving with the table")
    ap.add_argument("--ratio-max", type=float, default=1.5, metavar="R",
                    help="top of the tilt/alpha colour scale (default 1.5)")
    ap.add_argument("--state", metavar="OUT.pvsm", help="save a ParaView state file")
    ap.add_argument("--screenshot", metavar="OUT.png", help="save a picture (1200 x 800)")
    ap.add_argument("--time", default="start", metavar="start|end|T",
                    help="time shown in the screenshot (default start)")
    a = ap.parse_args(argv)
    if not a.run:
        ap.error("give RUN.h5 (or set RDPARAVIEW_RUN)")
    if not os.path.exists(a.run):
        sys.stderr.write("rdparaview: error: %s: no such file\n" % a.run)
        return 2
    mode = rendering(argv)
    if mode is None:
        sys.stderr.write(NO_RENDERING + "\n")
        return 2
    xmf = sidecar(a.run, a.every, a.frame)
    from paraview import simple as pv
    view, reader = scene(xmf, a.ratio_max)
    ts = list(reader.TimestepValues) or [0.0]
    t = ts[0] if a.time == "start" else ts[-1] if a.time == "end" else float(a.time)
    pv.GetAnimationScene().AnimationTime = t
    if a.screenshot:
        pv.SaveScreenshot(a.screenshot, view, ImageResolution=[1200, 800])
    if a.state:
        pv.SaveState(a.state)
    print("rdparaview: %s: %d steps from %g to %g s%s%s (rendering: %s)" % (
        xmf, len(ts), ts[0], ts[-1], "; state " + a.state if a.state else "",
        "; picture " + a.screenshot if a.screenshot else "", mode))
    if os.environ.get("RDPARAVIEW_XVFB"):
        # ParaView's teardown on Xvfb's GLX fails (GLXBadContext, exit 1) after everything is
        # written: leave without it
        sys.stdout.flush()
        os._exit(0)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
elif os.environ.get("RDPARAVIEW_RUN"):  # paraview --script=tools/rdparaview.py
    scene(sidecar(os.environ["RDPARAVIEW_RUN"], 1, "ground"))
