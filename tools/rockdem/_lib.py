"""ctypes view of librockdem.so (include/rockdem/*.h): the structs the module passes by value or
reads back, and the prototypes of the functions it calls.

The library is looked for, in order: $ROCKDEM_LIB; librockdem.so beside this file (a pip
install copies it here); build/librockdem.so of the repository this file sits in
(tools/rockdem/ -> ../../build); the system's library path. `make python` builds it."""
import ctypes
import ctypes.util
import os
from typing import Iterator

RD_NAME_MAX = 64      # include/rockdem/scenario.h
RD_MAX_FENCES = 8     # include/rockdem/scenario.h
RD_ERROR_MAX = 512    # include/rockdem/error.h

HERE = os.path.dirname(os.path.abspath(__file__))
REPO = os.path.dirname(os.path.dirname(HERE))

STATUS = ("done", "overturned", "interrupted", "unstable", "io_error", "error", "penetrated", "lost",
          "untrusted")  # rd_status


class Error(ctypes.Structure):
    _fields_ = [("msg", ctypes.c_char * RD_ERROR_MAX)]

    @property
    def text(self):
        return self.msg.decode("utf-8", "replace")


class FenceHit(ctypes.Structure):  # rd_fence_hit
    _fields_ = [("crossings", ctypes.c_int),
                ("time", ctypes.c_double),
                ("energy", ctypes.c_double),
                ("speed", ctypes.c_double),
                ("height", ctypes.c_double),
                ("point", ctypes.c_double * 3)]


class BodySummary(ctypes.Structure):  # rd_body_summary
    _fields_ = [("name", ctypes.c_char * RD_NAME_MAX),
                ("overturned", ctypes.c_int),
                ("overturn_time", ctypes.c_double),
                ("max_tilt", ctypes.c_double),
                ("alpha", ctypes.c_double),
                ("alpha_min", ctypes.c_double),
                ("alpha_min_direction", ctypes.c_double),
                ("tip_accel_min", ctypes.c_double),
                ("max_tilt_ratio", ctypes.c_double),
                ("max_slide", ctypes.c_double),
                ("final_slide", ctypes.c_double),
                ("uplifted", ctypes.c_int),
                ("slid", ctypes.c_int),
                ("max_rocking_in", ctypes.c_double),
                ("max_rocking_out", ctypes.c_double),
                ("max_twist", ctypes.c_double),
                ("final_twist", ctypes.c_double),
                ("unsupported", ctypes.c_int),
                ("final_position", ctypes.c_double * 3),
                ("travel", ctypes.c_double),
                ("drop", ctypes.c_double),
                ("runout_direction", ctypes.c_double),  # runout (docs/RUNOUT.md)
                ("path_length", ctypes.c_double),
                ("max_speed", ctypes.c_double),
                ("max_energy", ctypes.c_double),
                ("max_bounce", ctypes.c_double),
                ("final_quaternion", ctypes.c_double * 4),
                ("left_time", ctypes.c_double),
                ("nfences", ctypes.c_int),
                ("fence", FenceHit * RD_MAX_FENCES)]


class Summary(ctypes.Structure):  # rd_summary
    _fields_ = [("nbodies", ctypes.c_int),
                ("body", ctypes.POINTER(BodySummary)),  # [nbodies], borrowed from the sim
                ("any_overturned", ctypes.c_int),
                ("end_time", ctypes.c_double),
                ("dt", ctypes.c_double),
                ("dt_critical", ctypes.c_double),
                ("steps", ctypes.c_long),
                ("settle_time", ctypes.c_double),
                ("energy_residual_max", ctypes.c_double),
                ("wall_seconds", ctypes.c_double),
                ("at_rest", ctypes.c_int),
                ("status", ctypes.c_int)]


class Event(ctypes.Structure):  # rd_event
    _fields_ = [("time", ctypes.c_double), ("body", ctypes.c_int),
                ("type", ctypes.c_char * 16), ("value", ctypes.c_double)]


class ThresholdOpts(ctypes.Structure):  # rd_threshold_opts
    _fields_ = [("lo", ctypes.c_double), ("hi", ctypes.c_double), ("nscan", ctypes.c_int),
                ("jobs", ctypes.c_int), ("rtol", ctypes.c_double)]


class ThresholdResult(ctypes.Structure):  # rd_threshold_result
    _fields_ = [("found", ctypes.c_int), ("amplitude", ctypes.c_double),
                ("below", ctypes.c_double), ("static_amp", ctypes.c_double),
                ("w_over_p", ctypes.c_double), ("runs", ctypes.c_int),
                ("lifted_off", ctypes.c_int), ("own_scale", ctypes.c_int)]


class JointSummary(ctypes.Structure):  # rd_joint_summary
    _fields_ = [("a", ctypes.c_char * RD_NAME_MAX), ("b", ctypes.c_char * RD_NAME_MAX),
                ("kn", ctypes.c_double), ("ks", ctypes.c_double), ("friction", ctypes.c_double),
                ("cohesion", ctypes.c_double), ("tension", ctypes.c_double),
                ("damping", ctypes.c_double), ("closed", ctypes.c_int),
                ("max_opening", ctypes.c_double), ("max_slip", ctypes.c_double),
                ("final_slip", ctypes.c_double)]


RD_NENERGY = 7  # include/rockdem/observer.h
ENERGY = ("kinetic", "gravitational", "elastic", "friction", "damping", "ground_work", "residual")
_DP = ctypes.POINTER(ctypes.c_double)


