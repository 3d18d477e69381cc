"""Build a scenario in code: each method writes one line of the scenario language (README,
"Scenario language"), so what runs is exactly what a scenario file would say.

    s = (rockdem.Scene("a block on a pad")
         .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True)
         .brick("block", size=(0.4, 0.4, 1.6), position=(0, 0, 0.8))
         .contact(kn=1e10, ks=1e9, friction=40)
         .pulse("one-sine", amplitude="0.4g", frequency=2)
         .solve(3))
    run = s.build().run("block.h5")
"""


def _num(v):
    return v if isinstance(v, str) else repr(float(v))


def _vec(v):
    return " ".join(_num(x) for x in v)


class Scene:
    """Scenario text built line by line; build() parses it into a rockdem.Scenario."""

    def __init__(self, title=None, folder="."):
        self.lines = []
        self.folder = folder  # relative mesh and record paths are taken from here
        if title:
            self.line("model title '%s'" % title.replace("'", ""))

    def line(self, text):
        """Append any scenario line as written."""
        self.lines.append(text)
        return self

    def gravity(self, g):
        return self.line("model gravity %s" % _num(g))

    def brick(self, name, size, position, fixed=False, density=None, mass=None):
        """A box of edge lengths size (m) with its centre of mass at position (m)."""
        s = "block create brick size %s position %s" % (_vec(size), _vec(position))
        if density is not None:
            s += " density %s" % _num(density)
        if mass is not None:
            s += " mass %s" % _num(mass)
        return self.line(s + (" fixed" if fixed else "") + " name %s" % name)

    def mesh(self, name, path, seat_on=None, density=None):
        """A closed triangle mesh (OBJ, PLY, STL), optionally seated on another body's top."""
        s = "block import mesh '%s'" % path
        if seat_on:
            s += " seat-on %s" % seat_on
        if density is not None:
            s += " density %s" % _num(density)
        return self.line(s + " name %s" % name)

    def contact(self, kn=1e10, ks=1e11, friction=40, spacing=None):
        """Coulomb-slip joint: KN, KS (Pa/m; rockdem's defaults 1e10 and 1e11 = 10 KN),
        friction angle (degrees), subcontact spacing (m, 'vertices' or 'auto'; default
        rockdem's: the faces' vertices)."""
        s = "contact property stiffness-normal %s stiffness-shear %s friction %s" % (
            _num(kn), _num(ks), _num(friction))
        if spacing is not None:
            s += " spacing %s" % (spacing if isinstance(spacing, str) else _num(spacing))
        return self.line(s)

    def pulse(self, kind="one-sine", amplitude="0.3g", frequency=2, direction=0):
        """A horizontal pulse; amplitude in m/s^2 or "0.3g", frequency in Hz, direction in
        degrees from +x."""
        return self.line("ground-motion pulse %s amplitude %s frequency %s direction %s" % (
            kind, _num(amplitude), _num(frequency), _num(direction)))

    def stochastic(self, seed=1, pga="0.2g", duration=8, direction=0):
        """A Kanai-Tajimi synthetic record scaled to pga (m/s^2 or "0.2g")."""
        return self.line("ground-motion stochastic seed %d pga %s duration %s direction %s" % (
            int(seed), _num(pga), _num(duration), _num(direction)))

    def overturn(self, criterion="tilt-ratio", value=1.0):
        return self.line("model overturn %s %s" % (criterion, _num(value)))

    def solve(self, time):
        """Seconds of shaking (and free motion) after settling."""
        return self.line("model solve time %s" % _num(time))

    def output(self, path="rockdem.h5", interval=0.005):
        return self.line("output hdf5 '%s' interval %s" % (path, _num(interval)))

    @property
    def text(self):
        return "\n".join(self.lines) + "\n"

    def build(self, name="scene.dat"):
        from . import Scenario
        import os
        return Scenario.from_text(self.text, name=os.path.join(self.folder, name))
