"""Build a scenario in code: each method writes one line of the scenario language (README, "A
scenario, line by line"), so what runs is exactly what a scenario file would say, and every
value is range-checked by the library's parser when the scene is built (one line naming the
scene's line and the problem).

    s = (rockdem.Scene("a block on a pad")
         .brick("pad", size=(4, 4, 0.5), position=(0, 0, -0.25), fixed=True, group="pad")
         .brick("block", size=(0.4, 0.4, 1.6), seat_on="pad", group="block")
         .preset("rigid")
         .contact(kn=5e9, ks=5e10, friction=30, range=("pad", "block"))
         .history_body("block", "all").history_joint("pad", "block", "all")
         .pulse("one-sine", amplitude="0.4g", frequency=2)
         .solve(3))
    run = s.build().run("block.h5")

Units: SI (m, kg, kg/m^3, s, Pa/m, Pa), angles in degrees as in the language; an acceleration
may be a str such as "0.3g"."""
from __future__ import annotations

import os
from typing import Any, Optional, Sequence, Tuple, Union

Number = Union[int, float, str]
Vec = Sequence[Number]


def _num(v: Number) -> str:
    """A number as the language writes it (exactly: repr), or a str as given ("0.3g")."""
    if isinstance(v, bool):
        raise TypeError("rockdem: a number was expected, got %r" % v)
    if isinstance(v, str):
        return v
    return repr(float(v))


def _vec(v: Vec, n: int = 3) -> str:
    v = list(v)
    if len(v) != n:
        raise ValueError("rockdem: expected %d numbers, got %r" % (n, v))
    return " ".join(_num(x) for x in v)


def _quote(s: str) -> str:
    """A quoted name or path (the language's quotes are single; one inside is refused)."""
    s = os.fspath(s)
    if "'" in s or "\n" in s or "\0" in s:
        raise ValueError("rockdem: a quoted name or path cannot hold a quote, a newline or a NUL: %r"
                         % s)
    return "'%s'" % s


def _placement(position: Optional[Vec], seat_on: Optional[str], at: Optional[Vec]) -> str:
    if (position is None) == (seat_on is None):
        raise ValueError("rockdem: give a body either position=(x, y, z) or seat_on=NAME")
    if position is not None:
        if at is not None:
            raise ValueError("rockdem: at=(x, y) goes with seat_on, not with position")
        return " position " + _vec(position)
    return " seat-on %s" % seat_on + (" at " + _vec(at, 2) if at is not None else "")


def _body_options(rotation: Optional[Vec] = None, density: Optional[Number] = None,
                  mass: Optional[Number] = None, name: Optional[str] = None, fixed: bool = False,
                  group: Optional[str] = None) -> str:
    if density is not None and mass is not None:
        raise ValueError("rockdem: give density or mass, not both")
    s = ""
    if rotation is not None:
        s += " rotation " + _vec(rotation)
    if density is not None:
        s += " density " + _num(density)
    if mass is not None:
        s += " mass " + _num(mass)
    if name is not None:
        s += " name " + name
    if group is not None:
        s += " group " + _quote(group)
    return s + (" fixed" if fixed else "")


