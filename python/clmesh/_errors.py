"""clmesh's exceptions: the library's typed errors, as Python classes.

The compiled module raises these for the C++ errors of the same names
(include/clmesh/errors.hpp), with the library's message.
"""


class Error(Exception):
    """Base of every error clmesh raises."""


class InputError(Error, ValueError):
    """Input that cannot be meshed: wrong shapes or dtypes, NaN, indices out of range."""


class OptionError(Error, ValueError):
    """Unknown, unsupported or malformed switches, or ones that do not go together."""


class DeviceError(Error, RuntimeError):
    """No usable OpenCL device, or one without double precision."""


class OpenCLError(Error, RuntimeError):
    """An OpenCL call failed (names the code, the phase and the kernel)."""


class InternalError(Error, RuntimeError):
    """The library met a state it cannot handle (a bug, reported rather than hidden)."""


class CheckError(Error, RuntimeError):
    """-C: the exact check found the mesh invalid (the message lists the problems)."""
