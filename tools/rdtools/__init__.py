"""rdtools — post-processing of rockdem HDF5 runs (plots, tables, XDMF sidecars, fragility).

Modules:
  runfile    open and validate a rockdem run file, read its datasets and attributes
  rotation   quaternion -> rotation matrix, world vertices of the bodies
  table      one summary row per run and body; CSV in and out
  plot       the one-page plot of a run
  xdmf       XDMF + companion HDF5 sidecar for ParaView
  fragility  logistic regression (seed 002 eq. 3), 2-D logistic surface, lognormal ML fit,
             classification metrics (seed 002 Table 4)
  cli        shared command-line plumbing (one-line errors, exit codes)

Needs Debian's /usr/bin/python3 with python3-h5py, -numpy, -scipy, -matplotlib only.
"""
__version__ = "0.1.0"


class RDError(Exception):
    """A user-facing error: printed as one line 'tool: error: message', exit status 2."""