class Scene:
    """Scenario text built line by line; build() parses it into a rockdem.Scenario. Every method
    returns the Scene (calls chain). folder: where relative mesh and record paths are taken
    from (the scene's file name is folder/name at build)."""

    def __init__(self, title: Optional[str] = None, folder: str = ".") -> None:
        self.lines: list = []
        self.folder = os.fspath(folder)
        if title:
            self.title(title)

    def line(self, text: str) -> "Scene":
        """Append any scenario line as written."""
        if "\n" in text or "\0" in text:
            raise ValueError("rockdem: one line at a time, without NUL bytes")
        self.lines.append(text)
        return self

    # --- model ---------------------------------------------------------------------------
    def title(self, text: str) -> "Scene":
        """model title: stored in the output."""
        return self.line("model title " + _quote(text))

    def gravity(self, g: Number) -> "Scene":
        """model gravity: m/s^2 (default 9.81)."""
        return self.line("model gravity " + _num(g))

    def density(self, rho: Number) -> "Scene":
        """model density: the default block density, kg/m^3 (default 2700)."""
        return self.line("model density " + _num(rho))

    def damping(self, kind: str = "none", value: Optional[Number] = None) -> "Scene":
        """model damping none | viscous ZETA (dashpot ratio 0-10) | local ALPHA (Cundall)."""
        if kind not in ("none", "viscous", "local"):
            raise ValueError("rockdem: damping kind is none, viscous or local, got %r" % kind)
        if (kind == "none") != (value is None):
            raise ValueError("rockdem: damping %s %s a value" % (kind, "takes no" if kind == "none" else "needs"))
        return self.line("model damping " + kind + ("" if value is None else " " + _num(value)))

    def timestep(self, safety: Optional[Number] = None, fixed: Optional[Number] = None) -> "Scene":
        """model timestep auto [safety F] (default F = 0.2 of the critical step) | fixed DT (s)."""
        if fixed is not None:
            if safety is not None:
                raise ValueError("rockdem: timestep takes safety or fixed, not both")
            return self.line("model timestep fixed " + _num(fixed))
        return self.line("model timestep auto" + ("" if safety is None else " safety " + _num(safety)))

    def settle(self, on: bool = True, ratio: Optional[Number] = None,
               time_limit: Optional[Number] = None) -> "Scene":
        """model settle on|off [ratio R (unbalanced force / weight)] [time-limit T (s)]."""
        s = "model settle " + ("on" if on else "off")
        if ratio is not None:
            s += " ratio " + _num(ratio)
        if time_limit is not None:
            s += " time-limit " + _num(time_limit)
        return self.line(s)

    def solve(self, time: Number, tail: Optional[Number] = None) -> "Scene":
        """model solve time T (s of shaking and free motion after settling) [tail D (s at most
        run on until every body is at rest)]."""
        return self.line("model solve time " + _num(time) + ("" if tail is None else " tail " + _num(tail)))

    def overturn(self, criterion: str = "tilt-ratio", value: Number = 1.0,
                 stop: Optional[bool] = None) -> "Scene":
        """model overturn tilt-ratio X | angle DEG | height F [stop on|off]."""
        if criterion not in ("tilt-ratio", "angle", "height"):
            raise ValueError("rockdem: overturn criterion is tilt-ratio, angle or height")
        s = "model overturn %s %s" % (criterion, _num(value))
        return self.line(s + ("" if stop is None else " stop " + ("on" if stop else "off")))

    def save(self, path: str) -> "Scene":
        """model save: write a checkpoint after settling (the run continues)."""
        return self.line("model save " + _quote(path))

    def restore(self, path: str) -> "Scene":
        """model restore: start from a checkpoint of the same blocks instead of settling."""
        return self.line("model restore " + _quote(path))

    def reference_restitution(self, e: Number) -> "Scene":
        """model reference restitution E: the rigid reference solver's impact restitution."""
        return self.line("model reference restitution " + _num(e))

    # --- blocks --------------------------------------------------------------------------
    def brick(self, name: str, size: Vec, position: Optional[Vec] = None, fixed: bool = False,
              density: Optional[Number] = None, mass: Optional[Number] = None,
              seat_on: Optional[str] = None, at: Optional[Vec] = None,
              rotation: Optional[Vec] = None, group: Optional[str] = None) -> "Scene":
        """A box of edge lengths size (m), its centre of mass at position (m) or seated on an
        earlier body (seat_on, above (x, y) = at); rotation in degrees; fixed: a pedestal."""
        return self.line("block create brick size " + _vec(size) + _placement(position, seat_on, at)
                         + _body_options(rotation, density, mass, name, fixed, group))

    def prism(self, name: str, sides: int, radius: Number, height: Number,
              position: Optional[Vec] = None, radius_top: Optional[Number] = None,
              seat_on: Optional[str] = None, at: Optional[Vec] = None, fixed: bool = False,
              density: Optional[Number] = None, mass: Optional[Number] = None,
              rotation: Optional[Vec] = None, group: Optional[str] = None) -> "Scene":
        """An n-sided drum, axis vertical: circumradius (m), optional taper to radius_top (m),
        height (m)."""
        s = "block create prism sides %d radius %s" % (int(sides), _num(radius))
        if radius_top is not None:
            s += " radius-top " + _num(radius_top)
        s += " height " + _num(height)
        return self.line(s + _placement(position, seat_on, at)
                         + _body_options(rotation, density, mass, name, fixed, group))

    def polyhedron(self, name: str, vertices: Sequence[Vec], position: Optional[Vec] = None,
                   seat_on: Optional[str] = None, at: Optional[Vec] = None, fixed: bool = False,
                   density: Optional[Number] = None, mass: Optional[Number] = None,
                   rotation: Optional[Vec] = None, group: Optional[str] = None) -> "Scene":
        """The convex hull of the points (m)."""
        s = "block create polyhedron vertices " + " ".join(_vec(v) for v in vertices)
        return self.line(s + _placement(position, seat_on, at)
                         + _body_options(rotation, density, mass, name, fixed, group))

    def mesh(self, name: str, path: str, seat_on: Optional[str] = None,
             density: Optional[Number] = None, position: Optional[Vec] = None,
             at: Optional[Vec] = None, fixed: bool = False, mass: Optional[Number] = None,
             rotation: Optional[Vec] = None, group: Optional[str] = None) -> "Scene":
        """A closed triangle mesh (OBJ, PLY, STL; path relative to the scene's folder), placed at
        position or seated on an earlier body."""
        s = "block import mesh " + _quote(path)
        if position is not None or seat_on is not None:
            s += _placement(position, seat_on, at)
        return self.line(s + _body_options(rotation, density, mass, name, fixed, group))

    def column(self, drums: int, diameter: Number, height: Number, seat_on: str,
               name: Optional[str] = None, sides: Optional[int] = None,
               taper: Optional[Number] = None, plinth: Optional[Tuple[Number, Number]] = None,
               capital: Optional[Number] = None, abacus: Optional[Tuple[Number, Number]] = None,
               at: Optional[Vec] = None, density: Optional[Number] = None,
               group: Optional[str] = None) -> "Scene":
        """A drum column: NAME-plinth (width, height m), NAME-d1..dN, NAME-capital (height m),
        NAME-abacus (width, height m); diameter and height of the shaft (m); taper: top
        diameter / bottom."""
        s = "block create column drums %d diameter %s height %s" % (int(drums), _num(diameter), _num(height))
        if sides is not None:
            s += " sides %d" % int(sides)
        if taper is not None:
            s += " taper " + _num(taper)
        if plinth is not None:
            s += " plinth " + _vec(plinth, 2)
        if capital is not None:
            s += " capital " + _num(capital)
        if abacus is not None:
            s += " abacus " + _vec(abacus, 2)
        s += " seat-on " + seat_on + (" at " + _vec(at, 2) if at is not None else "")
        return self.line(s + _body_options(None, density, None, name, False, group))

    def stack(self, lower: Vec, upper: Vec, seat_on: str, name: Optional[str] = None,
              at: Optional[Vec] = None, density: Optional[Number] = None,
              group: Optional[str] = None) -> "Scene":
        """A two-block assembly (statue on pedestal): NAME-lower and NAME-upper, edge lengths m."""
        s = "block create stack lower %s upper %s seat-on %s" % (_vec(lower), _vec(upper), seat_on)
        s += " at " + _vec(at, 2) if at is not None else ""
        return self.line(s + _body_options(None, density, None, name, False, group))

    def initial(self, name: str, tilt: Optional[Number] = None,
                direction: Optional[Number] = None, velocity: Optional[Vec] = None,
                angular_velocity: Optional[Vec] = None) -> "Scene":
        """block initial: conditions applied after settling: tilt (degrees, about the base edge
        on the side of direction, degrees), velocity (m/s), angular_velocity (rad/s)."""
        s = "block initial name " + name
        if tilt is not None:
            s += " tilt " + _num(tilt)
        if direction is not None:
            s += " direction " + _num(direction)
        if velocity is not None:
            s += " velocity " + _vec(velocity)
        if angular_velocity is not None:
            s += " angular-velocity " + _vec(angular_velocity)
        return self.line(s)

    # --- contact -------------------------------------------------------------------------
    def contact(self, kn: Optional[Number] = 1e10, ks: Optional[Number] = 1e11,
                friction: Optional[Number] = 40, spacing: Optional[Number] = None,
                cohesion: Optional[Number] = None, tension: Optional[Number] = None,
                restitution: Optional[Number] = None, damping: Optional[Number] = None,
                range: Optional[Sequence[str]] = None, block: Optional[str] = None) -> "Scene":
        """contact property: KN, KS (Pa/m; defaults 1e10 and 1e11 = 10 KN), friction angle
        (degrees), subcontact spacing (m, 'auto' or 'vertices'), cohesion and tension (Pa),
        restitution in [0, 1]. With range=("A",) or ("A", "B") the joint of the pairs of
        group-A and group-B bodies (block: one body by name), with its own damping ratio; None
        leaves a value to the default joint."""
        s = "contact property"
        for kw, v in (("stiffness-normal", kn), ("stiffness-shear", ks), ("friction", friction),
                      ("cohesion", cohesion), ("tension", tension)):
            if v is not None:
                s += " %s %s" % (kw, _num(v))
        if spacing is not None:
            s += " spacing " + (spacing if spacing in ("auto", "vertices") else _num(spacing))
        if damping is not None:
            if range is None and block is None:
                raise ValueError("rockdem: a joint's own damping goes with range= or block=; "
                                 "the default joint's is damping('viscous', zeta)")
            s += " damping " + _num(damping)
        if restitution is not None:
            s += " restitution " + _num(restitution)
        if range is not None or block is not None:
            s += " range"
            for g in (range or ()):
                s += " group " + _quote(g)
            if block is not None:
                s += " block " + _quote(block)
        return self.line(s)

    def preset(self, name: str) -> "Scene":
        """contact preset rigid | 3dec | default: a whole contact setting, before any contact
        property without range and any model damping line."""
        if name not in ("rigid", "3dec", "default"):
            raise ValueError("rockdem: contact preset is rigid, 3dec or default, got %r" % name)
        return self.line("contact preset " + name)

    # --- histories -----------------------------------------------------------------------
    def history_interval(self, dt: Number) -> "Scene":
        """history interval: sampling interval of the histories, s (default 0.001)."""
        return self.line("history interval " + _num(dt))

    def history_body(self, name: str, *quantities: str) -> "Scene":
        """history body: position rotation velocity angular-velocity | all."""
        return self.line("history body %s %s" % (_quote(name), " ".join(quantities or ("all",))))

    def history_joint(self, a: str, b: str, *quantities: str) -> "Scene":
        """history joint: normal-force shear-force opening slip area pressure-centre | all."""
        return self.line("history joint %s %s %s" % (_quote(a), _quote(b),
                                                     " ".join(quantities or ("all",))))

    def history_energy(self) -> "Scene":
        """history energy: the energy terms at the history interval."""
        return self.line("history energy")

    # --- ground motion -------------------------------------------------------------------
    def pulse(self, kind: str = "one-sine", amplitude: Number = "0.3g",
              frequency: Optional[Number] = 2, direction: Optional[Number] = None,
              duration: Optional[Number] = None, cycles: Optional[Number] = None,
              start: Optional[Number] = None, vertical: bool = False) -> "Scene":
        """A built-in pulse (one-sine, one-cosine, rectangular, triangle, harmonic): amplitude
        in m/s^2 or "0.3g", frequency (Hz) or duration (s), cycles, start (s), direction
        (degrees from +x; default 0); vertical: a vertical component instead."""
        s = "ground-motion pulse %s amplitude %s" % (kind, _num(amplitude))
        if duration is not None:
            s += " duration " + _num(duration)
        elif frequency is not None:
            s += " frequency " + _num(frequency)
        if cycles is not None:
            s += " cycles " + _num(cycles)
        if start is not None:
            s += " start " + _num(start)
        if direction is not None:
            s += " direction " + _num(direction)
        return self.line(s + (" vertical" if vertical else ""))

    def record(self, path: str, format: Optional[str] = None, units: Optional[str] = None,
               dt: Optional[Number] = None, record: Optional[str] = None,
               component: Optional[str] = None, direction: Optional[Number] = None,
               scale: Optional[Number] = None, scale_pga: Optional[Number] = None,
               scale_pgv: Optional[Number] = None, baseline: Optional[Union[int, str]] = None) -> "Scene":
        """ground-motion import: a recorded component (AT2, CSV, text, FEMA P695 .h5; path
        relative to the scene's folder); units g | m/s2 | cm/s2; dt s; component h1 | h2 |
        vertical | a | b; direction degrees; one of scale (factor), scale_pga (m/s^2 or "0.3g"),
        scale_pgv (m/s); baseline: polynomial degree 2-8 or "off"."""
        s = "ground-motion import " + _quote(path)
        for kw, v in (("format", format), ("units", units), ("record", record),
                      ("component", component)):
            if v is not None:
                s += " %s %s" % (kw, v)
        for kw, v in (("dt", dt), ("direction", direction), ("scale", scale),
                      ("scale-pga", scale_pga), ("scale-pgv", scale_pgv)):
            if v is not None:
                s += " %s %s" % (kw, _num(v))
        if baseline is not None:
            s += " baseline " + (baseline if isinstance(baseline, str) else "%d" % baseline)
        return self.line(s)

    def stochastic(self, seed: int = 1, pga: Number = "0.2g", duration: Number = 8,
                   direction: Number = 0, **options: Number) -> "Scene":
        """A Kanai-Tajimi synthetic record scaled to pga (m/s^2 or "0.2g"), duration s; other
        keywords of the line as options (dt, frequency, damping, highpass, highpass_damping,
        peak_time, end_level, component, baseline: underscores for hyphens)."""
        s = "ground-motion stochastic seed %d pga %s duration %s direction %s" % (
            int(seed), _num(pga), _num(duration), _num(direction))
        for k, v in options.items():
            s += " %s %s" % (k.replace("_", "-"), v if isinstance(v, str) else _num(v))
        return self.line(s)

    # --- output --------------------------------------------------------------------------
    def output(self, path: str = "rockdem.h5", interval: Number = 0.005) -> "Scene":
        """output hdf5: the run file and the sampling interval (s) of samples and callbacks."""
        return self.line("output hdf5 %s interval %s" % (_quote(path), _num(interval)))

    @property
    def text(self) -> str:
        """The scenario text so far."""
        return "\n".join(self.lines) + "\n"

    def build(self, name: str = "scene.dat") -> "Scenario":  # noqa: F821
        """Parse the text into a Scenario named folder/name (errors: RockdemError naming the
        line)."""
        from .scenario import Scenario
        return Scenario.from_text(self.text, name=os.path.join(self.folder, name))