class Sample(ctypes.Structure):  # rd_sample
    _fields_ = [("time", ctypes.c_double), ("nbodies", ctypes.c_int),
                ("position", _DP), ("quaternion", _DP), ("velocity", _DP),
                ("angular_velocity", _DP), ("tilt", _DP), ("rotation", _DP),
                ("ground_acc", ctypes.c_double * 3), ("ground_vel", ctypes.c_double * 3),
                ("ground_disp", ctypes.c_double * 3), ("energy", ctypes.c_double * RD_NENERGY)]


class BodyInfo(ctypes.Structure):  # rd_body_info
    _fields_ = [("name", ctypes.c_char_p), ("fixed", ctypes.c_int),
                ("position", ctypes.c_double * 3), ("quaternion", ctypes.c_double * 4),
                ("mass", ctypes.c_double), ("inertia", ctypes.c_double * 3),
                ("size", ctypes.c_double * 3), ("alpha", ctypes.c_double),
                ("nvert", ctypes.c_int), ("vertices", _DP), ("ntri", ctypes.c_int),
                ("triangles", ctypes.POINTER(ctypes.c_int)), ("nprec", ctypes.c_int),
                ("precariousness", _DP)]


_E = ctypes.POINTER(Error)
OBS_BEGIN = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p, _E)
OBS_SAMPLE = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                              ctypes.POINTER(Sample), _E)
OBS_EVENT = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                             ctypes.POINTER(Event), _E)
OBS_END = ctypes.CFUNCTYPE(ctypes.c_int, ctypes.c_void_p, ctypes.c_void_p,
                           ctypes.POINTER(Summary), _E)
OBS_RELEASE = ctypes.CFUNCTYPE(None, ctypes.c_void_p)


class Observer(ctypes.Structure):  # rd_observer
    _fields_ = [("user", ctypes.c_void_p), ("every", ctypes.c_int), ("begin", OBS_BEGIN),
                ("sample", OBS_SAMPLE), ("event", OBS_EVENT), ("end", OBS_END),
                ("release", OBS_RELEASE)]


PROGRESS = ctypes.CFUNCTYPE(None, ctypes.c_void_p, ctypes.c_double, ctypes.c_double)


def _candidates() -> "Iterator[str]":
    env = os.environ.get("ROCKDEM_LIB")
    if env:
        yield env
    yield os.path.join(HERE, "librockdem.so")
    yield os.path.join(REPO, "build", "librockdem.so")
    found = ctypes.util.find_library("rockdem")
    if found:
        yield found


def _prototypes(lib):
    P, D, I = ctypes.c_void_p, ctypes.c_double, ctypes.c_int
    E = ctypes.POINTER(Error)
    protos = {
        "rd_scenario_new": (P, []),
        "rd_scenario_delete": (None, [P]),
        "rd_scenario_load": (I, [P, ctypes.c_char_p, E]),
        "rd_scenario_parse": (I, [P, ctypes.c_char_p, ctypes.c_char_p, E]),
        "rd_scenario_set": (I, [P, ctypes.c_char_p, E]),
        "rd_scenario_validate": (I, [P, E]),
        "rd_sim_create": (P, [P, E]),
        "rd_sim_write_hdf5": (I, [P, ctypes.c_char_p, E]),
        "rd_sim_run": (I, [P]),
        "rd_sim_summary": (None, [P, ctypes.POINTER(Summary)]),
        "rd_sim_error": (ctypes.c_char_p, [P]),
        "rd_sim_events": (ctypes.POINTER(Event), [P, ctypes.POINTER(I)]),
        "rd_sim_request_stop": (None, []),
        "rd_sim_free": (None, [P]),
        "rd_sim_stop": (None, [P]),
        "rd_sim_start": (I, [P]),
        "rd_sim_advance": (I, [P, ctypes.c_long, D]),
        "rd_sim_finish": (I, [P]),
        "rd_sim_time": (D, [P]),
        "rd_sim_end_time": (D, [P]),
        "rd_sim_dt": (D, [P]),
        "rd_sim_add_observer": (I, [P, ctypes.POINTER(Observer), E]),
        "rd_sim_body_count": (I, [P, ctypes.POINTER(I)]),
        "rd_sim_body_info": (None, [P, I, ctypes.POINTER(BodyInfo)]),
        "rd_sim_body_state": (None, [P, I, _DP, _DP, _DP, _DP]),
        "rd_sim_body_summary": (None, [P, I, ctypes.POINTER(BodySummary)]),
        "rd_sim_energy": (None, [P, _DP]),
        "rd_sim_joint_count": (I, [P]),
        "rd_sim_joint": (None, [P, I, ctypes.POINTER(JointSummary)]),
        "rd_scenario_limit": (I, [ctypes.c_char_p, ctypes.POINTER(D), ctypes.POINTER(D)]),
        "rd_set_progress": (None, [PROGRESS, P]),
        "rd_threshold_opts_default": (ThresholdOpts, []),
        "rd_threshold": (I, [P, I, ctypes.POINTER(ThresholdOpts),
                             ctypes.POINTER(ThresholdResult), E]),
    }
    for name, (res, args) in protos.items():
        fn = getattr(lib, name)
        fn.restype, fn.argtypes = res, args
    return lib


_lib = None


def lib() -> ctypes.CDLL:
    """The loaded library (loaded once). OSError naming every place looked at if none works."""
    global _lib
    if _lib is None:
        tried = []
        for path in _candidates():
            if not os.path.exists(path) and os.sep in path:
                tried.append(path + " (absent)")
                continue
            try:
                _lib = _prototypes(ctypes.CDLL(path))
                break
            except (OSError, AttributeError) as e:
                tried.append("%s (%s)" % (path, e))
        if _lib is None:
            raise OSError("rockdem: librockdem.so not found; run `make python` in the repository "
                          "or set ROCKDEM_LIB. Tried: " + "; ".join(tried))
    return _lib
